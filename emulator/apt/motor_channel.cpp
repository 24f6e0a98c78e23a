#include "emulator/apt/motor_channel.hpp"

#include <algorithm>
#include <cmath>

namespace rigsim::apt {

namespace {

/// A rotation stage's "travel": far enough for any client, near enough for the 32-bit counter.
constexpr double kRotaryTravelCounts = 1 << 30;

} // namespace

MotorChannel::MotorChannel(const ControllerModel& controller, const StageModel& stage, models::World& world,
                           const std::string& /*key*/)
    : controller_(controller), stage_(stage), clock_(world.clock()), travel_max_(stage.travel_mm * stage.counts_per_mm)
{
    if (stage.rotary) {
        travel_min_ = -kRotaryTravelCounts;
        travel_max_ = kRotaryTravelCounts;
    }
    limit_min_ = travel_min_;
    limit_max_ = travel_max_;
    const double cpm = stage.counts_per_mm;
    velocity.max = static_cast<std::int32_t>(std::lround(stage.max_velocity_mm_s * cpm * velocity_factor()));
    velocity.acceleration = static_cast<std::int32_t>(std::lround(stage.acceleration_mm_s2 * cpm * acceleration_factor()));
    design_velocity_ = velocity;
    jog.step_size = static_cast<std::int32_t>(std::lround(0.1 * cpm));
    jog.velocity = velocity;
    home_params.velocity = static_cast<std::int32_t>(std::lround(stage.home_velocity_mm_s * cpm * velocity_factor()));
    home_params.offset = static_cast<std::int32_t>(std::lround(stage.home_offset_mm * cpm));
    // Power-up: the stage stands mid-travel (a rotation stage half a turn from its home
    // switch); the counters read 0 there (not homed).
    state_ = models::AxisState(stage.travel_mm * stage.counts_per_mm / 2, 0.0);
    counter_offset_ = state_[0];
    encoder_offset_ = state_[0];
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

std::int32_t MotorChannel::min_position() const
{
    return static_cast<std::int32_t>(std::lround(limit_min_));
}

std::int32_t MotorChannel::max_position() const
{
    return static_cast<std::int32_t>(std::lround(limit_max_));
}

void MotorChannel::narrow_travel(std::int32_t min_position, std::int32_t max_position)
{
    const double lo = std::max(limit_min_, static_cast<double>(min_position));
    const double hi = std::min(limit_max_, static_cast<double>(max_position));
    if (lo < hi) {
        limit_min_ = lo;
        limit_max_ = hi;
    }
}

std::int32_t MotorChannel::position() const
{
    return static_cast<std::int32_t>(std::lround(state_[0] - counter_offset_));
}

void MotorChannel::set_position(std::int32_t counts)
{
    counter_offset_ = state_[0] - counts;
}

std::int32_t MotorChannel::encoder() const
{
    return static_cast<std::int32_t>(std::lround(state_[0] - encoder_offset_));
}

void MotorChannel::set_encoder(std::int32_t counts)
{
    encoder_offset_ = state_[0] - counts;
}

std::int16_t MotorChannel::velocity_word() const
{
    // DCSTATUSUPDATE (p. 79): "Scaling is 204.8 per mm/sec".
    const double word = state_[1] / stage_.counts_per_mm * 204.8;
    return static_cast<std::int16_t>(std::clamp(std::lround(word), -32768L, 32767L));
}

std::uint32_t MotorChannel::status_bits() const
{
    std::uint32_t bits = status::kMotorConnected | fault_bits_;
    if (!stage_.rotary && state_[0] <= travel_min_ + 0.5 && (limit_switch.ccw_hard & 0x7f) != 1)
        bits |= status::kReverseHardLimit;
    if (!stage_.rotary && state_[0] >= travel_counts() - 0.5 && (limit_switch.cw_hard & 0x7f) != 1)
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
        bits |= state_[1] >= 0 && profile_.target() >= state_[0] ? status::kMovingForward : status::kMovingReverse;
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

double MotorChannel::run_target(bool forward) const
{
    if (stage_.rotary)
        return forward ? travel_max_ : travel_min_;
    const double beyond = travel_max_ - travel_min_;
    return forward ? travel_max_ + beyond : travel_min_ - beyond;
}

double MotorChannel::next_home_switch(bool forward) const
{
    const double turn = 360.0 * stage_.counts_per_mm;
    return forward ? std::ceil((state_[0] + 0.5) / turn) * turn : std::floor((state_[0] - 0.5) / turn) * turn;
}

void MotorChannel::start_profile(double target_physical, double v, double a, Motion motion)
{
    const Ticks now = clock_.now();
    sample(now);
    fault_bits_ = 0;   // a new move clears a stall
    profile_slip_ = 0;
    // The controller ends a move at the limit switch ahead, or at a travel that
    // PMDSTAGEAXISPARAMS narrowed; past an ignored switch the axis runs into the end stop.
    double target = target_physical;
    if (!stage_.rotary && (target > limit_max_ || target < limit_min_)) {
        const bool forward = target > limit_max_;
        const bool narrowed = forward ? limit_max_ < travel_max_ : limit_min_ > travel_min_;
        if (narrowed || switch_stops(forward, motion == Motion::HomingToLimit))
            target = std::clamp(target, limit_min_, limit_max_);
    }
    if (v <= 0) {
        motion_ = Motion::Idle;
        return;
    }
    // S-curve when MOT_SET_PMDPROFILEMODEPARAMS asks for it (p. 69); jerk scaling of 7.1.
    const double j = controller_.jerk_per_count_s3 > 0 ? jerk / controller_.jerk_per_count_s3 : 0;
    profile_ = profile_mode == 2 && j > 0 ? models::MotionProfile::plan_s_curve(state_, target, v, a, j)
                                          : models::MotionProfile::plan(state_, target, v, a);
    start_ = now;
    end_ = now + static_cast<Ticks>(std::ceil(profile_.duration() * clock_.tick_hz() - 1e-9));
    motion_ = motion;
    if (end_ <= now)
        finish(now);
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
    // and stops dead when it gets there (soft_stop()).
    if (!soft_limits_active() || (limit_switch.mode & 0x7f) != 3)
        return target_physical;
    return std::clamp(target_physical, limit_switch.ccw_soft + counter_offset_, limit_switch.cw_soft + counter_offset_);
}

void MotorChannel::move_to(double target_physical)
{
    sample(clock_.now());
    target_physical = within_soft_limits(target_physical);
    // GENMOVEPARAMS backlash: a move in the reverse direction overshoots by the backlash
    // distance and comes back forward, so that every move ends approaching forward.
    if (backlash > 0 && target_physical < state_[0] - 0.5) {
        pending_backlash_target_ = target_physical - counter_offset_;
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
    move_to(counts + counter_offset_);
}

void MotorChannel::move_relative(std::int32_t counts)
{
    if (!enabled_)
        return;
    sample(clock_.now());
    move_to(state_[0] + counts);
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
    sample(clock_.now());
    start_profile(stage_.rotary ? next_home_switch(to_forward) : run_target(to_forward),
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
        start_profile(within_soft_limits(run_target(forward)), v, a, Motion::Jogging);
        return;
    }
    sample(clock_.now());
    const double step = forward ? jog.step_size : -jog.step_size;
    start_profile(within_soft_limits(state_[0] + step), v, a, Motion::Jogging);
}

void MotorChannel::move_velocity(bool forward)
{
    if (!enabled_)
        return;
    start_profile(within_soft_limits(run_target(forward)), counts_per_s(velocity.max),
                  counts_per_s2(velocity.acceleration), Motion::Moving);
}

void MotorChannel::stop(bool immediate)
{
    const Ticks now = clock_.now();
    sample(now);
    pending_backlash_target_.reset();
    if (motion_ == Motion::Idle) {
        events_.push_back(MotorEvent::Stopped);   // MOVE_STOPPED for every MOVE_STOP
        return;
    }
    if (immediate || counts_per_s2(velocity.acceleration) <= 0) {
        state_[1] = 0;
        motion_ = Motion::Idle;
        events_.push_back(MotorEvent::Stopped);
        return;
    }
    // Profiled stop: decelerate at the acceleration parameter.
    const double a = counts_per_s2(velocity.acceleration);
    const double v = state_[1];
    const double stop_at = state_[0] + v * std::abs(v) / (2 * a);
    // An end on the way stops the axis first (enforce_ends()).
    profile_ = models::MotionProfile::plan(state_, stop_at, std::max(std::abs(v), 1.0), a);
    profile_slip_ = 0;
    start_ = now;
    end_ = now + static_cast<Ticks>(std::ceil(profile_.duration() * clock_.tick_hz() - 1e-9));
    motion_ = Motion::Stopping;
    if (end_ <= now)
        finish(now);
}

void MotorChannel::sample(Ticks now)
{
    if (motion_ == Motion::Idle)
        return;
    const double before = state_[0];
    state_ = profile_.sample(clock_.seconds(now - start_));
    state_[0] -= profile_slip_;
    if (!soft_stop(before))
        enforce_ends();
}

bool MotorChannel::soft_stop(double before)
{
    if (!soft_limits_active() || (limit_switch.mode & 0x7f) != 2 || motion_ == Motion::HomingToLimit
        || motion_ == Motion::HomingBackOff)
        return false;
    // Only a crossing counts: a stage set beyond a limit may move back in.
    const double cw = limit_switch.cw_soft + counter_offset_, ccw = limit_switch.ccw_soft + counter_offset_;
    double limit;
    if (before < cw && state_[0] >= cw)
        limit = cw;
    else if (before > ccw && state_[0] <= ccw)
        limit = ccw;
    else
        return false;
    state_ = models::AxisState(limit, 0.0);
    pending_backlash_target_.reset();
    conclude();
    return true;
}

bool MotorChannel::enforce_ends()
{
    constexpr double kTolerance = 1e-6;   // counts: a profile that ends on a limit may round past it
    if (stage_.rotary || motion_ == Motion::Idle)
        return false;
    const bool forward = state_[0] > limit_max_ + kTolerance;
    if (!forward && state_[0] >= limit_min_ - kTolerance)
        return false;
    const double limit = forward ? limit_max_ : limit_min_;
    const bool narrowed = forward ? limit_max_ < travel_max_ : limit_min_ > travel_min_;
    if (narrowed || switch_stops(forward, motion_ == Motion::HomingToLimit)) {
        state_ = models::AxisState(limit, 0.0);   // the switch (or the narrowed limit) stops it
        conclude();
        return true;
    }
    hit_end_stop(limit);
    return motion_ == Motion::Idle;
}

void MotorChannel::hit_end_stop(double end)
{
    if (controller_.motor == MotorKind::Stepper) {
        // Open loop: the motor keeps stepping against the stop; the counters count the
        // microsteps the carriage does not make, and the profile runs on.
        const double lost = state_[0] - end;
        profile_slip_ += lost;
        counter_offset_ -= lost;
        encoder_offset_ -= lost;
        state_ = models::AxisState(end, 0.0);
        return;
    }
    // The motor stalls against the stop: its current limit (DC servo) or the position error
    // limit (brushless, PMDPOSITIONLOOPPARAMS) trips, and the controller stops the axis.
    state_ = models::AxisState(end, 0.0);
    motion_ = Motion::Idle;
    pending_backlash_target_.reset();
    fault_bits_ = controller_.motor == MotorKind::Brushless ? status::kMotionError : status::kCurrentLimit;
    events_.push_back(MotorEvent::Fault);
    events_.push_back(MotorEvent::Stopped);
}

void MotorChannel::finish(Ticks now)
{
    (void)now;
    const double before = state_[0];
    state_ = models::AxisState(profile_.target() - profile_slip_, 0.0);
    if (!soft_stop(before) && !enforce_ends())
        conclude();
}

void MotorChannel::conclude()
{
    switch (motion_) {
    case Motion::Idle:
        return;
    case Motion::Moving:
        if (pending_backlash_target_) {   // the backlash leg is done: approach forward
            const double target = *pending_backlash_target_ + counter_offset_;
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
        if (!stage_.rotary && !switch_stops(homing_forward_, true)) {
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
            start_profile(state_[0] + back, counts_per_s(home_params.velocity), counts_per_s2(velocity.acceleration),
                          Motion::HomingBackOff);
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
    // A brushless stage's counters count from its reverse end (PMDSTAGEAXISPARAMS MinPos 0).
    const double zero = controller_.motor == MotorKind::Brushless ? travel_min_ : state_[0];
    counter_offset_ = zero;
    encoder_offset_ = zero;
    homed_ = true;
    events_.push_back(MotorEvent::Homed);
}

std::vector<MotorEvent> MotorChannel::take_events()
{
    std::vector<MotorEvent> e;
    e.swap(events_);
    return e;
}

Ticks MotorChannel::next_change(Ticks now) const
{
    return motion_ == Motion::Idle ? kNever : now + 1;
}

void MotorChannel::tick(Ticks now)
{
    if (motion_ == Motion::Idle)
        return;
    if (now >= end_)
        finish(now);
    else
        sample(now);
}

} // namespace rigsim::apt
