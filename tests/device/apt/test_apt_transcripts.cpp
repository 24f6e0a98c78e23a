// APT golden transcripts: hex sessions replayed byte for byte on a stepped clock (1 kHz).
//
// Format (tests/device/apt/transcripts/*.txt), one item per line:
//   # comment                 ignored, as are blank lines; cite the manual page here
//   @ TDC001 MTS50-Z8         a freshly powered-up device: the model, then its stage, or for a
//   @ BBD203 MLS203-X MLS203-Y  card-slot controller the stage of each bay from bay 0 (0x21) on.
//   @ TDC001 {"serial_number":83000002}
//                             or the model, then the device's "apt" object of the rig JSON inline
//                             (docs/config.md; checked as the rig loader checks it).
//   @ KST101 firmware=issue-44.1 ZST225B
//                             either form with the device's "firmware" right after the model
//                             (default: the manual's, "issue-3").
//                             Required before the first step; a later '@' starts a new world with a
//                             new device (device 1, named "transcript").
//   @+ TSG001 {"gauge":{...}}  one more device on the same world and clock (device 2, 3, ...;
//                             named "transcript2", "transcript3", ...), in either form of '@'.
//   > 11 04 01 00 50 01       bytes sent to device 1 (hex, one byte per token)
//   >2 11 04 01 00 50 01      bytes sent to device 2 (the number right after '>', no space)
//   ~ 100ms                   advance the clock (also "~ 3s")
//   < 12 04 06 00 81 50 ...   bytes device 1 sent during the step above, in order; '<2' those of
//                             device 2. Consecutive '<' ('<2') lines concatenate; together they must
//                             equal, exactly, everything that device sent since that step. A step
//                             with no '<N' line asserts that device N sent nothing. A first token
//                             "49x" repeats the line's bytes 49 times.
// A mismatch reports the file and line of the step, the device, the expected and the actual hex.
#include "apt_harness.hpp"

