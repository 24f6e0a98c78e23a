// APT motors against an obstacle of a collision (models::Axis::set_obstacles, as the collision
// watch sets it): a DC servo stalls there with the same messages and status as against its end
// stop, a stepper loses microsteps (its counter counts them, no fault); motion away is free.
#include "apt_harness.hpp"

#include "models/axis.hpp"

#include <optional>

namespace test_apt_collision {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;

namespace {

models::Axis& axis_of(AptHarness& h)
{
    auto* axis = h.world().find_as<models::Axis>("cube/1");
    REQUIRE(axis);
    return *axis;
}

} // namespace

TEST_CASE("APT DC servo meeting an obstacle mid-move: stalled there, as at its end stop", "[device][apt][collision]")
{
    AptHarness h(apt_cube("KDC101", "Z825B"));
    models::Axis& axis = axis_of(h);
    CHECK(h.send("53 04 06 00 D0 01 01 00 " + le32(300'000)) == "");   // MOVE_ABSOLUTE
    h.advance_ms(2'000);
    CHECK(h.take() == "");
    const std::int32_t counter = position_of(h.send("11 04 01 00 50 01"));
    CHECK(counter > 0);
    axis.set_obstacles(std::nullopt, axis.position_counts());   // the watch stops it where it is
    h.advance_ms(1);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 2);
    // The KDC101's stall: HW_RICHRESPONSE "Motor stalled" for the MOVE_ABSOLUTE, then
    // MOVE_STOPPED with the current limit bit and no limit switch bit.
    const auto rich = bytes(out[0]);
    REQUIRE(rich.size() == 74);
    CHECK(hex(rich.substr(0, 10)) == "81 00 44 00 81 50 53 04 01 00");
    CHECK(rich.substr(10, 13) == "Motor stalled");
    CHECK(out[1].substr(0, 35) == "66 04 0E 00 81 50 01 00 " + le32(counter));
    CHECK(status_of(out[1]) == (status::kMotorConnected | status::kCurrentLimit | status::kSettled | status::kEnabled));
    // Further in: stalled again at once.
    CHECK(h.send("53 04 06 00 D0 01 01 00 " + le32(400'000)) == "");
    h.advance_ms(100);
    const auto again = frames(h.take());
    REQUIRE(again.size() == 2);
    CHECK(again[1].substr(0, 35) == "66 04 0E 00 81 50 01 00 " + le32(counter));
    // Away: free, and the next move clears the stall bit.
    CHECK(h.send("53 04 06 00 D0 01 01 00 " + le32(0)) == "");
    h.advance_ms(10'000);
    const auto back = frames(h.take());
    REQUIRE(back.size() == 1);
    CHECK(back[0].substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(0));
    CHECK((status_of(back[0]) & status::kCurrentLimit) == 0);
}

TEST_CASE("APT stepper against an obstacle loses microsteps: the counter counts them, no fault",
          "[device][apt][collision][stepper]")
{
    AptHarness h(apt_cube("KST101", "DRV014"));
    models::Axis& axis = axis_of(h);
    const double start = axis.position_counts();
    axis.set_obstacles(std::nullopt, start + 100'000);
    CHECK(h.send("53 04 06 00 D0 01 01 00 " + le32(300'000)) == "");   // MOVE_ABSOLUTE, from 0
    h.advance_ms(30'000);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 1);
    CHECK(out[0].substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(300'000));   // MOVE_COMPLETED
    CHECK((status_of(out[0]) & (status::kCurrentLimit | status::kMotionError)) == 0);
    CHECK(axis.position_counts() == start + 100'000);   // the carriage stands at the obstacle
    CHECK(axis.lost_counts() == Approx(200'000));
    // The obstacle gone, a move of 100,000 more takes the carriage there; the counter reads
    // 200,000 more than the carriage went.
    axis.set_obstacles(std::nullopt, std::nullopt);
    CHECK(h.send("53 04 06 00 D0 01 01 00 " + le32(400'000)) == "");
    h.advance_ms(30'000);
    CHECK(frames(h.take()).size() == 1);
    CHECK(axis.position_counts() == Approx(start + 200'000));
}

} // namespace test_apt_collision
