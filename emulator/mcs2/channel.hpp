#pragma once
// One MCS2 channel: the protocol's view of a stick-slip positioner (MCS2 Programmer's Guide 1.0.6,
// chapters 2.6-2.12 and the channel properties of chapter 4): positioner type, sensor power mode,
// measuring scale, range limit, move modes, hold time, calibration, referencing, the 32-bit channel
// state and the channel error. The physics is the channel's body in the world, a
// models::StickSlipPositioner under "<device>/<index>" (the same positioner the MCS drives): the
// channel commands it in nm (µ° on rotary stages) and reads it at the clock's now; the protocol's
// unit is pm (n°), a thousandth of the body's.
//
// No I/O. Movement commands return at once; their result is the channel's state and error (2.6.7).

#include "emulator/mcs2/config.hpp"
#include "emulator/mcs2/errors.hpp"
#include "emulator/mcs2/positioner_types.hpp"
#include "models/clock.hpp"
#include "models/stick_slip.hpp"
#include "models/world.hpp"

#include <array>
#include <functional>
#include <utility>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rigsim::mcs2 {

/// Channel state bits (2.8.3).
namespace state {
inline constexpr std::uint32_t kActivelyMoving = 1u << 0;
inline constexpr std::uint32_t kClosedLoopActive = 1u << 1;
inline constexpr std::uint32_t kCalibrating = 1u << 2;
inline constexpr std::uint32_t kReferencing = 1u << 3;
inline constexpr std::uint32_t kMoveDelayed = 1u << 4;
inline constexpr std::uint32_t kSensorPresent = 1u << 5;
inline constexpr std::uint32_t kIsCalibrated = 1u << 6;
inline constexpr std::uint32_t kIsReferenced = 1u << 7;
inline constexpr std::uint32_t kEndStopReached = 1u << 8;
inline constexpr std::uint32_t kRangeLimitReached = 1u << 9;
inline constexpr std::uint32_t kFollowingLimitReached = 1u << 10;
inline constexpr std::uint32_t kMovementFailed = 1u << 11;
inline constexpr std::uint32_t kIsStreaming = 1u << 12;
inline constexpr std::uint32_t kReferenceMark = 1u << 15;
} // namespace state

/// Move modes (4.4.8).
enum class MoveMode : std::int32_t { ClAbsolute = 0, ClRelative = 1, ScanAbsolute = 2, ScanRelative = 3, Step = 4 };
/// Sensor power modes (4.4.23).
enum class SensorPower : std::int32_t { Disabled = 0, Enabled = 1, PowerSave = 2 };

/// The volatile and non-volatile settings a channel keeps itself (the table's stored properties
/// are the controller's).
struct ChannelSettings {
    std::int64_t velocity = 0;        ///< pm/s; 0: no velocity control
    std::int64_t acceleration = 0;    ///< pm/s²; 0: no acceleration control
    std::int64_t hold_ms = 0xffffffffLL;   ///< SA_CTL_INFINITE by default
    std::int64_t control_options = 0; ///< PCONtrol:OPTions (non-volatile)
    std::int64_t max_frequency = 18500;
    std::int64_t step_frequency = 1000;
    std::int64_t step_amplitude = 65535;
    std::int64_t scan_velocity = 65535;
    std::int64_t referencing_options = 0;
    std::int64_t calibration_options = 0;
    std::int64_t safe_direction = 0;  ///< non-volatile
    std::int64_t range_min = 0;
    std::int64_t range_max = 0;
};

class Channel {
public:
    /// The guide's "few milliseconds" a power-save sensor takes to power up (2.9).
    static constexpr std::int64_t kSensorPowerUp_ms = 5;
    /// How far a reference search overshoots the mark before returning to it (2.7.2), unit.
    static constexpr double kOvershoot = 50'000'000;   // 50 µm

    /// The positioner joins `world` under `key`; `index` seeds its step jitter.
    Channel(int index, const ChannelConfig& config, models::World& world, const std::string& key);
    ~Channel();
    Channel(const Channel&) = delete;
    Channel& operator=(const Channel&) = delete;

    /// Power-up: motion stopped, position unknown (reading 0 where the stage stands), volatile
    /// settings to their defaults; the non-volatile ones (type, scale, calibration) kept.
    void power_up();
    /// Non-volatile settings back to the rig's (a power cycle that erases them).
    void restore_defaults();

    ChannelSettings& settings() { return settings_; }
    const ChannelSettings& settings() const { return settings_; }

