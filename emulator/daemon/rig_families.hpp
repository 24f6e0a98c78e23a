#pragma once
// The daemon layer's one wiring of the protocol families ("mcs", "apt") into the registry
// core reads rigs with, and the rig as this daemon reads it: files, text and the built-in
// default rig (config/default.json, compiled in).

#include "emulator/core/family_registry.hpp"
#include "emulator/core/rig_config.hpp"

#include <string>
#include <string_view>

namespace rigsim {

/// Every family this daemon knows, "mcs" then "apt".
const FamilyRegistry& rig_families();

/// parse_rig_config with rig_families().
RigConfig parse_rig_config(std::string_view json_text, std::string_view source);
/// load_rig_config with rig_families().
RigConfig load_rig_config(const std::string& path);

/// The built-in default rig (config/default.json, compiled in).
std::string_view default_rig_json();
RigConfig default_rig_config();

} // namespace rigsim
