#pragma once
// APT controllers and stages that a rig may name (manual 2.2 serial prefixes, 7.1 scaling).
// Every field has a default; the catalogue (catalogue.cpp) sets each controller's fields by
// name; the stages are files (config/stages/*.json, shipped_stages.hpp).

#include "emulator/apt/firmware.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace rigsim::apt {

enum class MotorKind { DcServo, Stepper, Brushless };

/// What a unit drives; it picks the module class a unit (or a rack's bay) is made of.
enum class UnitKind { Motor, Solenoid, Piezo, StrainGauge, Flipper, Polariser, PiezoMotor };

/// The message IDs a model takes beyond the generic ones (identify, enable state, info, update
/// messages, bays): its column of the manual's "Message Cross Reference by Unit Part Number"
/// tables, a takes list of messages.def (catalogue.cpp names each model's). Empty: the module's
/// own handlers decide (the motor controllers).
struct MessageSet {
    const std::uint16_t* ids = nullptr;
    std::size_t count = 0;
    bool empty() const { return count == 0; }
    bool contains(std::uint16_t id) const { return std::find(ids, ids + count, id) != ids + count; }
};

/// An APT controller model, as a firmware generation shapes it (find_controller).
struct ControllerModel {
    std::string_view name;          ///< e.g. "TDC001"
    /// The generation this entry follows (docs/protocol/apt.md, "Firmware generations").
    Firmware firmware = Firmware::Issue3;
    UnitKind kind = UnitKind::Motor;
    MessageSet takes;
    /// What a unit of the later firmware generation ("issue-44.1") takes beyond `takes`: a
    /// K-Cube's own messages, which the manual's generation ignores and logs.
    MessageSet later_takes;
    /// The host's "server alive" acknowledgement of status updates: MOT_ACK_DCSTATUSUPDATE
    /// (p. 80) for motor and solenoid units, PZ_ACK_PZSTATUSUPDATE (0x0662, p. 105) for piezo
    /// and strain-gauge units; the same cut-off after 50 unacknowledged updates.
    std::uint16_t ack_id = 0x0492;
    /// Piezo waveform look-up table: highest PZ_SET_OUTPUTLUT index (p. 106: 512 TPZ001,
    /// 7999 BPC30x) and the base sample interval the LUT timing counts in (p. 109).
    std::uint16_t lut_max_index = 0;
    std::uint32_t lut_base_interval_us = 0;
    /// Piezo closed loop: the rate the PI loop runs at (Hz).
    std::uint32_t loop_rate_hz = 0;
    std::uint32_t serial_prefix = 0;    ///< first two digits of the 8-digit serial number (2.2)
    std::uint16_t hw_type = 0;          ///< HW_GET_INFO "type" field
    /// HW_GET_INFO firmware version as its 4 bytes read little-endian: minor, interim, major, 0
    /// (p. 21): 0x00010003 is 1.0.3.
    std::uint32_t firmware_version = 0x00010003;
    MotorKind motor = MotorKind::DcServo;
    std::string_view notes;         ///< HW_GET_INFO notes
    /// Velocity/acceleration sample-time scaling of 7.1 (APT units per encoder count/s and
    /// per count/s²).
    double velocity_per_count_s = 0;
    double acceleration_per_count_s2 = 0;
    /// Position counts per count of the stage (stage files count the manual's 128 microsteps
    /// per full step; a later-generation stepper counts 2048: 16).
    double counts_per_stage_count = 1;
    /// HW_GET_INFO carries the later issue's fields (hardware version, modification state and
    /// the stage type word at data offset 76) rather than the manual's 64 bytes of notes.
    bool later_info_fields = false;
    /// HW_GET_INFO stage type word: the DC servo cubes report the stage they were set up for.
    bool reports_stage_type = false;
    /// Card-slot (rack) system: a motherboard at 0x11 and bays at 0x21 + n (section 4).
    bool rack = false;
    int max_bays = 1;
    std::uint16_t bay_hw_type = 0;  ///< HW_GET_INFO type of a bay's card
    std::uint32_t bay_serial_prefix = 0;
    /// S-curve jerk scaling (7.1, PMD "jerk" units per encoder count/s³); 0: no profile modes.
    double jerk_per_count_s3 = 0;
    /// MOT_SET_KCUBEMMIPARAMS drives a top-panel wheel; false: the unit reads the block's display
    /// words only (a solenoid cube: Kinesis' KSC_MMIParams calls the wheel words "unused").
    bool mmi_wheel = true;
    /// Faults go out as HW_RICHRESPONSE (K-Cubes, Thorlabs' later units) rather than the
    /// manual's HW_RESPONSE (p. 19).
    bool rich_fault_reports = false;
    /// An integrated unit (K10CR1, LTS150, LTS300): the shipped stage it is built on, which its
    /// "apt" object does not name and no other controller drives. Empty: the rig names the stage.
    std::string_view built_in_stage;
    /// Made after the 2012 manual: the unit exists in the later firmware generation only (its
    /// default; a rig's "issue-3" is refused, find_controller gives the later entry).
    bool later_only = false;
    /// HW_GET_INFO hardware version (the later issue's field at data offset 78).
    std::uint16_t hardware_version = 1;
    /// A polarisation controller's fibre paddles (MPC320 3, MPC220 2).
    int paddles = 0;
    /// A piezo motor controller's channels (KIM101, TIM101: 4), each a piezo inertia actuator.
    int pzmot_channels = 0;
    /// The status updates a USB unit sends without the host's acknowledgement before it stops
    /// (50, p. 80 and 105; a KIM101/TIM101 10, issue 37 p. 406).
    int updates_without_ack = 50;
    /// HW_GET_INFO model number when the unit names itself otherwise than its product (an MFF101
    /// reports "MFF002"); empty: the name.
    std::string_view reported_name;
    /// A rack whose bays hold modules of their own model (an MMR601's MPZ601 cards): their HW_GET_INFO
    /// model number; empty: the rack's.
    std::string_view bay_model_name;
    /// The channels of each bay's card (an MPZ601: 2, PiezoCard); 1: a bay is one channel.
    int bay_channels = 1;
    /// A rack that stops answering when a client addresses it as a single unit (0x50, "the wrong rack
    /// flag"), until it is power cycled (pyLabLib issues 81 and 97; docs/protocol/apt.md "Units of today").
    bool wrong_address_freezes = false;
};