    // ---- properties with behaviour ----
    std::uint32_t state_word() const;
    /// Channel Error (4.10.1): the last error, reset to 0 by reading it.
    std::int32_t take_error() { return std::exchange(error_, 0); }
    std::int32_t last_error() const { return error_; }
    std::int32_t type_code() const { return modified_ ? 0 : type_code_; }
    std::string type_name() const;
    const PositionerType& type() const { return *type_; }
    /// Positioner Type (4.4.6): stops, clears IS_CALIBRATED and IS_REFERENCED. A custom slot
    /// (250-253) is taken once a type was saved there.
    std::optional<Error> set_type(std::int64_t code);
    SensorPower sensor_power() const { return sensor_power_; }
    std::optional<Error> set_sensor_power(std::int64_t mode);
    bool amplifier() const { return amplifier_; }
    void set_amplifier(bool on);
    /// The module's power supply (4.3.1): off stops the channel and refuses movements.
    void set_power_supply(bool on);
    std::int32_t loop_input() const { return loop_input_; }
    std::optional<Error> set_loop_input(std::int64_t input);
    std::int32_t actuator_mode() const { return actuator_mode_; }
    std::optional<Error> set_actuator_mode(std::int64_t mode);
    std::optional<Error> set_velocity(std::int64_t v);
    std::optional<Error> set_acceleration(std::int64_t a);
    std::optional<Error> set_hold_time(std::int64_t ms);

    /// Position on the logical scale (pm or n°).
    std::int64_t position() const;
    /// Position (4.4.10) written: the scale shifts so that the stage reads `p` here (11.5).
    std::optional<Error> set_position(std::int64_t p);
    std::int64_t target() const { return target_; }
    /// The piezo's scan level, 0..65535.
    std::int64_t scan_position() const;
    /// The sensor's own reading (4.4.27): the position, whatever the control-loop input.
    std::optional<Error> sensor_value(std::int64_t& out) const;
    std::int64_t scale_offset() const { return scale_offset_; }
    void set_scale_offset(std::int64_t offset);
    bool scale_inverted() const { return inverted_; }
    void set_scale_inverted(bool inverted);
    std::int64_t distance_to_mark() const { return distance_to_mark_; }

    // ---- tuning (4.8): behind the write protection, "modified" until saved to a custom slot ----
    /// The 15 tuning properties, in the order of Id::TunMovementType..Id::TunTargetHold.
    static constexpr std::size_t kTuningCount = 15;
    using Tuning = std::array<std::int64_t, kTuningCount>;
    const Tuning& tuning() const { return tuning_; }
    bool write_protected() const { return write_protected_; }
    void set_write_protection(std::int64_t key) { write_protected_ = key != 0x534D4152; }
    /// Write tuning value `i`: PERMISSION_DENIED while protected; the type then reads 0, "modified".
    std::optional<Error> set_tuning(std::size_t i, std::int64_t value);
    /// :TUNing:SAVE: the modified set into custom slot `slot` (250-253), which becomes the type.
    std::optional<Error> save_tuning(std::int64_t slot);

    // ---- movement commands (3.2.34-3.2.37) ----
    /// :MOVE#: by the move mode (10.2). A command that cannot start sets MOVEMENT_FAILED and the
    /// channel error, and returns the error.
    std::optional<Error> move(MoveMode mode, std::int64_t value);
    std::optional<Error> calibrate();
    std::optional<Error> reference();
    /// :STOP#: stops any movement and the holding; the movement's result is ABORTED.
    void stop();
    /// Trajectory streaming (2.15): the channel takes part (IS_STREAMING) and refuses movement
    /// commands meanwhile (BUSY_STREAMING); `false` ends its part, at rest where it is.
    void set_streaming(bool on);
    bool streaming() const { return streaming_; }
    /// One frame's target (logical, unit), reached in `duration` ticks at constant speed (linear
    /// interpolation), or as fast as the stage goes (`interpolate` false).
    void stream_to(double target, Ticks duration, bool interpolate);
    /// The stream ended the channel's part with `e` (a buffer underflow, an abort).
    void stream_failed(Error e);
    /// Why a movement cannot start now, if it cannot (locked device, power, amplifier, sensor).
    std::optional<Error> movement_refused(bool closed_loop) const;
    void set_locked(bool locked) { locked_ = locked; }
    bool moving() const { return motion_ != Activity::Idle && motion_ != Activity::Holding; }
    /// An end stop met since the last call (for the broadcast stop, 10.9).
    bool take_end_stop_event() { return std::exchange(end_stop_event_, false); }
    /// A calibration with Detect Distance Code Inversion ended since the last call: Distance Code
    /// Inverted (4.7.3) is to read what it found, 0.
    bool take_code_inversion_detected() { return std::exchange(code_inversion_detected_, false); }

