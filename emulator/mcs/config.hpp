#pragma once
// An MCS device's section of the rig ("mcs": system ID, interface version, channels): its
// structs with every default, and its loader (docs/config.md).

#include "emulator/core/rig_config.hpp"
#include "emulator/mcs/firmware.hpp"

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace rigsim {
class ConfigReader;
}

namespace rigsim::mcs {

/// One MCS channel: a positioner (the default) or an end effector.
struct McsChannelConfig {
    std::string kind = "positioner";             ///< "positioner" or "end_effector"
    /// End effector: the gripper's jaws touch the object at this voltage (1/100 V) ...
    std::int64_t gripper_contact_cv = 8000;
    /// ... and beyond it the force sensor reads this many 1/10 µN per 1/100 V.
    std::int64_t gripper_stiffness_dun_per_cv = 5;
    std::string sensor_type = "S";               ///< appendix 4.3 symbol, or "none"
    std::int64_t travel_min_nm = -10'500'000;     ///< mechanical end stop (physical position)
    std::int64_t travel_max_nm = 10'500'000;      ///< mechanical end stop (physical position)
    std::int64_t start_position_nm = 0;           ///< physical position at power-up (reads as 0)
    std::int64_t max_speed_nm_per_s = 10'000'000; ///< fastest the stage moves (speed control off)
    std::int64_t closed_loop_speed_nm_per_s = 0;  ///< SCLS power-up value, 0 = speed control off
    std::int64_t closed_loop_acceleration_um_per_s2 = 0;  ///< SCLA power-up value, 0 = off
    /// End stops of angular channels (goniometers, rotary stages with end stops), in µ°;
    /// rotary stages referenced by a mark, or not at all, turn endlessly.
    std::int64_t travel_min_udeg = -10'000'000;
    std::int64_t travel_max_udeg = 10'000'000;
    /// Physical position of the reference mark (nm, or µ° for angular sensors); with
    /// distance-coded marks, the mark that reads as the physical zero.
    std::int64_t reference_position = 0;
    /// Distance between distance-coded reference marks (nm or µ°).
    std::int64_t coded_mark_spacing = 2'000'000;
    /// How long CS takes (status 6), ms.
    std::int64_t calibration_ms = 3000;
    /// Open loop: width of one step at full amplitude (4095 = 100 V), nm (µ° on angular
    /// channels); the width grows in proportion to the amplitude.
    std::int64_t step_width_nm = 1000;
    /// Open loop: each step's width varies by up to this many percent (stick-slip drift).
    std::int64_t step_jitter_percent = 3;
    /// Scanning: piezo deflection at 100 V (level 4095), nm (µ° on angular channels).
    std::int64_t scan_range_nm = 1500;
    /// Open loop: how fast the stage creeps while not under closed-loop control (at rest,
    /// not holding a target), nm/s (µ°/s), signed; it stops at an end stop. 0: no drift.
    std::int64_t drift_nm_per_s = 0;
};

/// The GIV answer `IV<high>,<low>,<update>`; the default is the version the manual documents.
struct McsInterfaceVersion {
    std::int64_t high = 1;
    std::int64_t low = 2;
    std::int64_t update = 44;
};

/// An MCS controller (SmarAct, ASCII protocol).
struct McsConfig {
    /// The firmware generation (the device's "firmware"; the manual's by default).
    Firmware firmware = Firmware::V1_2_44;
    std::uint32_t system_id = 1000;                ///< GSI answer
    McsInterfaceVersion interface_version;         ///< GIV answer ("interface_version": "1.2.44")
    std::vector<McsChannelConfig> channels;        ///< 1..255 channels
};

/// The model of an MCS device whose config names none.
inline constexpr const char* kDefaultMcsModel = "MCS-3D";

/// The MCS section of `device` (a default one if it has none yet).
inline McsConfig& config_of(DeviceConfig& device)
{
    return section_of<McsConfig>(device);
}
/// The MCS section of `device`; throws std::bad_any_cast for another family's device.
inline const McsConfig& config_of(const DeviceConfig& device)
{
    return section_of<McsConfig>(device);
}

/// The family loader: the "mcs" object of the device object `device` at `pointer` into
/// `config` (and the default model); throws ConfigError through `reader`.
void load_device_section(const ConfigReader& reader, const nlohmann::json& device, const std::string& pointer,
                         DeviceConfig& config);

} // namespace rigsim::mcs
