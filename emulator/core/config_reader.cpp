#include "emulator/core/config_reader.hpp"

namespace rigsim {

using nlohmann::json;

namespace {

/// Echoed values and keys longer than this are cut in messages.
constexpr std::size_t kMaxEcho = 80;

} // namespace

std::string pointer_to(const std::string& parent, std::string_view key)
{
    std::string p = parent + '/';
    for (char c : key) {
        if (c == '~')
            p += "~0";
        else if (c == '/')
            p += "~1";
        else
            p += c;
    }
    return p;
}

std::string pointer_to(const std::string& parent, std::size_t index)
{
    return parent + '/' + std::to_string(index);
}

std::string cut(std::string text)
{
    if (text.size() <= kMaxEcho)
        return text;
    const auto total = text.size();
    std::size_t end = kMaxEcho;
    while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80)
        --end;
    text.resize(end);
    return text + "... (" + std::to_string(total) + " characters)";
}

std::string dump(const json& value)
{
    return cut(value.dump(-1, ' ', false, json::error_handler_t::replace));
}

std::string quote(std::string_view s)
{
    return dump(json(std::string(s)));
}

bool is_name(const json& value)
{
    if (!value.is_string())
        return false;
    const auto& s = value.get_ref<const std::string&>();
    if (s.empty() || s.size() > kMaxNameLength)
        return false;
    for (char c : s)
        if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.'
              || c == '-'))
            return false;
    return true;
}

std::string describe(const json& value)
{
    if (value.is_array()) {
        if (value.empty())
            return "[]";
        return "an array of " + std::to_string(value.size()) +
               (value.size() == 1 ? " element" : " elements");
    }
    if (value.is_object())
        return value.empty() ? "{}" : "an object";
    return dump(value);
}

void fail(std::string_view source, const std::string& pointer, const std::string& what)
{
    constexpr std::size_t kMaxPointer = 160;
    const auto shown = pointer.size() <= kMaxPointer ? pointer : pointer.substr(0, kMaxPointer) + "...";
    throw ConfigError(std::string(source) + ": " + (pointer.empty() ? "/" : shown) + ": " + what);
}

void ConfigReader::fail(const std::string& pointer, const std::string& what) const
{
    rigsim::fail(source_, pointer, what);
}

void ConfigReader::check_keys(const json& value, const std::string& pointer, const std::string_view* allowed,
                              std::size_t count) const
{
    if (!value.is_object())
        fail(pointer, "expected an object, got " + describe(value));
    for (const auto& item : value.items()) {
        bool known = false;
        for (std::size_t i = 0; i < count; ++i)
            known = known || item.key() == allowed[i];
        if (known)
            continue;
        std::string list;
        for (std::size_t i = 0; i < count; ++i)
            list += (list.empty() ? "" : ", ") + std::string(allowed[i]);
        fail(pointer, "unknown key " + quote(item.key()) + " (allowed: " + list + ")");
    }
}

const json* ConfigReader::find(const json& object, std::string_view key)
{
    const auto it = object.find(std::string(key));
    return it == object.end() ? nullptr : &*it;
}

const json& ConfigReader::require(const json& object, const std::string& pointer, std::string_view key) const
{
    const auto* v = find(object, key);
    if (!v)
        fail(pointer_to(pointer, key), "required key missing");
    return *v;
}

std::int64_t ConfigReader::get_int(const json& v, const std::string& pointer, std::int64_t min, std::int64_t max,
                                   std::string_view note) const
{
    bool ok = false;
    std::int64_t n = 0;
    if (v.is_number_unsigned()) {
        // nlohmann reads every non-negative integer as unsigned.
        const auto u = v.get<std::uint64_t>();
        n = static_cast<std::int64_t>(u);
        ok = max >= 0 && u <= static_cast<std::uint64_t>(max) && n >= min;
    } else if (v.is_number_integer()) {
        n = v.get<std::int64_t>();
        ok = n >= min && n <= max;
    }
    if (!ok)
        fail(pointer, "expected an integer " + std::to_string(min) + ".." + std::to_string(max) + std::string(note) +
                          ", got " + describe(v));
    return n;
}

const std::string& ConfigReader::get_string(const json& v, const std::string& pointer,
                                            std::string_view expected) const
{
    if (!v.is_string() || v.get_ref<const std::string&>().empty())
        fail(pointer, "expected " + std::string(expected) + ", got " + describe(v));
    return v.get_ref<const std::string&>();
}

} // namespace rigsim
