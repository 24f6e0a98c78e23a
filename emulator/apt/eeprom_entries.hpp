#pragma once
// A unit's saved SETs in the state file (what MOT_/PZ_SET_EEPROMPARAMS write, p. 60, p. 113):
// an entry per bay and message, keyed "bay0/0x0413", its data as hex, replayed at power-up as
// the frame the host would have sent.

#include "emulator/apt/catalogue.hpp"
#include "emulator/apt/frame_framer.hpp"
#include "emulator/apt/messages.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace rigsim::apt {

/// The manual name of message `id`, or its ID in hex.
std::string message_name(std::uint16_t id);
/// State file key of a saved SET message: "bay0/0x0413".
std::string eeprom_key(std::size_t bay, std::uint16_t id);
/// The bay and message of a key exactly as eeprom_key writes it, or nullopt.
std::optional<std::pair<std::size_t, std::uint16_t>> parse_eeprom_key(const std::string& key);
/// `data` as lower-case hex, two digits a byte.
std::string to_hex(std::string_view data);
/// `hex` (an even number of [0-9a-fA-F]) as bytes in `out`, or false and why not in `why`.
bool from_hex(const std::string& hex, std::string& out, std::string& why);
/// The EEPROMPARAMS message of a unit kind: MOT_ (p. 60) for motor and solenoid units, PZ_
/// (p. 113) for piezo and strain gauge units.
const char* eeprom_message(UnitKind kind);
/// The frame a stored SET is replayed as, from the host to `dest`: its data packet, or for a
/// header-only SET its param1 and param2 (`data` outlives the frame).
Frame saved_frame(const MessageInfo& info, std::uint8_t dest, const std::string& data);

} // namespace rigsim::apt
