// End effector channels through the protocol: SEET/GEET, MGOA/MGOR/GGO, MGFA/GF, SZF
// (3.2-3.4), status 8 and 6, 145, SRC reports, channel type 1.
#include "mcs_harness.hpp"
#include "models/gripper.hpp"

#include <catch2/catch.hpp>

namespace test_mcs_end_effectors {

using rigsim::test::McsHarness;
using rigsim::test::mcs_device_config;

namespace {

rigsim::DeviceConfig with_gripper()
{
    auto c = mcs_device_config(2);
    rigsim::mcs::config_of(c).channels[1].kind = "end_effector";
    return c;
}

} // namespace

TEST_CASE("an end effector channel: type 1, 145 until SEET, SEET/GEET", "[device][mcs][end-effector]")
{
    McsHarness h(with_gripper());
    CHECK(h.send(":GCT1\n:GCT0\n:GS1\n") == ":CT1,1\n:CT0,0\n:S1,0\n");
    CHECK(h.send(":GEET1\n:GGO1\n:MGOA1,100,10\n") == ":EET1,0,0,0\n:E1,145\n:E1,145\n");
    CHECK(h.send(":SEET1,1,10000,0\n:GEET1\n") == ":E-1,0\n:EET1,1,10000,0\n");
    CHECK(h.send(":SEET1,1,99,0\n:SEET1,4,1,0\n") == ":E1,7\n:E1,7\n");
    CHECK(h.send(":GF1\n:MGFA1,100,10,0\n:SZF1\n") == ":E1,145\n:E1,145\n:E1,145\n");
    CHECK(h.send(":GP1\n:MPA1,0,0\n:SEET0,1,100,0\n:GFV1\n") == ":E1,7\n:E1,7\n:E0,7\n:FV1,9,1,5,0,9,1,5,0\n");
}

TEST_CASE("MGOA ramps the gripper voltage with status 8, MGOR is relative", "[device][mcs][end-effector]")
{
    McsHarness h(with_gripper());
    CHECK(h.send(":SEET1,1,10000,0\n:MGOA1,5000,50\n") == ":E-1,0\n:E1,0\n");
    h.advance_ms(500);
    CHECK(h.send(":GS1\n:GGO1\n") == ":S1,8\n:GO1,2500\n");
    h.advance_ms(500);
    CHECK(h.send(":GS1\n:GGO1\n") == ":S1,0\n:GO1,5000\n");
    CHECK(h.send(":MGOR1,-1000,40\n") == ":E1,0\n");
    h.advance_ms(250);
    CHECK(h.send(":GGO1\n") == ":GO1,4000\n");
    CHECK(h.send(":MGOA1,20000,225000\n") == ":E1,0\n");       // clipped to the gripper's 100 V
    h.advance_ms(10);
    CHECK(h.send(":GGO1\n") == ":GO1,10000\n");
    CHECK(h.send(":MGOA1,22501,1\n:MGOA1,0,0\n:MGOR1,22501,1\n") == ":E1,7\n:E1,7\n:E1,7\n");
    CHECK(h.send(":MGOA1,0,10\n") == ":E1,0\n");
    h.advance_ms(100);
    CHECK(h.send(":S1\n:GS1\n:GGO1\n") == ":E1,0\n:S1,0\n:GO1,9900\n");   // 10 V/s for 0.1 s
}

TEST_CASE("force gripper: SZF status 6 for a second, MGFA holds a force (status 4, 3)", "[device][mcs][end-effector]")
{
    McsHarness h(with_gripper());
    CHECK(h.send(":SEET1,3,3000,22500\n:SZF1\n") == ":E-1,0\n:E1,0\n");
    h.advance_ms(999);
    CHECK(h.send(":GS1\n") == ":S1,6\n");
    h.advance_ms(1);
    CHECK(h.send(":GS1\n:GF1\n") == ":S1,0\n:F1,0\n");
    CHECK(h.send(":MGFA1,1000,1000,0\n") == ":E1,0\n");         // 100 µN
    CHECK(h.send(":GS1\n") == ":S1,4\n");
    h.advance_ms(1000);
    CHECK(h.send(":GS1\n") == ":S1,3\n");
    const auto f = h.send(":GF1\n");
    const int force = std::stoi(f.substr(f.find(',') + 1));
    CHECK(force == Approx(1000).margin(5));
    h.advance_ms(60'000);
    CHECK(h.send(":GS1\n:S1\n:GS1\n") == ":S1,3\n:E1,0\n:S1,0\n");
    CHECK(h.send(":MGFA1,100001,1,0\n") == ":E1,7\n");
}

TEST_CASE("end effectors report completion (SRC) in async mode", "[device][mcs][end-effector]")
{
    McsHarness h(with_gripper());
    CHECK(h.send(":SCM1\n:SRC1,1\n:SEET1,1,10000,0\n:MGOA1,100,100\n") == "");
    h.advance_ms(10);
    CHECK(h.send(":GS1\n") == ":C1\n:S1,0\n");
    CHECK(h.send(":S\n") == "");
}

TEST_CASE("K stops positioners only, R opens the gripper and keeps its type", "[device][mcs][end-effector]")
{
    McsHarness h(with_gripper());
    CHECK(h.send(":SEET1,1,10000,0\n:K200\n:MGOA1,5000,10\n") == ":E-1,0\n:E-1,0\n:E1,0\n");
    h.advance_ms(300);                                         // the keep-alive timed out at 200 ms
    CHECK(h.send(":GS1\n:GGO1\n") == ":S1,8\n:GO1,300\n");
    CHECK(h.send(":K0\n:R\n") == ":E-1,0\n:E-1,0\n");
    CHECK(h.send(":GS1\n:GGO1\n:GEET1\n") == ":S1,0\n:GO1,0\n:EET1,1,10000,0\n");
}

TEST_CASE("an end effector channel's body in the world is its gripper, not a positioner", "[device][mcs][end-effector]")
{
    McsHarness h(with_gripper());
    REQUIRE(h.world().find("mcs-test/0") != nullptr);   // the positioner of channel 0
    CHECK(h.world().find("mcs-test/0")->kind() == rigsim::models::BodyKind::Linear);
    const auto* gripper = h.world().find_as<rigsim::models::Gripper>("mcs-test/1");
    REQUIRE(gripper);
    CHECK(gripper->kind() == rigsim::models::BodyKind::Gripper);
    CHECK(h.world().size() == 2);
    // Nothing that could be mounted on a joint.
    std::string key;
    const auto refused = h.device().axis_body_key(1, key);
    REQUIRE(refused);
    CHECK(refused->message.find("end effector") != std::string::npos);
    // SEET1 (a gripper of 100 V), MGOA to 50 V at 100 V/s: the world wakes the gripper at the
    // ramp's end, and the controller reports it there (status 8 until then).
    CHECK(h.send(":SEET1,1,10000,0\n") == ":E-1,0\n");
    CHECK(h.send(":MGOA1,5000,100\n") == ":E1,0\n");
    CHECK(gripper->settling());
    h.advance_ms(499);
    CHECK(h.send(":GS1\n") == ":S1,8\n");
    h.advance_ms(1);
    CHECK_FALSE(gripper->settling());
    CHECK(gripper->voltage_v() == Approx(50.0));
    CHECK(h.send(":GS1\n") == ":S1,0\n");
    CHECK(h.send(":GGO1\n") == ":GO1,5000\n");
}

} // namespace test_mcs_end_effectors
