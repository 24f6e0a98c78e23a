#pragma once
// One APT motor channel: parameters (SET/REQ/GET trios), position counters, homing and
// backlash legs, and the status bits of MOT_GET_DCSTATUSUPDATE. No I/O, no physics: the
// channel's models::Axis (in the World under the channel's key) moves; the channel translates
// APT units (7.1), counters and offsets, limit switch modes and the axis's events.

#include "emulator/apt/catalogue.hpp"
#include "models/clock.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rigsim::models {
class Axis;
class World;
enum class AxisEvent;
} // namespace rigsim::models

namespace rigsim::apt {

/// Status bits (MOT_GET_STATUSUPDATE / MOT_GET_DCSTATUSUPDATE tables; errata: 0x00000008).
namespace status {
inline constexpr std::uint32_t kForwardHardLimit = 0x00000001;
inline constexpr std::uint32_t kReverseHardLimit = 0x00000002;
inline constexpr std::uint32_t kForwardSoftLimit = 0x00000004;
inline constexpr std::uint32_t kReverseSoftLimit = 0x00000008;   ///< errata: "80000000x0"
inline constexpr std::uint32_t kMovingForward = 0x00000010;
inline constexpr std::uint32_t kMovingReverse = 0x00000020;
inline constexpr std::uint32_t kJoggingForward = 0x00000040;
inline constexpr std::uint32_t kJoggingReverse = 0x00000080;
inline constexpr std::uint32_t kMotorConnected = 0x00000100;
inline constexpr std::uint32_t kHoming = 0x00000200;
inline constexpr std::uint32_t kHomed = 0x00000400;
inline constexpr std::uint32_t kSettled = 0x00002000;
inline constexpr std::uint32_t kMotionError = 0x00004000;    ///< excessive position error (p. 79)
inline constexpr std::uint32_t kCurrentLimit = 0x01000000;   ///< motor current limit reached (p. 79)
inline constexpr std::uint32_t kEnabled = 0x80000000;
} // namespace status

/// What a channel reports by itself when a movement ends. A Fault (the carriage ran into its
/// mechanical end stop with the limit switch ignored: the motor stalls) precedes the Stopped
/// of the move it ended.
enum class MotorEvent { MoveCompleted, Homed, Stopped, Fault };

struct VelocityParams { std::int32_t min = 0, acceleration = 0, max = 0; };
struct JogParams {
    std::uint16_t mode = 2;          ///< 1 continuous, 2 single step
    std::int32_t step_size = 0;
    VelocityParams velocity;
    std::uint16_t stop_mode = 2;     ///< 1 immediate, 2 profiled
};
struct HomeParams {
    std::uint16_t direction = 2;     ///< 1 forward, 2 reverse
    std::uint16_t limit_switch = 1;  ///< 1 hardware reverse, 4 hardware forward
    std::int32_t velocity = 0;
    std::int32_t offset = 0;
};
struct LimitSwitchParams {
    /// 1 ignore (or no switch), 2/3 makes/breaks on contact, 4/5 the same for homing only,
    /// 6 index mark (PMD); the upper bit (0x80) marks swapped switches. CW is forward.
    std::uint16_t cw_hard = 2, ccw_hard = 2;
    std::int32_t cw_soft = 0, ccw_soft = 0;
    std::uint16_t mode = 1;                     ///< 1: ignore software limits
};

class MotorChannel {
public:
    /// The channel's axis joins `world` under `key` ("<device>/<bay>"). It counts `stage` as
    /// the controller does (driven_stage: a later-generation stepper's finer microsteps).
    MotorChannel(const ControllerModel& controller, const StageModel& stage, models::World& world,
                 const std::string& key);
    ~MotorChannel();
    MotorChannel(const MotorChannel&) = delete;
    MotorChannel& operator=(const MotorChannel&) = delete;

    std::int32_t position() const;               ///< position counter (counts)
    void set_position(std::int32_t counts);
    std::int32_t encoder() const;
    void set_encoder(std::int32_t counts);
    /// Actual velocity for DCSTATUSUPDATE (APT velocity units / 65536 as the manual's word).
    std::int16_t velocity_word() const;
    std::uint32_t status_bits() const;

    bool enabled() const { return enabled_; }
    /// The stage's power-up velocity parameters: its design limits (PMDSTAGEAXISPARAMS).
    const VelocityParams& design_velocity() const { return design_velocity_; }
    /// The stage as this controller counts it (driven_stage).
    const StageModel& stage() const { return stage_; }
    /// The travel the controller allows, in the stage's own counts from its reverse end
    /// (MOT_GET_PMDSTAGEAXISPARAMS Min/MaxPos, p. 75: "typically zero" and the travel).
    std::int32_t min_position() const;
    std::int32_t max_position() const;
    /// MOT_SET_PMDSTAGEAXISPARAMS may only raise the minimum and lower the maximum; the
    /// controller then stops moves there (the end stops stay where they are).
    void narrow_travel(std::int32_t min_position, std::int32_t max_position);
    void set_enabled(bool e);

    VelocityParams velocity;
    JogParams jog;
    HomeParams home_params;
    LimitSwitchParams limit_switch;
    std::int32_t backlash = 0;
    /// MOT_SET_PMDPROFILEMODEPARAMS: 0 trapezoidal, 2 S-curve with `jerk` (PMD jerk units).
    std::uint16_t profile_mode = 0;
    std::uint32_t jerk = 0;
    std::int32_t relative_distance = 0;
    std::int32_t absolute_position = 0;

