#include "emulator/core/rig_families.hpp"

#include "emulator/apt/apt_device.hpp"
#include "emulator/apt/catalogue.hpp"
#include "emulator/apt/config.hpp"
#include "emulator/core/config_reader.hpp"
#include "emulator/mcs/config.hpp"
#include "emulator/mcs/mcs_device.hpp"

#include <memory>
#include <string>
#include <string_view>

namespace rigsim {
namespace {

/// The unit kinds with a catalogue entry and rig keys but no modules yet, for messages.
std::string_view unserved_kind(apt::UnitKind kind)
{
    switch (kind) {
    case apt::UnitKind::Motor:
    case apt::UnitKind::Solenoid:
        return {};
    case apt::UnitKind::Piezo:
        return "piezo";
    case apt::UnitKind::StrainGauge:
        return "strain gauge";
    }
    return {};
}

/// An APT device. The piezo and strain gauge units are validated like every other,
/// but their modules do not exist yet: the daemon refuses to run them.
std::unique_ptr<Device> make_apt_device(const DeviceConfig& config, const DeviceContext& context)
{
    const auto* model = apt::find_controller(config.model);
    if (const auto kind = model ? unserved_kind(model->kind) : std::string_view{}; !kind.empty())
        fail(config.source, pointer_to(config.pointer, "model"),
             config.model + " is a " + std::string(kind) + " unit: its keys are valid, but rigsim does not emulate " +
                 std::string(kind) + " units yet");
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
