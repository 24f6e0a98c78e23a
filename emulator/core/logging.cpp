#include "emulator/core/logging.hpp"

#include "emulator/core/device.hpp"

#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

namespace rigsim {
namespace {

std::optional<spdlog::level::level_enum> parse_level(std::string_view s)
{
    for (int l = spdlog::level::trace; l < spdlog::level::n_levels; ++l) {
        const auto level = static_cast<spdlog::level::level_enum>(l);
        const auto name = spdlog::level::to_string_view(level);
        if (s == std::string_view(name.data(), name.size()))
            return level;
    }
    if (s == "warn")   // spdlog spells it "warning"; the flag documents "warn"
        return spdlog::level::warn;
    return std::nullopt;
}

} // namespace

std::optional<std::string> apply_log_level(std::string_view arg, LogLevels& levels)
{
    const auto eq = arg.find('=');
    const auto level_text = eq == std::string_view::npos ? arg : arg.substr(eq + 1);
    const auto level = parse_level(level_text);
    if (!level)
        return "--log-level: unknown level \"" + std::string(level_text)
            + "\" (expected trace, debug, info, warn, error, critical or off)";
    if (eq == std::string_view::npos) {
        levels.global = *level;
    } else {
        if (eq == 0)
            return "--log-level: expected LEVEL or NAME=LEVEL, got \"" + std::string(arg) + "\"";
        levels.per_logger[std::string(arg.substr(0, eq))] = *level;
    }
    return std::nullopt;
}

std::shared_ptr<spdlog::logger> make_logger(const std::string& name, const LogLevels& levels)
{
    if (auto existing = spdlog::get(name))
        return existing;
    // _mt: the state file's writer thread logs too (StateStore).
    static const auto sink = std::make_shared<spdlog::sinks::stderr_sink_mt>();
    auto logger = std::make_shared<spdlog::logger>(name, sink);
    logger->set_pattern("%Y-%m-%d %H:%M:%S.%e %^%-5l%$ [%n] %v");
    const auto it = levels.per_logger.find(name);
    logger->set_level(it != levels.per_logger.end() ? it->second : levels.global);
    logger->flush_on(spdlog::level::warn);
    spdlog::register_logger(logger);
    return logger;
}

std::string printable(std::string_view bytes, std::size_t max)
{
    static constexpr char kHex[] = "0123456789abcdef";
    std::string s;
    const auto n = std::min(bytes.size(), max);
    for (std::size_t i = 0; i < n; ++i) {
        const auto c = static_cast<unsigned char>(bytes[i]);
        if (c >= 0x20 && c < 0x7f && c != '\\' && c != '"') {
            s += static_cast<char>(c);
        } else {
            s += "\\x";
            s += kHex[c >> 4];
            s += kHex[c & 0xf];
        }
    }
    if (bytes.size() > max)
        s += "...(" + std::to_string(bytes.size()) + " bytes)";
    return s;
}

} // namespace rigsim
