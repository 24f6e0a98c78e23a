#include "models/axis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rigsim::models {

namespace {

constexpr double kTolerance = 1e-6;   // counts: a profile that ends on a limit may round past it

int sign(double x)
{
    return (x > 0) - (x < 0);
}

} // namespace

Axis::Axis(const Clock& clock, const AxisConfig& config)
    : clock_(clock), config_(config), limit_min_counts_(config.travel_min_counts),
      limit_max_counts_(config.travel_max_counts)
{
    if (travel_of(config.kind) == Travel::None)
        throw std::invalid_argument("an axis is linear, rotary or a goniometer");
    if (config.rotary != (config.kind == BodyKind::Rotary))
        throw std::invalid_argument("an axis is rotary (no end stops) exactly when its kind is rotary");
    if (!(config.si_per_count >= 0) || !std::isfinite(config.si_per_count))
        throw std::invalid_argument("an axis's SI units per count are >= 0 and finite");
    anchor_.position_counts = config.start_position_counts;
}

namespace {

/// The axis's scale, or std::logic_error for a bare axis.
double scale_of(const AxisConfig& c)
{
    if (c.si_per_count <= 0)
        throw std::logic_error("this axis was built without SI units per count: it has no physical face");
    return c.si_per_count;
}

std::optional<double> counts_of(std::optional<double> si, double k)
{
    return si ? std::optional<double>(*si / k) : std::nullopt;
}

} // namespace

double Axis::si_position() const
{
    return position_counts() * scale_of(config_);
}

double Axis::si_velocity() const
{
    return velocity_counts_per_s() * scale_of(config_);
}

TravelRange Axis::si_travel() const
{
    const double k = scale_of(config_);
    if (config_.rotary)
        return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    return {config_.travel_min_counts * k, config_.travel_max_counts * k};
}

void Axis::si_place(double position)
{
    place(position / scale_of(config_));
}

void Axis::si_set_obstacles(std::optional<double> min, std::optional<double> max)
{
    const double k = scale_of(config_);
    set_obstacles(counts_of(min, k), counts_of(max, k));
}

double Axis::profile_at(Ticks k) const
{
    return k >= end_ ? profile_.target() : profile_.sample(clock_.seconds(k - start_)).position;
}

Axis::Track Axis::now_track() const
{
    if (!moving_)
        return anchor_;
    if (!jammed_)
        return scan(anchor_, clock_.now(), false).track;
    const Ticks now = clock_.now();
    if (config_.drive == Drive::Servo)
        return Track{now, anchor_.position_counts, anchor_.lost_counts, 0};
    // The motor runs its profile (motor position = profile + offset); the carriage stays.
    const double motor = profile_at(now) + motor_offset_;
    return Track{now, jam_position_counts_, motor - jam_position_counts_, 0};
}

double Axis::position_counts() const
{
    return now_track().position_counts;
}

double Axis::lost_counts() const
{
    return now_track().lost_counts;
}

double Axis::motor_position_counts() const
{
    const Track t = now_track();
    return t.position_counts + t.lost_counts;
}

double Axis::velocity_counts_per_s() const
{
    const Ticks now = clock_.now();
    if (!moving_ || now >= end_ || jammed_ || now_track().contact != 0)
        return 0;   // at rest, or pressed on an end stop
    // On the tick a motion is commanded the axis still moves as it did: a profile without an
    // acceleration limit starts at full speed, from the next tick.
    return now == start_ ? start_velocity_counts_per_s_ : profile_.sample(clock_.seconds(now - start_)).velocity;
}

void Axis::set_limits(double min_counts, double max_counts)
{
    if (min_counts == limit_min_counts_ && max_counts == limit_max_counts_)
        return;
    settle();
    limit_min_counts_ = min_counts;
    limit_max_counts_ = max_counts;
    replan();
}

void Axis::set_obstacles(std::optional<double> min_counts, std::optional<double> max_counts)
{
    // A carriage already past an obstacle is held where it stands, not put back on it.
    const double x = position_counts();
    if (min_counts)
        min_counts = std::min(*min_counts, x);
    if (max_counts)
        max_counts = std::max(*max_counts, x);
    if (min_counts == obstacle_min_counts_ && max_counts == obstacle_max_counts_)
        return;
    settle();
    obstacle_min_counts_ = min_counts;
    obstacle_max_counts_ = max_counts;
    replan();
}

