#pragma once
// What every route file of the control API shares: JSON answers, errors naming the field,
// and reading a request body or query.

#include "emulator/control/http_server.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <string_view>

namespace rigsim::control {

/// An error naming what was wrong; thrown while reading a request, answered by handle().
struct BadRequest {
    unsigned status = 400;
    std::string message;
};

/// `value` as compact JSON; bytes that are not UTF-8 become U+FFFD rather than an exception.
std::string dump(const nlohmann::json& value);
HttpReply ok(const nlohmann::json& body, unsigned status = 200);
HttpReply error(unsigned status, const std::string& message);

/// How deep a request body may nest (no route takes more than 2 levels).
inline constexpr int kMaxBodyDepth = 32;

/// The body as a JSON object (at most kMaxBodyDepth deep); an empty body is `{}` when `empty_ok`.
nlohmann::json parse_object(std::string_view text, bool empty_ok = false);
/// `key`'s value as an integer in lo..hi (a float with no fraction is refused too).
std::int64_t require_int(const nlohmann::json& body, const char* key, std::int64_t lo, std::int64_t hi);
/// `key`'s value as a number in lo..hi.
double require_number(const nlohmann::json& body, const char* key, double lo, double hi);
/// `key`'s value as a boolean.
bool require_bool(const nlohmann::json& body, const char* key);

/// The path of a request target, without its query string.
std::string_view path_of(std::string_view target);
/// `s` with its %XX escapes decoded (a path part: '+' stays '+').
std::string percent_decode(std::string_view s);
/// The query string's parameters (`?a=1&b=x`, percent-decoded); a repeated key keeps the last.
std::map<std::string, std::string> query_of(std::string_view target);

} // namespace rigsim::control
