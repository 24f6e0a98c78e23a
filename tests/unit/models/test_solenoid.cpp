// models::Solenoid: the output of a solenoid driver (APT manual p.84-92) on the stepped clock:
// cycle edges exactly on their ticks, runs of n cycles and forever, open and close.

#include "models/solenoid.hpp"
#include "models/world.hpp"

#include <catch2/catch.hpp>

#include <utility>
#include <vector>

namespace test_solenoid {

using namespace rigsim;
using namespace rigsim::models;

namespace {

struct Rig {
    Clock clock;
    World world{clock};
    Solenoid& sol = world.emplace<Solenoid>("tsc001/1");
    std::vector<std::pair<Ticks, bool>> edges;
    Rig()
    {
        sol.set_listener([this](Ticks at, bool active) { edges.emplace_back(at, active); });
    }
};

} // namespace

TEST_CASE("solenoid: on 1000 ms / off 1000 ms x 20 switches on its ticks and ends at 40 s",
          "[unit][models][solenoid]")
{
    Rig r;
    r.sol.start_cycles(0, 1000, 1000, 20);   // p.87 example: 4000 x 250 us each, 20 cycles
    CHECK(r.sol.active_at(0));
    CHECK(r.sol.active_at(999));
    CHECK_FALSE(r.sol.active_at(1000));
    CHECK_FALSE(r.sol.active_at(1999));
    CHECK(r.sol.active_at(2000));
    CHECK(r.sol.end_tick() == 40'000);
    CHECK(r.world.next_change(0) == 1000);

    r.clock.advance(39'999);
    CHECK(r.sol.running(r.clock.now()));
    CHECK(r.sol.cycles_done(r.clock.now()) == 19);
    CHECK_FALSE(r.sol.active_at(r.clock.now()));
    REQUIRE(r.edges.size() == 39);   // 20 on->off, 19 off->on
    for (std::size_t i = 0; i < r.edges.size(); ++i) {
        CHECK(r.edges[i].first == static_cast<Ticks>(1000 * (i + 1)));
        CHECK(r.edges[i].second == (i % 2 == 1));
    }

    r.clock.advance(1);   // 40 s: the run is over, the output stays off
    CHECK_FALSE(r.sol.running(40'000));
    CHECK(r.sol.cycles_done(40'000) == 20);
    CHECK_FALSE(r.sol.active_at(40'000));
    CHECK(r.world.next_change(r.clock.now()) == kNever);
    r.clock.advance(100'000);
    CHECK(r.edges.size() == 39);
    CHECK(r.sol.cycles_done(r.clock.now()) == 20);
}

TEST_CASE("solenoid: 0 cycles run until closed", "[unit][models][solenoid]")
{
    Rig r;
    r.sol.start_cycles(100, 300, 200, 0);
    CHECK(r.sol.end_tick() == kNever);
    CHECK(r.sol.cycles_total() == 0);
    r.clock.advance(1'000'100);
    CHECK(r.sol.running(r.clock.now()));
    CHECK(r.sol.cycles_done(r.clock.now()) == 2000);
    CHECK(r.sol.active_at(r.clock.now()));          // a new cycle starts on this tick
    CHECK_FALSE(r.sol.active_at(r.clock.now() - 1));
    CHECK(r.edges.size() == 4000);
    CHECK(r.world.next_change(r.clock.now()) == r.clock.now() + 300);
}

TEST_CASE("solenoid: close during a cycle switches off at once and keeps the cycles done",
          "[unit][models][solenoid]")
{
    Rig r;
    r.sol.start_cycles(0, 1000, 1000, 20);
    r.clock.advance(2500);   // in the on time of the second cycle
    CHECK(r.sol.active_at(2500));
    r.sol.close(2500);
    CHECK_FALSE(r.sol.active_at(2500));
    CHECK_FALSE(r.sol.running(2500));
    CHECK(r.sol.cycles_done(2500) == 1);
    CHECK(r.world.next_change(2500) == kNever);
    r.clock.advance(50'000);
    CHECK(r.edges.size() == 2);
    CHECK(r.sol.cycles_done(r.clock.now()) == 1);

    r.sol.open(r.clock.now());   // manual mode: on until closed, no events
    CHECK(r.sol.active_at(r.clock.now() + 1'000'000));
    CHECK(r.world.next_change(r.clock.now()) == kNever);
    r.sol.start_cycles(r.clock.now(), 0, 0, 1);   // 0 ticks are taken as 1
    CHECK(r.sol.end_tick() == r.clock.now() + 2);
    CHECK(r.sol.active_at(r.clock.now()));
    CHECK_FALSE(r.sol.active_at(r.clock.now() + 1));
    r.clock.advance(2);
    CHECK(r.sol.cycles_done(r.clock.now()) == 1);
    CHECK_FALSE(r.sol.running(r.clock.now()));
}

} // namespace test_solenoid