void Axis::place(double counts)
{
    anchor_ = now_track();
    anchor_.position_counts = config_.rotary ? counts : std::clamp(counts, config_.travel_min_counts, config_.travel_max_counts);
    if (obstacle_min_counts_)
        obstacle_min_counts_ = std::min(*obstacle_min_counts_, anchor_.position_counts);
    if (obstacle_max_counts_)
        obstacle_max_counts_ = std::max(*obstacle_max_counts_, anchor_.position_counts);
    anchor_.contact = 0;
    jam_position_counts_ = anchor_.position_counts;
    moving_ = false;
    replan();
}

void Axis::set_jammed(bool jammed)
{
    if (jammed == jammed_)
        return;
    settle();   // anchored under the rules the motion ran by so far
    jammed_ = jammed;
    jam_position_counts_ = anchor_.position_counts;
    replan();
}

void Axis::set_slip(double counts, double fraction)
{
    slip_counts_ = std::max(counts, 0.0);
    slip_fraction_ = std::clamp(fraction, 0.0, 1.0);
}

void Axis::set_switch_pressed(int side)
{
    if (side == switch_pressed_)
        return;
    settle();
    switch_pressed_ = side;
    replan();
}

void Axis::set_loop_open(bool open)
{
    loop_open_ = open;
    set_jammed(faults().stalled || loop_open_);
}

void Axis::set_switch_held(int side)
{
    switch_held_ = side;
    set_switch_pressed(faults().switch_pressed != 0 ? faults().switch_pressed : switch_held_);
}

std::optional<std::string> Axis::refuses(BodyFault& fault) const
{
    if (fault.kind != PhysicalFault::Slip)
        return std::nullopt;
    if (config_.drive == Drive::Servo)
        return "slip: a servo closes its position loop on the encoder, so it loses no steps (a stepper "
               "controller does; try stall or sensor_failure)";
    if (!fault.slip_steps && !fault.slip_fraction)
        return "slip needs \"counts\" (microsteps lost per move) or \"fraction\" (of each move, 0..1)";
    return std::nullopt;
}

void Axis::apply_faults()
{
    set_jammed(faults().stalled || loop_open_);
    set_slip(faults().slip_steps, faults().slip_fraction);
    set_switch_pressed(faults().switch_pressed != 0 ? faults().switch_pressed : switch_held_);
}

int Axis::motion_direction() const
{
    return moving_ ? sign(profile_.target() - profile_at(clock_.now())) : 0;
}

std::optional<Axis::Hit> Axis::forced_hit() const
{
    if (!moving_)
        return std::nullopt;
    const Ticks next = std::max(anchor_.tick, clock_.now()) + 1;
    if (jammed_ && config_.drive == Drive::Servo)
        return Hit{AxisEvent::Stalled, Track{next, anchor_.position_counts, anchor_.lost_counts, 0}};
    if (jammed_)
        return Hit{AxisEvent::Arrived,
                   Track{end_, jam_position_counts_, profile_.target() + motor_offset_ - jam_position_counts_, 0}};
    const int dir = motion_direction();
    if (switch_pressed_ != 0 && dir == switch_pressed_ && !config_.rotary && stops_at(dir > 0)) {
        Track at = scan(anchor_, next, false).track;
        at.tick = next;
        at.contact = 0;
        return Hit{AxisEvent::StoppedAtLimit, at};
    }
    return std::nullopt;
}

void Axis::set_limit_switches(bool forward_stops, bool reverse_stops)
{
    if (forward_stops == forward_switch_stops_ && reverse_stops == reverse_switch_stops_)
        return;
    settle();
    forward_switch_stops_ = forward_stops;
    reverse_switch_stops_ = reverse_stops;
    replan();
}