/// What a stage's carriage does: move along a line (unit mm), turn without end (unit degree), or
/// tilt through a limited angle range, with end stops and limit switches like a linear stage
/// (a goniometer; unit degree).
enum class StageKind { Linear, Rotary, Goniometer };

/// Which ends of a linear stage's or a goniometer's travel have a limit switch.
enum class LimitSwitches { Both, Forward, Reverse, None };

/// A stage (actuator) the controller drives: a shipped stage file (config/stages/*.json) or a
/// rig's inline stage object, read by stage_file.cpp (docs/config.md, "APT stages"). Its unit is
/// the mm for a linear stage and the degree for a rotary stage or a goniometer: the fields named
/// per mm hold per-degree values there.
struct StageModel {
    std::string name;               ///< e.g. "MTS50-Z8"; empty for an unnamed inline stage
    StageKind kind = StageKind::Linear;
    MotorKind motor = MotorKind::DcServo;
    double travel_mm = 0;           ///< linear: from 0 at the reverse end stop to the forward one
    /// Goniometer: the angles of the reverse and forward end stops (angle_range_deg).
    double angle_min_deg = 0;
    double angle_max_deg = 0;
    double counts_per_mm = 0;           ///< encoder counts (DC servo, brushless) or microsteps (stepper) per unit
    double max_velocity_mm_s = 0;       ///< power-up VELPARAMS
    double acceleration_mm_s2 = 0;
    double home_velocity_mm_s = 0;
    double home_offset_mm = 0;          ///< back-off distance from the limit (home) switch
    /// Velocity/acceleration scaling of the stage itself when the manual gives it per mm
    /// (7.1, MLS203 with BBDxxx); 0: derived from the controller's per-count factors.
    double velocity_per_mm_s = 0;
    double acceleration_per_mm_s2 = 0;
    /// Linear stages and goniometers: the ends with a limit switch (power-up LIMSWITCHPARAMS).
    /// A rotation stage has none: a home switch once per turn (at 0 of the physical angle).
    LimitSwitches limit_switches = LimitSwitches::Both;
    /// Power-up HOMEPARAMS: homing runs forward (to the forward limit switch; a rotation stage to
    /// the next home switch forward) rather than in reverse. A brushless channel always homes
    /// forward (p. 37).
    bool home_forward = false;
    /// MOT_GET_PMDSTAGEAXISPARAMS (p. 75): stage ID (named for MLS203 X/Y only), part number
    /// (empty: the name), and the design's maximum velocity and acceleration in PMD units
    /// (0: the power-up VELPARAMS).
    std::uint16_t pmd_stage_id = 0;
    std::string pmd_part_number;
    std::int32_t pmd_max_velocity = 0;
    std::int32_t pmd_max_acceleration = 0;

    /// Degrees rather than mm: a rotary stage or a goniometer.
    bool angular() const { return kind != StageKind::Linear; }
};

/// The controller with this name as firmware generation `firmware` shapes it, or nullptr.
const ControllerModel* find_controller(std::string_view name, Firmware firmware = Firmware::Issue3);
/// `stage` as `controller` counts it: counts_per_mm × ControllerModel::counts_per_stage_count.
StageModel driven_stage(const ControllerModel& controller, StageModel stage);
/// HW_GET_INFO's stage type word (later issue) for the shipped stage `name` on a DC servo
/// cube, 0 for one the public table does not name.
std::uint16_t dc_stage_type(std::string_view name);
/// Names for error messages ("TDC001, KDC101").
std::string_view controller_names();
/// The integrated unit whose built-in stage the shipped stage `stage` is, or nullptr.
const ControllerModel* built_into(std::string_view stage);

} // namespace rigsim::apt
