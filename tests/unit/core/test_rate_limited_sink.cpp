// Log amplification (issue: 3 MB of bad input made 76 MB of log): warnings, and info lines that
// name a connection, are limited per logger and connection, the rest counted into one summary
// line per window.
#include "emulator/core/rate_limited_sink.hpp"

#include <catch2/catch.hpp>
#include <spdlog/details/log_msg.h>
#include <spdlog/sinks/base_sink.h>
#include <spdlog/details/null_mutex.h>

#include <string>
#include <vector>

namespace test_rate_limited_sink {

namespace {

using namespace std::chrono_literals;
using rigsim::RateLimitedSink;

/// Keeps what reaches it: "<logger>|<level>|<payload>".
class RecordingSink : public spdlog::sinks::base_sink<spdlog::details::null_mutex> {
public:
    std::vector<std::string> lines;

protected:
    void sink_it_(const spdlog::details::log_msg& msg) override
    {
        lines.push_back(std::string(msg.logger_name.data(), msg.logger_name.size()) + "|"
                        + std::to_string(static_cast<int>(msg.level)) + "|"
                        + std::string(msg.payload.data(), msg.payload.size()));
    }
    void flush_() override {}
};

struct Fixture {
    std::shared_ptr<RecordingSink> out = std::make_shared<RecordingSink>();
    RateLimitedSink::TimePoint now{};
    RateLimitedSink sink{out, 3, 1000ms, [this] { return now; }};

    void log(const char* logger, spdlog::level::level_enum level, const std::string& text)
    {
        sink.log(spdlog::details::log_msg(logger, level, text));
    }
};

} // namespace

TEST_CASE("rate-limited log: a flood of warnings from one connection becomes N lines and a count",
          "[unit][logging]")
{
    Fixture f;
    for (int i = 0; i < 1000; ++i)
        f.log("mcs0", spdlog::level::warn, "tcp 127.0.0.1:5000: \":FOO\": error 2");
    CHECK(f.out->lines.size() == 3);
    CHECK(f.sink.suppressed_total() == 997);
    // The window ends: the next message (any level, any logger) brings the summary first.
    f.now += 1000ms;
    f.log("rigsimd", spdlog::level::info, "something else");
    REQUIRE(f.out->lines.size() == 5);
    CHECK(f.out->lines[3]
          == "mcs0|3|tcp 127.0.0.1:5000: 997 more warning(s) suppressed in the last 1.0 s (at most 3 per 1000 ms are logged)");
    CHECK(f.out->lines[4] == "rigsimd|2|something else");
    // A new window logs again.
    f.log("mcs0", spdlog::level::warn, "tcp 127.0.0.1:5000: \":FOO\": error 2");
    CHECK(f.out->lines.size() == 6);
}

TEST_CASE("rate-limited log: connections, loggers and other levels are limited separately",
          "[unit][logging]")
{
    Fixture f;
    for (int i = 0; i < 10; ++i) {
        f.log("mcs0", spdlog::level::warn, "tcp 127.0.0.1:5000: bad");
        f.log("mcs0", spdlog::level::warn, "tcp 127.0.0.1:5001: bad");
        f.log("tdc001", spdlog::level::warn, "tcp 127.0.0.1:5000: bad");
        f.log("mcs0", spdlog::level::err, "tcp 127.0.0.1:5000: write failed");
        f.log("mcs0", spdlog::level::debug, "tcp 127.0.0.1:5000: \":GP0\"");
    }
    // 3 warnings per source, every error and debug line.
    CHECK(f.out->lines.size() == 3 * 3 + 10 + 10);
    CHECK(f.sink.suppressed_total() == 3 * 7);
}

TEST_CASE("rate-limited log: info lines naming a connection share its budget, the daemon's own pass",
          "[unit][logging]")
{
    Fixture f;
    // 3 MB of MOD_IDENTIFY once made 47 MB of info lines.
    for (int i = 0; i < 1000; ++i)
        f.log("tdc001", spdlog::level::info, "tcp 127.0.0.1:5000: MOD_IDENTIFY: front panel flashes");
    f.log("tdc001", spdlog::level::warn, "tcp 127.0.0.1:5000: bad");
    for (int i = 0; i < 5; ++i)
        f.log("rigsimd", spdlog::level::info, "rig running");   // no peer: every one
    CHECK(f.out->lines.size() == 3 + 5);
    CHECK(f.sink.suppressed_total() == 998);
    f.now += 1000ms;
    f.sink.flush();
    CHECK(f.out->lines.back()
          == "tdc001|3|tcp 127.0.0.1:5000: 1 more warning(s) and 997 more info line(s) suppressed in the last 1.0 s "
             "(at most 3 per 1000 ms are logged)");
    f.log("tdc001", spdlog::level::info, "tcp 127.0.0.1:5000: MOD_IDENTIFY: front panel flashes");
    f.log("tdc001", spdlog::level::info, "tcp 127.0.0.1:5000: MOD_IDENTIFY: front panel flashes");
    f.log("tdc001", spdlog::level::info, "tcp 127.0.0.1:5000: MOD_IDENTIFY: front panel flashes");
    f.log("tdc001", spdlog::level::info, "tcp 127.0.0.1:5000: MOD_IDENTIFY: front panel flashes");
    f.sink.flush_summaries();
    CHECK(f.out->lines.back()
          == "tdc001|3|tcp 127.0.0.1:5000: 1 more info line(s) suppressed in the last 0.0 s (at most 3 per 1000 ms are logged)");
}

TEST_CASE("rate-limited log: held-back counts are written at exit and by a periodic flush",
          "[unit][logging]")
{
    Fixture f;
    for (int i = 0; i < 5; ++i)
        f.log("mcs0", spdlog::level::warn, "pty /tmp/rigsim/mcs0: bad");
    CHECK(f.out->lines.size() == 3);
    f.sink.flush();   // window not over: nothing yet
    CHECK(f.out->lines.size() == 3);
    f.now += 1500ms;
    f.sink.flush();
    REQUIRE(f.out->lines.size() == 4);
    CHECK(f.out->lines[3].find("pty /tmp/rigsim/mcs0: 2 more warning(s) suppressed in the last 1.5 s") != std::string::npos);

    f.log("mcs0", spdlog::level::warn, "no peer in this one");
    f.log("mcs0", spdlog::level::warn, "no peer in this one");
    f.log("mcs0", spdlog::level::warn, "no peer in this one");
    f.log("mcs0", spdlog::level::warn, "no peer in this one");
    f.sink.flush_summaries();
    CHECK(f.out->lines.back() == "mcs0|3|1 more warning(s) suppressed in the last 0.0 s (at most 3 per 1000 ms are logged)");
}

TEST_CASE("rate-limited log: the peer is the text before the first \": \"", "[unit][logging]")
{
    CHECK(rigsim::log_peer("tcp 127.0.0.1:5000: \":FOO\": error 2") == "tcp 127.0.0.1:5000");
    CHECK(rigsim::log_peer("pty /tmp/x: closed") == "pty /tmp/x");
    CHECK(rigsim::log_peer("no separator") == "");
}

} // namespace test_rate_limited_sink
