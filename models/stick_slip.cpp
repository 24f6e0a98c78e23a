#include "models/stick_slip.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rigsim::models {

namespace {

constexpr double kTolerance_nm = 1e-6;   // a profile that ends on an obstacle may round past it

/// The tick `seconds` after `now`, rounded up; a duration past 10^18 ticks (a slow move over a
/// huge distance) is that far away, not an overflow.
Ticks end_after(Ticks now, double seconds, std::uint32_t tick_hz)
{
    const double ticks = std::ceil(seconds * tick_hz - 1e-9);
    return now + static_cast<Ticks>(std::clamp(ticks, 0.0, 1e18));
}

} // namespace

StickSlipPositioner::StickSlipPositioner(const Clock& clock, const StickSlipConfig& config)
    : clock_(clock), config_(config), rest_nm_(config.start_position_nm), jitter_state_(config.jitter_seed),
      scanner_(clock, config.scan_range_nm)
{
}

double StickSlipPositioner::si_per_nm() const
{
    constexpr double kPi = 3.14159265358979323846;
    return travel_of(config_.kind) == Travel::Angle ? kPi / 180.0 * 1e-6 : 1e-9;
}

double StickSlipPositioner::si_position() const
{
    return position_nm() * si_per_nm();
}

double StickSlipPositioner::si_velocity() const
{
    return velocity_nm_per_s() * si_per_nm();
}

TravelRange StickSlipPositioner::si_travel() const
{
    return {config_.travel_min_nm * si_per_nm(), config_.travel_max_nm * si_per_nm()};
}

void StickSlipPositioner::si_place(double position)
{
    place(std::clamp(position / si_per_nm(), config_.travel_min_nm, config_.travel_max_nm));
}

void StickSlipPositioner::si_set_obstacles(std::optional<double> min, std::optional<double> max)
{
    const auto nm = [this](std::optional<double> si) {
        return si ? std::optional<double>(*si / si_per_nm()) : std::nullopt;
    };
    set_obstacles(nm(min), nm(max));
}

std::optional<std::string> StickSlipPositioner::refuses(BodyFault& fault) const
{
    if (fault.kind == PhysicalFault::LimitSwitch)
        return "\"kind\": limit_switch: a stick-slip positioner has no limit switches (its end stops are "
               "mechanical; use stall)";
    if (fault.kind != PhysicalFault::Slip)
        return std::nullopt;
    if (fault.slip_steps)
        return "counts: a stick-slip positioner slips by a fraction of each step, not by counts (fraction)";
    // A positioner that lost every step would not move at all: that is the stall fault.
    if (!fault.slip_fraction)
        fault.slip_fraction = 0.5;
    if (*fault.slip_fraction >= 1)
        return "fraction: a number from 0 up to (not including) 1 is required";
    return std::nullopt;
}

void StickSlipPositioner::apply_faults()
{
    set_slip(faults().slip_fraction);
    set_blocked(faults().stalled);
}

void StickSlipPositioner::set_kind(BodyKind kind)
{
    if (travel_of(kind) == Travel::None)
        throw std::invalid_argument("a stick-slip positioner is linear, rotary or a goniometer");
    config_.kind = kind;
}

void StickSlipPositioner::set_travel(double min_nm, double max_nm)
{
    config_.travel_min_nm = min_nm;
    config_.travel_max_nm = max_nm;
}

double StickSlipPositioner::stop_min_nm() const
{
    return obstacle_min_nm_ ? std::max(end_min_nm(), *obstacle_min_nm_) : end_min_nm();
}

double StickSlipPositioner::stop_max_nm() const
{
    return obstacle_max_nm_ ? std::min(end_max_nm(), *obstacle_max_nm_) : end_max_nm();
}

double StickSlipPositioner::within_obstacles(double x, double from) const
{
    if (obstacle_max_nm_ && x > *obstacle_max_nm_)
        x = std::max(*obstacle_max_nm_, from);
    if (obstacle_min_nm_ && x < *obstacle_min_nm_)
        x = std::min(*obstacle_min_nm_, from);
    return x;
}

