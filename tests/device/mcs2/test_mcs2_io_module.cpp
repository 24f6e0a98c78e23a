// An MCS2 with its I/O module (rig key mcs2.io_module; MCS2 Programmer's Guide 1.0.6, 2.16-2.17):
// the trigger input's emergency stop in each Emergency Stop Mode, command groups and streams
// started by it, the modules' I/O values, and what a unit without the module answers.

#include "mcs2_harness.hpp"

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <string>

using rigsim::test::Mcs2Harness;
using rigsim::test::mcs2_device_config;

namespace {

rigsim::DeviceConfig with_io_module()
{
    auto config = mcs2_device_config();
    rigsim::mcs2::config_of(config).io_module = true;
    return config;
}

/// The control API's PATCH of the trigger input (docs/control-api/mcs2.md).
void trig_in(Mcs2Harness& h, const char* level)
{
    const auto refused = h.device().patch_channel(0, nlohmann::json{{"trig_in", level}});
    REQUIRE(!refused);
}

std::int64_t moving(Mcs2Harness& h, int channel)
{
    return h.number(":CHAN" + std::to_string(channel) + ":STAT?") & 0x1;
}

} // namespace

TEST_CASE("MCS2 I/O module: present in the module state, its values stored, DOUT set and cleared by bits",
          "[device][mcs2]")
{
    Mcs2Harness h(with_io_module());
    CHECK(h.ask(":MOD0:STAT?") == "9");   // SM_PRESENT | IOM_PRESENT (2.8.2)
    h.send(":MOD0:IOM:OPT 7;VOLT 1;AINP:RANG 3");
    CHECK(h.ask(":MOD0:IOM:OPT?;VOLT?;AINP:RANG?") == "7; 1; 3");
    h.send(":MOD0:AUX:DOUT 5;:MOD0:AUX:DOUT:SET 2;:MOD0:AUX:DOUT:CLE 4");
    CHECK(h.ask(":MOD0:AUX:DOUT?") == "3");
    h.send(":MOD0:AUX:AOUT:VAL1 -32768");
    CHECK(h.ask(":MOD0:AUX:AOUT:VAL1?;:MOD0:AUX:AOUT:VAL0?;:MOD0:AUX:DINP?") == "-32768; 0; 0");
    CHECK(h.ask(":CHAN0:AUX:IOM:INP:VAL1?;:CHAN0:CLIN:AUX?") == "0; 0");
    h.send(":CHAN0:TRIG:PCOM:LMIN 10;LMAX 5;:CHAN0:TRIG:OUTP:MODE 1");   // limits the wrong way round
    h.send(":CHAN0:TRIG:OUTP:MODE 3;:CHAN0:CLIN 2");
    CHECK(h.errors() == std::vector<std::string>{"41,\"Invalid configuration\"", "32765,\"Feature not supported\""});
    CHECK(h.ask(":CHAN0:TRIG:OUTP:MODE?") == "3");
    // Without the module (the default unit): 257 for each, and no trigger input to drive.
    Mcs2Harness plain;
    CHECK(plain.ask(":MOD0:STAT?") == "1");
    plain.send(":MOD0:AUX:DOUT 5;:DEV:TRIG:INP:MODE 1");
    CHECK(plain.errors() == std::vector<std::string>{"257,\"No IO module present\"", "257,\"No IO module present\""});
    CHECK(plain.device().patch_channel(0, nlohmann::json{{"trig_in", "high"}})->status == 400);
}

TEST_CASE("MCS2 emergency stop: NORMAL stops, RESTRICTED locks until the mode is written, AUTO_RELEASE at the "
          "inverse edge",
          "[device][mcs2]")
{
    Mcs2Harness h(with_io_module());
    h.send(":DEV:TRIG:INP:MODE 1;COND 0");   // EMERGENCY_STOP on a rising edge
    h.send(":CHAN0:VEL 1000000000;ACC 1000000000;:MOVE0 1000000000;:MOVE1 1000000000");
    h.advance_ms(100);
    trig_in(h, "high");
    CHECK(moving(h, 0) == 0);   // hard, under acceleration control too
    CHECK(moving(h, 1) == 0);
    CHECK(h.ask(":CHAN0:ERR?") == "25");
    CHECK(h.number(":DEV:STAT?") == 0);   // NORMAL: no lock
    trig_in(h, "low");
    h.send(":DEV:EST:MODE 1;:MOVE0 0");
    CHECK(moving(h, 0) == 1);
    trig_in(h, "high");
    CHECK(h.number(":DEV:STAT?") == 2);   // MOVEMENT_LOCKED (2.8.1)
    h.send(":MOVE0 0");
    CHECK(h.ask(":CHAN0:ERR?") == "37");   // MOVEMENT_LOCKED
    trig_in(h, "low");
    CHECK(h.number(":DEV:STAT?") == 2);   // RESTRICTED outlasts the line
    h.send(":DEV:EST:MODE 2");            // writing the mode releases it
    CHECK(h.number(":DEV:STAT?") == 0);
    trig_in(h, "high");
    CHECK(h.number(":DEV:STAT?") == 2);
    trig_in(h, "low");                    // AUTO_RELEASE: the inverse edge
    CHECK(h.number(":DEV:STAT?") == 0);
    h.send(":DEV:TRIG:INP:COND 1");       // FALLING
    trig_in(h, "high");                   // not the edge that acts
    CHECK(h.number(":DEV:STAT?") == 0);
    h.send(":MOVE0 5000000000");
    CHECK(moving(h, 0) == 1);
    trig_in(h, "low");                    // the falling edge stops and locks
    CHECK(moving(h, 0) == 0);
    CHECK(h.number(":DEV:STAT?") == 2);
    trig_in(h, "high");                   // the rising one, its inverse, releases
    CHECK(h.number(":DEV:STAT?") == 0);
    CHECK(h.errors() == std::vector<std::string>{"37,\"Movement locked\""});
}

TEST_CASE("MCS2 external triggers: a command group and a stream wait for the input", "[device][mcs2]")
{
    Mcs2Harness h(with_io_module());
    h.send(":CGR:OPEN 1");
    CHECK(h.errors() == std::vector<std::string>{"265,\"Invalid input trigger mode\""});
    h.send(":DEV:TRIG:INP:MODE 3");
    h.send(":CGR:OPEN 1");
    h.send(":MOVE0 1000000");
    h.send(":CGR:CLOS");
    CHECK(h.ask(":CGR:FIN?") == "0");   // armed (6.4.2's third example)
    CHECK(moving(h, 0) == 0);
    trig_in(h, "pulse");
    CHECK(h.ask(":CGR:FIN?") == "1");
    CHECK(moving(h, 0) == 1);

    h.send(":DEV:TRIG:INP:MODE 2");
    h.advance_ms(100);
    h.send(":DEV:STR:BAS 100;:STR:OPEN 1;:STR:FRAM 1,1000000;:STR:FRAM 1,2000000;:STR:CLOS");
    h.advance_ms(100);
    CHECK(h.number(":DEV:STAT?") == 0);   // ready, waiting for its trigger
    trig_in(h, "pulse");
    CHECK(h.number(":DEV:STAT?") == 0x1000);
    h.advance_ms(31);
    CHECK(h.number(":CHAN1:POS?") == 2'000'000);
    CHECK(h.number(":DEV:STAT?") == 0);
    CHECK(h.errors().empty());
}
