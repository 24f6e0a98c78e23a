#include "models/motion_profile.hpp"

#include <cmath>

namespace rigsim::models {

AxisState integrate(const AxisState& s, double a, double t)
{
    return AxisState{s.position + s.velocity * t + 0.5 * a * t * t, s.velocity + a * t};
}

AxisState integrate(const AxisState& s, double a, double j, double t)
{
    return AxisState{s.position + s.velocity * t + 0.5 * a * t * t + j * t * t * t / 6, s.velocity + a * t + 0.5 * j * t * t};
}

void MotionProfile::append(double duration, const AxisState& start, double acceleration, double jerk)
{
    if (duration <= 0)
        return;
    const double t0 = segments_.empty() ? 0.0 : segments_.back().t0 + segments_.back().duration;
    segments_.push_back(Segment{t0, duration, start, acceleration, jerk});
}

namespace {

/// Reaching speed `v` from rest with jerk `j` and acceleration at most `a`: the jerk time,
/// the constant-acceleration time, the peak acceleration, and the distance covered.
struct Ramp {
    double t_jerk, t_const, a_peak, distance;
};

Ramp s_ramp(double v, double a, double j)
{
    Ramp r{};
    if (v * j >= a * a) {   // the acceleration limit is reached
        r.t_jerk = a / j;
        r.t_const = v / a - a / j;
        r.a_peak = a;
    } else {
        r.t_jerk = std::sqrt(v / j);
        r.t_const = 0;
        r.a_peak = j * r.t_jerk;
    }
    // The ramp is symmetric about its midpoint in time: the mean speed is v / 2.
    r.distance = v * (2 * r.t_jerk + r.t_const) / 2;
    return r;
}

} // namespace

MotionProfile MotionProfile::plan_s_curve(const AxisState& from, double target, double v_max, double a_max,
                                                double j_max)
{
    if (a_max <= 0 || j_max <= 0 || from.velocity != 0 || v_max <= 0)
        return plan(from, target, v_max, a_max);
    MotionProfile p;
    p.target_ = target;
    const double d = target - from.position;
    if (d == 0)
        return p;
    const double dir = std::copysign(1.0, d);
    const double x = std::abs(d);
    double v = v_max;
    Ramp r = s_ramp(v, a_max, j_max);
    if (2 * r.distance > x) {   // no cruise at v_max: find the peak speed that just fits
        double lo = 0, hi = v_max;
        for (int i = 0; i < 100; ++i) {
            const double mid = (lo + hi) / 2;
            (2 * s_ramp(mid, a_max, j_max).distance > x ? hi : lo) = mid;
        }
        v = lo;
        r = s_ramp(v, a_max, j_max);
    }
    const double cruise = v > 0 ? (x - 2 * r.distance) / v : 0;
    // Seven stretches: jerk up, hold, jerk down, cruise, and the mirror image to rest.
    const struct {
        double duration, jerk;
    } plan[] = {{r.t_jerk, j_max},  {r.t_const, 0}, {r.t_jerk, -j_max}, {cruise, 0},
                {r.t_jerk, -j_max}, {r.t_const, 0}, {r.t_jerk, j_max}};
    AxisState s = from;
    double a = 0;
    for (const auto& stretch : plan) {
        if (stretch.duration <= 0)
            continue;
        p.append(stretch.duration, s, dir * a, dir * stretch.jerk);
        s = integrate(s, dir * a, dir * stretch.jerk, stretch.duration);
        a += stretch.jerk * stretch.duration;
    }
    return p;
}

MotionProfile MotionProfile::plan(const AxisState& from, double target, double v_max,
                                        double a_max)
{
    MotionProfile p;
    p.target_ = target;
    if (v_max <= 0)
        return p;   // cannot move: the caller refuses such moves before planning
    p.plan_from(from, v_max, a_max);
    return p;
}

void MotionProfile::plan_from(AxisState s, double v_max, double a_max)
{
    // Each pass either finishes the plan or brings the axis to a simpler state
    // (at rest, or moving toward the target no faster than v_max); three passes suffice.
    for (int pass = 0; pass < 4; ++pass) {
        const double d = target_ - s.position;
        if (a_max <= 0) {   // unlimited acceleration: constant speed all the way
            if (d != 0)
                append(std::abs(d) / v_max, AxisState{s.position, std::copysign(v_max, d)}, 0);
            return;
        }
        if (d == 0 && s.velocity == 0)
            return;
        // Work in the frame where the target lies ahead (sign +1).
        const double dir = d != 0 ? std::copysign(1.0, d) : std::copysign(1.0, -s.velocity);
        const double x = dir * d;       // distance to go, >= 0
        const double u = dir * s.velocity;    // speed toward the target
        if (u < 0) {                    // moving away: brake to rest first
            const double t = -u / a_max;
            append(t, s, dir * a_max);
            s = integrate(s, dir * a_max, t);
            s.velocity = 0;
            continue;
        }
        if (u > v_max) {                // faster than allowed: brake to v_max first
            const double t = (u - v_max) / a_max;
            append(t, s, -dir * a_max);
            s = integrate(s, -dir * a_max, t);
            s.velocity = dir * v_max;
            continue;
        }
        if (u * u / (2 * a_max) > x) {  // cannot stop in time: overshoot, come back from rest
            const double t = u / a_max;
            append(t, s, -dir * a_max);
            s = integrate(s, -dir * a_max, t);
            s.velocity = 0;
            continue;
        }
        const double full_ramps = (2 * v_max * v_max - u * u) / (2 * a_max);
        double v_peak = v_max;
        double cruise = 0;
        if (full_ramps <= x)
            cruise = (x - full_ramps) / v_max;
        else
            v_peak = std::sqrt((2 * a_max * x + u * u) / 2);
        const double t_up = (v_peak - u) / a_max;
        append(t_up, s, dir * a_max);
        s = integrate(s, dir * a_max, t_up);
        s.velocity = dir * v_peak;
        append(cruise, s, 0);
        s = integrate(s, 0, cruise);
        append(v_peak / a_max, s, -dir * a_max);
        return;
    }
}

double MotionProfile::duration() const
{
    return segments_.empty() ? 0.0 : segments_.back().t0 + segments_.back().duration;
}

AxisState MotionProfile::sample(double t) const
{
    if (segments_.empty() || t >= duration())
        return AxisState{target_, 0.0};
    const Segment* seg = &segments_.front();
    for (const auto& s : segments_) {
        if (s.t0 > t)
            break;
        seg = &s;
    }
    return integrate(seg->start, seg->acceleration, seg->jerk, std::max(0.0, t - seg->t0));
}

} // namespace rigsim::models
