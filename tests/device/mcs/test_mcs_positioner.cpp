// MCS positioner slice: bytes in -> bytes out on a stepped clock (manual 3.1-3.4).
#include "mcs_harness.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace test_mcs_positioner {

using rigsim::test::McsHarness;
using rigsim::test::mcs_device_config;

TEST_CASE("initialization commands answer with the configured system", "[device][mcs]")
{
    McsHarness h;
    CHECK(h.send(":GNC\n") == ":N3\n");
    CHECK(h.send(":GSI\n") == ":ID3118100\n");
    CHECK(h.send(":GIV\n") == ":IV1,2,44\n");   // manual title page: interface version 1.2.44
    CHECK(h.send(":GCT2\n") == ":CT2,0\n");
    CHECK(h.send(":GST1\n") == ":ST1,1\n");
}

TEST_CASE("GIV answers the configured interface version", "[device][mcs]")
{
    auto config = mcs_device_config();
    rigsim::mcs::config_of(config).interface_version = {2, 0, 7};
    McsHarness h(config);
    CHECK(h.send(":GIV\n") == ":IV2,0,7\n");
    CHECK(h.send(":GFV0\n") == ":FV0,2,1,5,0,3,1,5,0\n");   // firmware versions are not the interface version
}

TEST_CASE("MPA moves at the configured speed, GS reports targeting then stopped", "[device][mcs]")
{
    McsHarness h;
    CHECK(h.send(":SCLS0,1000000\n") == ":E-1,0\n");      // 1 mm/s
    CHECK(h.send(":MPA0,2000000,0\n") == ":E0,0\n");
    CHECK(h.send(":GS0\n") == ":S0,4\n");
    h.advance_ms(1000);
    CHECK(h.send(":GP0\n") == ":P0,1000000\n");
    CHECK(h.send(":GS0\n") == ":S0,4\n");
    h.advance_ticks(999);
    CHECK(h.send(":GS0\n") == ":S0,4\n");
    h.advance_ticks(1);
    CHECK(h.send(":GS0\n") == ":S0,0\n");
    CHECK(h.send(":GP0\n") == ":P0,2000000\n");
    CHECK(h.send(":GP1\n") == ":P1,0\n");                   // other channels untouched
}

TEST_CASE("arrival time follows speed and acceleration within one tick", "[device][mcs]")
{
    McsHarness h;
    // v = 2 mm/s, a = 10 mm/s^2, d = 3 mm: T = d/v + v/a = 1.5 s + 0.2 s.
    CHECK(h.send(":SCLS1,2000000\n") == ":E-1,0\n");
    CHECK(h.send(":SCLA1,10000\n") == ":E1,0\n");
    CHECK(h.send(":GCLA1\n") == ":CLA1,10000\n");
    CHECK(h.send(":MPA1,-3000000,0\n") == ":E1,0\n");
    h.advance_ticks(1699);
    CHECK(h.send(":GS1\n") == ":S1,4\n");
    h.advance_ticks(2);
    CHECK(h.send(":GS1\n") == ":S1,0\n");
    CHECK(h.send(":GP1\n") == ":P1,-3000000\n");
}

TEST_CASE("hold time keeps status 3 for its duration and 60000 holds until stopped", "[device][mcs]")
{
    McsHarness h;
    CHECK(h.send(":MPA0,100000,500\n") == ":E0,0\n");      // 10 ms at 10 mm/s
    h.advance_ms(10);
    CHECK(h.send(":GS0\n") == ":S0,3\n");
    h.advance_ms(499);
    CHECK(h.send(":GS0\n") == ":S0,3\n");
    h.advance_ms(1);
    CHECK(h.send(":GS0\n") == ":S0,0\n");

    CHECK(h.send(":MPA0,0,60000\n") == ":E0,0\n");
    h.advance_ms(3'600'000);
    CHECK(h.send(":GS0\n") == ":S0,3\n");
    CHECK(h.send(":S0\n") == ":E0,0\n");
    CHECK(h.send(":GS0\n") == ":S0,0\n");
    CHECK(h.send(":GP0\n") == ":P0,0\n");
}

