// models::Flipper: a flip mount's arm (MFF101/MFF102) on the stepped clock: a flip takes its transit
// time to the tick, a turn back on the way as long as the arm had travelled, the listener of the
// module that owns it hears each arrival.

#include "models/flipper.hpp"
#include "models/world.hpp"

#include <catch2/catch.hpp>

#include <utility>
#include <vector>

namespace test_flipper {

using namespace rigsim;
using namespace rigsim::models;

namespace {

struct Rig {
    Clock clock;
    World world{clock};
    Flipper& arm = world.emplace<Flipper>("mff101/1", 1);
    std::vector<std::pair<Ticks, int>> arrivals;
    int owner = 0;
    Rig()
    {
        world.link_all();
        arm.set_listener(&owner, [this](Ticks at, int position) { arrivals.emplace_back(at, position); });
    }
};

} // namespace

TEST_CASE("flipper: a flip takes the transit time to the tick, and the arm stands at its position",
          "[unit][models][flipper]")
{
    Rig r;
    CHECK(r.arm.kind() == BodyKind::Flipper);
    CHECK(r.arm.position_at(0) == 1);
    CHECK(r.arm.next_event(0) == kNever);
    r.arm.move_to(0, 2, 500);
    CHECK(r.arm.moving_at(0));
    CHECK(r.arm.position_at(499) == 0);
    CHECK(r.arm.next_event(0) == 500);
    r.clock.advance(499);
    CHECK(r.arrivals.empty());
    r.clock.advance(1);
    CHECK(r.arrivals == std::vector<std::pair<Ticks, int>>{{500, 2}});
    CHECK(r.arm.position_at(500) == 2);
    CHECK_FALSE(r.arm.moving_at(500));
    CHECK(r.arm.next_event(500) == kNever);
    // Toward where it stands: nothing.
    r.arm.move_to(600, 2, 500);
    CHECK(r.arm.next_event(600) == kNever);
}

TEST_CASE("flipper: turned back on the way it arrives after as long as it travelled, place puts it without a flip",
          "[unit][models][flipper]")
{
    Rig r;
    r.arm.move_to(0, 2, 1000);
    r.clock.advance(300);
    r.arm.move_to(300, 1, 1000);   // 300 ticks out: 300 back
    CHECK(r.arm.target() == 1);
    r.clock.advance(299);
    CHECK(r.arrivals.empty());
    r.clock.advance(1);
    CHECK(r.arrivals == std::vector<std::pair<Ticks, int>>{{600, 1}});
    r.arm.place(2);
    CHECK(r.arm.position_at(r.clock.now()) == 2);
    CHECK(r.arrivals.size() == 1);
    // A listener cleared by another owner stays; by its own, goes.
    int other = 0;
    r.arm.clear_listener(&other);
    r.arm.move_to(r.clock.now(), 1, 10);
    r.clock.advance(10);
    CHECK(r.arrivals.size() == 2);
    r.arm.clear_listener(&r.owner);
    r.arm.move_to(r.clock.now(), 2, 10);
    r.clock.advance(10);
    CHECK(r.arrivals.size() == 2);
    CHECK(r.arm.position_at(r.clock.now()) == 2);
}

} // namespace test_flipper
