// Software range limits (2.3.4, SPL/SAL 3.2) against every kind of movement: a limit whose
// maximum is below its minimum ("the positioner will not move at all") stops open-loop steps,
// closed-loop moves, the reference search and the calibration where they start; scans are
// exempt ("all movements except scan movements").
#include "mcs_harness.hpp"

#include <catch2/catch.hpp>

namespace test_mcs_range_limits {

using rigsim::test::McsHarness;
using rigsim::test::mcs_device_config;

namespace {

/// One channel of `sensor` standing on its mark (physical 0), steps exactly 1 µm wide.
rigsim::DeviceConfig one_channel(const char* sensor)
{
    auto c = mcs_device_config(1);
    auto& ch = rigsim::mcs::config_of(c).channels[0];
    ch.sensor_type = sensor;
    ch.start_position_nm = 0;
    ch.step_jitter_percent = 0;
    return c;
}

/// FRM at the mark: the physical position becomes known, as SPL/SAL require (148 otherwise).
void reference(McsHarness& h)
{
    REQUIRE(h.send(":FRM0,0,0,1\n") == ":E0,0\n");
    h.advance_ms(10);
    REQUIRE(h.send(":GS0\n:GPPK0\n") == ":S0,0\n:PPK0,1\n");
}

} // namespace

TEST_CASE("an empty SPL limit stops MST before its first step: 147 in async mode, status 0", "[device][mcs][limits]")
{
    McsHarness h(one_channel("S"));
    reference(h);
    CHECK(h.send(":SPL0,1000000,-1000000\n:GPL0\n") == ":E0,0\n:PL0,1000000,-1000000\n");
    // Synchronous mode: acknowledged, and 147 is an asynchronous-mode error (4.2).
    CHECK(h.send(":MST0,100,4095,100\n:GS0\n") == ":E0,0\n:S0,0\n");
    h.advance_ms(1000);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,0\n");   // 100 steps at 100 Hz would be 100 µm
    CHECK(h.send(":SCM1\n:MST0,-100,4095,100\n") == ":E0,147\n");
    h.advance_ms(1000);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,0\n");
}

TEST_CASE("an empty SPL limit stops an endless MST at once: no travel, 147", "[device][mcs][limits]")
{
    McsHarness h(one_channel("S"));
    reference(h);
    CHECK(h.send(":SPL0,1000000,-1000000\n:SCM1\n") == ":E0,0\n");
    CHECK(h.send(":MST0,30000,4095,18500\n") == ":E0,147\n");
    h.advance_ms(1000);                                     // 18.5 mm of steps, had it started
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,0\n");
    CHECK(h.send(":MST0,-30000,4095,700\n") == ":E0,147\n");
    h.advance_ms(10'000);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,0\n");
}

TEST_CASE("a limit with its maximum above its minimum still lets MST step up to it", "[device][mcs][limits]")
{
    McsHarness h(one_channel("S"));
    reference(h);
    CHECK(h.send(":SPL0,-100000,100000\n:SCM1\n") == ":E0,0\n");
    CHECK(h.send(":MST0,1000,4095,1000\n") == "");           // 1 µm per step at 1 kHz
    h.advance_ms(50);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,1\n:P0,50000\n");
    h.advance_ms(100);                                      // the 101st step meets the limit
    CHECK(h.send(":GS0\n:GP0\n") == ":E0,147\n:S0,0\n:P0,100000\n");
}

TEST_CASE("an empty SPL limit stops MPA and MPR where they start", "[device][mcs][limits]")
{
    McsHarness h(one_channel("S"));
    reference(h);
    CHECK(h.send(":SPL0,1000000,-1000000\n") == ":E0,0\n");
    CHECK(h.send(":MPA0,500000,0\n:GS0\n") == ":E0,0\n:S0,0\n");   // sync: acknowledged, stopped
    h.advance_ms(1000);
    CHECK(h.send(":GP0\n") == ":P0,0\n");
    CHECK(h.send(":SCM1\n:MPA0,500000,1000\n:MPR0,-500000,0\n") == ":E0,147\n:E0,147\n");
    h.advance_ms(1000);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,0\n");
}

TEST_CASE("an empty SPL limit fails FRM where it starts (144): no search, the position stays known", "[device][mcs][limits][frm]")
{
    McsHarness h(one_channel("S"));
    reference(h);
    CHECK(h.send(":MPA0,2000000,0\n") == ":E0,0\n");
    h.advance_ms(1000);
    CHECK(h.send(":SPL0,1000000,-1000000\n:GP0\n") == ":E0,0\n:P0,2000000\n");
    CHECK(h.send(":FRM0,1,0,1\n:GS0\n") == ":E0,0\n:S0,0\n");       // sync: acknowledged, no search
    CHECK(h.send(":SCM1\n:FRM0,1,0,1\n") == ":E0,144\n");
    h.advance_ms(5000);                                             // the mark is 2 s away
    CHECK(h.send(":GS0\n:GP0\n:GPPK0\n") == ":S0,0\n:P0,2000000\n:PPK0,1\n");
}

TEST_CASE("an empty SPL limit fails FRM on an end-stop type too: it is not referenced where it stands", "[device][mcs][limits][frm]")
{
    McsHarness h(one_channel("M"));
    CHECK(h.send(":CS0\n") == ":E0,0\n");                    // end-stop types: CS, then FRM (3.3)
    h.advance_ms(3000);
    CHECK(h.send(":FRM0,0,0,1\n") == ":E0,0\n");
    h.advance_ms(1);                                        // CS ended at the forward end stop
    CHECK(h.send(":GS0\n:GPPK0\n:GP0\n") == ":S0,0\n:PPK0,1\n:P0,0\n");
    CHECK(h.send(":MPA0,-2000000,0\n") == ":E0,0\n");
    h.advance_ms(1000);
    CHECK(h.send(":SPL0,0,-5000000\n:SCM1\n:FRM0,0,0,1\n") == ":E0,0\n:E0,144\n");
    h.advance_ms(5000);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,-2000000\n");   // neither moved nor re-zeroed
}

TEST_CASE("an empty SPL limit stops CS where it starts (147), and scans are not limited (2.3.4)", "[device][mcs][limits]")
{
    McsHarness h(one_channel("S"));
    reference(h);
    CHECK(h.send(":SPL0,1000000,-1000000\n:CS0\n:GS0\n") == ":E0,0\n:E0,0\n:S0,0\n");
    CHECK(h.send(":SCM1\n:CS0\n") == ":E0,147\n");
    CHECK(h.send(":GS0\n") == ":S0,0\n");                  // not 6: no calibration runs
    CHECK(h.send(":MSCA0,2048,1024\n:GS0\n") == ":S0,2\n");   // "all movements except scan movements"
    h.advance_ms(2000);
    CHECK(h.send(":GS0\n:GVL0\n:GP0\n") == ":S0,0\n:VL0,2048\n:P0,750\n");
}

TEST_CASE("an empty SAL limit on a rotary channel stops MST, MAR and MAA where they start", "[device][mcs][limits][rotary]")
{
    McsHarness h(one_channel("SR"));
    CHECK(h.send(":SCLS0,10000000\n") == ":E-1,0\n");       // 10°/s
    reference(h);
    // 90° of revolution 0 up to 270° of revolution -1 (-90°): the maximum is below the minimum.
    CHECK(h.send(":SAL0,90000000,0,270000000,-1\n:GAL0\n") == ":E0,0\n:AL0,90000000,0,270000000,-1\n");
    CHECK(h.send(":MST0,100,4095,100\n:GS0\n") == ":E0,0\n:S0,0\n");
    h.advance_ms(1000);
    CHECK(h.send(":GA0\n") == ":A0,0,0\n");
    CHECK(h.send(":SCM1\n:MST0,30000,4095,1000\n:MAR0,10000000,0,0\n:MAA0,45000000,0,0\n")
          == ":E0,147\n:E0,147\n:E0,147\n");
    h.advance_ms(5000);
    CHECK(h.send(":GS0\n:GA0\n") == ":S0,0\n:A0,0,0\n");
    CHECK(h.send(":SAL0,0,0,0,0\n:MST0,100,4095,100\n") == "");   // equal pairs: no limit
    h.advance_ms(1000);
    CHECK(h.send(":GS0\n:GA0\n") == ":S0,0\n:A0,100000,0\n");
}

} // namespace test_mcs_range_limits
