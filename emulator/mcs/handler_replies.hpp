#pragma once
// The answer texts and acknowledges that the handler's files build alike (handler.cpp,
// handler_end_effector.cpp).

#include "emulator/mcs/commands.hpp"
#include "emulator/mcs/errors.hpp"

#include <charconv>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace rigsim::mcs::replies {

/// `<prefix><a>`, as an answer starts (`P0` ...; a prefix of at most 40 characters).
inline std::string join(std::string_view prefix, std::int64_t a)
{
    // Composed in place, one string made (an answer is most of a query's work).
    char text[64];
    const auto n = prefix.copy(text, 40);
    return std::string(text, std::to_chars(text + n, text + sizeof text, a).ptr);
}

/// `<prefix><a>,<b>`.
inline std::string join(std::string_view prefix, std::int64_t a, std::int64_t b)
{
    char text[96];
    const auto n = prefix.copy(text, 40);
    char* end = std::to_chars(text + n, text + 64, a).ptr;   // 40 + 20 digits and a sign at most
    *end++ = ',';
    return std::string(text, std::to_chars(end, text + sizeof text, b).ptr);
}

/// A reply for a channel setter: its error, or the acknowledge from `ack_channel`.
inline Reply result(std::optional<ErrorCode> err, int channel, int ack_channel)
{
    if (err)
        return Error{channel, *err};
    return Ack{ack_channel};
}

} // namespace rigsim::mcs::replies
