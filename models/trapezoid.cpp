#include "models/trapezoid.hpp"

#include <cmath>

namespace rigsim::models {

AxisState integrate(const AxisState& s, double a, double t)
{
    return AxisState{s[0] + s[1] * t + 0.5 * a * t * t, s[1] + a * t};
}

void TrapezoidProfile::append(double duration, const AxisState& start, double acceleration)
{
    if (duration <= 0)
        return;
    const double t0 = segments_.empty() ? 0.0 : segments_.back().t0 + segments_.back().duration;
    segments_.push_back(Segment{t0, duration, start, acceleration});
}

TrapezoidProfile TrapezoidProfile::plan(const AxisState& from, double target, double v_max,
                                        double a_max)
{
    TrapezoidProfile p;
    p.target_ = target;
    if (v_max <= 0)
        return p;   // cannot move: the caller refuses such moves before planning
    p.plan_from(from, v_max, a_max);
    return p;
}

void TrapezoidProfile::plan_from(AxisState s, double v_max, double a_max)
{
    // Each pass either finishes the plan or brings the axis to a simpler state
    // (at rest, or moving toward the target no faster than v_max); three passes suffice.
    for (int pass = 0; pass < 4; ++pass) {
        const double d = target_ - s[0];
        if (a_max <= 0) {   // unlimited acceleration: constant speed all the way
            if (d != 0)
                append(std::abs(d) / v_max, AxisState{s[0], std::copysign(v_max, d)}, 0);
            return;
        }
        if (d == 0 && s[1] == 0)
            return;
        // Work in the frame where the target lies ahead (sign +1).
        const double dir = d != 0 ? std::copysign(1.0, d) : std::copysign(1.0, -s[1]);
        const double x = dir * d;       // distance to go, >= 0
        const double u = dir * s[1];    // speed toward the target
        if (u < 0) {                    // moving away: brake to rest first
            const double t = -u / a_max;
            append(t, s, dir * a_max);
            s = integrate(s, dir * a_max, t);
            s[1] = 0;
            continue;
        }
        if (u > v_max) {                // faster than allowed: brake to v_max first
            const double t = (u - v_max) / a_max;
            append(t, s, -dir * a_max);
            s = integrate(s, -dir * a_max, t);
            s[1] = dir * v_max;
            continue;
        }
        if (u * u / (2 * a_max) > x) {  // cannot stop in time: overshoot, come back from rest
            const double t = u / a_max;
            append(t, s, -dir * a_max);
            s = integrate(s, -dir * a_max, t);
            s[1] = 0;
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
        s[1] = dir * v_peak;
        append(cruise, s, 0);
        s = integrate(s, 0, cruise);
        append(v_peak / a_max, s, -dir * a_max);
        return;
    }
}

double TrapezoidProfile::duration() const
{
    return segments_.empty() ? 0.0 : segments_.back().t0 + segments_.back().duration;
}

AxisState TrapezoidProfile::sample(double t) const
{
    if (segments_.empty() || t >= duration())
        return AxisState{target_, 0.0};
    const Segment* seg = &segments_.front();
    for (const auto& s : segments_) {
        if (s.t0 > t)
            break;
        seg = &s;
    }
    return integrate(seg->start, seg->acceleration, std::max(0.0, t - seg->t0));
}

} // namespace rigsim::models
