#pragma once
// spdlog set-up: one stderr sink, one logger for the daemon ("rigsimd") and one per device,
// named after the device, each with its own level (--log-level LEVEL | NAME=LEVEL).
// Warnings are rate-limited per connection (rate_limited_sink.hpp).

#include <spdlog/logger.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace rigsim {

struct LogLevels {
    spdlog::level::level_enum global = spdlog::level::info;
    std::map<std::string, spdlog::level::level_enum, std::less<>> per_logger;
};

/// Apply one --log-level argument ("warn" or "mcs0=debug"); returns an error message.
std::optional<std::string> apply_log_level(std::string_view arg, LogLevels& levels);

/// The logger called `name`, created on first use with its configured level.
std::shared_ptr<spdlog::logger> make_logger(const std::string& name, const LogLevels& levels);

/// Write the summary lines of warnings still held back by the rate limit (at exit).
void flush_log_summaries();

} // namespace rigsim
