// --log-level parsing: LEVEL or NAME=LEVEL, the names the --help text documents.
#include "emulator/core/logging.hpp"

#include <catch2/catch.hpp>

namespace test_logging {

using rigsim::LogLevels;
using rigsim::apply_log_level;

TEST_CASE("log levels: every documented level is accepted", "[unit][logging]")
{
    const std::pair<const char*, spdlog::level::level_enum> levels[] = {
        {"trace", spdlog::level::trace}, {"debug", spdlog::level::debug},
        {"info", spdlog::level::info},   {"warn", spdlog::level::warn},
        {"warning", spdlog::level::warn}, {"error", spdlog::level::err},
        {"critical", spdlog::level::critical}, {"off", spdlog::level::off},
    };
    for (const auto& [name, level] : levels) {
        LogLevels l;
        INFO(name);
        CHECK_FALSE(apply_log_level(name, l));
        CHECK(l.global == level);
    }
}

TEST_CASE("log levels: NAME=LEVEL sets one logger and bad values are named", "[unit][logging]")
{
    LogLevels l;
    CHECK_FALSE(apply_log_level("mcs0=debug", l));
    CHECK_FALSE(apply_log_level("rigsimd=warn", l));
    CHECK(l.global == spdlog::level::info);
    CHECK(l.per_logger.at("mcs0") == spdlog::level::debug);
    CHECK(l.per_logger.at("rigsimd") == spdlog::level::warn);
    CHECK(*apply_log_level("loud", l)
          == "--log-level: unknown level \"loud\" (expected trace, debug, info, warn, error, critical or off)");
    CHECK(*apply_log_level("=debug", l) == "--log-level: expected LEVEL or NAME=LEVEL, got \"=debug\"");
}

} // namespace test_logging
