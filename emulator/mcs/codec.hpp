#pragma once
// MCS command strings <-> typed commands and answers (manual chapter 3, appendix 4.2).
// The codec knows no device: it checks syntax, numbers and parameter counts; ranges
// and channel indexes are the handler's business.

#include "emulator/mcs/commands.hpp"
#include "emulator/mcs/errors.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

namespace rigsim::mcs {

// ---- Commands (emulator/mcs/commands.hpp) ----

/// The channel a command addresses, if it addresses one.
std::optional<std::int32_t> channel_of(const Command& command);
/// Movement commands: the ones the command queue takes after ATC (2.4.5).
bool is_movement(const Command& command);

/// `:<answer>\n`
std::string encode(const Reply& reply);
void encode(const Reply& reply, std::string& out);

/// Result of decoding one command string.
struct Decoded {
    std::optional<Command> command;   ///< set when the string is a valid command
    Error error{kSystem, ErrorCode::None};   ///< otherwise, the answer the manual gives
    std::string_view name;            ///< the command name as sent (for logs)
};

/// Decode one command string (without ':' and '\n').
Decoded decode(std::string_view line);

/// A command of chapter 3 as the codec's table declares it (codec.cpp, one entry per command).
struct CommandInfo {
    std::string_view mnemonic;   ///< "MPA"
    std::string_view name;       ///< the manual's name, "Move to Position Absolute"
    std::string_view params;     ///< the manual's parameter names, comma-separated
};

/// The command with this mnemonic, or nullptr when the codec knows none.
const CommandInfo* find_command(std::string_view mnemonic);

} // namespace rigsim::mcs
