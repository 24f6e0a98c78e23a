// models::StickSlipPositioner under the control API's faults: a stall blocks the stage where
// it stands, slip shortens steps and slows closed-loop moves; and its velocity.

#include "models/stick_slip.hpp"
#include "models/world.hpp"

#include <catch2/catch.hpp>

namespace test_stick_slip_faults {

using namespace rigsim;
using namespace rigsim::models;

namespace {

StickSlipConfig plain()
{
    StickSlipConfig c;
    c.travel_min_nm = -1e7;
    c.travel_max_nm = 1e7;
    c.step_width_nm = 1000;
    return c;
}

StepBurst burst(std::int64_t steps, double frequency_hz)
{
    StepBurst b;
    b.steps = steps;
    b.frequency_hz = frequency_hz;
    return b;
}

} // namespace

TEST_CASE("stick-slip stall: a move under way ends where the stage is, outcome Blocked", "[unit][models][stick_slip]")
{
    Clock clock;
    World world(clock);
    auto& p = world.emplace<StickSlipPositioner>("mcs/0", clock, plain());
    int heard = 0;
    p.set_listener([&] { ++heard; });
    p.move_to(1'000'000, 1'000'000, 0);   // 1 s
    clock.advance(250);
    p.set_blocked(true);
    CHECK(heard == 1);
    CHECK(p.take_outcome() == StickSlipPositioner::Outcome::Blocked);
    CHECK(p.motion() == StickSlipPositioner::Motion::Rest);
    CHECK(p.position_nm() == Approx(250'000));
    CHECK(p.stop_min_nm() == Approx(250'000));
    CHECK(p.stop_max_nm() == Approx(250'000));
    clock.advance(2000);
    CHECK(p.position_nm() == Approx(250'000));
    p.set_blocked(false);
    CHECK(p.stop_max_nm() == 1e7);
}

TEST_CASE("stick-slip stall: steps go on without moving, from the step the stall began", "[unit][models][stick_slip]")
{
    Clock clock;
    World world(clock);
    auto& p = world.emplace<StickSlipPositioner>("mcs/0", clock, plain());
    p.start_burst(burst(100, 1000));
    clock.advance(10);
    p.set_blocked(true);   // the 10 steps due so far were made
    clock.advance(50);
    CHECK(p.steps_done() == 60);
    CHECK(p.position_nm() == 10'000.0);
    CHECK(p.velocity_nm_per_s() == 0.0);
    p.set_blocked(false);
    clock.advance(10);
    CHECK(p.position_nm() == 20'000.0);
    CHECK(p.velocity_nm_per_s() == 1'000'000.0);   // 1000 nm × 1000 Hz
}

TEST_CASE("stick-slip slip: shorter steps and slower closed-loop moves", "[unit][models][stick_slip]")
{
    Clock clock;
    World world(clock);
    auto& p = world.emplace<StickSlipPositioner>("mcs/0", clock, plain());
    p.set_slip(0.25);
    p.start_burst(burst(10, 1000));
    clock.advance(20);
    CHECK(p.position_nm() == 7'500.0);
    const Ticks end = p.move_to(17'500, 10'000, 0);   // 10 µm at 7.5 µm/s
    CHECK(end - clock.now() == 1334);
    clock.advance(667);
    CHECK(p.velocity_nm_per_s() == Approx(7'500));
}

} // namespace test_stick_slip_faults
