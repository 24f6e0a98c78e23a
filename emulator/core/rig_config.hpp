#pragma once
// The rig: every device, its endpoints and its channels, as read from JSON.
// All defaults live here in the structs; the loader rejects unknown keys, wrong types,
// out-of-range values and collisions, naming the JSON pointer (docs/config.md).

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace rigsim {

enum class Protocol { Mcs, Apt };

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
};

/// An MCS controller (SmarAct, ASCII protocol).
/// The GIV answer `IV<high>,<low>,<update>`; the default is the version the manual documents.
struct McsInterfaceVersion {
    std::int64_t high = 1;
    std::int64_t low = 2;
    std::int64_t update = 44;
};

struct McsConfig {
    std::uint32_t system_id = 1000;                ///< GSI answer
    McsInterfaceVersion interface_version;         ///< GIV answer ("interface_version": "1.2.44")
    std::vector<McsChannelConfig> channels;        ///< 1..255 channels
};

/// An APT motor controller (Thorlabs): its stage, or for a card-slot (rack) controller the
/// stage of each occupied bay.
struct AptConfig {
    std::string stage = "MTS50-Z8";   ///< a stage of the catalogue (emulator/apt/catalogue.cpp)
    std::vector<std::string> bays;    ///< rack controllers: the stage in bay 0, 1, ...
    std::uint32_t serial_number = 0;  ///< 8 digits with the model's prefix; 0 = prefix × 10^6 + 1
};

struct DeviceConfig {
    std::string name;                 ///< unique; names the pty symlink and the logger
    Protocol protocol = Protocol::Mcs;
    std::string model = "MCS-3D";     ///< controller model
    std::uint16_t tcp_port = 0;       ///< 0 = ephemeral
    std::string pty;                  ///< symlink path; empty = <pty dir>/<name>
    /// Pace the pty's output at the controller's baud rate (MCS: CB, effective after R).
    bool faithful_timing = false;
    McsConfig mcs;
    AptConfig apt;
};

struct RigConfig {
    std::uint32_t tick_hz = 1000;     ///< physics tick (1..100000 Hz)
    std::vector<DeviceConfig> devices;
};

/// A config error: `what()` is the whole message, naming the JSON pointer.
class ConfigError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Parse and validate a rig from JSON text. `source` names the text in messages
/// (a file name); throws ConfigError.
RigConfig parse_rig_config(std::string_view json_text, std::string_view source);
/// Read and parse a rig file; throws ConfigError (also for unreadable files).
RigConfig load_rig_config(const std::string& path);

/// Give every device without a configured pty path the path `<pty_dir>/<name>`, and
/// reject two devices whose resolved paths collide (ConfigError naming /devices/N/pty).
void resolve_pty_paths(RigConfig& config, const std::string& pty_dir, std::string_view source);

/// The built-in default rig (config/default.json, compiled in).
std::string_view default_rig_json();
RigConfig default_rig_config();

std::string_view to_string(Protocol p);

} // namespace rigsim
