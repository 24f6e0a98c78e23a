#pragma once
// One MCS positioner channel: the protocol's view of a stick-slip positioner: sensor,
// measuring scale, reference, range limit, closed-loop settings, status codes, event
// receivers and command queue. The physics (steps, scans, closed-loop profiles, end stops)
// is the channel's body in the world, models::StickSlipPositioner under "<device>/<index>":
// the channel commands it in physical units and reads its position at the clock's now.
// No I/O. What the channel reports by itself (asynchronous errors, completion, triggered)
// is queued in events() for the controller to deliver.

#include "models/clock.hpp"
#include "emulator/mcs/config.hpp"
#include "emulator/mcs/commands.hpp"
#include "emulator/mcs/errors.hpp"
#include "emulator/mcs/firmware.hpp"
#include "emulator/mcs/sensor_types.hpp"
#include "models/stick_slip.hpp"
#include "models/world.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rigsim::mcs {

/// Channel status codes of appendix 4.1 (8: gripper moving, per the errata).
enum class ChannelStatus : int {
    Stopped = 0,
    Stepping = 1,
    Scanning = 2,
    Holding = 3,
    Targeting = 4,
    MoveDelay = 5,
    Calibrating = 6,
    FindingReferenceMark = 7,
    GripperMoving = 8,
    Locked = 9,
};

/// GCT channel types.
enum class ChannelType : int { Positioner = 0, EndEffector = 1 };

/// Sensor operation modes (2.3.2; SSE, channel property 134938625).
enum class SensorMode : int { Disabled = 0, Enabled = 1, PowerSave = 2 };

/// Something a channel reports by itself; the controller turns it into an answer.
struct ChannelEvent {
    enum class Kind {
        Error,       ///< an asynchronous error (142, 144, 147)
        Completed,   ///< a movement completed (SRC)
        Triggered,   ///< a queued command was triggered (SRT)
    };
    Kind kind;
    ErrorCode code = ErrorCode::None;   ///< for Kind::Error
};

class Channel {
public:
    /// The hold time that means "hold until stopped" (MPA/MPR, manual 3.3).
    static constexpr std::int32_t kHoldForever_ms = 60'000;
    static constexpr std::int32_t kMaxClosedLoopSpeed = 100'000'000;       ///< SCLS range
    static constexpr std::int32_t kMaxClosedLoopAcceleration = 10'000'000; ///< SCLA range
    static constexpr std::int32_t kMinFrequency_hz = 50;                   ///< SCLF range
    static constexpr std::int32_t kMaxFrequency_hz = 18'500;
    /// Power save: "it takes a few milliseconds to power up the sensor" (2.3.2).
    static constexpr std::int64_t kSensorPowerUp_ms = 5;
    /// Acceleration that enabling low vibration mode switches on (2.5.1 "default settings").
    static constexpr std::int32_t kDefaultLowVibrationAcceleration = 1'000'000;

    /// The channel's positioner joins `world` under `key` ("<device>/<index>"); `firmware`:
    /// the generation whose commands it answers (FRM's directions, firmware.hpp).
    Channel(int index, const McsChannelConfig& config, Firmware firmware, models::World& world,
            const std::string& key);
    ~Channel();
    Channel(const Channel&) = delete;
    Channel& operator=(const Channel&) = delete;

    ChannelType type() const { return ChannelType::Positioner; }
    ChannelStatus status() const;
    /// Appendix 4.3 entry, or nullptr for a positioner without sensor.
    const SensorType* sensor() const { return sensor_; }

    /// Back to the power-up state (R): motion stopped, position unknown and reading 0 where
    /// the stage stands, volatile settings to their defaults. Non-volatile settings (sensor
    /// type, scale, safe direction, sensor mode) are kept.
    void reset();

    /// SST: implicitly stops the positioner.
    std::optional<ErrorCode> set_sensor_type(std::int32_t code);
    SensorMode sensor_mode() const { return sensor_mode_; }
    /// SSE / channel property: implicitly stops the positioner.
    void set_sensor_mode(SensorMode mode);

    /// Errors 129 (no sensor), 140 (sensor disabled), 143 (not a linear sensor).
    std::optional<ErrorCode> check_linear_sensor() const;
    /// Errors 129, 140, 143 (not a rotary or goniometer sensor).
    std::optional<ErrorCode> check_angular_sensor() const;
    /// Position on the logical scale: nm, or µ° (angle + 360,000,000 × revolution).
    std::int64_t position() const;
    std::int64_t position_nm() const { return position(); }
    bool physical_position_known() const;

