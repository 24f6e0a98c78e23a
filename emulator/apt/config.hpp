#pragma once
// An APT device's section of the rig ("apt": stage or bays, serial number): its struct with
// every default, and its loader (docs/config.md).

#include "emulator/core/rig_config.hpp"

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace rigsim {
class ConfigReader;
}

namespace rigsim::apt {

/// An APT motor controller (Thorlabs): its stage, or for a card-slot (rack) controller the
/// stage of each occupied bay.
struct AptConfig {
    std::string stage = "MTS50-Z8";   ///< a stage of the catalogue (emulator/apt/catalogue.cpp)
    std::vector<std::string> bays;    ///< rack controllers: the stage in bay 0, 1, ...
    std::uint32_t serial_number = 0;  ///< 8 digits with the model's prefix; 0 = prefix × 10^6 + 1
};

/// The APT section of `device` (a default one if it has none yet).
inline AptConfig& config_of(DeviceConfig& device)
{
    return section_of<AptConfig>(device);
}
/// The APT section of `device`; throws std::bad_any_cast for another family's device.
inline const AptConfig& config_of(const DeviceConfig& device)
{
    return section_of<AptConfig>(device);
}

/// The family loader: the model and the "apt" object of the device object `device` at
/// `pointer` into `config`; throws ConfigError through `reader`.
void load_device_section(const ConfigReader& reader, const nlohmann::json& device, const std::string& pointer,
                         DeviceConfig& config);

} // namespace rigsim::apt
