#pragma once
// The manual's names for the MCS wire log (docs/control-api/mcs.md "Wire log"): each command
// string and answer string decoded into {"text", "command", "name", "fields"}, with the
// parameter names of chapter 3 and the error meanings of appendix 4.2. Runs only when someone
// reads the log or listens to the event stream.

#include "emulator/mcs/commands.hpp"

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <string_view>

namespace rigsim::mcs {

/// `line` (one command or answer string, with or without ':' and '\n') decoded; `inbound`:
/// a command (else an answer).
void decode_line(std::string_view line, bool inbound, nlohmann::json& out);
/// The manual's meaning of error `code` (appendix 4.2), e.g. "End Stop Reached".
std::string_view error_name(int code);
/// The manual's name of a command mnemonic ("MPA" -> "Move to Position Absolute"), or "".
std::string_view command_name(std::string_view mnemonic);
/// A queued (movement) command as its command string, e.g. "MPA0,1000000,0".
std::string command_text(const Command& command);

} // namespace rigsim::mcs