TEST_CASE("MPR is relative and accumulates while targeting", "[device][mcs]")
{
    McsHarness h;
    CHECK(h.send(":SCLS2,1000000\n") == ":E-1,0\n");
    CHECK(h.send(":MPR2,500000,0\n") == ":E2,0\n");
    h.advance_ms(100);
    CHECK(h.send(":MPR2,500000,0\n") == ":E2,0\n");   // target becomes 1 mm, not 0.6 mm
    h.advance_ms(2000);
    CHECK(h.send(":GP2\n") == ":P2,1000000\n");
    CHECK(h.send(":MPR2,-250000,0\n") == ":E2,0\n");
    h.advance_ms(1000);
    CHECK(h.send(":GP2\n") == ":P2,750000\n");
}

TEST_CASE("S stops where the stage is and S without channel stops all", "[device][mcs]")
{
    McsHarness h;
    CHECK(h.send(":SCLS0,1000000\n:SCLS1,1000000\n") == ":E-1,0\n:E-1,0\n");
    CHECK(h.send(":MPA0,1000000,0\n:MPA1,-1000000,0\n") == ":E0,0\n:E1,0\n");
    h.advance_ms(250);
    CHECK(h.send(":S0\n") == ":E0,0\n");
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,250000\n");
    h.advance_ms(250);
    CHECK(h.send(":GP0\n") == ":P0,250000\n");
    CHECK(h.send(":S\n") == ":E-1,0\n");
    CHECK(h.send(":GS1\n:GP1\n") == ":S1,0\n:P1,-500000\n");
}

TEST_CASE("a target beyond the end stop stops the stage at the stop, status 0", "[device][mcs]")
{
    McsHarness h;
    CHECK(h.send(":MPA0,20000000,60000\n") == ":E0,0\n");
    h.advance_ms(5000);
    CHECK(h.send(":GS0\n") == ":S0,0\n");
    CHECK(h.send(":GP0\n") == ":P0,10500000\n");
}

TEST_CASE("start position reads as zero at power-up and end stops are physical", "[device][mcs]")
{
    auto config = mcs_device_config(1);
    rigsim::mcs::config_of(config).channels[0].start_position_nm = 10'000'000;
    McsHarness h(config);
    CHECK(h.send(":GP0\n") == ":P0,0\n");
    CHECK(h.send(":MPA0,1000000,0\n") == ":E0,0\n");
    h.advance_ms(1000);
    CHECK(h.send(":GP0\n") == ":P0,500000\n");   // end stop at +10.5 mm physical
}

TEST_CASE("SCLS/SCLA dependency chain (2.5.1) and ranges", "[device][mcs]")
{
    McsHarness h;
    CHECK(h.send(":GCLS0\n:GCLA0\n") == ":CLS0,0\n:CLA0,0\n");
    CHECK(h.send(":SCLA0,1000\n") == ":E0,0\n");
    CHECK(h.send(":GCLS0\n") == ":CLS0,10000000\n");   // speed control switched on
    CHECK(h.send(":SCLS0,0\n") == ":E-1,0\n");
    CHECK(h.send(":GCLA0\n") == ":CLA0,0\n");          // acceleration control switched off
    CHECK(h.send(":SCLS0,100000001\n") == ":E0,7\n");
    CHECK(h.send(":SCLS0,-1\n") == ":E0,7\n");
    CHECK(h.send(":SCLA0,10000001\n") == ":E0,7\n");
    CHECK(h.send(":GCLS0\n") == ":CLS0,0\n");
}

TEST_CASE("sensor types: rotary channels refuse GP and MPA, no sensor gives 129", "[device][mcs]")
{
    auto config = mcs_device_config(3);
    rigsim::mcs::config_of(config).channels[1].sensor_type = "SR";
    rigsim::mcs::config_of(config).channels[2].sensor_type = "none";
    McsHarness h(config);
    CHECK(h.send(":GST1\n") == ":ST1,2\n");
    CHECK(h.send(":GP1\n") == ":E1,143\n");
    CHECK(h.send(":MPA1,0,0\n") == ":E1,143\n");
    CHECK(h.send(":GP2\n") == ":E2,129\n");
    CHECK(h.send(":GST2\n") == ":E2,129\n");
    CHECK(h.send(":MPR2,1,0\n") == ":E2,129\n");
    CHECK(h.send(":SST0,2\n") == ":E0,0\n");
    CHECK(h.send(":GST0\n:GP0\n") == ":ST0,2\n:E0,143\n");
    CHECK(h.send(":SST0,1\n") == ":E0,0\n");
    CHECK(h.send(":SST0,3\n") == ":E0,7\n");           // 3 is not in appendix 4.3
    CHECK(h.send(":GP0\n") == ":P0,0\n");
}

