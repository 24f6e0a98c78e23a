// Golden transcripts replayed through the real rigsimd, once over TCP and once over its pty.
// The files are those of the [device] transcript test (tests/device/transcripts/*.txt, format
// in tests/device/mcs/test_mcs_transcripts.cpp), but here the daemon's clock runs on the wall
// clock, scaled by kTimeScale, instead of being stepped. Nothing sleeps for a fixed time.
//
// Replay rules:
//  1. '> CMD' sends CMD + '\n'; the '<' lines after it are read back in order, each within
//     kAnswerTimeout, and must equal them unless a rule below relaxes that. A command with
//     no '<' line reads nothing: a stray answer then fails the next command.
//  2. '~ N ms' / '~ N ticks' sends nothing (ticks count at the rig's tick_hz; advances with
//     no command between them add up). The next '>' is a checkpoint: it is sent again and
//     again until all its answers match, within (N ms / kTimeScale) x 3 + 2 s. Since it may
//     be sent many times it must be a query (':G...') with at least one '<' line; the parser
//     rejects anything else.
//  3. The daemon's clock never lags the transcript's at a checkpoint (rule 2 waits for it)
//     but runs on in between, so it may be ahead. At a checkpoint, an expected position
//     ':P<ch>,<n>' therefore also matches ':P<ch>,<m>' with m between n and the next position
//     the transcript expects for channel <ch>, both inclusive: a sample taken mid-move cannot
//     be hit exactly, but the channel must have got at least that far and no further than
//     where it is said to be next. Without a later position for <ch>, it must equal n.
//  4. Outside checkpoints, an expected status ':S<ch>,<code>' matches any ':S<ch>,<m>': at
//     kTimeScale a move the transcript sees under way (':S0,4' right after MPA) may already
//     have ended. The checkpoints pin states down.
//  5. '@ config PATH' runs the daemon with --config <source tree>/PATH and replays on the
//     rig's first device; without it, on the default rig's first device.
// A lost answer stops the replay: the answers after it could no longer be attributed.

#include <catch2/catch.hpp>

#include <algorithm>
#include <memory>
#include <optional>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "e2e_support.hpp"