    void move_absolute(std::int32_t counts);
    void move_relative(std::int32_t counts);
    void home();
    /// MOVE_JOG: one step of the jog step size (single step mode) or until stopped.
    void jog_move(bool forward);
    /// MOVE_VELOCITY: run at the velocity parameters until stopped or at a limit.
    void move_velocity(bool forward);
    /// MOVE_STOP: 1 immediate, 2 profiled (decelerate).
    void stop(bool immediate);
    bool moving() const { return motion_ != Motion::Idle; }
    /// On the way to the home switch or backing off from it.
    bool homing() const { return motion_ == Motion::HomingToLimit || motion_ == Motion::HomingBackOff; }

    /// End-of-move events since the last call. Also hands the axis the LIMSWITCHPARAMS
    /// written to `limit_switch` since (the device calls this after every batch of messages).
    std::vector<MotorEvent> take_events();

    /// For the device's clock hook: due at once while end-of-move events wait to be sent.
    Ticks next_change(Ticks now) const;

    /// The physics of this channel (World key "<device>/<bay>").
    const models::Axis& axis() const { return axis_; }
    models::Axis& axis() { return axis_; }

    // ---- Control API (docs/control-api/apt.md): set-up and faults ----
    bool homed() const { return homed_; }
    /// The homed status bit, as if homing had (or had not) been done.
    void set_homed(bool homed) { homed_ = homed; }
    /// The carriage to `counts` of the axis (from a linear stage's reverse end, from 0° of a
    /// rotation stage or goniometer), at rest; the counters follow.
    void place(double counts);
    /// A limit switch reads pressed (+1 forward, -1 reverse, 0 none: the axis's, from a
    /// limit_switch fault or a test's set-up): its status bit is set, a move toward it stops at
    /// once as the switch would stop it.
    int switch_pressed() const;
    /// The stage's stall fault (models::Axis::faults()): a DC servo or brushless motor ends a move
    /// with the current limit or motion error fault; a stepper loses its microsteps.
    bool stalled() const;
    /// Read the axis's faults: when its encoder failed (sensor_failure) the counter stops and a
    /// servo's position loop cannot hold (motion error, no move); a stepper (open loop) still
    /// moves.
    void sync_faults();
    bool encoder_failed() const { return encoder_failed_; }
    /// Power-up state: parameters, counters (0 where the carriage stands), not homed, enabled.
    void power_up();
    /// The carriage's configured power-up position (stage counts).
    double start_position_counts() const;

private:
    enum class Motion { Idle, Moving, Jogging, HomingToLimit, HomingBackOff, Stopping };

    /// The axis position (counts) of the stage's reverse end, from which the stage's own
    /// counts run (PMDSTAGEAXISPARAMS): 0 but for a goniometer, whose axis counts from 0°.
    double reverse_end_counts() const;
    /// APT velocity units per count/s and acceleration units per count/s² (7.1).
    double velocity_factor() const;
    double acceleration_factor() const;
    double counts_per_s(std::int32_t apt_velocity) const;
    double counts_per_s2(std::int32_t apt_acceleration) const;
    /// Whether the hardware limit switch ahead stops the axis (LIMSWITCHPARAMS hard modes).
    bool switch_stops(bool forward, bool homing) const;
    /// Hand the axis the rules of the leg `leg`: which switches stop it, its soft stops.
    void sync_axis(Motion leg);
    /// The carriage position (axis counts) at which the position counter reads 0.
    double counter_origin() const;
    void start_profile(double target_physical, double v, double a, Motion motion);
    void on_axis_event(models::AxisEvent event);
    /// What follows when the motion reaches its end: the next leg, or the end-of-move event.
    void conclude();
    void complete_homing();
    bool soft_limits_active() const;
    double within_soft_limits(double target_physical) const;
    void move_to(double target_physical);
    /// The power-up parameters of the stage (velocity, jog, home, limit switches).
    void set_power_up_params();

    const ControllerModel& controller_;
    const StageModel stage_;
    models::Axis& axis_;
    bool enabled_ = true;
    bool homed_ = false;
    double counter_offset_;          ///< motor position (axis counts) at which the position counter reads 0
    double encoder_offset_;
    Motion motion_ = Motion::Idle;
    bool jog_direction_forward_ = true;
    bool homing_forward_ = false;
    VelocityParams design_velocity_;
    std::uint32_t fault_bits_ = 0;   ///< kCurrentLimit / kMotionError until the next move
    bool encoder_failed_ = false;    ///< the axis's sensor_failure fault, as the counters last saw it
    std::int32_t frozen_position_ = 0;   ///< counters read while the encoder has failed
    std::int32_t frozen_encoder_ = 0;
    std::vector<MotorEvent> events_;
    /// What sync_axis() last handed the axis (it depends on nothing else): take_events() after
    /// every batch of messages then costs a comparison.
    struct Synced {
        LimitSwitchParams limit_switch;
        Motion leg;
        double counter_offset;
    };
    std::optional<Synced> synced_;
    std::optional<double> pending_backlash_target_;   ///< counter value of the forward approach after a backlash overshoot
};

} // namespace rigsim::apt