void StickSlipPositioner::set_obstacles(std::optional<double> min_nm, std::optional<double> max_nm)
{
    // The steps due so far were made without them (position_nm() replays them).
    const double here = position_nm();
    if (min_nm)
        min_nm = std::min(*min_nm, here);
    if (max_nm)
        max_nm = std::max(*max_nm, here);
    if (min_nm == obstacle_min_nm_ && max_nm == obstacle_max_nm_)
        return;
    if (motion_ == Motion::Rest) {   // the drift so far crept under the old stops
        rest_nm_ = here;
        rest_since_ = clock_.now();
    }
    obstacle_min_nm_ = min_nm;
    obstacle_max_nm_ = max_nm;
    reschedule();
}

Ticks StickSlipPositioner::obstacle_tick() const
{
    if (motion_ != Motion::Profile)
        return kNever;
    const bool forward = profile_.target() > rest_nm_;
    const std::optional<double>& obstacle = forward ? obstacle_max_nm_ : obstacle_min_nm_;
    if (!obstacle)
        return kNever;
    const auto past = [&](Ticks k) {
        const double x = k >= profile_end_ ? profile_.target()
                                           : profile_.sample(clock_.seconds(k - profile_start_)).position;
        return forward ? x > *obstacle + kTolerance_nm : x < *obstacle - kTolerance_nm;
    };
    if (!past(profile_end_))
        return kNever;
    // A profile from rest runs one way: the first tick past the obstacle, by bisection.
    Ticks lo = profile_start_, hi = profile_end_;
    while (hi - lo > 1) {
        const Ticks mid = lo + (hi - lo) / 2;
        (past(mid) ? hi : lo) = mid;
    }
    return hi;
}

void StickSlipPositioner::set_closed_loop_hold(bool hold)
{
    if (motion_ == Motion::Rest) {
        const Ticks now = clock_.now();
        rest_nm_ = rest_position(now);
        rest_since_ = now;
    }
    hold_ = hold;
}

double StickSlipPositioner::rest_position(Ticks now) const
{
    if (config_.drift_nm_per_s == 0 || hold_)
        return rest_nm_;
    const double drifted = rest_nm_ + config_.drift_nm_per_s * clock_.seconds(now - rest_since_);
    // Drift stops at an end stop (and never pulls a stage placed beyond one further out).
    return std::clamp(drifted, std::min(stop_min_nm(), rest_nm_), std::max(stop_max_nm(), rest_nm_));
}

double StickSlipPositioner::velocity_nm_per_s() const
{
    const Ticks now = clock_.now();
    switch (motion_) {
    case Motion::Rest: {
        const double drifted = config_.drift_nm_per_s * clock_.seconds(now - rest_since_);
        const bool creeping = config_.drift_nm_per_s != 0 && !hold_ && !blocked_;
        return creeping && rest_position(now) == rest_nm_ + drifted ? config_.drift_nm_per_s : 0.0;
    }
    case Motion::Profile: {
        if (now >= profile_end_)
            return 0.0;
        const AxisState s = profile_.sample(clock_.seconds(now - profile_start_));
        return within_obstacles(s.position, rest_nm_) == s.position ? s.velocity : 0.0;   // 0: on an obstacle
    }
    case Motion::Burst: {
        catch_up();
        const bool pressing = burst_.direction > 0 ? replay_.position_nm >= stop_max_nm()
                                                   : replay_.position_nm <= stop_min_nm();
        if (replay_.limit_met || (burst_.steps > 0 && replay_.done >= burst_.steps) || blocked_ || pressing)
            return 0.0;
        return burst_.direction * step_width_nm_ * burst_.frequency_hz;
    }
    case Motion::Scan: {
        if (now >= scanner_.end_tick() || blocked_)
            return 0.0;
        const auto at = [&](Ticks k) {
            return std::clamp(rest_nm_ + scanner_.displacement_nm(k), stop_min_nm(), stop_max_nm());
        };
        return (at(now + 1) - at(now)) * clock_.tick_hz();
    }
    }
    return 0.0;
}

void StickSlipPositioner::set_blocked(bool blocked)
{
    if (blocked == blocked_)
        return;
    if (!blocked) {
        catch_up();   // the steps due so far were made against the obstacle
        blocked_ = false;
        if (motion_ == Motion::Rest)
            rest_since_ = clock_.now();
        return;
    }
    const bool driven = motion_ == Motion::Profile;
    catch_up();
    block_nm_ = position_nm();
    if (driven) {   // a closed-loop move or search meets the obstacle where the stage is
        settle();
        blocked_ = true;
        end_motion(Outcome::Blocked);
        reschedule();
        return;
    }
    if (motion_ == Motion::Rest) {
        rest_nm_ = block_nm_;
        rest_since_ = clock_.now();
    }
    blocked_ = true;
    reschedule();
}