#ifndef RIGSIM_SOURCE_DIR
#error "RIGSIM_SOURCE_DIR is set by tests/e2e/CMakeLists.txt"
#endif

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {

/// Physics runs this many times faster than wall time (--time-scale).
constexpr int kTimeScale = 10;
/// The tick rate of a rig config that does not set tick_hz (and of the default rig).
constexpr long long kDefaultTickHz = 1000;
/// The slack added to every checkpoint's deadline (rule 2).
constexpr Millis kCheckpointSlack{2000};

const std::regex kPositionAnswer(":P([0-9]+),(-?[0-9]+)");
const std::regex kStatusAnswer(":S([0-9]+),([0-9]+)");

/// How one answer line is compared (replay rules 1, 3 and 4).
enum class Match { Exact, PositionBetween, AnyStatusOfChannel };

struct ExpectedAnswer {
    std::string text;        ///< as in the transcript, without '\n'
    Match match = Match::Exact;
    std::string channel;     ///< for the relaxed matches, as written
    long long low_nm = 0;    ///< PositionBetween bounds, inclusive
    long long high_nm = 0;
};

/// The '~' lines since the previous command.
struct Advance {
    long long ms = 0;
    long long ticks = 0;
};

struct Step {
    int line = 0;                          ///< transcript line of the '>'
    std::string command;                   ///< as sent, without '\n'
    std::vector<ExpectedAnswer> answers;
    std::optional<Advance> checkpoint;     ///< set if the step follows an advance (rule 2)
};

struct Transcript {
    std::string name;          ///< for messages: path or label
    std::string config_path;   ///< relative to the source tree; empty: the default rig
    std::vector<Step> steps;
};

/// Rule 3 and 4: relax the answers whose exact value depends on when they were sampled.
void relax_time_dependent_answers(std::vector<Step>& steps)
{
    for (std::size_t i = 0; i < steps.size(); ++i) {
        for (std::size_t j = 0; j < steps[i].answers.size(); ++j) {
            auto& a = steps[i].answers[j];
            std::smatch m;
            if (steps[i].checkpoint && std::regex_match(a.text, m, kPositionAnswer)) {
                const std::string channel = m[1];
                const long long here = std::stoll(m[2]);
                // The next expected position of the same channel, later in this step or after.
                std::optional<long long> next;
                for (std::size_t k = i, l = j + 1; k < steps.size() && !next; ++k, l = 0) {
                    for (; l < steps[k].answers.size() && !next; ++l) {
                        std::smatch n;
                        if (std::regex_match(steps[k].answers[l].text, n, kPositionAnswer) &&
                            n[1] == channel)
                            next = std::stoll(n[2]);
                    }
                }
                a.match = Match::PositionBetween;
                a.channel = channel;
                a.low_nm = std::min(here, next.value_or(here));
                a.high_nm = std::max(here, next.value_or(here));
            } else if (!steps[i].checkpoint && std::regex_match(a.text, m, kStatusAnswer)) {
                a.match = Match::AnyStatusOfChannel;
                a.channel = m[1];
            }
        }
    }
}

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
            if (!rest.empty()) {
                ExpectedAnswer answer;
                answer.text = rest;
                t.steps.back().answers.push_back(answer);
            }
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
    for (const auto& step : t.steps) {
        if (!step.checkpoint)
            continue;
        if (step.command.rfind(":G", 0) != 0)
            fail(step.line, "a command after '~' may be sent repeatedly, so it must be a query "
                            "(':G...'), not '" + step.command + "'");
        if (step.answers.empty())
            fail(step.line, "a command after '~' needs an expected answer to wait for");
    }
    relax_time_dependent_answers(t.steps);
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

bool matches(const ExpectedAnswer& expected, const std::string& answer)
{
    switch (expected.match) {
    case Match::Exact:
        return answer == expected.text;
    case Match::PositionBetween: {
        std::smatch m;
        if (!std::regex_match(answer, m, kPositionAnswer) || m[1] != expected.channel)
            return false;
        const long long at = std::stoll(m[2]);
        return at >= expected.low_nm && at <= expected.high_nm;
    }
    case Match::AnyStatusOfChannel: {
        std::smatch m;
        return std::regex_match(answer, m, kStatusAnswer) && m[1] == expected.channel;
    }
    }
    return false;
}

std::string describe(const ExpectedAnswer& expected)
{
    switch (expected.match) {
    case Match::Exact:
        return expected.text;
    case Match::PositionBetween:
        return ":P" + expected.channel + ",[" + std::to_string(expected.low_nm) + ".." +
               std::to_string(expected.high_nm) + "]";
    case Match::AnyStatusOfChannel:
        return ":S" + expected.channel + ",<any>";
    }
    return expected.text;
}

template <typename T, typename F>
std::string join(const std::vector<T>& items, F&& show)
{
    std::string out;
    for (const auto& item : items)
        out += (out.empty() ? "" : " | ") + show(item);
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

bool all_match(const Step& step, const Exchange& e)
{
    if (e.lost || e.answers.size() != step.answers.size())
        return false;
    for (std::size_t i = 0; i < e.answers.size(); ++i)
        if (!matches(step.answers[i], e.answers[i]))
            return false;
    return true;
}

struct ReplayResult {
    std::size_t steps_done = 0;          ///< steps replayed to the end (matched or not)
    std::vector<std::string> failures;   ///< one line per failed step
};

/// Replays `t` on `client` (rules at the top of the file); returns what did not match.
ReplayResult replay(const Transcript& t, LineClient& client, long long tick_hz)
{
    ReplayResult result;
    for (const auto& step : t.steps) {
        const std::string where = t.name + ":" + std::to_string(step.line) + " " + step.command;
        const auto expected = join(step.answers, describe);
        Exchange last;
        int attempts = 0;
        bool ok = false;
        Millis deadline{0};
        if (!step.checkpoint) {
            last = exchange(client, step);
            attempts = 1;
            ok = all_match(step, last);
        } else {
            const double advance_ms = static_cast<double>(step.checkpoint->ms) +
                                      static_cast<double>(step.checkpoint->ticks) * 1000.0 /
                                          static_cast<double>(tick_hz);
            deadline = Millis{static_cast<long long>(advance_ms / kTimeScale * 3.0)} +
                       kCheckpointSlack;
            wait_until(
                [&] {
                    last = exchange(client, step);
                    ++attempts;
                    ok = all_match(step, last);
                    return ok || last.lost;
                },
                deadline);
        }
        const auto got = join(last.answers, [](const std::string& s) { return s; });
        if (last.lost) {
            result.failures.push_back(where + ": expected " + expected + ", got only " + got +
                                      " (then nothing within " +
                                      std::to_string(kAnswerTimeout.count()) +
                                      " ms); replay stopped");
            return result;
        }
        if (!ok) {
            std::string failure = where + ": expected " + expected + ", got " + got;
            if (step.checkpoint)
                failure += " (last of " + std::to_string(attempts) + " attempts within " +
                           std::to_string(deadline.count()) + " ms)";
            result.failures.push_back(failure);
        }
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

/// Runs `t` on a fresh daemon over `transport`; the daemon's log is added to any failure.
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
    options.extra_args = {"--time-scale", std::to_string(kTimeScale)};
    Daemon daemon(options);
    // The first "name" in the endpoints file is the first device's (rule 5).
    const auto first_device = json_string_value(daemon.endpoints_json(), "name");
    if (!first_device)
        throw std::runtime_error("no device in endpoints file: " + daemon.endpoints_json());
    const Endpoint ep = daemon.endpoint(*first_device);

    std::unique_ptr<LineClient> client;
    if (transport == Transport::Tcp)
        client = std::make_unique<TcpClient>(ep);
    else
        client = std::make_unique<PtyClient>(ep.pty);
    auto result = replay(t, *client, tick_hz);
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

TEST_CASE("transcript replay: wrong answers are reported despite the relaxed rules",
          "[e2e][transcript]")
{
    // The slice with three answers broken, one per rule that decides them: an exact answer
    // (rule 1), a status at a checkpoint (rule 2, so it costs that checkpoint's deadline) and
    // a status outside checkpoints of the wrong channel (rule 4).
    std::string text =
        read_file(std::string(RIGSIM_SOURCE_DIR) + "/" + kPositionerSlice).value_or("");
    auto mutate = [&](const std::string& from, const std::string& to) {
        const auto at = text.find(from);
        REQUIRE(at != std::string::npos);
        text.replace(at, from.size(), to);
    };
    mutate("< :ID3118100\n", "< :ID3118101\n");
    mutate("> :GS0\n< :S0,4\n", "> :GS0\n< :S1,4\n");
    mutate("~ 100ms\n> :GS0\n< :S0,0\n", "~ 100ms\n> :GS0\n< :S0,3\n");
    const auto t = parse_transcript(text, "mutated slice");
    const auto result = replay_on_daemon(t, Transport::Tcp);

    CHECK(result.steps_done == t.steps.size());
    REQUIRE(result.failures.size() == 4);   // three mismatches and the daemon's log
    INFO(join(result.failures, [](const std::string& s) { return s; }));
    CHECK(result.failures[0].find(":GSI: expected :ID3118101, got :ID3118100") !=
          std::string::npos);
    CHECK(result.failures[1].find(":GS0: expected :S1,<any>, got :S0,") != std::string::npos);
    CHECK(result.failures[2].find(":GS0: expected :S0,3, got :S0,0 (last of") !=
          std::string::npos);
}
