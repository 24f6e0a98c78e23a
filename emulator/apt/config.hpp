#pragma once
// An APT device's section of the rig ("apt": stage or bays, solenoid, actuator, gauge, serial
// number): its structs with every default, its loader and the rig-wide check (docs/config.md).
// Plain data: the device's modules map it onto their models.

#include "emulator/apt/catalogue.hpp"
#include "emulator/apt/firmware.hpp"
#include "emulator/core/rig_config.hpp"

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace rigsim {
class ConfigReader;
}

namespace rigsim::apt {

/// A solenoid controller's set-up (TSC001, KSC101: "solenoid").
struct SolenoidConfig {
    /// The interlock plug is fitted at power-up (with interlock mode 1 the output opens only
    /// while it is, p. 89); the control API pulls and refits it.
    bool interlock_fitted = true;
};

/// A flip mount's set-up (MFF101, MFF102: "flipper").
struct FlipperConfig {
    int position = 1;   ///< where the arm stands at power-up: 1 or 2
};

/// A piezo inertia actuator on a KIM101/TIM101 channel (models::InertialDrive): a PIA13 by default.
struct InertialActuatorConfig {
    double travel_mm = 13;        ///< from the reverse end stop (0) to the forward one
    double position_mm = 6.5;     ///< where the screw stands when the rig starts
    double step_forward_nm = 20;  ///< one forward pulse at 110 V
    double step_reverse_nm = 18;  ///< one reverse pulse at 110 V
};

/// A piezo actuator (stack or stage) on a piezo output: a TPZ001/KPZ101's "actuator", or a
/// BPC30x bay.
struct PiezoActuatorConfig {
    double travel_um = 20.0;      ///< extension at max_voltage_v: 0.1..6553.5 (GET_MAXTRAVEL's 100 nm word)
    int max_voltage_v = 75;       ///< the actuator's rating: 75, 100 or 150
    double response_ms = 1.0;     ///< first-order time constant: 0.1..1000
    double hysteresis = 0.05;     ///< major-loop width over travel: 0..0.3
    double creep = 0.01;          ///< creep per decade of time, over the last step: 0..0.05
};

/// A BPC30x bay ("bays"[n]): its actuator and whether the stage has a strain gauge.
struct PiezoBayConfig {
    PiezoActuatorConfig actuator; ///< the bay object's actuator keys
    bool strain_gauge = false;    ///< the stage feeds a strain gauge back: closed loop possible
    int zero_time_ms = 2000;      ///< PZ_SET_ZERO takes this long: 0..60000
};

/// Where a strain gauge reader's output reaches its piezo's feedback input (TPZ_IOSETTINGS
/// HubAnalogInput 1, 2, 3; p. 115).
enum class GaugeRoute { HubA, HubB, Sma };

/// A strain gauge reader's set-up (TSG001, KSG101: "gauge").
struct StrainGaugeConfig {
    /// The TPZ001/KPZ101 device whose actuator carries the gauge; empty: no gauge fitted.
    std::string mounted_on;
    GaugeRoute route = GaugeRoute::HubA;   ///< the cabling: "sma", or "hub_a"/"hub_b" (the power-up hub output)
    double noise_um = 0.002;      ///< standard deviation of each 500 Hz sample: 0..1
    std::uint32_t seed = 1;       ///< of the noise: the same seed reads the same noise
    double stiffness_n_per_um = 1.0;    ///< force per extension for display mode 3 (N): > 0, <= 1e6
    int zero_time_ms = 2000;      ///< PZ_SET_ZERO takes this long: 0..60000
};

/// The stage of a motor controller whose "apt" object names none: the shipped MTS50-Z8.
StageModel default_stage();

/// An APT controller (Thorlabs). Its model's unit kind (catalogue.hpp) decides which keys it
/// has: a motor controller a stage (a motor rack one per bay), a solenoid controller
/// "solenoid", a piezo controller "actuator" (a piezo rack "hardware_max_voltage_v" and a bay
/// object per bay), a strain gauge reader "gauge"; the others keep their defaults.
struct AptConfig {
    /// The firmware generation (the device's "firmware"; the manual's by default).
    Firmware firmware = Firmware::Issue3;
    /// A single unit's stage: a shipped stage (config/stages, by name) or the rig's stage object.
    StageModel stage = default_stage();
    std::vector<StageModel> bays;     ///< motor racks: the stage in bay 0, 1, ...
    std::uint32_t serial_number = 0;  ///< 8 digits with the model's prefix; 0 = prefix × 10^6 + 1
    SolenoidConfig solenoid;          ///< solenoid controllers
    FlipperConfig flipper;            ///< flip mounts
    /// KIM101/TIM101: the actuator of channel 1, 2, ... (the loader fills every channel).
    std::vector<InertialActuatorConfig> inertial_actuators;
    PiezoActuatorConfig actuator;     ///< TPZ001, KPZ101
    StrainGaugeConfig gauge;          ///< TSG001, KSG101
    int hardware_max_voltage_v = 150; ///< BPC30x amplifier's maximum: 75, 100 or 150
    /// BPC30x: bay 0, 1, ...; the loader gives a rack without "bays" a default bay per slot.
    std::vector<PiezoBayConfig> piezo_bays;
    /// The unit's non-volatile memory at power-up ("eeprom": the state file's entries, "bay0/0x0413"
    /// -> the SET's data in hex): replayed before the state file's own, as if a client had sent
    /// them. The loader checks each key and value's form; the device, at power-up, that its bay
    /// saves the SET and takes it (else a ConfigError naming the entry).
    std::map<std::string, std::string> eeprom;
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

/// The family's rig-wide check, once every device is loaded: each gauge's "mounted_on" names a
/// TPZ001/KPZ101 device of `rig`, and no piezo carries two gauges; throws ConfigError
/// through `reader`.
void validate_rig(const ConfigReader& reader, const RigConfig& rig);

} // namespace rigsim::apt