double StickSlipPositioner::position_nm() const
{
    const Ticks now = clock_.now();
    switch (motion_) {
    case Motion::Rest:
        return rest_position(now);
    case Motion::Profile:
        return within_obstacles(
            now >= profile_end_ ? profile_.target() : profile_.sample(clock_.seconds(now - profile_start_)).position,
            rest_nm_);
    case Motion::Burst:
        catch_up();
        return replay_.position_nm;
    case Motion::Scan:
        // End stops clamp a scan; the software range limit does not (MCS 2.3.4).
        return std::clamp(rest_nm_ + scanner_.displacement_nm(now), stop_min_nm(), stop_max_nm());
    }
    return rest_nm_;
}

StickSlipPositioner::Outcome StickSlipPositioner::take_outcome()
{
    const Outcome o = outcome_;
    outcome_ = Outcome::None;
    return o;
}

void StickSlipPositioner::settle()
{
    legs_nm_.clear();
    next_leg_ = 0;
    const Ticks now = clock_.now();
    switch (motion_) {
    case Motion::Rest:
        rest_nm_ = rest_position(now);
        break;
    case Motion::Profile:
        rest_nm_ = position_nm();
        break;
    case Motion::Burst:
        catch_up();
        rest_nm_ = replay_.position_nm;
        jitter_state_ = replay_.jitter_state;
        break;
    case Motion::Scan:
        rest_nm_ = position_nm();
        scanner_.settle(now);
        break;
    }
    motion_ = Motion::Rest;
    rest_since_ = now;
    hold_ = false;
}

void StickSlipPositioner::halt()
{
    settle();
    outcome_ = Outcome::None;
    reschedule();
}

void StickSlipPositioner::place(double position_nm)
{
    settle();
    rest_nm_ = position_nm;
    if (blocked_)
        block_nm_ = position_nm;   // the obstacle goes where the stage was put
    if (obstacle_min_nm_)
        obstacle_min_nm_ = std::min(*obstacle_min_nm_, position_nm);
    if (obstacle_max_nm_)
        obstacle_max_nm_ = std::max(*obstacle_max_nm_, position_nm);
    reschedule();
}

Ticks StickSlipPositioner::move_to(double target_nm, double speed_nm_per_s, double acceleration_nm_per_s2)
{
    settle();
    outcome_ = Outcome::None;
    const Ticks now = clock_.now();
    // Planned to the end stops; an obstacle is met on the way (outcome Blocked).
    target_nm = std::clamp(target_nm, std::min(end_min_nm(), rest_nm_), std::max(end_max_nm(), rest_nm_));
    profile_ = MotionProfile::plan(AxisState{rest_nm_, 0.0}, target_nm, speed_nm_per_s * (1.0 - slip_),
                                   acceleration_nm_per_s2);
    profile_start_ = now;
    profile_end_ = end_after(now, profile_.duration(), clock_.tick_hz());
    if (profile_end_ <= now)
        rest_nm_ = profile_.target();
    else
        motion_ = Motion::Profile;
    reschedule();
    return profile_end_;
}

