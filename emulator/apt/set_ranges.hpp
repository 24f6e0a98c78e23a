#pragma once
// The field ranges a unit checks before it acts on a SET: those the manual gives (page at each) and
// those the public sources of later protocol issues give for their motor blocks. Each parameter
// block lists its own beside its fields (RIGSIM_APT_RANGES in codec_*.hpp); out_of_range() walks them.

#include "emulator/apt/codec.hpp"

#include <optional>
#include <string>

namespace rigsim::apt {

/// The first field of `m` (a SET) outside its range, as "<name> <value> (<min>..<max>)";
/// nullopt for a message in range or without ranges. Fields the manual gives no range
/// (positions, distances, the backlash: signed longs) take any value, and so do the fields a
/// model does not read: without `mmi_wheel` (ControllerModel::mmi_wheel, a KSC101) the wheel
/// words of MOT_SET_KCUBEMMIPARAMS (msg::ReadBy::WheelUnit). Rules that tie two fields together,
/// and modes whose values are not a range, are the handlers' checks.
std::optional<std::string> out_of_range(const msg::Message& m, bool mmi_wheel);

} // namespace rigsim::apt
