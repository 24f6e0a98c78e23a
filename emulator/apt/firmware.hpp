#pragma once
// The firmware generations an APT device may follow (the rig's "firmware", docs/config.md):
// the manual's (the 2012 issue of the APT protocol, "Issue 3": the default) and a later one,
// named by the later protocol issue that documents it. Which behaviour changes with the
// generation, and the public source for each change: docs/protocol/apt.md, "Firmware
// generations".

#include <optional>
#include <string_view>

namespace rigsim::apt {

enum class Firmware {
    Issue3,      ///< Thorlabs' "APT Communications Protocol", Issue 3 (01-June-2012): the default
    Issue44_1,   ///< the later protocol issue 44.1 that K-Cube drivers cite
};

/// The rig-JSON name of `f`: "issue-3", "issue-44.1".
std::string_view firmware_name(Firmware f);

/// The generation named `name`, or nothing for a name the family does not know.
std::optional<Firmware> find_firmware(std::string_view name);

/// Every name, quoted and comma-separated, for error messages: "\"issue-3\", \"issue-44.1\"".
std::string_view firmware_names();

} // namespace rigsim::apt