void Axis::set_soft_stops(double min_motor_counts, double max_motor_counts)
{
    if (soft_stops_ && min_motor_counts == soft_min_motor_counts_ && max_motor_counts == soft_max_motor_counts_)
        return;
    settle();
    soft_stops_ = true;
    soft_min_motor_counts_ = min_motor_counts;
    soft_max_motor_counts_ = max_motor_counts;
    replan();
}

void Axis::clear_soft_stops()
{
    if (!soft_stops_)
        return;
    settle();
    soft_stops_ = false;
    replan();
}

double Axis::run_target_counts(bool forward) const
{
    if (config_.rotary)
        return forward ? config_.travel_max_counts : config_.travel_min_counts;
    const double beyond = config_.travel_max_counts - config_.travel_min_counts;
    return forward ? config_.travel_max_counts + beyond : config_.travel_min_counts - beyond;
}

double Axis::next_home_switch_counts(bool forward) const
{
    const double turn = config_.counts_per_turn;
    const double x = position_counts();
    return forward ? std::ceil((x + 0.5) / turn) * turn : std::floor((x - 0.5) / turn) * turn;
}

bool Axis::stops_at(bool forward) const
{
    // A travel the controller narrowed stops the axis whatever the switch.
    if (forward)
        return limit_max_counts_ < config_.travel_max_counts || forward_switch_stops_;
    return limit_min_counts_ > config_.travel_min_counts || reverse_switch_stops_;
}

std::optional<Axis::Stop> Axis::stop_ahead(bool forward) const
{
    const std::optional<double>& obstacle = forward ? obstacle_max_counts_ : obstacle_min_counts_;
    const double limit = forward ? limit_max_counts_ : limit_min_counts_;
    // An obstacle short of the travel limit is met first; at or past it, the limit is.
    if (obstacle && (config_.rotary || (forward ? *obstacle < limit : *obstacle > limit)))
        return Stop{*obstacle, false};
    if (config_.rotary)
        return std::nullopt;
    return Stop{limit, stops_at(forward)};
}

bool Axis::slips(int dir) const
{
    if (config_.drive != Drive::Stepper)
        return false;
    const auto stop = stop_ahead(dir > 0);
    return stop && !stop->stops;
}

void Axis::move_to(double target_counts, double velocity_counts_per_s, double acceleration_counts_per_s2,
                   double jerk_counts_per_s3)
{
    if (velocity_counts_per_s <= 0) {
        stop_immediately();
        return;
    }
    const AxisState from{position_counts(), Axis::velocity_counts_per_s()};
    anchor_ = now_track();
    double target = target_counts;
    if (!config_.rotary && (target > limit_max_counts_ || target < limit_min_counts_)
        && stops_at(target > limit_max_counts_))
        target = std::clamp(target, limit_min_counts_, limit_max_counts_);
    // A pressed limit switch ahead that stops the axis: the motion ends where it starts.
    const int dir = sign(target - from.position);
    if (!config_.rotary && switch_pressed_ != 0 && dir == switch_pressed_ && stops_at(dir > 0))
        target = from.position;
    start(jerk_counts_per_s3 > 0 ? MotionProfile::plan_s_curve(from, target, velocity_counts_per_s,
                                                               acceleration_counts_per_s2, jerk_counts_per_s3)
                                 : MotionProfile::plan(from, target, velocity_counts_per_s, acceleration_counts_per_s2),
          from.velocity);
}

void Axis::stop_immediately()
{
    anchor_ = now_track();
    anchor_.contact = 0;
    moving_ = false;
    replan();
}

void Axis::stop_profiled(double acceleration_counts_per_s2)
{
    const double a = acceleration_counts_per_s2;
    if (a <= 0 || !moving_) {
        stop_immediately();
        return;
    }
    const double v = velocity_counts_per_s();
    anchor_ = now_track();
    const double x = anchor_.position_counts;
    start(MotionProfile::plan(AxisState{x, v}, x + v * std::abs(v) / (2 * a), std::max(std::abs(v), 1.0), a), v);
}

