#pragma once
// The answer texts and acknowledges that the handler's files build alike (handler.cpp,
// handler_end_effector.cpp).

#include "emulator/mcs/commands.hpp"
#include "emulator/mcs/errors.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace rigsim::mcs::replies {

/// `<prefix><a>`, as an answer starts (`P0` ...).
inline std::string join(std::string_view prefix, std::int64_t a)
{
    std::string s(prefix);
    s += std::to_string(a);
    return s;
}

/// `<prefix><a>,<b>`.
inline std::string join(std::string_view prefix, std::int64_t a, std::int64_t b)
{
    std::string s = join(prefix, a);
    s += ',';
    s += std::to_string(b);
    return s;
}

/// A reply for a channel setter: its error, or the acknowledge from `ack_channel`.
inline Reply result(std::optional<ErrorCode> err, int channel, int ack_channel)
{
    if (err)
        return Error{channel, *err};
    return Ack{ack_channel};
}

} // namespace rigsim::mcs::replies
