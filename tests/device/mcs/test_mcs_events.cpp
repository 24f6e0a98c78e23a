// Channel properties (2.2, 4.4), emergency stop and broadcast stop (2.2.1, 2.2.3), the
// controller event system (2.4): software triggers, counters, capture buffers, command queues.
#include "mcs_harness.hpp"

#include <catch2/catch.hpp>

namespace test_mcs_events {

using rigsim::test::McsHarness;
using rigsim::test::mcs_device_config;

TEST_CASE("GCP/SCP read and write every property of appendix 4.4", "[device][mcs][properties]")
{
    McsHarness h;
    CHECK(h.send(":GCP0,16842753\n:GCP0,16842797\n:GCP0,16908289\n:GCP0,17039361\n:GCP0,17104913\n")
          == ":CPR0,16842753,0\n:CPR0,16842797,0\n:CPR0,16908289,0\n:CPR0,17039361,0\n:CPR0,17104913,1\n");
    CHECK(h.send(":GCP0,134938625\n:GCP0,135659567\n:GCP0,135659539\n")
          == ":CPR0,134938625,1\n:CPR0,135659567,0\n:CPR0,135659539,0\n");
    CHECK(h.send(":GCP0,33554433\n:GCP0,33554434\n:GCP0,33619969\n:GCP0,67108867\n:GCP0,67108869\n")
          == ":CPR0,33554433,0\n:CPR0,33554434,0\n:CPR0,33619969,0\n:CPR0,67108867,0\n:CPR0,67108869,0\n");
    CHECK(h.send(":GCP0,83886083\n:GCP0,100663300\n:GCP0,100663302\n")
          == ":CPR0,83886083,0\n:CPR0,100663300,0\n:CPR0,100663302,1\n");
    CHECK(h.send(":SCP0,67108869,1234\n:GCP0,67108869\n") == ":E-1,0\n:CPR0,67108869,1234\n");
    CHECK(h.send(":SCP0,135659567,5000\n:GSC0\n") == ":E-1,0\n:SC0,5000,0\n");
    CHECK(h.send(":SCP0,134938625,0\n:GP0\n:GP1\n") == ":E-1,0\n:E0,140\n:P1,0\n");   // one channel only
    // Errors: component 154, sub component 155, property 156 (also read-only), range 7.
    CHECK(h.send(":GCP0,50331649\n:GCP0,16973825\n:GCP0,16842754\n:GCP0,117440512\n")
          == ":E0,154\n:E0,155\n:E0,156\n:E0,156\n");
    CHECK(h.send(":SCP0,100663300,1\n:SCP0,16842753,4\n:SCP0,67108869,-1\n:SCP0,67108867,5\n")
          == ":E0,156\n:E0,7\n:E0,7\n:E0,7\n");
}

TEST_CASE("low vibration mode needs a stopped channel and pulls in acceleration control", "[device][mcs][properties]")
{
    McsHarness h;
    CHECK(h.send(":SCP0,16908289,1\n:GCLA0\n:GCLS0\n") == ":E-1,0\n:CLA0,1000000\n:CLS0,10000000\n");
    CHECK(h.send(":MPA0,5000000,0\n:SCP0,16908289,0\n") == ":E0,0\n:E0,150\n");
    CHECK(h.send(":SCLS0,0\n") == ":E0,150\n");                  // 2.5.1: can't drop it while moving
    h.advance_ms(2000);
    CHECK(h.send(":SCLS0,0\n:GCP0,16908289\n:GCLA0\n") == ":E-1,0\n:CPR0,16908289,0\n:CLA0,0\n");
}

TEST_CASE("broadcast stop: an end stop locks restricted channels (146, status 9)", "[device][mcs][estop]")
{
    McsHarness h;
    CHECK(h.send(":SCP0,17039361,1\n:SCP1,16842753,1\n:SCP2,16842753,2\n") == ":E-1,0\n:E-1,0\n:E-1,0\n");
    CHECK(h.send(":SCLS1,1000000\n:SCLS2,1000000\n:MPA1,5000000,0\n:MPA2,5000000,0\n")
          == ":E-1,0\n:E-1,0\n:E1,0\n:E2,0\n");
    CHECK(h.send(":MPA0,-20000000,0\n") == ":E0,0\n");         // hits -10.5 mm after 1.05 s
    h.advance_ms(1100);
    CHECK(h.send(":GS0\n:GS1\n:GS2\n") == ":S0,0\n:S1,9\n:S2,4\n");
    CHECK(h.send(":GP1\n") == ":P1,1050000\n");
    CHECK(h.send(":MPA1,0,0\n:MST1,1,100,100\n:FRM1,0,0,0\n:CS1\n:MSCA1,0,1\n")
          == ":E1,146\n:E1,146\n:E1,146\n:E1,146\n:E1,146\n");
    CHECK(h.send(":SCP1,16842753,0\n:GS1\n:MPA1,0,0\n") == ":E-1,0\n:S1,0\n:E1,0\n");   // unlocked
}

TEST_CASE("SESM/GESM set every channel's mode and unlock", "[device][mcs][estop]")
{
    McsHarness h;
    CHECK(h.send(":GESM\n:SESM1\n:GESM\n:GCP2,16842753\n") == ":ESM0\n:E-1,0\n:ESM1\n:CPR2,16842753,1\n");
    CHECK(h.send(":SCP0,17039361,1\n:MPA0,20000000,0\n") == ":E-1,0\n:E0,0\n");
    h.advance_ms(2000);
    CHECK(h.send(":GS0\n:GS2\n") == ":S0,9\n:S2,9\n");
    CHECK(h.send(":SESM0\n:GS2\n") == ":E-1,0\n:S2,0\n");
    CHECK(h.send(":SESM3\n") == ":E-1,7\n");
}

TEST_CASE("command queue: ATC, TC, SRT, 151/152/153, CTCQ, sync mode gives 8", "[device][mcs][events]")
{
    McsHarness h;
    CHECK(h.send(":ATC0,1792\n:TC0\n:CTCQ0\n:SRT0,1\n") == ":E-1,8\n:E-1,8\n:E-1,8\n:E-1,8\n");
    CHECK(h.send(":SCM1\n:SRT0,1\n:SRT1,1\n") == "");
    // The manual's example (2.4.5): both channels start together on TC0.
    CHECK(h.send(":ATC0,1792\n:MPR0,1000000,0\n:ATC1,1792\n:MPR1,1000000,0\n") == "");
    CHECK(h.send(":GCP0,100663300\n:GS0\n") == ":CPR0,100663300,1\n:S0,0\n");
    CHECK(h.send(":MPA0,0,0\n") == ":E0,151\n");                 // waiting for the trigger
    CHECK(h.send(":ATC0,1792\n:MPA0,0,0\n") == ":E0,153\n:E0,151\n");   // capacity 1
    h.advance_ms(1000);
    CHECK(h.send(":TC0\n") == ":T0\n:T1\n");
    CHECK(h.send(":GS0\n:GS1\n:GCP0,100663300\n") == ":S0,4\n:S1,4\n:CPR0,100663300,0\n");
    h.advance_ms(100);
    CHECK(h.send(":GP0\n:GP1\n") == ":P0,1000000\n:P1,1000000\n");
    CHECK(h.send(":ATC2,1793\n:GP2\n") == ":E2,152\n");           // not a movement command
    CHECK(h.send(":ATC2,1793\n:MPR2,5,0\n:CTCQ2\n:GCP2,100663300\n:MPA2,0,0\n") == ":CPR2,100663300,0\n");
    CHECK(h.send(":ATC2,0\n:ATC2,1000\n:TC256\n") == ":E2,7\n:E2,7\n:E-1,7\n");
    // A queued command that turns out invalid reports its error when triggered.
    CHECK(h.send(":ATC2,1794\n:MPA2,0,90000\n:TC2\n") == ":E2,7\n");
}

TEST_CASE("counters and capture buffer 0 follow their trigger source", "[device][mcs][events]")
{
    McsHarness h;
    CHECK(h.send(":SCM1\n:SCP0,67108867,1792\n:SCP0,83886083,1792\n:SCP1,67108867,1793\n") == "");
    CHECK(h.send(":MPA0,2000000,0\n") == "");
    h.advance_ms(100);
    CHECK(h.send(":TC0\n:TC0\n:TC5\n") == "");
    CHECK(h.send(":GCP0,67108869\n:GCP1,67108869\n:GB0,0\n")
          == ":CPR0,67108869,2\n:CPR1,67108869,0\n:CB0,0,1000000,0,2\n");
    h.advance_ms(100);
    CHECK(h.send(":GB0,0\n:TC0\n:GB0,0\n:GB0,1\n") == ":CB0,0,1000000,0,2\n:CB0,0,2000000,0,3\n:E0,7\n");
}

} // namespace test_mcs_events
