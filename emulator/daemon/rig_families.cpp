#include "emulator/daemon/rig_families.hpp"

#include "emulator/apt/apt_device.hpp"
#include "emulator/apt/config.hpp"
#include "emulator/mcs/config.hpp"
#include "emulator/mcs/mcs_device.hpp"
#include "emulator/mcs2/config_loader.hpp"
#include "emulator/mcs2/device.hpp"

#include <memory>
#include <string>
#include <string_view>

namespace rigsim {
namespace {

/// An APT device, of any unit kind of the catalogue.
std::unique_ptr<Device> make_apt_device(const DeviceConfig& config, const DeviceContext& context)
{
    return std::make_unique<apt::AptDevice>(config, context.world, context.log, &context.store, context.events);
}

FamilyRegistry make_families()
{
    FamilyRegistry families;
    families.add(Family{"mcs", "an MCS device", &mcs::load_device_section,
                        [](const DeviceConfig& config, const DeviceContext& context) -> std::unique_ptr<Device> {
                            return std::make_unique<mcs::McsDevice>(config, context.world, context.log, context.events);
                        }});
    families.add(Family{"apt", "an APT device", &apt::load_device_section, &make_apt_device, &apt::validate_rig});
    families.add(Family{"mcs2", "an MCS2 device", &mcs2::load_device_section,
                        [](const DeviceConfig& config, const DeviceContext& context) -> std::unique_ptr<Device> {
                            return std::make_unique<mcs2::Mcs2Device>(config, context.world, context.log, context.events);
                        }});
    return families;
}

} // namespace

const FamilyRegistry& rig_families()
{
    static const FamilyRegistry families = make_families();
    return families;
}

RigConfig parse_rig_config(std::string_view json_text, std::string_view source)
{
    return parse_rig_config(json_text, source, rig_families());
}

RigConfig load_rig_config(const std::string& path)
{
    return load_rig_config(path, rig_families());
}

RigConfig default_rig_config()
{
    return parse_rig_config(default_rig_json(), "built-in default rig");
}

} // namespace rigsim
