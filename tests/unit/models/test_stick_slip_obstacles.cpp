// models::StickSlipPositioner obstacles (a collision): each narrows the travel on its side like
// a mechanical end stop. A closed-loop move or a search meeting one ends Blocked (as the stall
// fault's), steps against one go on without moving; motion away is free; clearing frees.

#include "models/stick_slip.hpp"
#include "models/world.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace test_stick_slip_obstacles {

using namespace rigsim;
using namespace rigsim::models;

namespace {

using Outcome = StickSlipPositioner::Outcome;

StickSlipConfig plain()
{
    StickSlipConfig c;
    c.travel_min_nm = -1e7;
    c.travel_max_nm = 1e7;
    c.step_width_nm = 1000;
    return c;
}

struct Rig {
    Rig() : world(clock), p(world.emplace<StickSlipPositioner>("mcs/0", clock, plain()))
    {
        p.set_listener([this] { heard.emplace_back(p.take_outcome(), clock.now()); });
    }
    Clock clock;   // 1 kHz
    World world;
    StickSlipPositioner& p;
    std::vector<std::pair<Outcome, Ticks>> heard;
};

StepBurst burst(std::int64_t steps, double frequency_hz, double direction = 1)
{
    StepBurst b;
    b.steps = steps;
    b.direction = direction;
    b.frequency_hz = frequency_hz;
    return b;
}

} // namespace

TEST_CASE("stick-slip obstacle: a closed-loop move meeting one ends there, outcome Blocked, at the tick it is crossed",
          "[unit][models][stick_slip]")
{
    Rig r;
    r.p.set_obstacles(std::nullopt, 250'000.0);
    CHECK(r.p.stop_max_nm() == 250'000);
    CHECK(r.p.stop_min_nm() == -1e7);
    r.p.move_to(1'000'000, 1'000'000, 0);   // 1 µm per tick
    CHECK(r.p.next_event(0) == 251);        // 250 µm at tick 250 touches it, 251 would pass it
    r.clock.advance(250);
    CHECK(r.p.position_nm() == Approx(250'000));
    CHECK(r.heard.empty());
    r.clock.advance(1'000);
    REQUIRE(r.heard.size() == 1);
    CHECK(r.heard[0] == std::make_pair(Outcome::Blocked, Ticks{251}));
    CHECK(r.p.motion() == StickSlipPositioner::Motion::Rest);
    CHECK(r.p.position_nm() == 250'000);
}

TEST_CASE("stick-slip obstacle: set mid-move where the stage stands, the move ends on the next tick",
          "[unit][models][stick_slip]")
{
    Rig r;
    r.p.move_to(-1'000'000, 1'000'000, 0);
    r.clock.advance(300);
    CHECK(r.p.velocity_nm_per_s() < 0);
    r.p.set_obstacles(r.p.position_nm(), std::nullopt);
    CHECK(r.p.obstacle_min_nm() == Approx(-300'000));
    CHECK(r.p.next_event(r.clock.now()) == 301);
    r.clock.advance(5);
    REQUIRE(r.heard.size() == 1);
    CHECK(r.heard[0] == std::make_pair(Outcome::Blocked, Ticks{301}));
    CHECK(r.p.position_nm() == Approx(-300'000));
}

TEST_CASE("stick-slip obstacle: a reference search meeting one ends Blocked", "[unit][models][stick_slip]")
{
    Rig r;
    r.p.set_obstacles(std::nullopt, 200'000.0);
    CHECK(r.p.start_legs({500'000, -500'000}, 1'000'000));
    r.clock.advance(2'000);
    REQUIRE(r.heard.size() == 1);
    CHECK(r.heard[0] == std::make_pair(Outcome::Blocked, Ticks{201}));
    CHECK(r.p.position_nm() == 200'000);
}

TEST_CASE("stick-slip obstacle: steps against one go on without moving, as at an end stop",
          "[unit][models][stick_slip]")
{
    Rig r;
    r.p.set_obstacles(std::nullopt, 10'500.0);
    StepBurst b = burst(100, 1000);
    b.limit.active = true;   // a range limit far off: the obstacle is not it, the burst goes on
    b.limit.max_nm = 1e6;
    r.p.start_burst(b);
    r.clock.advance(50);
    CHECK(r.p.steps_done() == 50);
    CHECK(r.p.position_nm() == 10'500);
    CHECK(r.p.velocity_nm_per_s() == 0);
    r.clock.advance(100);
    REQUIRE(r.heard.size() == 1);
    CHECK(r.heard[0] == std::make_pair(Outcome::BurstDone, Ticks{100}));
    CHECK(r.p.steps_done() == 100);
    CHECK(r.p.position_nm() == 10'500);
}

TEST_CASE("stick-slip obstacle: motion away is free, and clearing it frees the stage", "[unit][models][stick_slip]")
{
    Rig r;
    r.p.set_obstacles(std::nullopt, 0.0);
    r.p.move_to(-300'000, 1'000'000, 0);
    r.clock.advance(1'000);
    CHECK(r.heard.back().first == Outcome::Arrived);
    CHECK(r.p.position_nm() == -300'000);
    r.p.start_burst(burst(10, 1000, -1));
    r.clock.advance(100);
    CHECK(r.p.position_nm() == -310'000);
    r.p.set_obstacles(std::nullopt, std::nullopt);
    CHECK(r.p.stop_max_nm() == 1e7);
    r.p.move_to(500'000, 1'000'000, 0);
    r.clock.advance(2'000);
    CHECK(r.heard.back().first == Outcome::Arrived);
    CHECK(r.p.position_nm() == 500'000);
}

TEST_CASE("stick-slip obstacle: a stage already past one is held where it stands", "[unit][models][stick_slip]")
{
    Rig r;
    r.p.place(40'000);
    r.p.set_obstacles(50'000.0, 30'000.0);   // both behind it
    CHECK(r.p.obstacle_min_nm() == 40'000);
    CHECK(r.p.obstacle_max_nm() == 40'000);
    CHECK(r.p.position_nm() == 40'000);
    r.p.move_to(100'000, 1'000'000, 0);
    r.clock.advance(10);
    CHECK(r.heard.back() == std::make_pair(Outcome::Blocked, Ticks{1}));
    CHECK(r.p.position_nm() == 40'000);
}

} // namespace test_stick_slip_obstacles