    /// MPA/MAA (`position` in nm or µ°), MPR/MAR (`distance`).
    std::optional<ErrorCode> move_absolute(std::int64_t position, std::int32_t hold_ms);
    std::optional<ErrorCode> move_relative(std::int64_t distance, std::int32_t hold_ms);
    std::optional<ErrorCode> move_angle_absolute(std::int64_t position_udeg, std::int32_t hold_ms);
    std::optional<ErrorCode> move_angle_relative(std::int64_t distance_udeg, std::int32_t hold_ms);
    /// FRM (2.3.3): search the reference mark(s), or the end stop in the safe direction;
    /// `direction` as the firmware generation reads it (frm_direction()).
    std::optional<ErrorCode> find_reference(std::int32_t direction, std::int32_t hold_ms, std::int32_t auto_zero);
    /// CS: status 6 for the calibration time; end-stop types end at the safe end stop.
    std::optional<ErrorCode> calibrate();
    /// MST: a burst of open-loop steps (status 1); ±30000 steps run until stopped, 0 stops.
    std::optional<ErrorCode> move_steps(std::int32_t steps, std::int32_t amplitude, std::int32_t frequency_hz);
    /// MSCA/MSCR: scan the piezo to a 12-bit level at `speed` levels per second (status 2).
    std::optional<ErrorCode> scan_absolute(std::int32_t target, std::int64_t speed);
    std::optional<ErrorCode> scan_relative(std::int32_t diff, std::int64_t speed);
    /// GVL: the piezo voltage level 0..4095.
    std::int32_t voltage_level() const;
    void stop();

    /// SPL/SAL (2.3.4): software range limit on the logical scale; min == max removes it.
    /// 148 while the physical position is unknown.
    std::optional<ErrorCode> set_range_limit(std::int64_t min, std::int64_t max);
    /// Current limit (0,0 when none).
    std::pair<std::int64_t, std::int64_t> range_limit() const;

    /// SP (and SZP with 0): the current position reads `position` from now on (2.3.3).
    std::optional<ErrorCode> set_position(std::int64_t position);
    /// SSC: shift and inversion of the logical scale (2.3.3, "Shifting the Measuring Scale").
    std::optional<ErrorCode> set_scale(std::int32_t offset, std::int32_t inverted);
    std::int32_t scale_offset() const { return scale_offset_; }
    bool scale_inverted() const { return scale_inverted_; }
    std::optional<ErrorCode> set_safe_direction(std::int32_t direction);
    std::int32_t safe_direction() const { return safe_direction_; }
    std::optional<ErrorCode> set_accumulate_relative(std::int32_t accumulate);
    std::optional<ErrorCode> set_step_while_scan(std::int32_t step);
    bool step_while_scan() const { return step_while_scan_; }

    std::optional<ErrorCode> set_closed_loop_speed(std::int32_t speed_nm_per_s);
    std::optional<ErrorCode> set_closed_loop_acceleration(std::int32_t acceleration_um_per_s2);
    std::optional<ErrorCode> set_closed_loop_max_frequency(std::int32_t frequency_hz);
    std::int32_t closed_loop_speed() const { return speed_nm_per_s_; }
    std::int32_t closed_loop_acceleration() const { return acceleration_um_per_s2_; }

    /// SRC: report completed movements (asynchronous mode only; checked by the handler).
    void set_report_on_complete(bool report) { report_on_complete_ = report; }
    /// SRT: report T<ch> when a queued command is triggered.
    void set_report_on_triggered(bool report) { report_on_triggered_ = report; }
    bool report_on_triggered() const { return report_on_triggered_; }

    /// GCP/SCP (2.2, appendix 4.4). Errors: 154 component, 155 sub component, 156 property
    /// (also for writing a read-only property), 7 value out of range, 150 not stopped.
    std::optional<ErrorCode> get_property(std::uint32_t key, std::int64_t& value) const;
    std::optional<ErrorCode> set_property(std::uint32_t key, std::int64_t value);

    /// Emergency stop (2.2.1): a falling edge of the ES line; `rising` the edge after it.
    void emergency_stop_edge(bool rising);
    bool locked() const { return locked_; }
    /// SESM: every channel's emergency stop mode; any SESM unlocks.
    void set_emergency_stop_mode(std::int32_t mode);
    /// Broadcast stop (2.2.3): this channel detected an end stop and wants every channel
    /// stopped; the controller reads and clears the flag.
    bool take_broadcast_request() { return std::exchange(broadcast_request_, false); }

