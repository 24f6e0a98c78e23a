// Golden transcripts: long sessions replayed byte for byte on a stepped clock.
//
// Format (tests/device/transcripts/*.txt), one item per line:
//   # comment             ignored, as are blank lines
//   > :GNC                bytes sent (a '\n' is appended)
//   < :N3                 one expected answer line, in order ("< " alone: nothing more)
//   ~ 250ms | ~ 3 ticks   advance the clock
//   @ config <path>       (before the first '>') run on the first device of this rig file,
//                         relative to the source tree, instead of the default rig's MCS
// After each '>' line, the answers the device gave must equal the '<' lines that follow;
// unprompted messages (asynchronous mode) appear before the answers of the next '>' line.
#include "mcs_harness.hpp"

#include "emulator/daemon/rig_families.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <memory>
#include <sstream>

namespace test_mcs_transcripts {

using rigsim::test::McsHarness;

namespace {

/// Replay `path` once; `keep`: on a clock that keeps its schedule, as the daemon's does.
void replay_on(const std::string& path, bool keep)
{
    INFO(path << (keep ? ", the clock keeping its schedule (models/clock.hpp)" : ""));
    std::ifstream in(path);
    REQUIRE(in);
    std::unique_ptr<McsHarness> harness;
    std::string line, pending_answer, expected;
    int number = 0, commands = 0;
    auto settle = [&](int at) {
        INFO(path << ":" << at);
        CHECK(pending_answer == expected);
        pending_answer.clear();
        expected.clear();
    };
    int last_command_line = 0;
    while (std::getline(in, line)) {
        ++number;
        if (line.empty() || line[0] == '#')
            continue;
        REQUIRE(line.size() >= 1);
        const char kind = line[0];
        const std::string rest = line.size() > 2 ? line.substr(2) : "";
        if (kind == '@') {
            REQUIRE(!harness);
            REQUIRE(rest.rfind("config ", 0) == 0);
            const auto rig = rigsim::load_rig_config(RIGSIM_SOURCE_DIR "/" + rest.substr(7));
            harness = std::make_unique<McsHarness>(rig.devices.at(0), rig.tick_hz);
            if (keep)
                harness->keep_schedule();
            continue;
        }
        if (!harness) {   // the default rig's MCS, as the e2e replay of the same file uses
            const auto rig = rigsim::default_rig_config();
            harness = std::make_unique<McsHarness>(rig.devices.at(0), rig.tick_hz);
            if (keep)
                harness->keep_schedule();
        }
        auto& h = *harness;
        if (kind == '>') {
            settle(last_command_line);
            pending_answer = h.send(rest + "\n");
            last_command_line = number;
            ++commands;
        } else if (kind == '<') {
            if (!rest.empty())
                expected += rest + "\n";
        } else if (kind == '~') {
            settle(last_command_line);
            std::istringstream s(rest);
            long long n = 0;
            std::string unit;
            s >> n >> unit;
            if (unit == "ms" || unit.empty())
                h.advance_ms(n);
            else if (unit == "ticks")
                h.advance_ticks(n);
            else
                FAIL(path << ":" << number << ": unknown unit " << unit);
        } else {
            FAIL(path << ":" << number << ": unknown line kind '" << kind << "'");
        }
    }
    settle(last_command_line);
    CHECK(commands > 0);
}

/// Replay `path` as the tests step the clock (every Tickable asked afresh at each call), then as
/// the daemon runs it (the schedule kept between announcements): the answers must be the same.
void replay(const std::string& path)
{
    replay_on(path, false);
    replay_on(path, true);
}

/// Every transcript in tests/device/transcripts/ is replayed by a test case below.

} // namespace

TEST_CASE("transcript: positioner slice session", "[device][mcs][transcript]")
{
    replay(RIGSIM_SOURCE_DIR "/tests/device/transcripts/mcs_positioner_slice.txt");
}

TEST_CASE("transcript: initialization", "[device][mcs][transcript]")
{
    replay(RIGSIM_SOURCE_DIR "/tests/device/transcripts/mcs_initialization.txt");
}

TEST_CASE("transcript: sensors and references", "[device][mcs][transcript]")
{
    replay(RIGSIM_SOURCE_DIR "/tests/device/transcripts/mcs_sensors_references.txt");
}

TEST_CASE("transcript: rotary", "[device][mcs][transcript]")
{
    replay(RIGSIM_SOURCE_DIR "/tests/device/transcripts/mcs_rotary.txt");
}

TEST_CASE("transcript: closed and open loop", "[device][mcs][transcript]")
{
    replay(RIGSIM_SOURCE_DIR "/tests/device/transcripts/mcs_closed_open_loop.txt");
}

TEST_CASE("transcript: events", "[device][mcs][transcript]")
{
    replay(RIGSIM_SOURCE_DIR "/tests/device/transcripts/mcs_events.txt");
}

TEST_CASE("transcript: end effectors", "[device][mcs][transcript]")
{
    replay(RIGSIM_SOURCE_DIR "/tests/device/transcripts/mcs_end_effectors.txt");
}

TEST_CASE("transcript: firmware generation 2.0.1", "[device][mcs][transcript][firmware]")
{
    replay(RIGSIM_SOURCE_DIR "/tests/device/transcripts/mcs_firmware_2.0.1.txt");
}

} // namespace test_mcs_transcripts
