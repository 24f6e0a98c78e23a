// models::Axis under the control API's set-up and faults: placing the carriage, a jam (servo
// stall, stepper losing its steps), lost microsteps (slip) and a limit switch held pressed.

#include "models/axis.hpp"

#include <catch2/catch.hpp>

#include <utility>
#include <vector>

namespace test_axis_faults {

using namespace rigsim;
using namespace rigsim::models;

namespace {

/// A linear axis of 100,000 counts standing at 50,000.
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
    std::vector<std::pair<AxisEvent, Ticks>> events;
};

} // namespace

TEST_CASE("Axis::place puts the carriage at rest within the end stops, lost steps kept", "[unit][models][axis]")
{
    Rig r(linear(Drive::Servo));
    r.axis.move_to(60'000, 10'000, 100'000);
    r.clock.advance_ms(100);
    r.axis.place(20'000);
    CHECK(!r.axis.moving());
    CHECK(r.axis.position_counts() == 20'000);
    r.clock.advance_ms(5000);
    CHECK(r.events.empty());   // the move it interrupted never ends
    r.axis.place(200'000);
    CHECK(r.axis.position_counts() == 100'000);
}

TEST_CASE("a jammed servo stalls on the tick after its motion starts, where it stands", "[unit][models][axis]")
{
    Rig r(linear(Drive::Servo));
    r.axis.set_jammed(true);
    r.axis.move_to(60'000, 10'000, 100'000);
    r.clock.advance_ms(10);
    REQUIRE(r.events.size() == 1);
    CHECK(r.events[0] == std::make_pair(AxisEvent::Stalled, Ticks{1}));
    CHECK(r.axis.position_counts() == 50'000);
    CHECK(!r.axis.moving());
    r.axis.set_jammed(false);
    r.axis.move_to(60'000, 10'000, 100'000);
    r.clock.advance_ms(5000);
    CHECK(r.events.back().first == AxisEvent::Arrived);
    CHECK(r.axis.position_counts() == Approx(60'000));
}

TEST_CASE("a jammed stepper's motor runs its profile, the carriage stays, unjammed mid-way it follows on", "[unit][models][axis]")
{
    Rig r(linear(Drive::Stepper));
    r.axis.move_to(60'000, 10'000, 100'000);
    r.clock.advance_ms(300);
    const double at_jam = r.axis.position_counts();
    r.axis.set_jammed(true);
    r.clock.advance_ms(200);
    CHECK(r.axis.position_counts() == at_jam);
    CHECK(r.axis.motor_position_counts() > at_jam);
    CHECK(r.axis.velocity_counts_per_s() == 0);
    const double motor_then = r.axis.motor_position_counts();
    r.axis.set_jammed(false);
    r.clock.advance_ms(5000);
    REQUIRE(r.events.size() == 1);
    CHECK(r.events[0].first == AxisEvent::Arrived);
    CHECK(r.axis.motor_position_counts() == Approx(60'000));
    CHECK(r.axis.position_counts() == Approx(60'000 - (motor_then - at_jam)));
}

TEST_CASE("slip: a stepper's carriage falls short by counts plus a fraction of the move, a servo's does not", "[unit][models][axis]")
{
    Rig r(linear(Drive::Stepper));
    r.axis.set_slip(100, 0.1);
    r.axis.move_to(60'000, 10'000, 100'000);
    r.clock.advance_ms(5000);
    CHECK(r.axis.motor_position_counts() == Approx(60'000));
    CHECK(r.axis.position_counts() == Approx(60'000 - 100 - 1'000));
    CHECK(r.axis.lost_counts() == Approx(1'100));

    Rig servo(linear(Drive::Servo));
    servo.axis.set_slip(100, 0.1);
    servo.axis.move_to(60'000, 10'000, 100'000);
    servo.clock.advance_ms(5000);
    CHECK(servo.axis.position_counts() == Approx(60'000));
}

TEST_CASE("a pressed limit switch ends motion toward it at once, and stops one under way", "[unit][models][axis]")
{
    Rig r(linear(Drive::Servo));
    r.axis.set_switch_pressed(+1);
    r.axis.move_to(60'000, 10'000, 100'000);
    REQUIRE(r.events.size() == 1);
    CHECK(r.events[0].first == AxisEvent::Arrived);
    CHECK(r.axis.position_counts() == 50'000);
    r.axis.move_to(40'000, 10'000, 100'000);   // away from it
    r.clock.advance_ms(5000);
    CHECK(r.axis.position_counts() == Approx(40'000));
    r.events.clear();
    r.axis.set_switch_pressed(0);
    r.axis.move_to(60'000, 10'000, 100'000);
    r.clock.advance_ms(300);
    r.axis.set_switch_pressed(+1);
    r.clock.advance_ms(10);
    REQUIRE(r.events.size() == 1);
    CHECK(r.events[0].first == AxisEvent::StoppedAtLimit);
    CHECK(!r.axis.moving());
    CHECK(r.axis.position_counts() > 40'000);
    CHECK(r.axis.position_counts() < 60'000);
}

} // namespace test_axis_faults
