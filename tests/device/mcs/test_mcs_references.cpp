// Defining positions (2.3.3), rotary channels (2.3.1), software range limits (2.3.4):
// FRM, CS, GPPK, SP/SSC after referencing, MAA/MAR/GA, SPL/GPL, SAL/GAL.
#include "mcs_harness.hpp"

#include "emulator/daemon/rig_families.hpp"

#include <catch2/catch.hpp>

namespace test_mcs_references {

using rigsim::test::McsHarness;
using rigsim::test::mcs_device_config;

namespace {

/// One channel of the given sensor type starting at `start` (physical), 1 mm/s search.
rigsim::DeviceConfig one_channel(const char* sensor, std::int64_t start = -3'000'000)
{
    auto c = mcs_device_config(1);
    rigsim::mcs::config_of(c).channels[0].sensor_type = sensor;
    rigsim::mcs::config_of(c).channels[0].start_position_nm = start;
    return c;
}

} // namespace

TEST_CASE("FRM finds a single mark, holds it, and makes the position known", "[device][mcs][frm]")
{
    McsHarness h(one_channel("S"));   // mark at physical 0, stage at -3 mm
    CHECK(h.send(":GPPK0\n:GP0\n") == ":PPK0,0\n:P0,0\n");
    CHECK(h.send(":FRM0,0,1000,1\n") == ":E0,0\n");
    CHECK(h.send(":GS0\n") == ":S0,7\n");
    h.advance_ms(2999);                                      // 3 mm at 1 mm/s
    CHECK(h.send(":GS0\n:GPPK0\n") == ":S0,7\n:PPK0,0\n");
    h.advance_ms(1);
    CHECK(h.send(":GS0\n:GPPK0\n:GP0\n") == ":S0,3\n:PPK0,1\n:P0,0\n");   // auto zero, holding
    h.advance_ms(1000);
    CHECK(h.send(":GS0\n") == ":S0,0\n");
}

TEST_CASE("the default rig's positioners start away from their marks: FRM takes a different, non-zero time on each", "[device][mcs][frm]")
{
    const auto rig = rigsim::default_rig_config();
    REQUIRE(rig.devices.at(0).protocol == "mcs");
    // Start positions -2.5, +4 and +3 mm, marks at 0, search at 1 mm/s forward (2.3.3): -2.5 mm
    // -> 2.5 s; +4 mm -> forward to the end stop at 10.5 mm, then back to the mark:
    // 6.5 + 10.5 mm = 17 s; +3 mm -> 7.5 + 10.5 mm = 18 s.
    const std::int64_t expected_ms[] = {2'500, 17'000, 18'000};
    for (int ch = 0; ch < 3; ++ch) {
        INFO("channel " << ch);
        McsHarness h(rig.devices[0]);
        const auto c = std::to_string(ch);
        CHECK(h.send(":FRM" + c + ",0,0,1\n") == ":E" + c + ",0\n");
        std::int64_t searched_ms = 0;
        while (h.send(":GS" + c + "\n") == ":S" + c + ",7\n" && searched_ms < 60'000) {
            h.advance_ms(1);
            ++searched_ms;
        }
        CHECK(searched_ms == expected_ms[ch]);
        CHECK(h.send(":GPPK" + c + "\n:GP" + c + "\n") == ":PPK" + c + ",1\n:P" + c + ",0\n");
    }
}

TEST_CASE("FRM backward reverses at the end stop and still finds the mark", "[device][mcs][frm]")
{
    McsHarness h(one_channel("S"));
    CHECK(h.send(":FRM0,1,0,1\n") == ":E0,0\n");
    h.advance_ms(7499);                                      // -3 -> -10.5 mm: 7.5 s
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,7\n:P0,-7499000\n");
    h.advance_ms(10'500);                                    // back to the mark
    CHECK(h.send(":GS0\n:GPPK0\n:GP0\n") == ":S0,7\n:PPK0,0\n:P0,2999000\n");
    h.advance_ms(1);
    CHECK(h.send(":GS0\n:GPPK0\n:GP0\n") == ":S0,0\n:PPK0,1\n:P0,0\n");
}

TEST_CASE("the manual's measuring-scale example (2.3.3) step by step", "[device][mcs][frm][scale]")
{
    McsHarness h(one_channel("S", 500'000));
    CHECK(h.send(":SP0,1000000\n:GP0\n") == ":E0,0\n:P0,1000000\n");        // (b)
    CHECK(h.send(":SSC0,2000000,0\n:GP0\n") == ":E-1,0\n:P0,1000000\n");    // (c) no effect yet
    CHECK(h.send(":FRM0,1,60000,0\n") == ":E0,0\n");                       // (d)
    h.advance_ms(500);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,3\n:P0,2000000\n");
    CHECK(h.send(":SP0,-1000000\n:GP0\n:GSC0\n") == ":E0,0\n:P0,-1000000\n:SC0,-1000000,0\n");  // (e)
    CHECK(h.send(":SSC0,-3000000,0\n:GP0\n") == ":E-1,0\n:P0,-3000000\n");  // (f)
    CHECK(h.send(":MPR0,100000,60000\n") == ":E0,0\n");
    h.advance_ms(100);
    CHECK(h.send(":GP0\n") == ":P0,-2900000\n");
    CHECK(h.send(":SSC0,0,1\n:GP0\n") == ":E-1,0\n:P0,-100000\n");          // (i) inverted
    CHECK(h.send(":SSC0,-3000000,1\n:GP0\n") == ":E-1,0\n:P0,-3100000\n");  // (j)
    CHECK(h.send(":MPR0,100000,0\n") == ":E0,0\n");                        // inverted: moves back
    h.advance_ms(100);
    CHECK(h.send(":GP0\n") == ":P0,-3000000\n");
}

TEST_CASE("FRM with distance-coded marks stops at the second mark", "[device][mcs][frm]")
{
    auto config = one_channel("SC", -2'500'000);              // marks every 2 mm from 0
    McsHarness h(config);
    CHECK(h.send(":FRM0,0,0,0\n") == ":E0,0\n");
    h.advance_ms(2499);                                      // first mark at -2 mm, second at 0
    CHECK(h.send(":GS0\n") == ":S0,7\n");
    h.advance_ms(1);
    CHECK(h.send(":GS0\n:GPPK0\n:GP0\n") == ":S0,0\n:PPK0,1\n:P0,0\n");
    // From the far end, the search reverses and needs two marks in the other direction.
    CHECK(h.send(":MPA0,9900000,0\n") == ":E0,0\n");
    h.advance_ms(1000);
    CHECK(h.send(":FRM0,0,0,1\n") == ":E0,0\n");
    h.advance_ms(600 + 3900);                                // to +10.5, back past 8 to 6 mm
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,0\n");      // auto zero at the second mark
}

TEST_CASE("FRM on end-stop types drives to the safe direction's end stop", "[device][mcs][frm]")
{
    McsHarness h(one_channel("M", 0));
    CHECK(h.send(":SSD0,1\n:CS0\n") == ":E-1,0\n:E0,0\n");
    CHECK(h.send(":GS0\n") == ":S0,6\n");
    h.advance_ms(2999);
    CHECK(h.send(":GS0\n") == ":S0,6\n");
    h.advance_ms(1);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,-10500000\n");  // CS ended at the end stop
    CHECK(h.send(":MPA0,0,0\n") == ":E0,0\n");
    h.advance_ms(2000);
    CHECK(h.send(":FRM0,0,0,1\n") == ":E0,0\n");             // direction ignored: backward
    h.advance_ms(10'500);
    CHECK(h.send(":GS0\n:GPPK0\n:GP0\n") == ":S0,0\n:PPK0,1\n:P0,0\n");
}

TEST_CASE("FRM failures: no reference (144) and a mark outside the range limit", "[device][mcs][frm]")
{
    auto config = mcs_device_config(2);
    rigsim::mcs::config_of(config).channels[0].sensor_type = "SR36M";             // rotary, cannot be referenced
    rigsim::mcs::config_of(config).channels[1].sensor_type = "S";
    rigsim::mcs::config_of(config).channels[1].start_position_nm = 1'000'000;
    McsHarness h(config);
    CHECK(h.send(":FRM0,0,0,0\n") == ":E0,144\n");
    CHECK(h.send(":FRM1,1,0,1\n") == ":E1,0\n");           // mark 1 mm behind: backward
    h.advance_ms(1000);
    CHECK(h.send(":GPPK1\n:SPL1,500000,2000000\n:GPL1\n") == ":PPK1,1\n:E1,0\n:PL1,500000,2000000\n");
    CHECK(h.send(":MPA1,1000000,0\n:SCM1\n") == ":E1,0\n");
    h.advance_ms(100);
    CHECK(h.send(":FRM1,0,0,1\n") == "");                    // the mark at 0 lies outside
    h.advance_ms(2499);                                      // to 2 mm, back to 0.5 mm
    CHECK(h.send(":GS1\n") == ":S1,7\n");
    h.advance_ms(1);
    CHECK(h.send(":GS1\n") == ":E1,144\n:S1,0\n");
    CHECK(h.send(":FRM1,0,0,3\n:FRM1,2,0,0\n:FRM1,0,60001,0\n") == ":E1,7\n:E1,7\n:E1,7\n");
}

TEST_CASE("software range limits: 148 before FRM, clipping with 147, only inward moves", "[device][mcs][limits]")
{
    McsHarness h(one_channel("S", 0));
    CHECK(h.send(":SPL0,-1000000,1000000\n") == ":E0,148\n");
    CHECK(h.send(":GPL0\n") == ":PL0,0,0\n");
    CHECK(h.send(":FRM0,0,0,1\n") == ":E0,0\n");
    h.advance_ms(10);
    CHECK(h.send(":SPL0,-1000000,1000000\n:SCM1\n") == ":E0,0\n");
    CHECK(h.send(":MPA0,3000000,0\n") == "");
    h.advance_ms(99);
    CHECK(h.send(":GS0\n") == ":S0,4\n");
    h.advance_ms(1);
    CHECK(h.send(":GS0\n:GP0\n") == ":E0,147\n:S0,0\n:P0,1000000\n");
    CHECK(h.send(":MPR0,500000,0\n") == ":E0,147\n");          // outward from the boundary
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,1000000\n");
    CHECK(h.send(":MPR0,-500000,0\n") == "");                 // back inside is allowed
    h.advance_ms(50);
    CHECK(h.send(":GP0\n") == ":P0,500000\n");
    CHECK(h.send(":SPL0,0,0\n:GPL0\n") == ":PL0,0,0\n");      // min == max: no limit
    CHECK(h.send(":MPA0,3000000,0\n") == "");
    h.advance_ms(250);
    CHECK(h.send(":GP0\n") == ":P0,3000000\n");
    CHECK(h.send(":SPL0,1000000,-1000000\n:MPA0,0,0\n") == ":E0,147\n");   // max < min: no movement
    CHECK(h.send(":SCM0\n:R\n:GPL0\n") == ":E-1,0\n:E-1,0\n:PL0,0,0\n");   // not kept over a reset
}

TEST_CASE("rotary channels: MAA, MAR and GA with revolutions, SAL/GAL", "[device][mcs][rotary]")
{
    auto config = one_channel("SR", 0);
    McsHarness h(config);
    CHECK(h.send(":GA0\n") == ":A0,0,0\n");
    CHECK(h.send(":GP0\n:MPA0,0,0\n") == ":E0,143\n:E0,143\n");
    CHECK(h.send(":SCLS0,10000000\n") == ":E-1,0\n");          // 10°/s, the stage's top speed
    CHECK(h.send(":MAA0,90000000,0,0\n") == ":E0,0\n");
    h.advance_ms(4500);
    CHECK(h.send(":GA0\n") == ":A0,45000000,0\n");
    h.advance_ms(4500);
    CHECK(h.send(":GS0\n:GA0\n") == ":S0,0\n:A0,90000000,0\n");
    CHECK(h.send(":MAR0,-45000000,-1,0\n") == ":E0,0\n");      // one full turn plus 45° back
    h.advance_ms(40'500);
    CHECK(h.send(":GA0\n") == ":A0,45000000,-1\n");           // -315°
    CHECK(h.send(":MAA0,360000000,0,0\n:MAA0,0,32768,0\n:MAR0,360000000,0,0\n")
          == ":E0,7\n:E0,7\n:E0,7\n");
    CHECK(h.send(":SAL0,315000000,-1,45000000,0\n") == ":E0,148\n");
    CHECK(h.send(":FRM0,0,0,1\n") == ":E0,0\n");             // the mark comes once per turn
    h.advance_ms(31'499);                                       // 315° at the SCLS speed
    CHECK(h.send(":GS0\n") == ":S0,7\n");
    h.advance_ms(1);
    CHECK(h.send(":GS0\n:GA0\n:GPPK0\n") == ":S0,0\n:A0,0,0\n:PPK0,1\n");
    CHECK(h.send(":SAL0,315000000,-1,45000000,0\n:GAL0\n") == ":E0,0\n:AL0,315000000,-1,45000000,0\n");
    CHECK(h.send(":MAA0,90000000,0,0\n") == ":E0,0\n");
    h.advance_ms(9000);
    CHECK(h.send(":GS0\n:GA0\n") == ":S0,0\n:A0,45000000,0\n");   // stopped at the limit
    CHECK(h.send(":GPL0\n:SPL0,0,1\n") == ":E0,143\n:E0,143\n");
}

TEST_CASE("SP on a rotary channel takes 0..359,999,999 and answers E<ch>,7 outside it", "[device][mcs][rotary]")
{
    McsHarness h(one_channel("SR", 0));
    // 3.2 SP: "In case of a rotary positioner the range of this parameter is limited to
    // 0 .. 359,999,999"; 4.2: error 7 "A parameter given exceeds the valid range".
    CHECK(h.send(":SP0,360000000\n:GA0\n") == ":E0,7\n:A0,0,0\n");
    CHECK(h.send(":SP0,-1\n:GA0\n") == ":E0,7\n:A0,0,0\n");
    CHECK(h.send(":SP0,359999999\n:GA0\n") == ":E0,0\n:A0,359999999,0\n");
    CHECK(h.send(":SP0,0\n:GA0\n") == ":E0,0\n:A0,0,0\n");
}

TEST_CASE("goniometers have end stops, linear channels refuse angle commands", "[device][mcs][rotary]")
{
    auto config = mcs_device_config(2);
    rigsim::mcs::config_of(config).channels[0].sensor_type = "G605S";
    McsHarness h(config);
    CHECK(h.send(":MAA0,20000000,0,0\n") == ":E0,0\n");      // beyond +10°: end stop
    h.advance_ms(5000);
    CHECK(h.send(":GS0\n:GA0\n") == ":S0,0\n:A0,10000000,0\n");
    CHECK(h.send(":GA1\n:MAA1,0,0,0\n:MAR1,0,0,0\n:GAL1\n") == ":E1,143\n:E1,143\n:E1,143\n:E1,143\n");
}

} // namespace test_mcs_references