TEST_CASE("SST stops a moving positioner", "[device][mcs]")
{
    McsHarness h;
    CHECK(h.send(":MPA0,5000000,0\n") == ":E0,0\n");
    h.advance_ms(100);
    CHECK(h.send(":SST0,5\n") == ":E0,0\n");
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,1000000\n");
}

TEST_CASE("client mistakes get the appendix 4.2 error with the right source", "[device][mcs]")
{
    McsHarness h;
    CHECK(h.send(":FOO\n") == ":E-1,2\n");
    CHECK(h.send(":GGO0\n") == ":E0,7\n");             // an end effector command to a positioner
    CHECK(h.send(":GP\n") == ":E-1,5\n");
    CHECK(h.send(":GP0,0\n") == ":E-1,6\n");
    CHECK(h.send(":GP3\n") == ":E-1,7\n");
    CHECK(h.send(":GP-1\n") == ":E-1,7\n");
    CHECK(h.send(":MPA5,0,0\n") == ":E-1,7\n");
    CHECK(h.send(":MPA0,0,60001\n") == ":E0,7\n");
    CHECK(h.send(":MPA0,0,-1\n") == ":E0,7\n");
    CHECK(h.send(":GP 0\n") == ":E-1,1\n");
    CHECK(h.send(":GP4294967296\n") == ":E-1,3\n");
    CHECK(h.send("\x01\x02garbage\n") == "");
    CHECK(h.send(":" + std::string(300, '9') + "\n") == ":E-1,1\n");
    CHECK(h.send(":GNC\n") == ":N3\n");                // state intact
}

TEST_CASE("two connections share the device, each gets its own answers", "[device][mcs]")
{
    McsHarness h;
    std::string other;
    auto second = h.open(other);
    second->receive(":MPA0,1000000,0\n:GP");            // partial command on the second
    CHECK(other == ":E0,0\n");
    CHECK(h.send(":GP0\n") == ":P0,0\n");                // first connection's framer is separate
    h.advance_ms(100);
    other.clear();
    second->receive("0\n");
    CHECK(other == ":P0,1000000\n");
}

TEST_CASE("an open-loop positioner drifts at drift_nm_per_s after a burst, not while it holds a target",
          "[device][mcs]")
{
    auto config = mcs_device_config();
    rigsim::mcs::config_of(config).channels[0].drift_nm_per_s = 1000;
    rigsim::mcs::config_of(config).channels[0].step_jitter_percent = 0;
    McsHarness h(config);
    CHECK(h.send(":MST0,10,4095,100\n") == ":E0,0\n");   // 10 steps of 1 µm, over at 100 ms
    h.advance_ms(100);
    CHECK(h.send(":GS0\n") == ":S0,0\n");
    CHECK(h.send(":GP0\n") == ":P0,10000\n");             // no drift while stepping
    h.advance_ms(2000);
    CHECK(h.send(":GP0\n") == ":P0,12000\n");             // 2 s at rest: 2000 nm more
    CHECK(h.send(":GP1\n") == ":P1,0\n");                 // channel 1 has no drift
    CHECK(h.send(":MPA0,20000,60000\n") == ":E0,0\n");    // then held for ever
    h.advance_ms(2000);
    CHECK(h.send(":GS0\n") == ":S0,3\n");
    CHECK(h.send(":GP0\n") == ":P0,20000\n");             // the held position stays
    CHECK(h.send(":S0\n") == ":E0,0\n");                  // stopped: no longer held
    h.advance_ms(1000);
    CHECK(h.send(":GP0\n") == ":P0,21000\n");
}

} // namespace test_mcs_positioner
