// MCS system commands, communication modes, sensor modes and the measuring scale
// (manual 2.1, 2.3.2, 2.3.3, 3.1, 3.2, 3.5) on a stepped clock.
#include "mcs_harness.hpp"

#include <catch2/catch.hpp>

namespace test_mcs_system {

using rigsim::test::McsHarness;

TEST_CASE("SCM switches to async mode: acknowledges vanish and errors remain", "[device][mcs][async]")
{
    McsHarness h;
    CHECK(h.send(":GCM\n") == ":CM0\n");
    CHECK(h.send(":SCM1\n") == "");                        // answers in the new mode
    CHECK(h.send(":GCM\n") == ":CM1\n");
    CHECK(h.send(":MPA0,100000,0\n") == "");
    CHECK(h.send(":MPA0,0,70000\n") == ":E0,7\n");
    CHECK(h.send(":GP9\n") == ":E-1,7\n");
    CHECK(h.send(":SCM2\n") == ":E-1,7\n");
    CHECK(h.send(":SCM0\n") == ":E-1,0\n");
    CHECK(h.send(":GCM\n") == ":CM0\n");
}

TEST_CASE("async mode reports end stops (142) and completions (SRC) unprompted", "[device][mcs][async]")
{
    McsHarness h;
    CHECK(h.send(":SRC0,1\n") == ":E-1,8\n");              // SRC needs async mode (2.1)
    std::string other;
    auto second = h.open(other);
    CHECK(h.send(":SCM1\n:SRC0,1\n") == "");
    CHECK(h.send(":MPA0,100000,0\n") == "");
    h.advance_ms(9);
    CHECK(h.send(":GS0\n") == ":S0,4\n");
    h.advance_ms(1);
    CHECK(h.send(":GS0\n") == ":C0\n:S0,0\n");               // the report arrived with the tick
    CHECK(other == ":C0\n");                                 // every connection hears it
    other.clear();
    CHECK(h.send(":MPA0,20000000,0\n") == "");
    h.advance_ms(3000);
    CHECK(other == ":E0,142\n");
    CHECK(h.send(":GS0\n:GP0\n") == ":E0,142\n:S0,0\n:P0,10500000\n");
}

TEST_CASE("sync mode never sends anything unprompted", "[device][mcs][async]")
{
    McsHarness h;
    std::string other;
    auto second = h.open(other);
    CHECK(h.send(":MPA0,20000000,0\n") == ":E0,0\n");
    h.advance_ms(3000);
    CHECK(other.empty());
    CHECK(h.send(":GS0\n") == ":S0,0\n");
}

TEST_CASE("R acknowledges and returns to the power-up state", "[device][mcs]")
{
    McsHarness h;
    CHECK(h.send(":SCLS0,1000000\n:MPA0,3000000,60000\n:SSC0,5000,1\n:CB57600\n")
          == ":E-1,0\n:E0,0\n:E-1,0\n:BR57142\n");
    h.advance_ms(500);
    CHECK(h.send(":SCM1\n:R\n") == "");                     // async: no acknowledge
    CHECK(h.send(":GCM\n") == ":CM0\n");                    // back in sync mode
    CHECK(h.send(":GS0\n:GP0\n:GPPK0\n") == ":S0,0\n:P0,0\n:PPK0,0\n");
    CHECK(h.send(":GCLS0\n") == ":CLS0,0\n");
    CHECK(h.send(":GSC0\n") == ":SC0,5000,1\n");             // the scale is non-volatile
    CHECK(h.send(":R\n") == ":E-1,0\n");
}

TEST_CASE("sensor modes: disabled gives 140, power save delays moves with status 5", "[device][mcs][sensor]")
{
    McsHarness h;
    CHECK(h.send(":GSE\n") == ":SE1\n");
    CHECK(h.send(":MPA0,5000000,0\n") == ":E0,0\n");
    h.advance_ms(100);
    CHECK(h.send(":SSE0\n") == ":E-1,0\n");                  // stops every positioner
    CHECK(h.send(":GSE\n:GS0\n") == ":SE0\n:S0,0\n");
    CHECK(h.send(":GP0\n") == ":E0,140\n");
    CHECK(h.send(":MPA0,0,0\n") == ":E0,140\n");
    CHECK(h.send(":MPR1,0,0\n") == ":E1,140\n");
    CHECK(h.send(":SSE3\n") == ":E-1,7\n");
    CHECK(h.send(":SSE2\n") == ":E-1,0\n");
    CHECK(h.send(":GP0\n") == ":P0,1000000\n");
    CHECK(h.send(":MPA0,1100000,0\n") == ":E0,0\n");
    CHECK(h.send(":GS0\n") == ":S0,5\n");
    h.advance_ms(4);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,5\n:P0,1000000\n");
    h.advance_ms(1);                                         // sensor up after 5 ms
    CHECK(h.send(":GS0\n") == ":S0,4\n");
    h.advance_ms(10);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,1100000\n");
}

TEST_CASE("SP and SZP define the current position while the physical one is unknown", "[device][mcs][scale]")
{
    McsHarness h;
    CHECK(h.send(":GPPK0\n") == ":PPK0,0\n");
    CHECK(h.send(":SP0,1000000\n") == ":E0,0\n");
    CHECK(h.send(":GP0\n") == ":P0,1000000\n");
    CHECK(h.send(":MPA0,1500000,0\n") == ":E0,0\n");
    h.advance_ms(50);
    CHECK(h.send(":GP0\n") == ":P0,1500000\n");
    CHECK(h.send(":SZP0\n:GP0\n") == ":E0,0\n:P0,0\n");
    // Unknown physical position: SSC only changes the stored scale (2.3.3 table).
    CHECK(h.send(":SSC0,2000000,0\n") == ":E-1,0\n");
    CHECK(h.send(":GP0\n:GSC0\n") == ":P0,0\n:SC0,2000000,0\n");
    CHECK(h.send(":SSC0,0,2\n") == ":E0,7\n");
}

TEST_CASE("SARP0 makes relative moves start from the current position", "[device][mcs]")
{
    McsHarness h;
    CHECK(h.send(":SCLS0,1000000\n:SARP0,0\n") == ":E-1,0\n:E0,0\n");
    CHECK(h.send(":MPR0,500000,0\n") == ":E0,0\n");
    h.advance_ms(100);
    CHECK(h.send(":MPR0,500000,0\n") == ":E0,0\n");          // from 0.1 mm: target 0.6 mm
    h.advance_ms(2000);
    CHECK(h.send(":GP0\n") == ":P0,600000\n");
    CHECK(h.send(":SARP0,2\n") == ":E0,7\n");
}

TEST_CASE("SCLF limits the top speed in proportion", "[device][mcs]")
{
    McsHarness h;
    CHECK(h.send(":SCLF0,9250\n") == ":E0,0\n");             // half of 18500 Hz: 5 mm/s
    CHECK(h.send(":MPA0,1000000,0\n") == ":E0,0\n");
    h.advance_ms(100);
    CHECK(h.send(":GP0\n") == ":P0,500000\n");
    CHECK(h.send(":SCLF0,49\n:SCLF0,18501\n") == ":E0,7\n:E0,7\n");
}

TEST_CASE("K stops every positioner when no command arrives in time", "[device][mcs]")
{
    McsHarness h;
    CHECK(h.send(":K50\n") == ":E-1,7\n");                   // 100..60000 or 0
    CHECK(h.send(":SCLS0,1000000\n:K200\n") == ":E-1,0\n:E-1,0\n");
    CHECK(h.send(":MPA0,1000000,0\n") == ":E0,0\n");
    h.advance_ms(150);
    CHECK(h.send(":GS0\n") == ":S0,4\n");                    // a parsed command resets the timer
    h.advance_ms(150);
    CHECK(h.send(":K\n") == ":E-1,0\n");
    h.advance_ms(199);
    CHECK(h.send(":GS0\n") == ":S0,4\n");
    h.advance_ms(200);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,699000\n");  // stopped at 499 ms + 200 ms
    CHECK(h.send(":K0\n") == ":E-1,0\n");
}

TEST_CASE("identification: SHE, CB, GSN, GFV, GFP, GSD/SSD, SSWS", "[device][mcs]")
{
    McsHarness h;
    CHECK(h.send(":SHE0\n:SHE2\n:SHE3\n") == ":E-1,0\n:E-1,0\n:E-1,7\n");
    CHECK(h.send(":CB9600\n:CB115200\n:CB9599\n") == ":BR9592\n:BR114285\n:E-1,7\n");
    CHECK(h.send(":GSN1\n") == ":SN1,0x2f941401\n");
    CHECK(h.send(":GFV0\n") == ":FV0,2,1,5,0,3,1,5,0\n");
    CHECK(h.send(":GFP0,255\n:GFP0,0\n:GFP0,1\n") == ":FP0,1\n:FP0,254\n:E0,7\n");
    CHECK(h.send(":GSD0\n:SSD0,1\n:GSD0\n:SSD0,2\n") == ":SD0,0\n:E-1,0\n:SD0,1\n:E0,7\n");
    CHECK(h.send(":SSWS0,0\n:SSWS0,3\n") == ":E0,0\n:E0,7\n");
    CHECK(h.send(":GSN3\n") == ":E-1,7\n");
}

} // namespace test_mcs_system
