#pragma once
// Point-to-point motion profiles in one axis: trapezoidal (bang-coast-bang) and
// jerk-limited S-curve.
//
// A profile is planned once, from the axis state (position, velocity) at the moment a
// move is commanded, as a list of constant-acceleration segments; it is then sampled at
// any time since planning. Sampling is exact, so arrival time does not depend on the
// physics tick. Units are whatever the caller uses consistently (rigsim: nm, nm/s, nm/s^2).

#include <vector>

namespace rigsim::models {

/// One axis's state at an instant, in the caller's stage unit (nm, counts, ...) and that unit per second.
struct AxisState {
    double position = 0;   ///< stage unit
    double velocity = 0;   ///< stage unit per second
};

/// One constant-jerk stretch of a profile (jerk 0: constant acceleration).
struct Segment {
    double t0 = 0;         ///< start, seconds since the profile was planned
    double duration = 0;   ///< seconds
    AxisState start;       ///< state at t0
    double acceleration = 0;   ///< at t0
    double jerk = 0;
};

class MotionProfile {
public:
    /// Plan a move from `from` to `target`. `v_max` > 0; `a_max` == 0 means unlimited
    /// acceleration (the axis jumps to v_max). A start velocity pointing away from the
    /// target, or too fast to stop in time, is first braked to rest.
    static MotionProfile plan(const AxisState& from, double target, double v_max, double a_max);
    /// Plan a jerk-limited (S-curve) move: acceleration ramps from 0 to at most `a_max` at
    /// `j_max` and back, the same in reverse to stop at the target (seven segments, fewer
    /// for short moves). From a moving start, or with `a_max` or `j_max` <= 0, this is plan().
    static MotionProfile plan_s_curve(const AxisState& from, double target, double v_max, double a_max,
                                         double j_max);

    /// State at `t` seconds after planning; the target at rest from duration() on.
    AxisState sample(double t) const;
    double duration() const;
    double target() const { return target_; }
    const std::vector<Segment>& segments() const { return segments_; }

private:
    void append(double duration, const AxisState& start, double acceleration, double jerk = 0);
    void plan_from(AxisState from, double v_max, double a_max);

    std::vector<Segment> segments_;
    double target_ = 0;
};

/// State after `t` seconds of constant acceleration `a` from `s`.
AxisState integrate(const AxisState& s, double a, double t);
/// State after `t` seconds from `s` with acceleration `a` at the start and constant jerk `j`.
AxisState integrate(const AxisState& s, double a, double j, double t);

} // namespace rigsim::models
