// Trapezoidal motion: a move takes the time its speed and acceleration imply.
#include "models/motion_profile.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace test_motion_profile {

using rigsim::models::AxisState;
using rigsim::models::MotionProfile;

TEST_CASE("unlimited acceleration moves at constant speed", "[unit][models]")
{
    const auto p = MotionProfile::plan(AxisState{0, 0}, 2e6, 1e7, 0);
    CHECK(p.duration() == Approx(0.2));
    CHECK(p.sample(0.1).position == Approx(1e6));
    CHECK(p.sample(0.1).velocity == Approx(1e7));
    CHECK(p.sample(0.3).position == 2e6);
    CHECK(p.sample(0.3).velocity == 0);
}

TEST_CASE("a long move reaches top speed: T = d/v + v/a", "[unit][models]")
{
    const double d = 5e6, v = 1e6, a = 1e7;   // nm, nm/s, nm/s^2
    const auto p = MotionProfile::plan(AxisState{0, 0}, -d, v, a);
    CHECK(p.duration() == Approx(d / v + v / a));
    CHECK(p.sample(v / a).velocity == Approx(-v));                   // end of the ramp
    CHECK(p.sample(v / a).position == Approx(-0.5 * v * v / a));
    CHECK(p.sample(p.duration() / 2).velocity == Approx(-v));         // cruising
    CHECK(p.sample(p.duration()).position == -d);
}

TEST_CASE("a short move is triangular: T = 2 sqrt(d/a)", "[unit][models]")
{
    const double d = 1e4, v = 1e6, a = 1e7;
    const auto p = MotionProfile::plan(AxisState{100, 0}, 100 + d, v, a);
    CHECK(p.duration() == Approx(2 * std::sqrt(d / a)));
    CHECK(p.sample(p.duration() / 2).position == Approx(100 + d / 2));
    CHECK(p.sample(p.duration() / 2).velocity == Approx(std::sqrt(d * a)));
}

TEST_CASE("retargeting while moving brakes and comes back", "[unit][models]")
{
    const double v = 1e6, a = 1e7;
    // Moving at +v, new target behind: brake (v/a), then a triangle/trapezoid back.
    const auto p = MotionProfile::plan(AxisState{0, v}, -1e6, v, a);
    const double brake = v / a;
    const double stop_pos = v * v / (2 * a);
    CHECK(p.sample(brake).velocity == Approx(0).margin(1e-6));
    CHECK(p.sample(brake).position == Approx(stop_pos));
    CHECK(p.duration() == Approx(brake + (1e6 + stop_pos) / v + v / a));
    CHECK(p.sample(p.duration()).position == -1e6);

    // Moving toward a target too close to stop in time: overshoot, then return.
    const auto q = MotionProfile::plan(AxisState{0, v}, 1000, v, a);
    double peak = 0;
    for (double t = 0; t < q.duration(); t += q.duration() / 1000)
        peak = std::max(peak, q.sample(t).position);
    CHECK(peak == Approx(v * v / (2 * a)).epsilon(1e-3));
    CHECK(q.sample(q.duration()).position == 1000);
}

TEST_CASE("position is continuous along a profile", "[unit][models]")
{
    const auto p = MotionProfile::plan(AxisState{0, -3e5}, 4e6, 1e6, 2e6);
    AxisState prev = p.sample(0);
    const double dt = p.duration() / 10000;
    for (double t = dt; t <= p.duration(); t += dt) {
        const auto s = p.sample(t);
        CHECK(std::abs(s.position - prev.position) <= 1e6 * dt * 1.01 + 1e-6);
        prev = s;
    }
}

TEST_CASE("an S-curve move takes d/v + v/a + a/j and ends at rest on the target", "[unit][models]")
{
    // a reached (v j >= a^2): each ramp lasts v/a + a/j; cruise makes up the rest.
    const double v = 10, a = 20, j = 1000, d = 100;
    const auto p = MotionProfile::plan_s_curve(AxisState{5, 0}, 5 + d, v, a, j);
    CHECK(p.duration() == Approx(d / v + v / a + a / j));
    CHECK(p.segments().size() == 7);
    CHECK(p.sample(p.duration()).position == 5 + d);
    CHECK(p.sample(p.duration() * 0.999999).position == Approx(5 + d));
    CHECK(p.sample(p.duration() * 0.999999).velocity == Approx(0).margin(1e-3));
    CHECK(p.sample(p.duration() / 2).velocity == Approx(v));
    // Jerk ramps the acceleration: after one jerk time it has just reached a.
    CHECK(p.sample(a / j).velocity == Approx(0.5 * j * (a / j) * (a / j)));
}

TEST_CASE("an S-curve limits acceleration and jerk and never runs backwards", "[unit][models]")
{
    const double v = 3, a = 8, j = 40;
    for (const double d : {-50.0, -0.2, 0.05, 1.0, 30.0}) {
        const auto p = MotionProfile::plan_s_curve(AxisState{0, 0}, d, v, a, j);
        const double dt = p.duration() / 20000;
        double prev_v = 0, prev_a = 0, prev_x = 0;
        for (double t = dt; t <= p.duration(); t += dt) {
            const auto s = p.sample(t);
            const double acc = (s.velocity - prev_v) / dt;
            CHECK(std::abs(s.velocity) <= v * (1 + 1e-9));
            CHECK(std::abs(acc) <= a * 1.001 + 1e-9);
            if (t > 2 * dt)
                CHECK(std::abs(acc - prev_a) <= j * dt * 1.01 + 1e-9);
            CHECK(std::copysign(1.0, d) * (s.position - prev_x) >= -1e-12);
            prev_v = s.velocity;
            prev_a = acc;
            prev_x = s.position;
        }
        CHECK(p.sample(p.duration()).position == d);
    }
}

TEST_CASE("an S-curve short move peaks below top speed and is slower than a trapezoid", "[unit][models]")
{
    const auto s = MotionProfile::plan_s_curve(AxisState{0, 0}, 0.5, 10, 20, 1000);
    const auto t = MotionProfile::plan(AxisState{0, 0}, 0.5, 10, 20);
    CHECK(s.sample(s.duration() / 2).velocity < 10);
    CHECK(s.sample(s.duration() / 2).position == Approx(0.25));
    CHECK(s.duration() > t.duration());
    // From a moving start the plan falls back to the trapezoid.
    const auto m = MotionProfile::plan_s_curve(AxisState{0, 1}, 5, 10, 20, 1000);
    CHECK(m.duration() == Approx(MotionProfile::plan(AxisState{0, 1}, 5, 10, 20).duration()));
}

} // namespace test_motion_profile
