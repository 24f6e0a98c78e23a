#pragma once
// The "mcs2" family's loader of a device's section (docs/config.md, "mcs2").

#include "emulator/core/rig_config.hpp"

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace rigsim {
class ConfigReader;
}

namespace rigsim::mcs2 {

/// The "mcs2" object of the device object `device` at `pointer` into `config` (and the default
/// model and firmware); throws ConfigError through `reader`.
void load_device_section(const ConfigReader& reader, const nlohmann::json& device, const std::string& pointer,
                         DeviceConfig& config);

} // namespace rigsim::mcs2