#include "emulator/apt/catalogue.hpp"
#include "emulator/apt/shipped_stages.hpp"
#include "emulator/apt/config.hpp"
#include "emulator/core/config_reader.hpp"

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace test_apt_transcripts {

using rigsim::test::AptHarness;

namespace {

/// The "apt" object inline after the model: read as the rig loader reads a device's.
void load_inline(const std::string& where, const std::string& text, rigsim::DeviceConfig& c)
{
    nlohmann::json device{{"name", c.name}, {"protocol", "apt"}, {"model", c.model}};
    try {
        device["apt"] = nlohmann::json::parse(text);
        rigsim::apt::load_device_section(rigsim::ConfigReader(where), device, "", c);
    } catch (const std::exception& e) {
        FAIL(where << ": " << e.what());
    }
}

/// A device line after '@' or '@+': the model, then a stage (single unit), one stage per bay
/// (rack), or the "apt" object inline; `name` is the device's.
rigsim::DeviceConfig device_from(const std::string& where, const std::string& spec, const std::string& name)
{
    std::istringstream s(spec);
    rigsim::DeviceConfig c;
    c.name = name;
    c.protocol = "apt";
    s >> c.model;
    const auto* model = rigsim::apt::find_controller(c.model);
    if (!model)
        FAIL(where << ": unknown APT model '" << c.model << "'");
    std::string rest;
    std::getline(s >> std::ws, rest);
    if (constexpr std::string_view key = "firmware="; rest.compare(0, key.size(), key) == 0) {
        const auto end = rest.find(' ');
        c.firmware = rest.substr(key.size(), end == std::string::npos ? std::string::npos : end - key.size());
        const auto firmware = rigsim::apt::find_firmware(c.firmware);
        if (!firmware)
            FAIL(where << ": unknown APT firmware '" << c.firmware << "'");
        rigsim::apt::config_of(c).firmware = *firmware;
        const auto next = end == std::string::npos ? std::string::npos : rest.find_first_not_of(' ', end);
        rest = next == std::string::npos ? std::string() : rest.substr(next);
    }
    if (!rest.empty() && rest[0] == '{') {
        load_inline(where, rest, c);
        return c;
    }
    std::istringstream stages_in(rest);
    std::vector<std::string> stages;
    for (std::string stage; stages_in >> stage;)
        stages.push_back(stage);
    if (stages.empty())
        FAIL(where << ": '@ " << spec << "' names no stage");
    for (const auto& stage : stages)
        if (!rigsim::apt::find_stage(stage))
            FAIL(where << ": '@ " << spec << "': no shipped stage named \"" << stage << "\"");
    if (model->rack) {
        for (const auto& stage : stages)
            rigsim::apt::config_of(c).bays.push_back(*rigsim::apt::find_stage(stage));
    } else {
        if (stages.size() != 1)
            FAIL(where << ": a single unit drives one stage, not " << stages.size());
        rigsim::apt::config_of(c).stage = *rigsim::apt::find_stage(stages.front());
    }
    return c;
}

/// The device a '>' or '<' line names: "2 ..." after the kind is device 2 (index 1); else device 1.
std::size_t device_of(const std::string& where, std::string& rest, std::size_t count)
{
    if (rest.empty() || !std::isdigit(static_cast<unsigned char>(rest[0])))
        return 0;
    const auto n = static_cast<std::size_t>(rest[0] - '0');
    if (n < 1 || n > count)
        FAIL(where << ": no device " << n << " (" << count << " on this world)");
    rest.erase(0, 1);
    return n - 1;
}

bool is_hex_byte(const std::string& t)
{
    return t.size() == 2 && std::isxdigit(static_cast<unsigned char>(t[0])) != 0
           && std::isxdigit(static_cast<unsigned char>(t[1])) != 0;
}

/// Hex tokens -> canonical "AA BB CC" (upper case, single spaces); "49x" first repeats.
std::string canonical_hex(const std::string& where, const std::string& text, bool allow_repeat)
{
    std::istringstream s(text);
    std::vector<std::string> tokens;
    for (std::string t; s >> t;)
        tokens.push_back(t);
    int repeat = 1;
    std::size_t first = 0;
    if (allow_repeat && !tokens.empty() && tokens[0].size() >= 2 && tokens[0].back() == 'x'
        && tokens[0].find_first_not_of("0123456789") == tokens[0].size() - 1) {
        repeat = std::stoi(tokens[0]);
        first = 1;
    }
    std::string one;
    for (std::size_t i = first; i < tokens.size(); ++i) {
        if (!is_hex_byte(tokens[i]))
            FAIL(where << ": '" << tokens[i] << "' is not a hex byte");
        if (!one.empty())
            one += ' ';
        for (char ch : tokens[i])
            one += static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    }
    std::string out;
    for (int r = 0; r < repeat; ++r) {
        if (!out.empty() && !one.empty())
            out += ' ';
        out += one;
    }
    return out;
}

/// Clock advance after '~': "250ms", "250 ms", "3s".
std::int64_t advance_ms(const std::string& where, const std::string& text)
{
    std::istringstream s(text);
    long long n = -1;
    std::string unit;
    s >> n >> unit;
    if (n < 0)
        FAIL(where << ": no duration in '~ " << text << "'");
    if (unit == "ms")
        return n;
    if (unit == "s")
        return n * 1000;
    FAIL(where << ": unknown unit '" << unit << "' (ms or s)");
    return 0;
}

/// Replay `name` once; `keep`: on a clock that keeps its schedule, as the daemon's does.
void replay_on(const std::string& name, bool keep)
{
    const std::string path = RIGSIM_SOURCE_DIR "/tests/device/apt/transcripts/" + name;
    std::ifstream in(path);
    INFO("transcript " << path << (keep ? ", the clock keeping its schedule (models/clock.hpp)" : ""));
    REQUIRE(in);
    std::unique_ptr<AptHarness> harness;
    int steps = 0;
    std::string line;
    std::vector<std::string> actual, expected;   // per device, of the last step
    int number = 0, step_line = 0;
    bool in_step = false;
    // Compare what each device sent in the last step with the '<' lines that followed it.
    auto settle = [&] {
        if (!in_step)
            return;
        for (std::size_t d = 0; d < actual.size(); ++d) {
            INFO(name << ":" << step_line << ": device " << d + 1);
            INFO(name << ":" << step_line << ": expected: " << (expected[d].empty() ? "(nothing)" : expected[d]));
            INFO(name << ":" << step_line << ": actual:   " << (actual[d].empty() ? "(nothing)" : actual[d]));
            CHECK(actual[d] == expected[d]);
        }
        in_step = false;
    };
    while (std::getline(in, line)) {
        ++number;
        if (!line.empty() && line.back() == '\r')
            line.pop_back();
        if (line.find_first_not_of(" \t") == std::string::npos || line[0] == '#')
            continue;
        const std::string where = name + ":" + std::to_string(number);
        const char kind = line[0];
        std::string rest = line.size() > 1 ? line.substr(1) : "";
        if (kind == '<') {
            if (!in_step)
                FAIL(where << ": '<' with no step before it");
            const auto d = device_of(where, rest, harness->device_count());
            const auto bytes = canonical_hex(where, rest, true);
            if (!expected[d].empty() && !bytes.empty())
                expected[d] += ' ';
            expected[d] += bytes;
            continue;
        }
        settle();
        if (kind == '@') {
            const bool more = !rest.empty() && rest[0] == '+';
            if (more && !harness)
                FAIL(where << ": '@+' with no '@' device before it");
            if (more)
                harness->add_device(device_from(where, rest.substr(1), "transcript" + std::to_string(harness->device_count() + 1)));
            else
                harness = std::make_unique<AptHarness>(device_from(where, rest, "transcript"));
            if (keep)
                harness->keep_schedule();
            continue;
        }
        if (!harness)
            FAIL(where << ": no '@' device line before the first step");
        actual.assign(harness->device_count(), "");
        expected.assign(harness->device_count(), "");
        if (kind == '>') {
            const auto d = device_of(where, rest, harness->device_count());
            const auto bytes = canonical_hex(where, rest, false);
            if (bytes.empty())
                FAIL(where << ": '>' with no bytes");
            actual[d] = harness->send(bytes, d);
        } else if (kind == '~') {
            harness->advance_ms(advance_ms(where, rest));
        } else {
            FAIL(where << ": unknown line kind '" << kind << "'");
        }
        for (std::size_t d = 0; d < actual.size(); ++d)
            actual[d] += harness->take(d);
        in_step = true;
        step_line = number;
        ++steps;
    }
    settle();
    CHECK(steps > 0);
}

/// Replay `name` as the tests step the clock (every Tickable asked afresh at each call), then as
/// the daemon runs it (the schedule kept between announcements): the bytes must be the same.
void replay(const std::string& name)
{
    replay_on(name, false);
    replay_on(name, true);
}

/// Every transcript has a test case below.
const std::vector<std::string> kTranscripts = {
    "apt_system.txt", "apt_parameters.txt", "apt_moves.txt", "apt_homing.txt", "apt_limits.txt",
    "apt_status.txt", "apt_rack_bbd203.txt", "apt_bbd203_pmd.txt", "apt_stepper.txt", "apt_bad_input.txt",
    "apt_faults.txt", "apt_stages_scurve.txt", "apt_two_devices.txt",
    "apt_solenoid.txt", "apt_piezo_tpz001.txt", "apt_piezo_lut.txt", "apt_strain_gauge.txt",
    "apt_piezo_bpc303.txt", "apt_kdc101_issue44.txt", "apt_kst101_issue44.txt",
    "apt_kcube_msgs_issue44.txt", "apt_kcube_msgs_issue3.txt", "apt_pzmot_kim101.txt",
    "apt_mmr601.txt",
};

} // namespace

TEST_CASE("apt transcripts: every file in transcripts/ is replayed", "[device][apt][transcript]")
{
    for (const auto& entry : std::filesystem::directory_iterator(RIGSIM_SOURCE_DIR "/tests/device/apt/transcripts")) {
        const auto file = entry.path().filename().string();
        INFO(file);
        CHECK(std::find(kTranscripts.begin(), kTranscripts.end(), file) != kTranscripts.end());
    }
}

TEST_CASE("apt transcript: the KIM101's PZMOT messages", "[device][apt][transcript][pzmot]")
{
    replay("apt_pzmot_kim101.txt");
}

TEST_CASE("apt transcript: the MMR601 rack with an MPZ601 card", "[device][apt][transcript][mmr601]")
{
    replay("apt_mmr601.txt");
}

TEST_CASE("apt transcript: generic system messages", "[device][apt][transcript]")
{
    replay("apt_system.txt");
}

TEST_CASE("apt transcript: counters and parameter trios", "[device][apt][transcript]")
{
    replay("apt_parameters.txt");
}

TEST_CASE("apt transcript: moves", "[device][apt][transcript]")
{
    replay("apt_moves.txt");
}

TEST_CASE("apt transcript: homing", "[device][apt][transcript]")
{
    replay("apt_homing.txt");
}

TEST_CASE("apt transcript: limits and backlash", "[device][apt][transcript]")
{
    replay("apt_limits.txt");
}

TEST_CASE("apt transcript: status updates", "[device][apt][transcript]")
{
    replay("apt_status.txt");
}

TEST_CASE("apt transcript: BBD203 rack system", "[device][apt][transcript]")
{
    replay("apt_rack_bbd203.txt");
}

TEST_CASE("apt transcript: BBD203 brushless PMD parameters", "[device][apt][transcript]")
{
    replay("apt_bbd203_pmd.txt");
}

TEST_CASE("apt transcript: stepper cubes and the BSC203 rack", "[device][apt][transcript]")
{
    replay("apt_stepper.txt");
}

TEST_CASE("apt transcript: bad input", "[device][apt][transcript]")
{
    replay("apt_bad_input.txt");
}

TEST_CASE("apt transcript: faults at an ignored end of travel", "[device][apt][transcript]")
{
    replay("apt_faults.txt");
}

TEST_CASE("apt transcript: PRM1-Z8, DRV014, DDSM100 and S-curve moves", "[device][apt][transcript]")
{
    replay("apt_stages_scurve.txt");
}

TEST_CASE("apt transcript: two TDC001 devices on one world, set up inline, the second addressed as device 2", "[device][apt][transcript]")
{
    replay("apt_two_devices.txt");
}

TEST_CASE("apt transcript: TSC001 and KSC101 solenoid controllers", "[device][apt][transcript][solenoid]")
{
    replay("apt_solenoid.txt");
}

TEST_CASE("apt transcript: TPZ001 piezo driver, open loop", "[device][apt][transcript][piezo]")
{
    replay("apt_piezo_tpz001.txt");
}

TEST_CASE("apt transcript: TPZ001 waveform (LUT) output", "[device][apt][transcript][piezo][lut]")
{
    replay("apt_piezo_lut.txt");
}

TEST_CASE("apt transcript: TSG001 strain gauge reader on a TPZ001, closed loop", "[device][apt][transcript]")
{
    replay("apt_strain_gauge.txt");
}

TEST_CASE("apt transcript: BPC303 bays, maximum voltage, closed loop on one bay", "[device][apt][transcript][piezo]")
{
    replay("apt_piezo_bpc303.txt");
}

TEST_CASE("apt transcript: KDC101 at firmware issue-44.1", "[device][apt][transcript][firmware]")
{
    replay("apt_kdc101_issue44.txt");
}

TEST_CASE("apt transcript: KST101 at firmware issue-44.1", "[device][apt][transcript][firmware]")
{
    replay("apt_kst101_issue44.txt");
}

TEST_CASE("apt transcript: the later-issue motor messages at firmware issue-44.1", "[device][apt][transcript][firmware]")
{
    replay("apt_kcube_msgs_issue44.txt");
}

TEST_CASE("apt transcript: the later-issue motor messages at firmware issue-3 (ignored)",
          "[device][apt][transcript][firmware]")
{
    replay("apt_kcube_msgs_issue3.txt");
}

} // namespace test_apt_transcripts
