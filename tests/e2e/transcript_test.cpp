// Golden transcripts replayed through the real rigsimd, once over TCP and once over its pty.
// The files are those of the [device] transcript test (tests/device/transcripts/*.txt, format
// in tests/device/mcs/test_mcs_transcripts.cpp). The daemon starts with its clock paused
// (--paused) and the replay steps it through the control API, so every answer is compared
// exactly, as on the device test's stepped clock. On the wall clock a state shorter than a
// scheduling hiccup (the MCS hold after MPR: 100 ms of wall time at --time-scale 10) could
// not be observed under load. Running on the wall clock is covered by "APT over TCP: info,
// home, move, jog, status updates" and "APT over the pty: ..." (apt_test.cpp, moves and
// status updates at --time-scale 100) and "lifecycle: --time-scale 10 is accepted and the
// clock runs: a move completes".
//
// Replay rules:
//  1. '> CMD' sends CMD + '\n'; the '<' lines after it are read back in order, each within
//     kAnswerTimeout, and must equal them. A command with no '<' line reads nothing: a stray
//     answer then fails the next command.
//  2. '~ N ms' / '~ N ticks' sends nothing to the device: the clock advances by that much
//     through POST /api/clock {"step_ms": N} before the next command (ticks count at the
//     rig's tick_hz and must come to whole ms; advances with no command between them add
//     up). The clock stands still otherwise, so no answer needs a range or a relaxed status:
//     the wall-clock replay's position ranges and "any status" matches are gone.
//  3. '@ config PATH' runs the daemon with --config <source tree>/PATH and replays on the
//     rig's first device; without it, on the default rig's first device.
// A lost answer stops the replay: the answers after it could no longer be attributed.

#include <catch2/catch.hpp>

#include <memory>
#include <optional>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "control_support.hpp"
#include "e2e_support.hpp"

