#include "emulator/apt/config.hpp"

#include "emulator/apt/catalogue.hpp"
#include "emulator/core/config_reader.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <string_view>

namespace rigsim::apt {
namespace {

using nlohmann::json;

constexpr std::array<std::string_view, 3> kAptKeys{"stage", "bays", "serial_number"};

/// A stage of the catalogue whose motor suits `controller` (a single unit's "stage", or one of
/// a rack's "bays").
std::string load_stage(const ConfigReader& r, const json& v, const std::string& pointer,
                       const ControllerModel& controller, const std::string& model)
{
    auto stage = r.get_string(v, pointer);
    const auto* found = find_stage(stage);
    if (!found)
        r.fail(pointer, "unknown stage " + quote(stage) + " (expected one of " + std::string(stage_names()) + ")");
    if (found->motor != controller.motor)
        r.fail(pointer, "stage " + quote(stage) + " has another kind of motor than a " + model);
    return stage;
}

/// The "apt" object `a` at `apt_pointer` of a device whose model is `controller`.
AptConfig load_apt(const ConfigReader& r, const json& a, const std::string& apt_pointer,
                   const ControllerModel& controller, const std::string& model)
{
    AptConfig apt;
    if (!a.is_object())
        r.fail(apt_pointer, "expected an object, got " + describe(a));
    r.check_keys(a, apt_pointer, kAptKeys);
    if (const auto* st = r.find(a, "stage"))
        apt.stage = load_stage(r, *st, pointer_to(apt_pointer, "stage"), controller, model);
    if (controller.rack) {
        if (r.find(a, "stage"))
            r.fail(pointer_to(apt_pointer, "stage"), "a rack controller names a stage per bay in \"bays\"");
        const auto bays_pointer = pointer_to(apt_pointer, "bays");
        const auto& bays = r.require(a, apt_pointer, "bays");
        const auto max = static_cast<std::size_t>(controller.max_bays);
        if (!bays.is_array() || bays.empty() || bays.size() > max)
            r.fail(bays_pointer, "expected an array of 1.." + std::to_string(max) + " stages, got " + describe(bays));
        for (std::size_t i = 0; i < bays.size(); ++i)
            apt.bays.push_back(load_stage(r, bays[i], pointer_to(bays_pointer, i), controller, model));
    } else if (r.find(a, "bays")) {
        r.fail(pointer_to(apt_pointer, "bays"), "only rack controllers have bays; " + model + " names one \"stage\"");
    } else if (!r.find(a, "stage") && find_stage(apt.stage)->motor != controller.motor) {
        r.fail(pointer_to(apt_pointer, "stage"),
               "required key missing (the default " + apt.stage + " is not a stage for a " + model + ")");
    }
    if (const auto* sn = r.find(a, "serial_number")) {
        const std::int64_t lo = controller.serial_prefix * 1'000'000LL;
        apt.serial_number = static_cast<std::uint32_t>(
            r.get_int(*sn, pointer_to(apt_pointer, "serial_number"), lo, lo + 999'999, " (the model's serial prefix)"));
    }
    return apt;
}

} // namespace

void load_device_section(const ConfigReader& reader, const json& device, const std::string& pointer,
                         DeviceConfig& config)
{
    const bool named = reader.find(device, "model") != nullptr;
    const auto* controller = find_controller(config.model);
    if (!named || !controller)
        reader.fail(pointer_to(pointer, "model"), "expected an APT controller model (" +
                                                      std::string(controller_names()) + "), got " +
                                                      (named ? quote(config.model) : std::string("nothing")));
    const auto& a = reader.require(device, pointer, "apt");
    config.section = load_apt(reader, a, pointer_to(pointer, "apt"), *controller, config.model);
}

} // namespace rigsim::apt