void Axis::start(MotionProfile profile, double from_velocity_counts_per_s)
{
    const Ticks now = clock_.now();
    start_velocity_counts_per_s_ = from_velocity_counts_per_s;
    profile_ = std::move(profile);
    start_ = now;
    end_ = now + static_cast<Ticks>(std::ceil(profile_.duration() * clock_.tick_hz() - 1e-9));
    motor_offset_ = anchor_.lost_counts;
    anchor_ = Track{now, anchor_.position_counts, anchor_.lost_counts, 0};
    motion_from_counts_ = anchor_.position_counts;
    jam_position_counts_ = anchor_.position_counts;
    // The profile turns round only where a segment ends at rest: those ticks bound the pieces
    // over which its position is monotone.
    turns_.clear();
    int previous = 0;
    for (const auto& seg : profile_.segments()) {
        const int dir = sign(integrate(seg.start, seg.acceleration, seg.jerk, seg.duration).position - seg.start.position);
        if (dir != 0 && previous != 0 && dir != previous)
            turns_.push_back(start_ + static_cast<Ticks>(std::floor(seg.t0 * clock_.tick_hz())));
        if (dir != 0)
            previous = dir;
    }
    moving_ = true;
    if (end_ > now) {
        replan();
        return;
    }
    pending_.reset();
    if (const auto hit = classify(now, anchor_.position_counts, profile_at(now), anchor_.lost_counts))
        apply(*hit);
}

std::optional<Axis::Hit> Axis::classify(Ticks k, double profile_before, double profile, double lost_before) const
{
    // The carriage is where the profile is less what a stepper lost in this motion (exactly
    // the profile when it lost nothing).
    const double slip = lost_before - motor_offset_;
    // Only a crossing stops at a soft stop: a stage set beyond one may move back in.
    if (soft_stops_) {
        const double motor_before = profile_before + motor_offset_, motor = profile + motor_offset_;
        if (motor_before < soft_max_motor_counts_ && motor >= soft_max_motor_counts_)
            return Hit{AxisEvent::SoftStopped, Track{k, soft_max_motor_counts_ - lost_before, lost_before, 0}};
        if (motor_before > soft_min_motor_counts_ && motor <= soft_min_motor_counts_)
            return Hit{AxisEvent::SoftStopped, Track{k, soft_min_motor_counts_ - lost_before, lost_before, 0}};
    }
    const double x = profile - slip;
    for (const bool forward : {true, false}) {
        const auto stop = stop_ahead(forward);
        if (!stop || !(forward ? x > stop->at_counts + kTolerance : x < stop->at_counts - kTolerance))
            continue;
        const double end = stop->at_counts;
        if (stop->stops)
            return Hit{AxisEvent::StoppedAtLimit, Track{k, end, lost_before, 0}};
        if (config_.drive == Drive::Servo)
            return Hit{AxisEvent::Stalled, Track{k, end, lost_before, 0}};
        return Hit{AxisEvent::LostSteps, Track{k, end, lost_before + (x - end), forward ? 1 : -1}};
    }
    if (k >= end_)
        return Hit{AxisEvent::Arrived, Track{k, x, lost_before, 0}};
    return std::nullopt;
}

std::vector<Ticks> Axis::piece_ends(Ticks after, Ticks until) const
{
    std::vector<Ticks> ends;
    for (const Ticks turn : turns_)
        for (const Ticks t : {turn, turn + 1})
            if (t > after && t < until && (ends.empty() || t > ends.back()))
                ends.push_back(t);
    ends.push_back(until);
    return ends;
}

Axis::Scan Axis::scan(const Track& from, Ticks until, bool find_hits) const
{
    Scan r{from, std::nullopt};
    until = std::min(until, end_);
    if (until <= from.tick)
        return r;
    for (const Ticks b : piece_ends(from.tick, until))
        if ((r.hit = scan_piece(r.track, b, find_hits)))
            return r;
    return r;
}

