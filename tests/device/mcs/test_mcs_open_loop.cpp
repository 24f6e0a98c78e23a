// Open-loop movement (MST) and scanning (MSCA/MSCR, GVL) on a stepped clock (3.3, 3.4).
#include "mcs_harness.hpp"

#include <catch2/catch.hpp>

namespace test_mcs_open_loop {

using rigsim::test::McsHarness;
using rigsim::test::mcs_device_config;

namespace {

rigsim::DeviceConfig exact_steps()
{
    auto c = mcs_device_config(2);
    for (auto& ch : rigsim::mcs::config_of(c).channels)
        ch.step_jitter_percent = 0;   // every step exactly as wide: positions comparable
    return c;
}

std::int64_t position(McsHarness& h, int ch)
{
    const auto a = h.send(":GP" + std::to_string(ch) + "\n");
    return std::stoll(a.substr(a.find(',') + 1));
}

} // namespace

TEST_CASE("MST steps at the given frequency, width grows with amplitude", "[device][mcs][open-loop]")
{
    McsHarness h(exact_steps());
    CHECK(h.send(":MST0,100,4095,100\n") == ":E0,0\n");     // 100 steps of 1 µm at 100 Hz
    CHECK(h.send(":GS0\n") == ":S0,1\n");
    h.advance_ms(500);
    CHECK(h.send(":GP0\n") == ":P0,50000\n");
    h.advance_ms(500);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,100000\n");
    CHECK(h.send(":MST0,-100,2048,1000\n") == ":E0,0\n");   // half amplitude: half a step back
    h.advance_ms(100);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,49988\n");
    CHECK(h.send(":MST0,30001,100,100\n:MST0,1,4096,100\n:MST0,1,100,0\n:MST0,1,100,18501\n")
          == ":E0,7\n:E0,7\n:E0,7\n:E0,7\n");
}

TEST_CASE("MST +-30000 runs until S, which finishes the current step", "[device][mcs][open-loop]")
{
    McsHarness h(exact_steps());
    CHECK(h.send(":MST1,-30000,4095,10\n") == ":E1,0\n");
    h.advance_ms(10'050);                                      // 100 steps done, 101st begun
    CHECK(h.send(":GS1\n:GP1\n") == ":S1,1\n:P1,-100000\n");
    CHECK(h.send(":S1\n:GS1\n:GP1\n") == ":E1,0\n:S1,0\n:P1,-101000\n");
    CHECK(h.send(":MST1,10,4095,10\n:MST1,0,0,1\n:GS1\n") == ":E1,0\n:E1,0\n:S1,0\n");   // 0 stops
}

TEST_CASE("open-loop positions drift: steps vary in width", "[device][mcs][open-loop]")
{
    McsHarness h;                                              // default: 3 % jitter
    CHECK(h.send(":MST0,1000,4095,1000\n:MST1,1000,4095,1000\n") == ":E0,0\n:E1,0\n");
    h.advance_ms(1000);
    const auto p0 = position(h, 0), p1 = position(h, 1);
    CHECK(p0 != 1'000'000);
    CHECK(p0 == Approx(1'000'000).epsilon(0.03));
    CHECK(p1 != p0);                                           // every channel drifts its own way
}

TEST_CASE("open loop without sensor power loses the position", "[device][mcs][open-loop]")
{
    McsHarness h(exact_steps());
    CHECK(h.send(":SSE0\n:MST0,100,4095,1000\n") == ":E-1,0\n:E0,0\n");   // MST still runs
    h.advance_ms(100);
    CHECK(h.send(":GS0\n:SSE1\n:GP0\n") == ":S0,0\n:E-1,0\n:P0,0\n");     // moved 0.1 mm unseen
    CHECK(h.send(":MPA0,0,0\n") == ":E0,0\n");
    h.advance_ms(100);
    CHECK(h.send(":GP0\n") == ":P0,0\n");
}

TEST_CASE("MSCA/MSCR scan the piezo: status 2, GVL, deflection", "[device][mcs][scan]")
{
    McsHarness h(exact_steps());
    CHECK(h.send(":GVL0\n") == ":VL0,0\n");
    CHECK(h.send(":MSCA0,2048,1024\n") == ":E0,0\n");         // 2 s
    h.advance_ms(1000);
    CHECK(h.send(":GS0\n:GVL0\n:GP0\n") == ":S0,2\n:VL0,1024\n:P0,375\n");
    h.advance_ms(1000);
    CHECK(h.send(":GS0\n:GVL0\n:GP0\n") == ":S0,0\n:VL0,2048\n:P0,750\n");
    CHECK(h.send(":MSCR0,-1024,1024\n") == ":E0,0\n");        // to 25 V in one second
    h.advance_ms(1000);
    CHECK(h.send(":GVL0\n") == ":VL0,1024\n");
    CHECK(h.send(":MSCR0,4095,4095000000\n") == ":E0,0\n");   // stops at the boundary, fast
    h.advance_ms(1);
    CHECK(h.send(":GS0\n:GVL0\n") == ":S0,0\n:VL0,4095\n");
    CHECK(h.send(":MSCA0,4096,1\n:MSCA0,0,0\n:MSCA0,0,4095000001\n:MSCR0,4096,1\n")
          == ":E0,7\n:E0,7\n:E0,7\n:E0,7\n");
    CHECK(h.send(":MSCA0,0,4294967296\n") == ":E-1,3\n");
}

} // namespace test_mcs_open_loop
