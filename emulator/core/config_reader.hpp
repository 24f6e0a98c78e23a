#pragma once
// Reading a rig's JSON: the checks every loader makes (keys, types, ranges) and the one error
// format `<source>: <pointer>: <what>`, shared by the generic loader and the family sections.

#include "emulator/core/rig_config.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace rigsim {

/// `parent` extended by an object key, escaped as RFC 6901 says (`~` -> `~0`, `/` -> `~1`).
std::string pointer_to(const std::string& parent, std::string_view key);
/// `parent` extended by an array index.
std::string pointer_to(const std::string& parent, std::size_t index);

/// `text` cut to a sane length for a message (on a UTF-8 boundary), marked as cut.
std::string cut(std::string text);
/// `value` as compact JSON, cut to a sane length; never throws on odd UTF-8.
std::string dump(const nlohmann::json& value);
/// `s` as a JSON string literal (quoted, escaped).
std::string quote(std::string_view s);
/// A value for "got ..." in a message: scalars as JSON, containers by kind and size.
std::string describe(const nlohmann::json& value);

/// Longest name of a device, frame or tool point.
constexpr std::size_t kMaxNameLength = 64;
/// Whether `value` is a name: a string of 1..kMaxNameLength characters of [A-Za-z0-9_.-] (safe in
/// a file name, a logger name and a URL path segment).
bool is_name(const nlohmann::json& value);

/// Throw the one error format: `<source>: <pointer>: <what>`; the root shows as "/".
[[noreturn]] void fail(std::string_view source, const std::string& pointer, const std::string& what);

/// The checks of one rig text, whose errors name `source`.
class ConfigReader {
public:
    explicit ConfigReader(std::string_view source) : source_(source) {}

    /// Throw a ConfigError at `pointer`.
    [[noreturn]] void fail(const std::string& pointer, const std::string& what) const;

    /// `value` must be an object holding no key outside `allowed`.
    template <std::size_t N>
    void check_keys(const nlohmann::json& value, const std::string& pointer,
                    const std::array<std::string_view, N>& allowed) const
    {
        check_keys(value, pointer, allowed.data(), N);
    }
    /// `value` must be an object holding no key outside allowed[0..count).
    void check_keys(const nlohmann::json& value, const std::string& pointer, const std::string_view* allowed,
                    std::size_t count) const;

    /// The value of an optional key, or nullptr.
    static const nlohmann::json* find(const nlohmann::json& object, std::string_view key);
    /// The value of a required key; the error names the missing key's pointer.
    const nlohmann::json& require(const nlohmann::json& object, const std::string& pointer,
                                  std::string_view key) const;
    /// An integer in min..max; floats and booleans are type errors. `note` follows the
    /// range in the message.
    std::int64_t get_int(const nlohmann::json& v, const std::string& pointer, std::int64_t min, std::int64_t max,
                         std::string_view note = {}) const;
    /// A non-empty string; `expected` completes "expected ..." in the error.
    const std::string& get_string(const nlohmann::json& v, const std::string& pointer,
                                  std::string_view expected = "a non-empty string") const;

private:
    std::string_view source_;
};

} // namespace rigsim
