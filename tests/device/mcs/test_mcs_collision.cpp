// An MCS channel against an obstacle of a collision (StickSlipPositioner::set_obstacles, as the
// collision watch sets it): a closed-loop move ends with 142 as under the stall fault; steps make
// no way against it; motion away is free.
#include "mcs_harness.hpp"

#include "models/stick_slip.hpp"

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include <optional>

namespace test_mcs_collision {

using rigsim::test::McsHarness;

namespace {

rigsim::models::StickSlipPositioner& body_of(McsHarness& h, int channel)
{
    auto* body = h.world().find_as<rigsim::models::StickSlipPositioner>("mcs-test/" + std::to_string(channel));
    REQUIRE(body);
    return *body;
}

} // namespace

TEST_CASE("MCS obstacle met during a closed-loop move: 142 unprompted, as the stall fault's", "[device][mcs][collision]")
{
    McsHarness h;
    auto& body = body_of(h, 0);
    CHECK(h.send(":SCM1\n:MPA0,5000000,0\n") == "");
    h.advance_ms(100);
    body.set_obstacles(std::nullopt, body.position_nm());   // the watch stops it where it is
    h.advance_ticks(1);
    CHECK(h.send(":GS0\n") == ":E0,142\n:S0,0\n");
    h.advance_ms(500);
    CHECK(h.send(":GP0\n") == ":P0,1000000\n");
    nlohmann::json out = nlohmann::json::object();
    h.device().describe(out);
    CHECK(out["channels"][0]["last_outcome"] == "stalled");
    // Further in: 142 at once; away: free.
    CHECK(h.send(":MPA0,2000000,0\n") == ":E0,142\n");
    CHECK(h.send(":MPA0,0,0\n") == "");
    h.advance_ms(500);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,0\n");
}

TEST_CASE("MCS obstacle ahead: a closed-loop move runs to it and ends with 142, steps make no way past it",
          "[device][mcs][collision]")
{
    McsHarness h;
    auto& body = body_of(h, 1);
    body.set_obstacles(-2'000'000.0, 1'500'000.0);
    CHECK(h.send(":SCM1\n:MPA1,3000000,0\n") == "");
    h.advance_ms(1'000);
    CHECK(h.send(":GS1\n:GP1\n") == ":E1,142\n:S1,0\n:P1,1500000\n");
    CHECK(h.send(":MST1,100,4095,1000\n") == "");   // 100 steps forward: none makes way
    h.advance_ms(200);
    CHECK(h.send(":GP1\n") == ":P1,1500000\n");
    CHECK(h.send(":MPA1,-3000000,0\n") == "");      // down to the other one
    h.advance_ms(1'000);
    CHECK(h.send(":GS1\n:GP1\n") == ":E1,142\n:S1,0\n:P1,-2000000\n");
    body.set_obstacles(std::nullopt, std::nullopt);
    CHECK(h.send(":MPA1,-3000000,0\n") == "");
    h.advance_ms(1'000);
    CHECK(h.send(":GS1\n:GP1\n") == ":S1,0\n:P1,-3000000\n");
}

} // namespace test_mcs_collision