    /// Event receivers (2.4): counter 0, capture buffer 0, command queue.
    void on_event(std::int32_t source);
    /// GB buffer 0: position, revolution, counter 0 at the last capture.
    std::array<std::int64_t, 3> capture_buffer() const { return capture_; }
    /// Command queue (2.4.5), capacity 1.
    static constexpr std::size_t kQueueCapacity = 1;
    std::size_t queue_size() const { return queue_.size(); }
    void arm_queue(std::int32_t source) { atc_source_ = source; }
    std::optional<std::int32_t> armed_queue_source() const { return atc_source_; }
    /// Append the command that followed ATC; 153 when full.
    std::optional<ErrorCode> enqueue(Command command);
    void disarm_queue() { atc_source_.reset(); }
    void clear_queue();
    /// Queued commands whose trigger arrived, for the controller to execute in order.
    std::vector<Command> take_triggered();
    /// take_triggered() would return some.
    bool has_triggered() const { return !triggered_.empty(); }

    /// Messages the channel sends by itself: asynchronous errors (142, 147, 144) and
    /// completion reports. The controller delivers them only in asynchronous mode.
    std::vector<ChannelEvent>& events() { return events_; }

    /// The positioner in the world.
    const models::StickSlipPositioner& body() const { return body_; }
    models::StickSlipPositioner& body() { return body_; }

    // ---- Control API (docs/control-api/mcs.md): set-up and faults, not reachable by wire ----

    /// How the last movement ended: "completed", "stopped", "end_stop" (142), "range_limit"
    /// (147), "reference_not_found" (144), "stalled", "sensor_failure"; "" before any.
    const char* last_outcome() const { return outcome_; }
    /// The physical position becomes known (as after FRM at the configured mark) or unknown
    /// (the reading stays where it is, GPPK answers 0).
    void set_referenced(bool known);
    /// A failed sensor reads as none (129 for closed-loop commands, GP, FRM, CS, SP); a
    /// closed-loop movement stops and the physical position is lost. Repaired: the reading
    /// starts again at 0 where the stage stands, position unknown.
    void set_sensor_failed(bool failed);
    bool sensor_failed() const { return sensor_failed_; }
    /// Non-volatile settings back to the config: sensor type and mode, scale, safe
    /// direction, default emergency stop mode (a power cycle that erases them).
    void restore_defaults();
    /// The stage back at its configured start position (at rest).
    void place_at_start() { body_.place(static_cast<double>(config_.start_position_nm)); }
    /// The command queue as commands (queued, with their trigger sources).
    const std::vector<std::pair<std::int32_t, Command>>& queued() const { return queue_; }
    /// The physical travel a stage may be placed in (end stops; ±infinity when endless).
    std::pair<double, double> travel() const { return {travel_min(), travel_max()}; }
    bool rotary() const { return angular(); }

    /// Protocol timers (hold, move delay, calibration) and events of the body not yet
    /// handled: the next tick tick() must run at, or kNever. Never now + 1 merely because
    /// the positioner moves.
    Ticks next_change(Ticks now) const;
    void tick(Ticks now);

private:
    enum class Motion { Idle, MoveDelay, Targeting, Holding, Referencing, Calibrating, Stepping, Scanning };

    /// A physical position (nm or µ° on the travel axis) as read on the logical scale, and back.
    double logical_from_physical(double physical) const;
    double physical_from_logical(double logical) const;
    double top_speed() const;
    bool angular() const;
    /// Rotary stages referenced by a mark (or not at all) have no end stops.
    bool endless() const;
    double travel_min() const;
    double travel_max() const;
    /// Physical bounds a movement may not pass: end stops and the software range limit; an
    /// empty limit leaves only where the stage stands.
    std::pair<double, double> physical_limit() const;
    /// SPL/SAL (3.2): a limit whose maximum is below its minimum, under which "the positioner
    /// will not move at all", open-loop or closed-loop (every movement but a scan, 2.3.4).
    bool empty_limit() const;
    /// Under an empty limit a movement ends where it starts: status 0 and, in asynchronous
    /// mode, `code` (147, or 144 for FRM). False (and nothing done) under any other limit.
    bool stop_at_empty_limit(ErrorCode code);

    std::optional<ErrorCode> check_move(std::int32_t hold_ms) const;
    /// Runs `start` now, or after the sensor powered up (power save mode, status 5).
    void begin_movement(std::function<void(Ticks)> start);
    void start_closed_loop(double target_physical, std::int32_t hold_ms, Ticks now);
    /// What the body's last event means for the protocol (tick()).
    void on_body_event(Ticks now);
    void arrive(Ticks now);
    /// The legs of a reference search from physical `here` in direction `dir` (+1/-1) between
    /// the turning points `lo` and `hi` (or, `abort_at_end`, up to the first of them): sets
    /// reference_legs_, reference_found_, reference_point_.
    void plan_reference_search(double here, double dir, double lo, double hi, bool abort_at_end);
    /// The search's last leg has ended: the reference is known now, or 144.
    void finish_reference(Ticks now);
    void finish_movement();
    void become_known(double reference_physical, bool auto_zero);
    /// Queue an unprompted error of this channel (async mode: 142, 144, 147).
    void post_error(ErrorCode code);
    /// 129 (no sensor, or a failed one), 140 (sensor disabled).
    std::optional<ErrorCode> sensor_error() const;
    /// The range limit as the body's open-loop bursts see it.
    models::StepLimit step_limit() const;
    /// Stepping with the sensor disabled (2.3.2): once a step is made the physical position
    /// is lost and the reading stays where it was; commit that to the scale.
    void commit_blind();
    bool blind_stepped() const;
    /// A burst ended (body outcome BurstDone or LimitMet).
    void end_burst(bool limit_met);