Ticks StickSlipPositioner::decelerate(double acceleration_nm_per_s2, double* rest_nm)
{
    const Ticks now = clock_.now();
    if (motion_ != Motion::Profile || !legs_nm_.empty() || acceleration_nm_per_s2 <= 0) {
        halt();
        if (rest_nm)
            *rest_nm = position_nm();
        return now;
    }
    const auto state = profile_.sample(clock_.seconds(now - profile_start_));
    const double v = state.velocity;
    // Room before the move's own target and the end stops: the braking never passes either; it
    // brakes harder where the acceleration given would not stop it in time.
    const double limit = v >= 0 ? std::min(profile_.target(), stop_max_nm()) : std::max(profile_.target(), stop_min_nm());
    const double room = std::max(0.0, std::abs(limit - state.position));
    double a = acceleration_nm_per_s2;
    if (room > 0 && v * v / (2.0 * a) > room)
        a = v * v / (2.0 * room);
    const double distance = room > 0 ? std::min(room, v * v / (2.0 * a)) : 0.0;
    const double target = state.position + (v >= 0 ? distance : -distance);
    if (rest_nm)
        *rest_nm = target;
    if (distance <= 0) {
        halt();
        return now;
    }
    auto braking = MotionProfile::plan(state, target, std::abs(v), a);
    const Ticks end = end_after(now, braking.duration(), clock_.tick_hz());
    if (end <= now) {
        halt();
        return now;
    }
    outcome_ = Outcome::None;
    profile_ = std::move(braking);
    profile_start_ = now;
    profile_end_ = end;
    reschedule();
    return profile_end_;
}

bool StickSlipPositioner::start_legs(std::vector<double> legs_nm, double speed_nm_per_s)
{
    settle();
    outcome_ = Outcome::None;
    legs_nm_ = std::move(legs_nm);
    if (blocked_)   // the search meets the obstacle at once, in either direction
        std::fill(legs_nm_.begin(), legs_nm_.end(), rest_nm_);
    leg_speed_nm_per_s_ = speed_nm_per_s * (1.0 - slip_);
    const bool moving = next_leg(clock_.now());
    reschedule();
    return moving;
}

bool StickSlipPositioner::next_leg(Ticks now)
{
    while (next_leg_ < legs_nm_.size()) {
        const double to = legs_nm_[next_leg_++];
        profile_ = MotionProfile::plan(AxisState{rest_nm_, 0.0}, to, leg_speed_nm_per_s_, 0.0);
        profile_start_ = now;
        profile_end_ = end_after(now, profile_.duration(), clock_.tick_hz());
        if (profile_end_ > now) {
            motion_ = Motion::Profile;
            return true;
        }
        rest_nm_ = to;
    }
    legs_nm_.clear();
    next_leg_ = 0;
    motion_ = Motion::Rest;
    return false;
}

void StickSlipPositioner::start_burst(const StepBurst& burst)
{
    settle();
    outcome_ = Outcome::None;
    burst_ = burst;
    step_width_nm_ = config_.step_width_nm * burst.amplitude_levels / 4095.0 * (1.0 - slip_);
    burst_start_ = clock_.now();
    replay_ = Replay{rest_nm_, 0, jitter_state_, false};
    motion_ = Motion::Burst;
    reschedule();
}

std::int64_t StickSlipPositioner::steps_due(Ticks elapsed) const
{
    auto due = static_cast<std::int64_t>(std::floor(clock_.seconds(elapsed) * burst_.frequency_hz + 1e-9));
    if (burst_.steps > 0)
        due = std::min(due, burst_.steps);
    return due;
}

Ticks StickSlipPositioner::tick_of_step(std::int64_t n) const
{
    // An estimate a little early, then forward with the expression steps_due() uses.
    const double estimate = static_cast<double>(n) / burst_.frequency_hz * clock_.tick_hz();
    Ticks t = burst_start_ + std::max<Ticks>(0, static_cast<Ticks>(estimate) - 2);
    while (std::floor(clock_.seconds(t - burst_start_) * burst_.frequency_hz + 1e-9) < static_cast<double>(n))
        ++t;
    return t;
}

bool StickSlipPositioner::step(double& position_nm, double delta_nm) const
{
    const StepLimit& l = burst_.limit;
    const double base = l.follows_stage ? position_nm : 0.0;
    const double lo = std::max(stop_min_nm(), base + l.min_nm);
    const double hi = std::min(stop_max_nm(), base + l.max_nm);
    const double target = position_nm + delta_nm;
    const double reached = std::clamp(target, std::min(lo, position_nm), std::max(hi, position_nm));
    position_nm = reached;
    if (reached == target)
        return true;
    // Against a mechanical end stop the steps go on without moving; a range limit ends them.
    const bool at_end_stop = reached <= stop_min_nm() || reached >= stop_max_nm();
    return !l.active || at_end_stop;
}

