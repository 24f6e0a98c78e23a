#include "emulator/control/json_reply.hpp"

#include "emulator/core/json_text.hpp"

#include <cmath>

namespace rigsim::control {

using nlohmann::json;

std::string dump(const json& value)
{
    return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

HttpReply ok(const json& body, unsigned status)
{
    return HttpReply{status, dump(body) + "\n", {}, {}, {}};
}

HttpReply error(unsigned status, const std::string& message)
{
    return HttpReply{status, dump(json{{"error", message}}) + "\n", {}, {}, {}};
}

json parse_object(std::string_view text, bool empty_ok)
{
    if (empty_ok && text.find_first_not_of(" \t\r\n") == std::string_view::npos)
        return json::object();
    json body;
    // Copying and printing a value recurse: a 64 KiB body of nested arrays would take them
    // 32,000 levels deep. A key twice in one object would keep only its last value.
    try {
        body = parse_json_text(text, JsonTextLimits{kMaxBodyDepth, true});
    } catch (const JsonTextError& e) {
        switch (e.kind) {
        case JsonTextError::Kind::Syntax:
            throw BadRequest{400, "body: expected a JSON object, got invalid JSON (at byte " + std::to_string(e.byte) + ")"};
        case JsonTextError::Kind::NumberOverflow:
            throw BadRequest{400, "body: expected a JSON object, got a number too large for a double"};
        case JsonTextError::Kind::DuplicateKey:
            throw BadRequest{400, "body" + e.pointer + ": " + e.what()};
        case JsonTextError::Kind::TooDeep:
            throw BadRequest{400, "body: " + std::string(e.what())};
        }
        throw;
    }
    if (!body.is_object())
        throw BadRequest{400, "body: expected a JSON object, got " + std::string(body.type_name())};
    return body;
}

std::int64_t require_int(const json& body, const char* key, std::int64_t lo, std::int64_t hi)
{
    const auto& v = body.at(key);
    const bool integer = v.is_number_integer() || v.is_number_unsigned();
    const bool too_big = integer && v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(hi);
    if (!integer || too_big || v.get<std::int64_t>() < lo || v.get<std::int64_t>() > hi)
        throw BadRequest{400, std::string("\"") + key + "\": expected an integer " + std::to_string(lo) + ".."
                                  + std::to_string(hi) + ", got " + dump(v)};
    return v.get<std::int64_t>();
}

double require_number(const json& body, const char* key, double lo, double hi)
{
    const auto& v = body.at(key);
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < lo || v.get<double>() > hi)
        throw BadRequest{400, std::string("\"") + key + "\": expected a number " + dump(json(lo)) + ".."
                                  + dump(json(hi)) + ", got " + dump(v)};
    return v.get<double>();
}

bool require_bool(const json& body, const char* key)
{
    const auto& v = body.at(key);
    if (!v.is_boolean())
        throw BadRequest{400, std::string("\"") + key + "\": expected true or false, got " + dump(v)};
    return v.get<bool>();
}

std::string_view path_of(std::string_view target)
{
    return target.substr(0, target.find('?'));
}

namespace {

std::string decode(std::string_view s, bool form)
{
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        const auto hex = [](char c) -> int {
            if (c >= '0' && c <= '9')
                return c - '0';
            if (c >= 'a' && c <= 'f')
                return c - 'a' + 10;
            if (c >= 'A' && c <= 'F')
                return c - 'A' + 10;
            return -1;
        };
        if (s[i] == '%' && i + 2 < s.size() && hex(s[i + 1]) >= 0 && hex(s[i + 2]) >= 0) {
            out.push_back(static_cast<char>(hex(s[i + 1]) * 16 + hex(s[i + 2])));
            i += 2;
        } else {
            out.push_back(s[i] == '+' && form ? ' ' : s[i]);
        }
    }
    return out;
}

} // namespace

std::string percent_decode(std::string_view s)
{
    return decode(s, false);
}

std::map<std::string, std::string> query_of(std::string_view target)
{
    std::map<std::string, std::string> out;
    const auto q = target.find('?');
    if (q == std::string_view::npos)
        return out;
    auto rest = target.substr(q + 1);
    while (!rest.empty()) {
        const auto amp = rest.find('&');
        const auto part = rest.substr(0, amp);
        const auto eq = part.find('=');
        if (!part.empty())
            out[decode(part.substr(0, eq), true)] = eq == std::string_view::npos ? "" : decode(part.substr(eq + 1), true);
        if (amp == std::string_view::npos)
            break;
        rest.remove_prefix(amp + 1);
    }
    return out;
}

} // namespace rigsim::control