    Firmware firmware_;
    const Clock& clock_;
    models::StickSlipPositioner& body_;
    bool body_event_ = false;        ///< the body had an event that tick() has not handled
    McsChannelConfig config_;
    const SensorType* sensor_;
    SensorMode sensor_mode_;
    double travel_min_nm_;
    double travel_max_nm_;
    double reference_nm_;            ///< physical position of the reference point

    // Measuring scale (2.3.3). Unknown physical position: logical = physical - unknown_base_.
    // Known: logical = ±(physical - reference_nm_) + scale_offset_.
    bool known_ = false;
    double unknown_base_nm_;
    std::int32_t scale_offset_ = 0;  ///< non-volatile
    bool scale_inverted_ = false;    ///< non-volatile
    std::int32_t safe_direction_ = 0;
    bool accumulate_relative_ = true;
    bool step_while_scan_ = true;
    bool report_on_complete_ = false;
    bool report_on_triggered_ = false;

    // Channel properties (appendix 4.4).
    std::int32_t es_mode_ = 0;
    std::int32_t es_default_mode_ = 0;   ///< non-volatile
    bool locked_ = false;
    bool low_vibration_ = false;
    bool broadcast_stop_ = false;
    bool broadcast_request_ = false;
    bool forced_slip_ = true;            ///< 2.2.4: "enabled by default"
    std::array<std::int32_t, 2> digital_in_mode_{};
    std::array<std::int32_t, 2> digital_in_edge_{};
    std::int32_t counter_source_ = 0;
    std::int64_t counter_ = 0;
    std::int32_t capture_source_ = 0;
    std::array<std::int64_t, 3> capture_{};
    std::vector<std::pair<std::int32_t, Command>> queue_;   ///< trigger source, command
    std::optional<std::int32_t> atc_source_;
    std::vector<Command> triggered_;

    std::int32_t speed_nm_per_s_;
    std::int32_t acceleration_um_per_s2_;
    std::int32_t max_frequency_hz_ = kMaxFrequency_hz;

    Motion motion_ = Motion::Idle;
    std::function<void(Ticks)> pending_start_;   ///< movement waiting for the sensor
    Ticks delay_until_ = 0;
    Ticks hold_until_ = 0;           ///< kNever: hold until stopped
    std::int32_t hold_ms_ = 0;
    bool end_stop_hit_ = false;      ///< the target lay beyond a mechanical end stop
    bool limit_hit_ = false;         ///< the target lay beyond the software range limit
    std::optional<std::pair<std::int64_t, std::int64_t>> limit_;   ///< logical min, max
    // FRM: the legs planned for the body, and the outcome at the end of the last.
    std::vector<double> reference_legs_;
    bool reference_found_ = false;
    double reference_point_ = 0;     ///< physical position that becomes the reference
    bool auto_zero_ = false;
    double search_speed_ = 0;
    Ticks calibrate_until_ = 0;
    bool calibrated_ = false;
    /// MST with the sensor disabled: the logical position the reading stays at.
    std::optional<double> blind_logical_;
    double target_physical_nm_ = 0;  ///< MPR accumulates onto this while targeting
    std::vector<ChannelEvent> events_;
    bool sensor_failed_ = false;
    const char* outcome_ = "";
};

// Inline: the clock asks after every command (Controller::next_change, for each positioner).
inline Ticks Channel::next_change(Ticks now) const
{
    if (body_event_)
        return now + 1;
    switch (motion_) {
    case Motion::MoveDelay:
        return std::max(delay_until_, now + 1);
    case Motion::Holding:
        return hold_until_;
    case Motion::Calibrating:
        return std::max(calibrate_until_, now + 1);
    case Motion::Idle:
    case Motion::Targeting:
    case Motion::Referencing:
    case Motion::Stepping:
    case Motion::Scanning:
        return kNever;   // idle, or moving: the body wakes at the movement's events
    }
    return kNever;
}

} // namespace rigsim::mcs
