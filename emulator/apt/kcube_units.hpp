#pragma once
// The K-Cube piezo driver's and strain gauge reader's own parameter blocks (later protocol
// issues; codec_kcube_units.hpp): what a KPZ101/KSG101 of the later firmware generation holds at
// power-up, and the ranges its SETs must keep. docs/protocol/apt.md "K-Cube units" gives the
// public source of each range.

#include "emulator/apt/codec.hpp"

#include <optional>
#include <string>

namespace rigsim::apt {

/// Power-up blocks. No public source gives the factory values: rigsim's choice, in range (the
/// display at msl-equipment's KSC defaults, 50 %, 2 min, 5; the wheel in its first modes; the
/// trigger ports disabled, active high).
msg::KpzMmiParams kpz_mmi_power_up();
msg::KpzTrigIoConfig kpz_trig_power_up();
msg::KsgMmiParams ksg_mmi_power_up();
msg::KsgTrigIoConfig ksg_trig_power_up();

/// The first field of `p` outside what the sources document, as "<name> <value> (<allowed>)";
/// nullopt when every documented field is in range (fields no source bounds take any value).
std::optional<std::string> kcube_out_of_range(const msg::KpzMmiParams& p);
std::optional<std::string> kcube_out_of_range(const msg::KpzTrigIoConfig& p);
std::optional<std::string> kcube_out_of_range(const msg::KsgMmiParams& p);
std::optional<std::string> kcube_out_of_range(const msg::KsgTrigIoConfig& p);

} // namespace rigsim::apt
