#include "emulator/apt/motor_channel.hpp"

#include "models/axis.hpp"
#include "models/world.hpp"

#include <algorithm>
#include <cmath>

namespace rigsim::apt {

namespace {

/// A rotation stage's "travel": far enough for any client, near enough for the 32-bit counter.
constexpr double kRotaryTravelCounts = 1 << 30;

models::AxisConfig axis_config(const ControllerModel& controller, const StageModel& stage)
{
    models::AxisConfig c;
    // DC servo and brushless motors stall at an end stop; a stepper loses its microsteps.
    c.drive = controller.motor == MotorKind::Stepper ? models::Drive::Stepper : models::Drive::Servo;
    const double cpu = stage.counts_per_mm;
    // The axis counts the physical position: from the reverse end stop of a linear stage, from
    // 0° of a rotation stage or a goniometer (whose end stops sit at its angle range).
    switch (stage.kind) {
    case StageKind::Linear:
        c.kind = models::BodyKind::Linear;
        c.travel_min_counts = 0.0;
        c.travel_max_counts = stage.travel_mm * cpu;
        break;
    case StageKind::Rotary:
        c.kind = models::BodyKind::Rotary;
        c.rotary = true;
        c.travel_min_counts = -kRotaryTravelCounts;
        c.travel_max_counts = kRotaryTravelCounts;
        break;
    case StageKind::Goniometer:
        c.kind = models::BodyKind::Goniometer;
        c.travel_min_counts = stage.angle_min_deg * cpu;
        c.travel_max_counts = stage.angle_max_deg * cpu;
        break;
    }
    // The stage's resolution for the world's physical face: counts per mm, per degree when it turns.
    constexpr double kPi = 3.14159265358979323846;
    c.si_per_count = stage.kind == StageKind::Linear ? 1e-3 / cpu : kPi / 180.0 / cpu;
    c.counts_per_turn = 360.0 * cpu;
    // Power-up: the stage stands mid-travel (a rotation stage half a turn from its home
    // switch); the counters read 0 there (not homed).
    c.start_position_counts = stage.kind == StageKind::Rotary
                                  ? 180.0 * cpu
                                  : c.travel_min_counts + (c.travel_max_counts - c.travel_min_counts) / 2;
    return c;
}

} // namespace

MotorChannel::MotorChannel(const ControllerModel& controller, const StageModel& stage, models::World& world,
                           const std::string& key)
    : controller_(controller), stage_(driven_stage(controller, stage)),
      axis_(world.emplace<models::Axis>(key, world.clock(), axis_config(controller, stage_)))
{
    set_power_up_params();
    counter_offset_ = axis_.motor_position_counts();
    encoder_offset_ = counter_offset_;
    axis_.set_listener([this](models::AxisEvent e) { on_axis_event(e); });
    sync_axis(motion_);
}

void MotorChannel::set_power_up_params()
{
    const double cpm = stage_.counts_per_mm;
    velocity = VelocityParams{};
    velocity.max = static_cast<std::int32_t>(std::lround(stage_.max_velocity_mm_s * cpm * velocity_factor()));
    velocity.acceleration = static_cast<std::int32_t>(std::lround(stage_.acceleration_mm_s2 * cpm * acceleration_factor()));
    design_velocity_ = velocity;
    jog = JogParams{};
    jog.step_size = static_cast<std::int32_t>(std::lround(0.1 * cpm));
    jog.velocity = velocity;
    home_params = HomeParams{};
    home_params.velocity = static_cast<std::int32_t>(std::lround(stage_.home_velocity_mm_s * cpm * velocity_factor()));
    home_params.offset = static_cast<std::int32_t>(std::lround(stage_.home_offset_mm * cpm));
    if (stage_.home_forward) {
        home_params.direction = 1;
        home_params.limit_switch = 4;
    }
    limit_switch = LimitSwitchParams{};
    // 1: no switch at that end (p. 39); a rotation stage's home switch is not a limit.
    const auto fitted = stage_.limit_switches;
    if (fitted == LimitSwitches::Reverse || fitted == LimitSwitches::None)
        limit_switch.cw_hard = 1;
    if (fitted == LimitSwitches::Forward || fitted == LimitSwitches::None)
        limit_switch.ccw_hard = 1;
    backlash = 0;
    profile_mode = 0;
    jerk = 0;
    relative_distance = 0;
    absolute_position = 0;
}

void MotorChannel::power_up()
{
    axis_.stop_immediately();
    motion_ = Motion::Idle;
    pending_backlash_target_.reset();
    events_.clear();
    set_power_up_params();
    axis_.set_limits(axis_.travel_min_counts(), axis_.travel_max_counts());
    enabled_ = true;
    homed_ = false;
    fault_bits_ = 0;
    counter_offset_ = axis_.motor_position_counts();
    encoder_offset_ = counter_offset_;
    frozen_position_ = frozen_encoder_ = 0;
    synced_.reset();
    sync_axis(motion_);
}

double MotorChannel::start_position_counts() const
{
    return axis_config(controller_, stage_).start_position_counts;
}

void MotorChannel::place(double counts)
{
    axis_.place(counts);
    frozen_position_ = position();
    frozen_encoder_ = encoder();
}

int MotorChannel::switch_pressed() const
{
    return axis_.switch_pressed();
}

bool MotorChannel::stalled() const
{
    return axis_.faults().stalled;
}

void MotorChannel::sync_faults()
{
    const bool failed = axis_.faults().sensor_failed;
    if (failed && !encoder_failed_) {
        frozen_position_ = position();
        frozen_encoder_ = encoder();
    }
    encoder_failed_ = failed;
    // A failed encoder leaves a servo without its position loop: it cannot move.
    axis_.set_loop_open(encoder_failed_ && controller_.motor != MotorKind::Stepper);
}

MotorChannel::~MotorChannel()
{
    axis_.set_listener({});   // the World outlives its devices
}

double MotorChannel::velocity_factor() const
{
    return stage_.velocity_per_mm_s > 0 ? stage_.velocity_per_mm_s / stage_.counts_per_mm : controller_.velocity_per_count_s;
}

double MotorChannel::acceleration_factor() const
{
    return stage_.acceleration_per_mm_s2 > 0 ? stage_.acceleration_per_mm_s2 / stage_.counts_per_mm
                                             : controller_.acceleration_per_count_s2;
}

double MotorChannel::counts_per_s(std::int32_t apt_velocity) const
{
    return std::abs(static_cast<double>(apt_velocity)) / velocity_factor();
}

double MotorChannel::counts_per_s2(std::int32_t apt_acceleration) const
{
    return std::abs(static_cast<double>(apt_acceleration)) / acceleration_factor();
}

double MotorChannel::reverse_end_counts() const
{
    // A goniometer's axis counts from 0°, its stage counts from its reverse end stop.
    return stage_.kind == StageKind::Goniometer ? axis_.travel_min_counts() : 0.0;
}

std::int32_t MotorChannel::min_position() const
{
    return static_cast<std::int32_t>(std::lround(axis_.limit_min_counts() - reverse_end_counts()));
}

std::int32_t MotorChannel::max_position() const
{
    return static_cast<std::int32_t>(std::lround(axis_.limit_max_counts() - reverse_end_counts()));
}

void MotorChannel::narrow_travel(std::int32_t min_position, std::int32_t max_position)
{
    const double lo = std::max(axis_.limit_min_counts(), min_position + reverse_end_counts());
    const double hi = std::min(axis_.limit_max_counts(), max_position + reverse_end_counts());
    if (lo < hi)
        axis_.set_limits(lo, hi);
}

double MotorChannel::counter_origin() const
{
    // The counters count the motor: a stepper's lost microsteps move the carriage's zero.
    return counter_offset_ - axis_.lost_counts();
}

std::int32_t MotorChannel::position() const
{
    // A servo's position counter is its encoder's (a stepper's counts its microsteps).
    if (encoder_failed_ && controller_.motor != MotorKind::Stepper)
        return frozen_position_;
    return static_cast<std::int32_t>(std::lround(axis_.motor_position_counts() - counter_offset_));
}

void MotorChannel::set_position(std::int32_t counts)
{
    counter_offset_ = axis_.motor_position_counts() - counts;
    sync_axis(motion_);   // the soft limits are in position steps
}

std::int32_t MotorChannel::encoder() const
{
    if (encoder_failed_)
        return frozen_encoder_;
    return static_cast<std::int32_t>(std::lround(axis_.motor_position_counts() - encoder_offset_));
}

void MotorChannel::set_encoder(std::int32_t counts)
{
    encoder_offset_ = axis_.motor_position_counts() - counts;
}

std::int16_t MotorChannel::velocity_word() const
{
    // DCSTATUSUPDATE (p. 79): "Scaling is 204.8 per mm/sec".
    const double word = axis_.velocity_counts_per_s() / stage_.counts_per_mm * 204.8;
    return static_cast<std::int16_t>(std::clamp(std::lround(word), -32768L, 32767L));
}

std::uint32_t MotorChannel::status_bits() const
{
    std::uint32_t bits = status::kMotorConnected | fault_bits_;
    if (encoder_failed_ && controller_.motor != MotorKind::Stepper)
        bits |= status::kMotionError;   // the position loop cannot hold without its encoder
    const double x = axis_.position_counts();
    const int pressed = axis_.switch_pressed();
    if (stage_.kind != StageKind::Rotary && (x <= axis_.travel_min_counts() + 0.5 || pressed < 0) && (limit_switch.ccw_hard & 0x7f) != 1)
        bits |= status::kReverseHardLimit;
    if (stage_.kind != StageKind::Rotary && (x >= axis_.travel_max_counts() - 0.5 || pressed > 0) && (limit_switch.cw_hard & 0x7f) != 1)
        bits |= status::kForwardHardLimit;
    if (soft_limits_active()) {
        if (position() >= limit_switch.cw_soft)
            bits |= status::kForwardSoftLimit;
        if (position() <= limit_switch.ccw_soft)
            bits |= status::kReverseSoftLimit;
    }
    switch (motion_) {
    case Motion::Idle:
        bits |= status::kSettled;
        break;
    case Motion::Moving:
    case Motion::Stopping:
        bits |= axis_.velocity_counts_per_s() >= 0 && axis_.target_counts() >= x ? status::kMovingForward
                                                                                : status::kMovingReverse;
        break;
    case Motion::Jogging:
        bits |= jog_direction_forward_ ? status::kJoggingForward : status::kJoggingReverse;
        break;
    case Motion::HomingToLimit:
    case Motion::HomingBackOff:
        bits |= status::kHoming;
        break;
    }
    if (homed_)
        bits |= status::kHomed;
    if (enabled_)
        bits |= status::kEnabled;
    return bits;
}

void MotorChannel::set_enabled(bool e)
{
    if (!e && moving())
        stop(true);   // a disabled channel does not move (MOD_SET_CHANENABLESTATE)
    enabled_ = e;
}

bool MotorChannel::switch_stops(bool forward, bool homing) const
{
    // p. 37: a brushless (MLS203) channel does not use the limit switches for homing.
    if (homing && controller_.motor == MotorKind::Brushless)
        return true;
    // p. 39: 1 ignores the switch (or there is none); 4 and 5 serve homing only.
    const auto mode = (forward ? limit_switch.cw_hard : limit_switch.ccw_hard) & 0x7f;
    return homing ? mode != 1 : mode == 2 || mode == 3 || mode == 6;
}

void MotorChannel::sync_axis(Motion leg)
{
    const auto& l = limit_switch;
    if (synced_ && synced_->leg == leg && synced_->counter_offset == counter_offset_
        && synced_->limit_switch.cw_hard == l.cw_hard && synced_->limit_switch.ccw_hard == l.ccw_hard
        && synced_->limit_switch.cw_soft == l.cw_soft && synced_->limit_switch.ccw_soft == l.ccw_soft
        && synced_->limit_switch.mode == l.mode)
        return;
    synced_ = Synced{l, leg, counter_offset_};
    const bool to_home_switch = leg == Motion::HomingToLimit;
    axis_.set_limit_switches(switch_stops(true, to_home_switch), switch_stops(false, to_home_switch));
    // LIMSWITCHPARAMS software limit mode 2 ("stop immediate at limit"): the axis stops dead
    // where it crosses a limit, except while homing. The limits are in position steps.
    const bool homing = to_home_switch || leg == Motion::HomingBackOff;
    if (!homing && soft_limits_active() && (limit_switch.mode & 0x7f) == 2)
        axis_.set_soft_stops(limit_switch.ccw_soft + counter_offset_, limit_switch.cw_soft + counter_offset_);
    else
        axis_.clear_soft_stops();
}

void MotorChannel::start_profile(double target_physical, double v, double a, Motion motion)
{
    fault_bits_ = 0;   // a new move clears a stall
    // The axis ends a move at the limit switch ahead, or at a travel that PMDSTAGEAXISPARAMS
    // narrowed; past an ignored switch it runs into the end stop.
    sync_axis(motion);
    if (v <= 0) {
        axis_.stop_immediately();
        motion_ = Motion::Idle;
        return;
    }
    // S-curve when MOT_SET_PMDPROFILEMODEPARAMS asks for it (p. 69); jerk scaling of 7.1.
    const double j = controller_.jerk_per_count_s3 > 0 ? jerk / controller_.jerk_per_count_s3 : 0;
    motion_ = motion;   // a move that ends at once concludes within move_to()
    axis_.move_to(target_physical, v, a, profile_mode == 2 ? j : 0.0);
}

bool MotorChannel::soft_limits_active() const
{
    const auto mode = limit_switch.mode & 0x7f;
    return (mode == 2 || mode == 3) && limit_switch.cw_soft > limit_switch.ccw_soft;
}

double MotorChannel::within_soft_limits(double target_physical) const
{
    // LIMSWITCHPARAMS software limits, in position steps (counter units). Mode 3 ("profiled
    // stop at limit") plans the move to stop there; mode 2 ("stop immediate at limit") runs on
    // and stops dead when it gets there (the axis's soft stops, sync_axis()).
    if (!soft_limits_active() || (limit_switch.mode & 0x7f) != 3)
        return target_physical;
    return std::clamp(target_physical, limit_switch.ccw_soft + counter_origin(), limit_switch.cw_soft + counter_origin());
}

void MotorChannel::move_to(double target_physical)
{
    target_physical = within_soft_limits(target_physical);
    // GENMOVEPARAMS backlash: a move in the reverse direction overshoots by the backlash
    // distance and comes back forward, so that every move ends approaching forward.
    if (backlash > 0 && target_physical < axis_.position_counts() - 0.5) {
        pending_backlash_target_ = target_physical - counter_origin();
        start_profile(target_physical - backlash, counts_per_s(velocity.max),
                      counts_per_s2(velocity.acceleration), Motion::Moving);
        return;
    }
    pending_backlash_target_.reset();
    start_profile(target_physical, counts_per_s(velocity.max), counts_per_s2(velocity.acceleration), Motion::Moving);
}

void MotorChannel::move_absolute(std::int32_t counts)
{
    if (!enabled_)
        return;
    move_to(counts + counter_origin());
}

void MotorChannel::move_relative(std::int32_t counts)
{
    if (!enabled_)
        return;
    move_to(axis_.position_counts() + counts);
}

void MotorChannel::home()
{
    if (!enabled_)
        return;
    // Drive to the configured limit switch at the homing velocity (HOMEPARAMS); a rotation
    // stage to its home switch, met once per turn.
    // p. 37: a brushless (MLS203) channel always homes in the positive direction.
    const bool to_forward = controller_.motor == MotorKind::Brushless || home_params.limit_switch == 4
                            || home_params.direction == 1;
    homed_ = false;
    homing_forward_ = to_forward;
    start_profile(stage_.kind == StageKind::Rotary ? axis_.next_home_switch_counts(to_forward) : axis_.run_target_counts(to_forward),
                  counts_per_s(home_params.velocity), counts_per_s2(velocity.acceleration), Motion::HomingToLimit);
}

void MotorChannel::jog_move(bool forward)
{
    if (!enabled_)
        return;
    pending_backlash_target_.reset();
    jog_direction_forward_ = forward;
    const double v = counts_per_s(jog.velocity.max);
    const double a = counts_per_s2(jog.velocity.acceleration);
    if (jog.mode == 1) {   // continuous: until stopped or at a limit
        start_profile(within_soft_limits(axis_.run_target_counts(forward)), v, a, Motion::Jogging);
        return;
    }
    const double step = forward ? jog.step_size : -jog.step_size;
    start_profile(within_soft_limits(axis_.position_counts() + step), v, a, Motion::Jogging);
}

void MotorChannel::move_velocity(bool forward)
{
    if (!enabled_)
        return;
    start_profile(within_soft_limits(axis_.run_target_counts(forward)), counts_per_s(velocity.max),
                  counts_per_s2(velocity.acceleration), Motion::Moving);
}

void MotorChannel::stop(bool immediate)
{
    pending_backlash_target_.reset();
    if (motion_ == Motion::Idle) {
        events_.push_back(MotorEvent::Stopped);   // MOVE_STOPPED for every MOVE_STOP
        return;
    }
    const double a = counts_per_s2(velocity.acceleration);
    if (immediate || a <= 0) {
        axis_.stop_immediately();
        motion_ = Motion::Idle;
        events_.push_back(MotorEvent::Stopped);
        return;
    }
    // Profiled stop: decelerate at the acceleration parameter; an end on the way stops the
    // axis first.
    motion_ = Motion::Stopping;
    sync_axis(motion_);
    axis_.stop_profiled(a);
}

void MotorChannel::on_axis_event(models::AxisEvent event)
{
    switch (event) {
    case models::AxisEvent::LostSteps:
        return;   // the counters count the motor's microsteps (motor_position_counts()): nothing to send
    case models::AxisEvent::Stalled:
        // The motor stalls against the stop: its current limit (DC servo) or the position error
        // limit (brushless, PMDPOSITIONLOOPPARAMS) trips, and the controller stops the axis.
        motion_ = Motion::Idle;
        pending_backlash_target_.reset();
        fault_bits_ = controller_.motor == MotorKind::Brushless || encoder_failed_ ? status::kMotionError
                                                                                   : status::kCurrentLimit;
        events_.push_back(MotorEvent::Fault);
        events_.push_back(MotorEvent::Stopped);
        return;
    case models::AxisEvent::SoftStopped:
        pending_backlash_target_.reset();
        conclude();
        return;
    case models::AxisEvent::StoppedAtLimit:
    case models::AxisEvent::Arrived:
        conclude();
        return;
    }
}

void MotorChannel::conclude()
{
    switch (motion_) {
    case Motion::Idle:
        return;
    case Motion::Moving:
        if (pending_backlash_target_) {   // the backlash leg is done: approach forward
            const double target = *pending_backlash_target_ + counter_origin();
            pending_backlash_target_.reset();
            motion_ = Motion::Idle;
            start_profile(target, counts_per_s(velocity.max), counts_per_s2(velocity.acceleration), Motion::Moving);
            return;
        }
        motion_ = Motion::Idle;
        events_.push_back(MotorEvent::MoveCompleted);
        return;
    case Motion::Jogging:
        motion_ = Motion::Idle;
        events_.push_back(MotorEvent::MoveCompleted);
        return;
    case Motion::Stopping:
        motion_ = Motion::Idle;
        events_.push_back(MotorEvent::Stopped);
        return;
    case Motion::HomingToLimit: {
        if (stage_.kind != StageKind::Rotary && !switch_stops(homing_forward_, true)) {
            // A stepper ran on into the end stop: no switch, no home (a DC motor stalled).
            motion_ = Motion::Idle;
            events_.push_back(MotorEvent::Stopped);
            return;
        }
        // At the switch: back off by the offset distance, then zero the counter there.
        // p. 37: a brushless channel has no offset; its counters read the full travel at the
        // forward end, so that the stage's positions run from 0 to its travel.
        const double back = controller_.motor == MotorKind::Brushless ? 0.0
                            : homing_forward_                          ? -home_params.offset
                                                                       : home_params.offset;
        motion_ = Motion::Idle;
        if (back != 0 && counts_per_s(home_params.velocity) > 0)
            start_profile(axis_.position_counts() + back, counts_per_s(home_params.velocity),
                          counts_per_s2(velocity.acceleration), Motion::HomingBackOff);
        else
            complete_homing();
        return;
    }
    case Motion::HomingBackOff:
        motion_ = Motion::Idle;
        complete_homing();
        return;
    }
}

void MotorChannel::complete_homing()
{
    // A brushless stage's counters count from its reverse end (PMDSTAGEAXISPARAMS MinPos 0); a
    // rotation stage's (a DDR25 on a KBD101 too) from its home switch.
    const double zero = controller_.motor == MotorKind::Brushless && stage_.kind != StageKind::Rotary
                            ? axis_.travel_min_counts()
                            : axis_.position_counts();
    counter_offset_ = zero + axis_.lost_counts();
    encoder_offset_ = counter_offset_;
    homed_ = true;
    events_.push_back(MotorEvent::Homed);
}

std::vector<MotorEvent> MotorChannel::take_events()
{
    sync_axis(motion_);
    std::vector<MotorEvent> e;
    e.swap(events_);
    return e;
}

Ticks MotorChannel::next_change(Ticks now) const
{
    return events_.empty() ? kNever : now + 1;
}

} // namespace rigsim::apt
