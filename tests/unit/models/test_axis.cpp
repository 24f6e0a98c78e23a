// models::Axis: a motor-driven axis whose state is a function of clock time, woken by the
// World only at its events (end of profile, a limit or soft stop crossed).

#include "models/axis.hpp"

#include "emulator/apt/catalogue.hpp"
#include "emulator/apt/shipped_stages.hpp"
#include "emulator/apt/motor_channel.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <utility>
#include <vector>

namespace test_axis {

using namespace rigsim;
using namespace rigsim::models;

namespace {

/// An axis that counts its wake-ups.
class CountingAxis : public Axis {
public:
    using Axis::Axis;
    void on_event(Ticks now) override
    {
        ++wakeups;
        Axis::on_event(now);
    }
    int wakeups = 0;
};

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
    explicit Rig(const AxisConfig& config)
        : world(clock), axis(world.emplace<CountingAxis>("dev/1", clock, config))
    {
        axis.set_listener([this](AxisEvent e) { events.emplace_back(e, clock.now()); });
    }
    Clock clock;   // 1 kHz
    World world;
    CountingAxis& axis;
    std::vector<std::pair<AxisEvent, Ticks>> events;
};

Ticks end_tick(const MotionProfile& p, Ticks start)
{
    return start + static_cast<Ticks>(std::ceil(p.duration() * 1000 - 1e-9));
}

/// The first tick at which sampling `p` every tick sees the position pass `limit` upward (the
/// old per-tick rule, with its tolerance for an end stop when `tolerance` is set).
Ticks first_tick_beyond(const MotionProfile& p, double limit, bool tolerance)
{
    const Ticks end = end_tick(p, 0);
    for (Ticks k = 1; k < end; ++k) {
        const double x = p.sample(k / 1000.0).position;
        if (tolerance ? x > limit + 1e-6 : x >= limit)
            return k;
    }
    return end;
}

} // namespace

