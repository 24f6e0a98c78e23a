#pragma once
// The firmware generations an MCS device may follow (the rig's "firmware", docs/config.md),
// named by the version of the document that describes them: the manual's interface 1.2.44
// is the default. Which behaviour changes with the generation, and the public source for
// each change: docs/protocol/mcs.md, "Firmware generations".

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace rigsim::mcs {

enum class Firmware {
    V1_2_44,   ///< SmarAct's "MCS ASCII Programming Interface", interface version 1.2.44: the default
    /// The later generation whose FRM takes the eight search directions of SmarAct's
    /// MCSControl software interface 2.0.1 (MCSControl.h as quoted in nanophotonics/nplab);
    /// no public source names the ASCII interface version that introduced them.
    V2_0_1,
};

/// The rig-JSON name of `f`: "1.2.44", "2.0.1".
std::string_view firmware_name(Firmware f);

/// The generation named `name`, or nothing for a name the family does not know.
std::optional<Firmware> find_firmware(std::string_view name);

/// Every name, quoted and comma-separated, for error messages.
std::string_view firmware_names();

/// The version a generation is named by, {high, low, update}: GIV's default answer.
std::array<std::int64_t, 3> firmware_version(Firmware f);

/// The newest generation whose version is not above `version` (the oldest, 1.2.44, for
/// versions below every generation's): the generation an interface version belongs to.
Firmware firmware_of_version(const std::array<std::int64_t, 3>& version);

/// An FRM direction parameter as a generation reads it.
struct FrmDirection {
    bool backward = false;            ///< the search starts backward
    bool abort_on_end_stop = false;   ///< the first end stop ends the search unsuccessfully
};

/// `direction` of FRM<ch>,<direction>,...: 0 forward, 1 backward (both generations); under
/// 2.0.1 also 2 forward-backward, 3 backward-forward (the manual's search, which reverses at
/// an end stop) and 4..7 the same four aborting at the first end stop. Nothing for a value
/// the generation does not know (the command answers error 7).
std::optional<FrmDirection> frm_direction(Firmware f, std::int32_t direction);

} // namespace rigsim::mcs
