#pragma once
// Parsing JSON text in time linear in its length, with the checks every reader of the daemon's
// JSON makes: a depth limit (copying and printing a value recurse) and, where asked, no key twice
// in one object (nlohmann would keep the last value silently). nlohmann's callback parser, used
// for these checks before, takes time quadratic in the length of an array of objects (400,000
// `{}` in a rig file: 43 s); this one builds the value from the parser's SAX events itself.

#include <nlohmann/json.hpp>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace rigsim {

struct JsonTextLimits {
    /// Containers nested deeper than this are refused.
    std::size_t max_depth = 100;
    /// Whether a key repeated in one object is refused.
    bool unique_keys = true;
};

/// Why a JSON text was refused.
class JsonTextError : public std::runtime_error {
public:
    enum class Kind {
        Syntax,         ///< not JSON; `byte` is the 1-based position of the error
        NumberOverflow, ///< a number no double holds (1e400)
        DuplicateKey,   ///< a key twice in one object
        TooDeep,        ///< containers nested deeper than JsonTextLimits::max_depth
    };
    JsonTextError(Kind kind, std::string what, std::size_t byte, std::string pointer)
        : std::runtime_error(std::move(what)), kind(kind), byte(byte), pointer(std::move(pointer))
    {
    }
    Kind kind;
    /// 1-based byte position where the parser stopped (nlohmann's convention).
    std::size_t byte;
    /// RFC 6901 pointer of the value at fault ("" = the root): the duplicate key's value, the
    /// overflowing number, the container one level too deep.
    std::string pointer;
};

/// `text` as a JSON value, or JsonTextError. Linear in text.size() (a key is looked up in its
/// object's map, logarithmic in that object's size).
nlohmann::json parse_json_text(std::string_view text, const JsonTextLimits& limits = {});

} // namespace rigsim
