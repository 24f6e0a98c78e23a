// models::Axis obstacles (a collision): each acts as the end stop on its side while set. A servo
// stalls against it, a stepper loses microsteps; motion away is free; clearing it frees the axis.

#include "models/axis.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <optional>
#include <utility>
#include <vector>

namespace test_axis_obstacles {

using namespace rigsim;
using namespace rigsim::models;

namespace {

using Events = std::vector<std::pair<AxisEvent, Ticks>>;

/// A linear axis of 100,000 counts standing at 50,000 (limit switches stop it: the default).
AxisConfig linear(Drive drive)
{
    AxisConfig c;
    c.drive = drive;
    c.travel_min_counts = 0;
    c.travel_max_counts = 100'000;
    c.start_position_counts = 50'000;
    return c;
}

struct Rig {
    explicit Rig(const AxisConfig& config) : world(clock), axis(world.emplace<Axis>("dev/1", clock, config))
    {
        axis.set_listener([this](AxisEvent e) { events.emplace_back(e, clock.now()); });
    }
    Clock clock;   // 1 kHz
    World world;
    Axis& axis;
    Events events;
};

Ticks end_tick(const MotionProfile& p, Ticks start)
{
    return start + static_cast<Ticks>(std::ceil(p.duration() * 1000 - 1e-9));
}

/// The first tick at which the profile (planned at tick 0) is past `at` (upward, or downward).
Ticks first_tick_past(const MotionProfile& p, double at, bool upward)
{
    const Ticks end = end_tick(p, 0);
    for (Ticks k = 1; k < end; ++k) {
        const double x = p.sample(k / 1000.0).position;
        if (upward ? x > at + 1e-6 : x < at - 1e-6)
            return k;
    }
    return end;
}

} // namespace

TEST_CASE("axis obstacle: a servo meeting one stalls there, at the tick it is crossed, no switch is pressed",
          "[unit][models][axis]")
{
    Rig r(linear(Drive::Servo));
    r.axis.set_obstacles(std::nullopt, 70'000.0);
    r.axis.move_to(90'000, 20'000, 40'000);
    const auto p = MotionProfile::plan(AxisState{50'000, 0}, 90'000, 20'000, 40'000);
    const Ticks crossing = first_tick_past(p, 70'000, true);
    CHECK(r.axis.next_event(0) == crossing);
    r.clock.advance(10'000);
    // Stalled (a motion error), not StoppedAtLimit: the limit switches would stop the axis.
    CHECK(r.events == Events{{AxisEvent::Stalled, crossing}});
    CHECK(r.axis.position_counts() == 70'000);
    CHECK_FALSE(r.axis.moving());
    CHECK(r.axis.switch_pressed() == 0);
    // Against it again: stalled on the next tick, where it stands.
    r.axis.move_to(80'000, 20'000, 40'000);
    r.clock.advance(10);
    CHECK(r.events.back() == std::make_pair(AxisEvent::Stalled, Ticks{10'001}));
    CHECK(r.axis.position_counts() == 70'000);
}

TEST_CASE("axis obstacle: set mid-motion where the carriage stands, it stops the motion on the next tick",
          "[unit][models][axis]")
{
    SECTION("servo: Stalled at the tick after, where the carriage was")
    {
        Rig r(linear(Drive::Servo));
        r.axis.move_to(10'000, 20'000, 40'000);   // downward
        r.clock.advance(700);
        const double here = r.axis.position_counts();
        CHECK(r.axis.velocity_counts_per_s() < 0);
        r.axis.set_obstacles(here, std::nullopt);
        CHECK(r.axis.position_counts() == here);   // not moved by the re-plan
        CHECK(r.axis.next_event(r.clock.now()) == 701);
        r.clock.advance(1);
        CHECK(r.events == Events{{AxisEvent::Stalled, 701}});
        CHECK(r.axis.position_counts() == here);
    }
    SECTION("an obstacle on the other side does not stop it")
    {
        Rig r(linear(Drive::Servo));
        r.axis.move_to(10'000, 20'000, 40'000);
        r.clock.advance(700);
        r.axis.set_obstacles(std::nullopt, r.axis.position_counts());
        r.clock.advance(10'000);
        CHECK(r.events.size() == 1);
        CHECK(r.events[0].first == AxisEvent::Arrived);
        CHECK(r.axis.position_counts() == 10'000);
    }
}

TEST_CASE("axis obstacle: a stepper loses microsteps against one and runs on, its counters count",
          "[unit][models][axis]")
{
    Rig r(linear(Drive::Stepper));
    r.axis.set_obstacles(std::nullopt, 70'000.0);
    r.axis.move_to(90'000, 20'000, 40'000);
    const auto p = MotionProfile::plan(AxisState{50'000, 0}, 90'000, 20'000, 40'000);
    const Ticks crossing = first_tick_past(p, 70'000, true);
    const Ticks end = end_tick(p, 0);
    r.clock.advance_to(crossing + 50);
    CHECK(r.events == Events{{AxisEvent::LostSteps, crossing}});
    CHECK(r.axis.moving());
    CHECK(r.axis.position_counts() == 70'000);
    CHECK(r.axis.velocity_counts_per_s() == 0);
    CHECK(r.axis.motor_position_counts() == Approx(p.sample((crossing + 50) / 1000.0).position));
    r.clock.advance(10'000);
    CHECK(r.events == Events{{AxisEvent::LostSteps, crossing}, {AxisEvent::Arrived, end}});
    CHECK(r.axis.position_counts() == 70'000);
    CHECK(r.axis.lost_counts() == Approx(20'000));
    CHECK(r.axis.motor_position_counts() == Approx(90'000));
}

TEST_CASE("axis obstacle: motion away is free, and clearing it frees the axis", "[unit][models][axis]")
{
    for (const Drive drive : {Drive::Servo, Drive::Stepper}) {
        Rig r(linear(drive));
        r.axis.set_obstacles(std::nullopt, 60'000.0);
        r.axis.move_to(40'000, 20'000, 40'000);   // away
        r.clock.advance(10'000);
        CHECK(r.events == Events{{AxisEvent::Arrived, r.events.at(0).second}});
        CHECK(r.axis.position_counts() == 40'000);
        r.axis.set_obstacles(std::nullopt, std::nullopt);
        CHECK_FALSE(r.axis.obstacle_max_counts());
        r.axis.move_to(90'000, 20'000, 40'000);   // through where it was
        r.clock.advance(10'000);
        CHECK(r.events.size() == 2);
        CHECK(r.events.back().first == AxisEvent::Arrived);
        CHECK(r.axis.position_counts() == 90'000);
        CHECK(r.axis.lost_counts() == 0);
    }
}

TEST_CASE("axis obstacle: cleared while a stepper presses on it, the carriage follows on from there",
          "[unit][models][axis]")
{
    Rig r(linear(Drive::Stepper));
    r.axis.set_obstacles(std::nullopt, 60'000.0);
    r.axis.move_to(90'000, 10'000, 0);   // 10,000 counts/s from the first tick: on the obstacle at 1 s
    r.clock.advance(1'500);
    CHECK(r.axis.position_counts() == 60'000);
    CHECK(r.axis.lost_counts() == Approx(5'000));
    r.axis.set_obstacles(std::nullopt, std::nullopt);
    CHECK(r.axis.position_counts() == 60'000);
    r.clock.advance(1'000);
    CHECK(r.axis.position_counts() == Approx(70'000));
    CHECK(r.axis.velocity_counts_per_s() == 10'000);
    r.clock.advance(10'000);
    // The motor reached its target; the carriage fell short by the steps lost on the obstacle.
    CHECK(r.axis.motor_position_counts() == Approx(90'000));
    CHECK(r.axis.position_counts() == Approx(85'000));
    CHECK(r.events.back().first == AxisEvent::Arrived);
}

TEST_CASE("axis obstacle: a carriage already past one is held where it stands, not put back",
          "[unit][models][axis]")
{
    Rig r(linear(Drive::Servo));
    r.axis.set_obstacles(20'000.0, 45'000.0);   // the carriage stands at 50,000
    CHECK(r.axis.obstacle_max_counts() == 50'000);
    CHECK(r.axis.obstacle_min_counts() == 20'000);
    CHECK(r.axis.position_counts() == 50'000);
    r.axis.move_to(60'000, 20'000, 40'000);
    r.clock.advance(10);
    CHECK(r.events == Events{{AxisEvent::Stalled, 1}});
    CHECK(r.axis.position_counts() == 50'000);
    r.axis.move_to(10'000, 20'000, 40'000);   // down to the other obstacle
    r.clock.advance(10'000);
    CHECK(r.events.back().first == AxisEvent::Stalled);
    CHECK(r.axis.position_counts() == 20'000);
}

TEST_CASE("axis obstacle: a rotation stage, which has no end stops, meets one too", "[unit][models][axis]")
{
    AxisConfig c;
    c.drive = Drive::Servo;
    c.rotary = true;
    c.kind = models::BodyKind::Rotary;
    c.travel_min_counts = -1e9;
    c.travel_max_counts = 1e9;
    c.counts_per_turn = 3'600;
    Rig r(c);
    r.axis.set_obstacles(std::nullopt, 1'000.0);
    r.axis.set_limit_switches(false, false);
    r.axis.move_to(r.axis.run_target_counts(true), 1'000, 0);
    r.clock.advance(5'000);
    CHECK(r.events == Events{{AxisEvent::Stalled, 1'001}});
    CHECK(r.axis.position_counts() == 1'000);
}

TEST_CASE("axis obstacle: a travel limit short of the obstacle stops the axis first", "[unit][models][axis]")
{
    Rig r(linear(Drive::Servo));
    r.axis.set_obstacles(std::nullopt, 95'000.0);
    r.axis.set_limits(0, 80'000);
    r.axis.move_to(90'000, 20'000, 40'000);
    r.clock.advance(10'000);
    CHECK(r.events.back().first == AxisEvent::Arrived);   // planned to the narrowed limit
    CHECK(r.axis.position_counts() == 80'000);
    r.axis.set_limits(0, 100'000);
    r.axis.move_to(100'000, 20'000, 40'000);
    r.clock.advance(10'000);
    CHECK(r.events.back().first == AxisEvent::Stalled);
    CHECK(r.axis.position_counts() == 95'000);
}

} // namespace test_axis_obstacles