void StickSlipPositioner::replay(Replay& r, std::int64_t target) const
{
    const double jitter = config_.step_jitter_fraction;
    while (r.done < target && !r.limit_met) {
        ++r.done;
        r.jitter_state = r.jitter_state * 1664525u + 1013904223u;
        const double u = static_cast<double>(r.jitter_state >> 8) / static_cast<double>(1u << 24) * 2.0 - 1.0;
        r.limit_met = !step(r.position_nm, burst_.direction * step_width_nm_ * (1.0 + jitter * u));
    }
}

void StickSlipPositioner::catch_up() const
{
    if (motion_ == Motion::Burst)
        replay(replay_, steps_due(clock_.now() - burst_start_));
}

std::int64_t StickSlipPositioner::steps_done() const
{
    catch_up();
    return replay_.done;
}

bool StickSlipPositioner::stop_burst()
{
    if (motion_ != Motion::Burst)
        return false;
    catch_up();
    bool limit_met = replay_.limit_met;
    const bool unfinished = burst_.steps == 0 || replay_.done < burst_.steps;
    if (!limit_met && unfinished
        && clock_.seconds(clock_.now() - burst_start_) * burst_.frequency_hz > static_cast<double>(replay_.done)) {
        ++replay_.done;
        limit_met = !step(replay_.position_nm, burst_.direction * step_width_nm_);
    }
    halt();
    return limit_met;
}

bool StickSlipPositioner::start_scan(double target_levels, double speed_levels_per_s)
{
    settle();
    outcome_ = Outcome::None;
    const Ticks now = clock_.now();
    scanner_.start(now, target_levels, speed_levels_per_s);
    const bool over = scanner_.end_tick() <= now;
    if (over) {
        scanner_.settle(now);
        rest_nm_ = std::clamp(rest_nm_, stop_min_nm(), stop_max_nm());
    } else {
        motion_ = Motion::Scan;
    }
    reschedule();
    return over;
}

double StickSlipPositioner::scan_level() const
{
    return scanner_.level_at(clock_.now());
}

Ticks StickSlipPositioner::next_event(Ticks now) const
{
    switch (motion_) {
    case Motion::Rest:
        return kNever;
    case Motion::Profile:
        return std::min(profile_end_, obstacle_tick());
    case Motion::Scan:
        return scanner_.end_tick();
    case Motion::Burst:
        break;
    }
    catch_up();
    if (replay_.limit_met)
        return now + 1;
    Ticks next = burst_.steps > 0 ? tick_of_step(burst_.steps) : kNever;
    const StepLimit& l = burst_.limit;
    const bool limit_ahead = l.active && (burst_.direction > 0 ? std::isfinite(l.max_nm) : std::isfinite(l.min_nm));
    if (!limit_ahead)
        return next;
    // The step that meets the limit depends on every jitter draw before it: replay ahead.
    Replay ahead = replay_;
    std::int64_t horizon = ahead.done + kLookAheadSteps;
    if (burst_.steps > 0)
        horizon = std::min(horizon, burst_.steps);
    replay(ahead, horizon);
    if (ahead.limit_met)
        return std::min(next, tick_of_step(ahead.done));
    return std::min(next, tick_of_step(horizon));   // look again from there
}

void StickSlipPositioner::on_event(Ticks now)
{
    switch (motion_) {
    case Motion::Rest:
        return;
    case Motion::Profile:
        if (now >= obstacle_tick()) {   // met an obstacle: held there, the move or search ends
            settle();
            end_motion(Outcome::Blocked);
            return;
        }
        if (now >= profile_end_) {
            rest_nm_ = profile_.target();
            rest_since_ = now;
            motion_ = Motion::Rest;
            if (!next_leg(now))
                end_motion(Outcome::Arrived);
        }
        return;
    case Motion::Scan:
        if (now >= scanner_.end_tick()) {
            settle();
            end_motion(Outcome::ScanDone);
        }
        return;
    case Motion::Burst:
        catch_up();
        if (replay_.limit_met) {
            settle();
            end_motion(Outcome::LimitMet);
        } else if (burst_.steps > 0 && replay_.done >= burst_.steps) {
            settle();
            end_motion(Outcome::BurstDone);
        }
        return;
    }
}

void StickSlipPositioner::end_motion(Outcome outcome)
{
    motion_ = Motion::Rest;
    outcome_ = outcome;
    if (listener_)
        listener_();
}

} // namespace rigsim::models