    // ---- set-up and faults (control API) ----
    const models::StickSlipPositioner& body() const { return body_; }
    models::StickSlipPositioner& body() { return body_; }
    void set_referenced(bool known);
    void set_sensor_failed(bool failed);
    bool sensor_failed() const { return sensor_failed_; }
    /// A sensor that reads: configured, and not failed.
    bool has_sensor() const { return config_.sensor && !sensor_failed_; }
    void place_at_start() { body_.place(static_cast<double>(config_.start_position) / 1000.0); }
    /// "completed", "stopped", "end_stop", "range_limit", "reference_not_found", "stalled", or "".
    const char* last_outcome() const { return outcome_; }
    const ChannelConfig& config() const { return config_; }
    std::pair<double, double> travel() const { return {travel_min_, travel_max_}; }

    Ticks next_change(Ticks now) const;
    void tick(Ticks now);

private:
    enum class Activity { Idle, MoveDelay, Targeting, Holding, Calibrating, Referencing, Stepping, Scanning };

    double physical_now() const { return body_.position_nm() * 1000.0; }
    double logical_from_physical(double physical) const;
    double physical_from_logical(double logical) const;
    double top_speed() const;
    bool range_limited() const { return settings_.range_max > settings_.range_min; }
    
    void apply_type();
    void fail(Error e);
    /// Start `start` now, or after the sensor powered up (power save, MOVE_DELAYED).
    void begin(Activity motion, std::function<void()> start);
    void start_closed_loop(double target_logical);
    void finish(Error result, const char* outcome);
    void on_body_event(Ticks now);
    void arrive(Ticks now);
    void plan_reference();
    void end_reference();

    const Clock& clock_;
    ChannelConfig config_;
    models::StickSlipPositioner& body_;
    bool body_event_ = false;
    const PositionerType* type_;
    std::int32_t type_code_;
    bool modified_ = false;
    Tuning tuning_{};
    bool write_protected_ = true;
    struct Slot {
        const PositionerType* base;
        Tuning tuning;
    };
    std::array<std::optional<Slot>, 4> slots_;   ///< custom slots 250-253 (non-volatile)
    double travel_min_;
    double travel_max_;
    ChannelSettings settings_;
    SensorPower sensor_power_ = SensorPower::Enabled;
    bool amplifier_ = true;
    bool power_supply_ = true;
    bool locked_ = false;
    std::int32_t loop_input_ = 1;
    std::int32_t actuator_mode_ = 0;
    std::int32_t error_ = 0;
    std::uint32_t sticky_ = 0;       ///< END_STOP/RANGE_LIMIT/FOLLOWING/MOVEMENT_FAILED bits
    bool calibrated_ = false;        ///< non-volatile (2.6.1)
    bool referenced_ = false;
    double unknown_base_ = 0;        ///< unreferenced: logical = physical - unknown_base_
    std::int64_t scale_offset_ = 0;  ///< non-volatile
    bool inverted_ = false;          ///< non-volatile
    std::optional<double> frozen_;   ///< sensor disabled: the reading stays here
    bool sensor_failed_ = false;
    std::int64_t target_ = 0;
    std::int64_t distance_to_mark_ = 0;
    Activity motion_ = Activity::Idle;
    Activity pending_motion_ = Activity::Idle;
    std::function<void()> pending_;
    Ticks delay_until_ = 0;
    Ticks hold_until_ = 0;
    Ticks calibrate_until_ = 0;
    std::optional<Error> arrival_error_;   ///< the target lay past an end stop or the range limit
    // Referencing: the legs driven, and where the reference lies (physical) once found.
    bool reference_found_ = false;
    double reference_point_ = 0;
    double reference_start_ = 0;
    bool end_stop_event_ = false;
    bool braking_ = false;           ///< a first stop brakes the closed-loop move under way
    double move_acceleration_ = 0;   ///< the closed-loop move's acceleration (unit/s²; 0: none)
    bool streaming_ = false;         ///< part of a trajectory stream
    bool code_inversion_detected_ = false;
    // What a reference search commits when it ends (4.7.2: "updated when a referencing sequence
    // finishes"): the reference point, the distance to the mark, the auto-zero offset.
    double pending_point_ = 0;
    std::int64_t pending_distance_ = 0;
    std::optional<std::int64_t> pending_offset_;
    std::optional<std::pair<double, double>> found_at_;   ///< the mark's physical position, the passing direction
    void commit_reference();
    const char* outcome_ = "";
};

} // namespace rigsim::mcs2