namespace transcript_test {

#ifndef RIGSIM_SOURCE_DIR
#error "RIGSIM_SOURCE_DIR is set by tests/e2e/CMakeLists.txt"
#endif

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {

/// The tick rate of a rig config that does not set tick_hz (and of the default rig).
constexpr long long kDefaultTickHz = 1000;

/// The '~' lines since the previous command.
struct Advance {
    long long ms = 0;
    long long ticks = 0;
};

struct Step {
    int line = 0;                          ///< transcript line of the '>'
    std::string command;                   ///< as sent, without '\n'
    std::vector<std::string> answers;      ///< as in the transcript, without '\n'
    std::optional<Advance> advance;        ///< the clock advance before the command (rule 2)
};

struct Transcript {
    std::string name;          ///< for messages: path or label
    std::string config_path;   ///< relative to the source tree; empty: the default rig
    std::vector<Step> steps;
};

/// Parses a transcript; throws std::runtime_error naming `name:line` on a malformed line.
Transcript parse_transcript(const std::string& text, const std::string& name)
{
    Transcript t;
    t.name = name;
    std::istringstream in(text);
    std::string line;
    int number = 0;
    std::optional<Advance> advance;
    auto fail = [&](int at, const std::string& why) {
        throw std::runtime_error(name + ":" + std::to_string(at) + ": " + why);
    };
    while (std::getline(in, line)) {
        ++number;
        if (line.empty() || line[0] == '#')
            continue;
        const char kind = line[0];
        const std::string rest = line.size() > 2 ? line.substr(2) : "";
        if (kind == '@') {
            if (!t.steps.empty() || !t.config_path.empty())
                fail(number, "'@ config' must come once, before the first command");
            if (rest.rfind("config ", 0) != 0 || rest.size() <= 7)
                fail(number, "expected '@ config <path>'");
            t.config_path = rest.substr(7);
        } else if (kind == '>') {
            t.steps.push_back(Step{number, rest, {}, advance});
            advance.reset();
        } else if (kind == '<') {
            if (t.steps.empty())
                fail(number, "an answer before any command");
            if (!rest.empty())
                t.steps.back().answers.push_back(rest);
        } else if (kind == '~') {
            std::istringstream s(rest);
            long long n = 0;
            std::string unit;
            if (!(s >> n) || n < 0)
                fail(number, "expected '~ <N>ms' or '~ <N> ticks'");
            s >> unit;
            if (!advance)
                advance.emplace();
            if (unit == "ms" || unit.empty())
                advance->ms += n;
            else if (unit == "ticks")
                advance->ticks += n;
            else
                fail(number, "unknown unit '" + unit + "'");
        } else {
            fail(number, std::string("unknown line kind '") + kind + "'");
        }
    }
    if (t.steps.empty())
        fail(number, "no command");
    return t;
}

Transcript load_transcript(const std::string& relative_path)
{
    const std::string path = std::string(RIGSIM_SOURCE_DIR) + "/" + relative_path;
    const auto text = read_file(path);
    if (!text)
        throw std::runtime_error("cannot read " + path);
    return parse_transcript(*text, relative_path);
}

std::string join(const std::vector<std::string>& items)
{
    std::string out;
    for (const auto& item : items)
        out += (out.empty() ? "" : " | ") + item;
    return out.empty() ? "<nothing>" : out;
}

/// The answers to one sending of a step's command.
struct Exchange {
    std::vector<std::string> answers;   ///< without their '\n'
    bool lost = false;                  ///< an expected answer did not come
};

Exchange exchange(LineClient& client, const Step& step)
{
    Exchange e;
    client.send(step.command + "\n");
    for (std::size_t i = 0; i < step.answers.size(); ++i) {
        auto line = client.read_line(kAnswerTimeout);
        if (!line) {
            e.lost = true;
            break;
        }
        if (!line->empty() && line->back() == '\n')
            line->pop_back();
        e.answers.push_back(std::move(*line));
    }
    return e;
}

/// The clock time of `advance` in whole ms, or nullopt if its ticks do not make whole ms.
std::optional<long long> advance_ms(const Advance& advance, long long tick_hz)
{
    if (advance.ticks * 1000 % tick_hz != 0)
        return std::nullopt;
    return advance.ms + advance.ticks * 1000 / tick_hz;
}

struct ReplayResult {
    std::size_t steps_done = 0;          ///< steps replayed to the end (matched or not)
    std::vector<std::string> failures;   ///< one line per failed step
};

/// Replays `t` on `client`, stepping the paused clock on `api` (rules at the top of the
/// file); returns what did not match.
ReplayResult replay(const Transcript& t, LineClient& client, LineClient& api, long long tick_hz)
{
    ReplayResult result;
    for (const auto& step : t.steps) {
        const std::string where = t.name + ":" + std::to_string(step.line) + " " + step.command;
        if (step.advance) {
            const auto ms = advance_ms(*step.advance, tick_hz);
            if (!ms) {
                result.failures.push_back(where + ": the advance before it is no whole number of ms at " +
                                          std::to_string(tick_hz) + " Hz; replay stopped");
                return result;
            }
            const auto stepped = http(api, "POST", "/api/clock", "{\"step_ms\": " + std::to_string(*ms) + "}");
            if (stepped.status != 200) {
                result.failures.push_back(where + ": step_ms " + std::to_string(*ms) + " answered " +
                                          std::to_string(stepped.status) + " " + stepped.body +
                                          "; replay stopped");
                return result;
            }
        }
        const Exchange got = exchange(client, step);
        if (got.lost) {
            result.failures.push_back(where + ": expected " + join(step.answers) + ", got only " +
                                      join(got.answers) + " (then nothing within " +
                                      std::to_string(kAnswerTimeout.count()) + " ms); replay stopped");
            return result;
        }
        if (got.answers != step.answers)
            result.failures.push_back(where + ": expected " + join(step.answers) + ", got " +
                                      join(got.answers));
        ++result.steps_done;
    }
    return result;
}

enum class Transport { Tcp, Pty };

/// The rig's tick_hz from a config file text, or the default.
long long tick_hz_of(const std::string& config_text)
{
    std::smatch m;
    static const std::regex kTickHz("\"tick_hz\"\\s*:\\s*([0-9]+)");
    return std::regex_search(config_text, m, kTickHz) ? std::stoll(m[1]) : kDefaultTickHz;
}

/// Runs `t` on a fresh daemon, its clock paused, over `transport`; the daemon's log is added
/// to any failure.
ReplayResult replay_on_daemon(const Transcript& t, Transport transport)
{
    Daemon::Options options;
    long long tick_hz = kDefaultTickHz;
    if (!t.config_path.empty()) {
        options.config_path = std::string(RIGSIM_SOURCE_DIR) + "/" + t.config_path;
        const auto config = read_file(options.config_path);
        if (!config)
            throw std::runtime_error("cannot read " + options.config_path);
        tick_hz = tick_hz_of(*config);
    }
    options.extra_args = {"--paused", "--control", "127.0.0.1:0"};
    Daemon daemon(options);
    TcpClient api(control_endpoint(daemon));
    // The first "name" in the endpoints file is the first device's (rule 3).
    const auto first_device = json_string_value(daemon.endpoints_json(), "name");
    if (!first_device)
        throw std::runtime_error("no device in endpoints file: " + daemon.endpoints_json());
    const Endpoint ep = daemon.endpoint(*first_device);

    std::unique_ptr<LineClient> client;
    if (transport == Transport::Tcp)
        client = std::make_unique<TcpClient>(ep);
    else
        client = std::make_unique<PtyClient>(ep.pty);
    auto result = replay(t, *client, api, tick_hz);
    if (!result.failures.empty())
        result.failures.push_back("rigsimd log:\n" + daemon.log());
    return result;
}

void check_replayed(const Transcript& t, const ReplayResult& result)
{
    for (const auto& f : result.failures)
        FAIL_CHECK(f);
    CHECK(result.steps_done == t.steps.size());
}

constexpr const char* kPositionerSlice = "tests/device/transcripts/mcs_positioner_slice.txt";

} // namespace

TEST_CASE("transcript over TCP: positioner slice session", "[e2e][transcript]")
{
    const auto t = load_transcript(kPositionerSlice);
    check_replayed(t, replay_on_daemon(t, Transport::Tcp));
}

TEST_CASE("transcript over the pty: positioner slice session", "[e2e][transcript]")
{
    const auto t = load_transcript(kPositionerSlice);
    check_replayed(t, replay_on_daemon(t, Transport::Pty));
}

TEST_CASE("transcript replay: every wrong answer is reported at its line, the replay goes on",
          "[e2e][transcript]")
{
    // The slice with four answers broken: an exact answer, a status right after a move
    // started, a status after a clock step, and a position mid-move that the wall-clock
    // replay's ranges accepted (it lies between this and the next expected position).
    std::string text =
        read_file(std::string(RIGSIM_SOURCE_DIR) + "/" + kPositionerSlice).value_or("");
    auto mutate = [&](const std::string& from, const std::string& to) {
        const auto at = text.find(from);
        REQUIRE(at != std::string::npos);
        text.replace(at, from.size(), to);
    };
    mutate("< :ID3118100\n", "< :ID3118101\n");
    mutate("> :GS0\n< :S0,4\n", "> :GS0\n< :S1,4\n");
    mutate("~ 100ms\n> :GP0\n< :P0,1000000\n", "~ 100ms\n> :GP0\n< :P0,1000001\n");
    mutate("~ 100ms\n> :GS0\n< :S0,0\n", "~ 100ms\n> :GS0\n< :S0,3\n");
    const auto t = parse_transcript(text, "mutated slice");
    const auto result = replay_on_daemon(t, Transport::Tcp);

    CHECK(result.steps_done == t.steps.size());
    REQUIRE(result.failures.size() == 5);   // four mismatches and the daemon's log
    INFO(join(result.failures));
    CHECK(result.failures[0].find(":GSI: expected :ID3118101, got :ID3118100") != std::string::npos);
    CHECK(result.failures[1].find(":GS0: expected :S1,4, got :S0,4") != std::string::npos);
    CHECK(result.failures[2].find(":GP0: expected :P0,1000001, got :P0,1000000") != std::string::npos);
    CHECK(result.failures[3].find(":GS0: expected :S0,3, got :S0,0") != std::string::npos);
}

} // namespace transcript_test