TEST_CASE("axis: a move ends at its planned tick and is sampled exactly in between", "[unit][models][axis]")
{
    Rig r(linear(Drive::Servo));
    r.clock.advance(7);
    r.axis.move_to(80'000, 10'000, 20'000);
    const auto p = MotionProfile::plan(AxisState{50'000, 0}, 80'000, 10'000, 20'000);
    const Ticks end = end_tick(p, 7);
    CHECK(r.axis.next_event(r.clock.now()) == end);
    for (const Ticks t : {Ticks{1}, Ticks{250}, Ticks{500}, Ticks{1999}, end - 8}) {
        r.clock.advance_to(7 + t);
        CHECK(r.axis.position_counts() == p.sample(t / 1000.0).position);
        CHECK(r.axis.velocity_counts_per_s() == p.sample(t / 1000.0).velocity);
        CHECK(r.axis.moving());
    }
    CHECK(r.events.empty());
    r.clock.advance_to(end);
    CHECK(r.events == std::vector<std::pair<AxisEvent, Ticks>>{{AxisEvent::Arrived, end}});
    CHECK(r.axis.position_counts() == 80'000);
    CHECK(r.axis.velocity_counts_per_s() == 0);
    CHECK_FALSE(r.axis.moving());
}

TEST_CASE("axis: a moving axis is woken once, at the end of its move, not once per tick", "[unit][models][axis]")
{
    Rig r(linear(Drive::Servo));
    r.axis.move_to(0, 5'000, 10'000, 40'000);   // an S-curve of about 10.5 s
    const Ticks end = r.axis.next_event(0);
    CHECK(end > 10'000);
    int clock_wakeups = 0;
    while (r.axis.moving()) {
        r.clock.advance_to(r.clock.next_wakeup());
        ++clock_wakeups;
    }
    CHECK(r.clock.now() == end);
    CHECK(r.axis.wakeups == 1);
    CHECK(clock_wakeups == 1);
    CHECK(r.axis.position_counts() == 0);
}

TEST_CASE("axis: at an end stop whose switch is ignored a servo stalls and a stepper loses steps",
          "[unit][models][axis]")
{
    const auto p = MotionProfile::plan(AxisState{50'000, 0}, 130'000, 20'000, 40'000);
    const Ticks crossing = first_tick_beyond(p, 100'000, true);
    SECTION("servo: stalled at the stop, the motion ends there")
    {
        Rig r(linear(Drive::Servo));
        r.axis.set_limit_switches(false, false);
        r.axis.move_to(130'000, 20'000, 40'000);
        CHECK(r.axis.next_event(0) == crossing);
        r.clock.advance(10'000);
        CHECK(r.events == std::vector<std::pair<AxisEvent, Ticks>>{{AxisEvent::Stalled, crossing}});
        CHECK(r.axis.position_counts() == 100'000);
        CHECK(r.axis.lost_counts() == 0);
        CHECK(r.axis.wakeups == 1);
    }
    SECTION("stepper: runs on against the stop to the profile's end, its motor counts the lost steps")
    {
        Rig r(linear(Drive::Stepper));
        r.axis.set_limit_switches(false, false);
        r.axis.move_to(130'000, 20'000, 40'000);
        const Ticks end = end_tick(p, 0);
        r.clock.advance_to(crossing + 100);
        CHECK(r.axis.position_counts() == 100'000);
        CHECK(r.axis.velocity_counts_per_s() == 0);
        CHECK(r.axis.motor_position_counts() == Approx(p.sample((crossing + 100) / 1000.0).position));
        r.clock.advance(10'000);
        CHECK(r.events
              == std::vector<std::pair<AxisEvent, Ticks>>{{AxisEvent::LostSteps, crossing}, {AxisEvent::Arrived, end}});
        CHECK(r.axis.position_counts() == 100'000);
        CHECK(r.axis.lost_counts() == Approx(30'000));
        CHECK(r.axis.wakeups == 2);
    }
}

TEST_CASE("axis: a limit switch that stops the axis ends the motion on it", "[unit][models][axis]")
{
    SECTION("planned: a target past the switch is planned to stop at it")
    {
        Rig r(linear(Drive::Servo));
        r.axis.move_to(130'000, 20'000, 40'000);
        CHECK(r.axis.target_counts() == 100'000);
        r.clock.advance(10'000);
        REQUIRE(r.events.size() == 1);
        CHECK(r.events[0].first == AxisEvent::Arrived);
        CHECK(r.axis.position_counts() == 100'000);
    }
    SECTION("switched on during a run past the end: stopped at the tick it is crossed")
    {
        Rig r(linear(Drive::Stepper));
        r.axis.set_limit_switches(false, false);
        r.axis.move_to(r.axis.run_target_counts(true), 20'000, 40'000);
        r.clock.advance(100);
        r.axis.set_limit_switches(true, true);
        const auto p = MotionProfile::plan(AxisState{50'000, 0}, 200'000, 20'000, 40'000);
        const Ticks crossing = first_tick_beyond(p, 100'000, true);
        CHECK(r.axis.next_event(r.clock.now()) == crossing);
        r.clock.advance(10'000);
        CHECK(r.events == std::vector<std::pair<AxisEvent, Ticks>>{{AxisEvent::StoppedAtLimit, crossing}});
        CHECK(r.axis.position_counts() == 100'000);
        CHECK(r.axis.lost_counts() == 0);
    }
}

TEST_CASE("axis: a soft stop stops the axis dead at the tick it is crossed", "[unit][models][axis]")
{
    Rig r(linear(Drive::Servo));
    r.axis.set_soft_stops(40'000, 60'000);
    r.axis.move_to(90'000, 20'000, 40'000);
    const auto p = MotionProfile::plan(AxisState{50'000, 0}, 90'000, 20'000, 40'000);
    const Ticks crossing = first_tick_beyond(p, 60'000, false);
    CHECK(r.axis.next_event(0) == crossing);
    r.clock.advance(10'000);
    CHECK(r.events == std::vector<std::pair<AxisEvent, Ticks>>{{AxisEvent::SoftStopped, crossing}});
    CHECK(r.axis.position_counts() == 60'000);
    // Only a crossing counts: standing on the stop, the axis may move back in.
    r.axis.move_to(45'000, 20'000, 40'000);
    r.clock.advance(10'000);
    CHECK(r.events.back().first == AxisEvent::Arrived);
    CHECK(r.axis.position_counts() == 45'000);
}

TEST_CASE("axis: a rotation stage has no ends and a home switch once per turn", "[unit][models][axis]")
{
    AxisConfig c;
    c.drive = Drive::Servo;
    c.rotary = true;
    c.kind = models::BodyKind::Rotary;
    c.travel_min_counts = -1e9;
    c.travel_max_counts = 1e9;
    c.counts_per_turn = 3'600;
    c.start_position_counts = 1'800;
    Rig r(c);
    CHECK(r.axis.next_home_switch_counts(true) == 3'600);
    CHECK(r.axis.next_home_switch_counts(false) == 0);
    r.axis.move_to(r.axis.next_home_switch_counts(true), 1'000, 0);
    r.clock.advance(2'000);
    CHECK(r.axis.position_counts() == 3'600);
    // From on a switch, the next one ahead is a turn away.
    CHECK(r.axis.next_home_switch_counts(true) == 7'200);
    CHECK(r.axis.next_home_switch_counts(false) == 0);
    // A run turns on through many turns: no end stop stalls it.
    r.axis.set_limit_switches(false, false);
    r.axis.move_to(r.axis.run_target_counts(true), 100'000, 0);
    r.clock.advance(2'000);
    CHECK(r.axis.position_counts() == Approx(203'600));
    CHECK(r.events.size() == 1);
    CHECK(r.axis.moving());
}

TEST_CASE("axis: an immediate stop stops dead, a profiled stop decelerates", "[unit][models][axis]")
{
    Rig r(linear(Drive::Servo));
    r.axis.move_to(100'000, 10'000, 20'000);
    r.clock.advance(1'000);   // cruising at 10,000 counts/s from 0.5 s
    const double x = r.axis.position_counts();
    SECTION("immediate: no event, at rest where it was")
    {
        r.axis.stop_immediately();
        CHECK(r.axis.next_event(r.clock.now()) == kNever);
        r.clock.advance(5'000);
        CHECK(r.events.empty());
        CHECK(r.axis.position_counts() == x);
        CHECK(r.axis.velocity_counts_per_s() == 0);
        CHECK(r.axis.wakeups == 0);
    }
    SECTION("profiled: decelerates at the given rate, Arrived where it comes to rest")
    {
        r.axis.stop_profiled(20'000);
        CHECK(r.axis.next_event(r.clock.now()) == 1'500);
        r.clock.advance(5'000);
        CHECK(r.events == std::vector<std::pair<AxisEvent, Ticks>>{{AxisEvent::Arrived, 1'500}});
        CHECK(r.axis.position_counts() == Approx(x + 10'000.0 * 10'000 / (2 * 20'000)));
    }
}

TEST_CASE("axis: a TDC001 channel's long move wakes the world once per move, not 1,000 times a second",
          "[unit][models][axis]")
{
    Clock clock;
    World world(clock);
    apt::MotorChannel ch(*apt::find_controller("TDC001"), *apt::find_stage("MTS50-Z8"), world, "cube/1");
    ch.move_relative(-800'000);   // 23.3 mm at 2.4 mm/s: about 10 s
    const Ticks end = world.next_change(clock.now());
    CHECK(end > 9'000);
    CHECK(world.find_as<Axis>("cube/1") == &ch.axis());
    CHECK(ch.axis().next_event(clock.now()) == end);
    int wakeups = 0;
    while (ch.moving()) {
        clock.advance_to(clock.next_wakeup());
        ++wakeups;
    }
    CHECK(clock.now() == end);
    CHECK(wakeups == 1);
    CHECK(ch.position() == -800'000);
    CHECK(ch.take_events() == std::vector<apt::MotorEvent>{apt::MotorEvent::MoveCompleted});
}

TEST_CASE("axis: on the tick a move is commanded the axis still moves as it did", "[unit][models][axis]")
{
    // A per-tick integration samples the new profile from the next tick on: a move without an
    // acceleration limit reaches full speed there, not at once.
    Rig r(linear(Drive::Servo));
    r.clock.advance(3);
    r.axis.move_to(60'000, 10'000, 0);
    CHECK(r.axis.velocity_counts_per_s() == 0);
    CHECK(r.axis.position_counts() == 50'000);
    r.clock.advance(1);
    CHECK(r.axis.velocity_counts_per_s() == 10'000);
    CHECK(r.axis.position_counts() == 50'010);
}

TEST_CASE("axis: a rule changed while a stepper presses on its end stop acts from then on", "[unit][models][axis]")
{
    Rig r(linear(Drive::Stepper));
    r.axis.set_limit_switches(false, false);
    r.axis.move_to(r.axis.run_target_counts(true), 20'000, 40'000);
    r.clock.advance(4'000);   // on the stop since about 2.75 s
    const double lost = r.axis.lost_counts();
    CHECK(lost > 20'000);
    // The switch now stops the axis: what was lost stays lost, the carriage stays on the stop...
    r.axis.set_limit_switches(true, true);
    CHECK(r.axis.position_counts() == 100'000);
    CHECK(r.axis.lost_counts() == lost);
    // ... and the next step against it stops the axis there.
    r.clock.advance(1);
    REQUIRE(r.events.size() == 2);
    CHECK(r.events[1] == std::make_pair(AxisEvent::StoppedAtLimit, Ticks{4'001}));
    CHECK(r.axis.position_counts() == 100'000);
    CHECK(r.axis.lost_counts() == lost);
}

} // namespace test_axis
