#pragma once
// The firmware generations an MCS device may follow (the rig's "firmware", docs/config.md),
// named by the ASCII interface version that documents them: the manual's 1.2.44 is the
// default. Which behaviour changes with the generation, and the public source for each
// change: docs/protocol/mcs.md, "Firmware generations".

#include <optional>
#include <string_view>

namespace rigsim::mcs {

enum class Firmware {
    V1_2_44,   ///< the manual in ../shared/specs (interface version 1.2.44): the default
};

/// The rig-JSON name of `f`: "1.2.44".
std::string_view firmware_name(Firmware f);

/// The generation named `name`, or nothing for a name the family does not know.
std::optional<Firmware> find_firmware(std::string_view name);

/// Every name, quoted and comma-separated, for error messages.
std::string_view firmware_names();

} // namespace rigsim::mcs