std::optional<Axis::Hit> Axis::scan_piece(Track& s, Ticks b, bool find_hits) const
{
    const Ticks a = s.tick;
    const double pa = profile_at(a), pb = profile_at(b);
    const int dir = sign(pb - pa);
    // A stepper pressing on (the profile runs on into the end stop it stands at): the carriage
    // stays, the motor's steps are lost.
    const bool pressing = dir != 0 && dir == s.contact && slips(dir);
    bool has_stop = false;   // a stop lies ahead, at `end`
    double end = 0;
    if (dir != 0)
        if (const auto stop = stop_ahead(dir > 0)) {
            has_stop = true;
            end = stop->at_counts;
        }
    const auto lost_at = [&](double profile) {
        if (!pressing)
            return s.lost_counts;
        const double lost = motor_offset_ + (profile - end);
        return dir > 0 ? std::max(s.lost_counts, lost) : std::min(s.lost_counts, lost);
    };
    const auto hit_at = [&](Ticks k) -> std::optional<Hit> {
        const double before = profile_at(k - 1);
        auto hit = classify(k, before, profile_at(k), lost_at(before));
        if (hit && pressing && hit->event == AxisEvent::LostSteps) {
            if (k < end_)
                return std::nullopt;   // pressing on: no news
            hit->event = AxisEvent::Arrived;
        }
        return hit;
    };
    // Past tick a+1 the position is monotone over the piece, and so is this test: the first
    // tick it holds is found by bisection.
    const double slip = s.lost_counts - motor_offset_;
    const auto crossed = [&](double p) {
        const double ma = pa + motor_offset_, m = p + motor_offset_;
        if (soft_stops_ && (dir > 0 ? ma < soft_max_motor_counts_ && m >= soft_max_motor_counts_
                                    : dir < 0 && ma > soft_min_motor_counts_ && m <= soft_min_motor_counts_))
            return true;
        if (pressing || !has_stop)
            return false;
        const double x = p - slip;
        return dir > 0 ? x > end + kTolerance : x < end - kTolerance;
    };
    for (Ticks lo = a + 1; find_hits && lo <= b;) {
        if (const auto hit = hit_at(lo))
            return hit;
        if (lo == b || !crossed(pb))
            break;
        Ticks hi = b;   // crossed at hi, not at lo
        while (hi - lo > 1) {
            const Ticks mid = lo + (hi - lo) / 2;
            (crossed(profile_at(mid)) ? hi : lo) = mid;
        }
        lo = hi;
    }
    if (find_hits && b >= end_ && b > a + 1)
        if (const auto hit = hit_at(b))
            return hit;
    s.lost_counts = lost_at(pb);
    s.position_counts = pressing ? end : pb - slip;
    if (dir != 0 && !pressing)
        s.contact = 0;
    s.tick = b;
    return std::nullopt;
}

void Axis::settle()
{
    if (moving_)
        anchor_ = now_track();
}

void Axis::replan()
{
    if (auto forced = forced_hit())
        pending_ = forced;
    else
        pending_ = moving_ ? scan(anchor_, end_, true).hit : std::nullopt;
    reschedule();
}

Ticks Axis::next_event(Ticks /*now*/) const
{
    return pending_ ? pending_->after.tick : kNever;
}

void Axis::on_event(Ticks now)
{
    if (pending_ && pending_->after.tick <= now)
        apply(*pending_);   // a copy: apply() plans the next hit
}

void Axis::apply(Hit hit)
{
    const bool ends = hit.event != AxisEvent::LostSteps || hit.after.tick >= end_;
    if (hit.event == AxisEvent::Arrived && config_.drive == Drive::Stepper && !jammed_) {
        // Lost microsteps (set_slip): the motor arrived, the carriage fell short.
        const double run = hit.after.position_counts - motion_from_counts_;
        const double lost = std::min(std::abs(run), slip_counts_ + slip_fraction_ * std::abs(run));
        hit.after.position_counts -= sign(run) * lost;
        hit.after.lost_counts += sign(run) * lost;
    }
    anchor_ = hit.after;
    if (ends) {
        moving_ = false;
        anchor_.contact = 0;
    }
    replan();
    if (listener_)
        listener_(hit.event);
    // A stepper that meets the end stop on the last tick of its profile has also arrived.
    if (hit.event == AxisEvent::LostSteps && ends && !moving_ && listener_)
        listener_(AxisEvent::Arrived);
}

} // namespace rigsim::models
