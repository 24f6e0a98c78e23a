// APT solenoid controllers (TSC001, KSC101; manual p.84-92, docs/protocol/apt.md "Solenoid"):
// the operating modes on the stepped clock, the interlock, the triggered mode through the
// control API's TRIG IN, EEPROM saves across a power cycle, bad parameters ignored.
#include "apt_harness.hpp"
#include "emulator/control/body_state.hpp"

#include <nlohmann/json.hpp>

namespace test_apt_solenoid {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;
using nlohmann::json;

namespace {

DeviceConfig solenoid(const std::string& model = "TSC001", bool plug = true)
{
    DeviceConfig c;
    c.name = "sol";
    c.protocol = "apt";
    c.model = model;
    config_of(c).solenoid.interlock_fitted = plug;
    return c;
}

// Host 0x01, unit 0x50.
const std::string kReqState = "CC 04 01 00 50 01";
const std::string kOn = "CB 04 01 01 50 01";
const std::string kOff = "CB 04 01 02 50 01";
const std::string kOutputOn = "CD 04 01 01 01 50";
const std::string kOutputOff = "CD 04 01 02 01 50";
/// SET_SOL_CYCLEPARAMS: 1 s on (4000 x 250 us), 1 s off, 3 cycles.
const std::string kCycle1s3 = "C3 04 0E 00 D0 01 01 00 A0 0F 00 00 A0 0F 00 00 03 00 00 00";

std::string set_mode(int mode)
{
    return "C0 04 01 0" + std::to_string(mode) + " 50 01";
}

json channel(AptHarness& h)
{
    json out = json::object();
    rigsim::control::describe_device(h.device(), &h.world(), out);   // as the control API does
    return out["channels"].at(0);
}

Refused patch(AptHarness& h, const json& body)
{
    return h.device().patch_channel(0, body);
}

} // namespace

TEST_CASE("apt solenoid: manual, single and auto modes time the output on the stepped clock", "[device][apt][solenoid]")
{
    for (const char* model : {"TSC001", "KSC101"}) {
        INFO(model);
        AptHarness h(solenoid(model));
        CHECK(h.send(kCycle1s3).empty());
        // Manual (power-up): ON holds until OFF.
        CHECK(h.send(kOn).empty());
        h.advance_ms(5000);
        CHECK(h.send(kReqState) == kOutputOn);
        CHECK(h.send(kOff).empty());
        CHECK(h.send(kReqState) == kOutputOff);
        // Single: one cycle; ON during it ignored (it does not restart the cycle).
        CHECK(h.send(set_mode(2)).empty());
        CHECK(h.send(kOn).empty());
        h.advance_ms(500);
        CHECK(h.send(kOn).empty());
        h.advance_ms(499);
        CHECK(h.send(kReqState) == kOutputOn);
        h.advance_ms(1);
        CHECK(h.send(kReqState) == kOutputOff);
        h.advance_ms(3000);
        CHECK(h.send(kReqState) == kOutputOff);
        CHECK(channel(h)["cycles_done"] == 1);
        // Auto: NumCycles (3) cycles, then closed.
        CHECK(h.send(set_mode(3)).empty());
        CHECK(h.send(kOn).empty());
        h.advance_ms(4500);
        CHECK(h.send(kReqState) == kOutputOn);   // the third cycle's on phase
        CHECK(channel(h)["cycles_done"] == 2);
        h.advance_ms(1500);
        CHECK(h.send(kReqState) == kOutputOff);
        CHECK(channel(h)["cycles_done"] == 3);
        h.advance_ms(10'000);
        CHECK(h.send(kReqState) == kOutputOff);
    }
}

TEST_CASE("apt solenoid: OFF and a mode change close a running output", "[device][apt][solenoid]")
{
    AptHarness h(solenoid());
    // NumCycles 0: auto mode cycles until stopped (p.87).
    CHECK(h.send("C3 04 0E 00 D0 01 01 00 A0 0F 00 00 A0 0F 00 00 00 00 00 00").empty());
    CHECK(h.send(set_mode(3)).empty());
    CHECK(h.send(kOn).empty());
    h.advance_ms(100'500);
    CHECK(h.send(kReqState) == kOutputOn);
    CHECK(h.send(kOff).empty());
    CHECK(h.send(kReqState) == kOutputOff);
    h.advance_ms(2000);
    CHECK(h.send(kReqState) == kOutputOff);
    CHECK(h.send(kOn).empty());
    h.advance_ms(200);
    CHECK(h.send(kReqState) == kOutputOn);
    CHECK(h.send(set_mode(1)).empty());   // to manual while running: closed, not reopened
    CHECK(h.send(kReqState) == kOutputOff);
    h.advance_ms(5000);
    CHECK(h.send(kReqState) == kOutputOff);
    CHECK(channel(h)["state"] == "off");
}

TEST_CASE("apt solenoid: triggered mode runs the programmed cycles on each TRIG IN rising edge once primed",
          "[device][apt][solenoid][control]")
{
    AptHarness h(solenoid());
    CHECK(h.send(kCycle1s3).empty());
    CHECK(h.send(set_mode(4)).empty());
    // Not primed: an edge does nothing.
    CHECK_FALSE(patch(h, {{"trig_in", "pulse"}}));
    h.advance_ms(10);
    CHECK(h.send(kReqState) == kOutputOff);
    // ON primes (p.85): the output stays closed until the edge.
    CHECK(h.send(kOn).empty());
    CHECK(channel(h)["primed"] == true);
    h.advance_ms(1000);
    CHECK(h.send(kReqState) == kOutputOff);
    CHECK_FALSE(patch(h, {{"trig_in", true}}));
    CHECK(channel(h)["trig_in"] == true);
    h.advance_ms(999);
    CHECK(h.send(kReqState) == kOutputOn);
    h.advance_ms(1);
    CHECK(h.send(kReqState) == kOutputOff);
    CHECK_FALSE(patch(h, {{"trig_in", true}}));   // a level, no new edge
    h.advance_ms(6000);
    CHECK(channel(h)["cycles_done"] == 3);
    CHECK(h.send(kReqState) == kOutputOff);
    // Still primed: the next rising edge runs the cycles again.
    CHECK_FALSE(patch(h, {{"trig_in", false}}));
    CHECK_FALSE(patch(h, {{"trig_in", "pulse"}}));
    CHECK(channel(h)["trig_in"] == false);
    h.advance_ms(500);
    CHECK(h.send(kReqState) == kOutputOn);
    // OFF closes and disarms: an edge after it does nothing.
    CHECK(h.send(kOff).empty());
    CHECK(channel(h)["primed"] == false);
    CHECK_FALSE(patch(h, {{"trig_in", "pulse"}}));
    h.advance_ms(100);
    CHECK(h.send(kReqState) == kOutputOff);
}

TEST_CASE("apt solenoid: the interlock plug gates ON in interlock mode 1, and pulling it closes the output",
          "[device][apt][solenoid][control]")
{
    AptHarness h(solenoid());
    CHECK(h.send(kOn).empty());
    CHECK(h.send(kReqState) == kOutputOn);
    CHECK_FALSE(patch(h, {{"interlock_fitted", false}}));
    CHECK(h.send(kReqState) == kOutputOff);
    CHECK(channel(h)["state"] == "off");
    CHECK(h.send(kOn).empty());   // ignored, logged
    CHECK(h.send(kReqState) == kOutputOff);
    CHECK_FALSE(patch(h, {{"interlock_fitted", true}}));   // refitted: stays closed until ON
    CHECK(h.send(kReqState) == kOutputOff);
    CHECK(h.send(kOn).empty());
    CHECK(h.send(kReqState) == kOutputOn);
    // Interlock disabled (mode 2): the plug does not matter.
    CHECK(h.send("C6 04 01 02 50 01").empty());
    CHECK_FALSE(patch(h, {{"interlock_fitted", false}}));
    CHECK(h.send(kReqState) == kOutputOn);
    // Enabling it without the plug closes the output.
    CHECK(h.send("C6 04 01 01 50 01").empty());
    CHECK(h.send(kReqState) == kOutputOff);
}

TEST_CASE("apt solenoid: bad parameters and channels are ignored", "[device][apt][solenoid]")
{
    AptHarness h(solenoid("KSC101"));
    CHECK(h.send("CB 04 01 03 50 01").empty());   // state 3
    CHECK(h.send("C6 04 01 00 50 01").empty());   // interlock mode 0
    CHECK(h.send("C0 04 01 00 50 01").empty());   // mode 0
    CHECK(h.send("CB 04 02 01 50 01").empty());   // channel 2
    CHECK(h.send(kReqState) == kOutputOff);
    CHECK(h.send("C7 04 01 00 50 01") == "C8 04 01 01 01 50");
    CHECK(h.send("C1 04 01 00 50 01") == "C2 04 01 01 01 50");
    // OffTime 40,000,001 (p.87: up to 40,000,000) and NumCycles -1: ignored.
    CHECK(h.send("C3 04 0E 00 D0 01 01 00 A0 0F 00 00 01 5A 62 02 00 00 00 00").empty());
    CHECK(h.send("C3 04 0E 00 D0 01 01 00 A0 0F 00 00 A0 0F 00 00 FF FF FF FF").empty());
    CHECK(h.send("C4 04 01 00 50 01") == "C5 04 0E 00 81 50 01 00 A0 0F 00 00 A0 0F 00 00 00 00 00 00");
    // The limits themselves are taken.
    CHECK(h.send("C3 04 0E 00 D0 01 01 00 90 01 00 00 00 5A 62 02 40 42 0F 00").empty());
    CHECK(h.send("C4 04 01 00 50 01") == "C5 04 0E 00 81 50 01 00 90 01 00 00 00 5A 62 02 40 42 0F 00");
}

TEST_CASE("apt solenoid: MOT_SET_EEPROMPARAMS saves the solenoid SETs across a power cycle", "[device][apt][solenoid][eeprom]")
{
    StateStore store;
    AptHarness h(solenoid(), &store);
    CHECK(h.send(kCycle1s3).empty());
    CHECK(h.send(set_mode(3)).empty());
    CHECK(h.send("C6 04 01 02 50 01").empty());             // interlock disabled, not saved
    CHECK(h.send("B9 04 04 00 D0 01 01 00 C3 04").empty());  // saves CYCLEPARAMS
    CHECK(h.send("B9 04 04 00 D0 01 01 00 C0 04").empty());  // saves OPERATINGMODE
    CHECK_FALSE(patch(h, {{"interlock_fitted", false}}));
    CHECK(h.send(kOn).empty());
    h.device().power_cycle(PowerCycle{true, false});
    CHECK(h.send(kReqState) == kOutputOff);   // the output is off after the power cycle
    CHECK(h.send("C4 04 01 00 50 01") == "C5 04 0E 00 81 50 01 00 A0 0F 00 00 A0 0F 00 00 03 00 00 00");
    CHECK(h.send("C1 04 01 00 50 01") == "C2 04 01 03 01 50");
    CHECK(h.send("C7 04 01 00 50 01") == "C8 04 01 01 01 50");   // power-up interlock mode
    CHECK(channel(h)["interlock_fitted"] == false);             // the plug is still out
    h.device().power_cycle(PowerCycle{false, false});
    CHECK(h.send("C1 04 01 00 50 01") == "C2 04 01 01 01 50");
}

TEST_CASE("apt solenoid: control API describe and PATCH of the channel", "[device][apt][solenoid][control]")
{
    AptHarness h(solenoid("TSC001", false));
    const auto ch = channel(h);
    CHECK(ch["index"] == 0);
    CHECK(ch["address"] == "0x50");
    CHECK(ch["mode"] == "manual");
    CHECK(ch["state"] == "off");
    CHECK(ch["output_active"] == false);
    CHECK(ch["cycles_done"] == 0);
    CHECK(ch["cycles_total"] == 0);
    CHECK(ch["primed"] == false);
    CHECK(ch["interlock_mode"] == "enabled");
    CHECK(ch["interlock_fitted"] == false);
    CHECK(ch["trig_in"] == false);
    CHECK(ch["status"] == 0x1000);
    const auto unknown = patch(h, {{"interlock_fitted", true}, {"position_si", 0}});
    REQUIRE(unknown);
    CHECK(unknown->status == 400);
    CHECK(unknown->message.find("\"position_si\"") != std::string::npos);
    CHECK(channel(h)["interlock_fitted"] == false);   // a refused PATCH changes nothing
    const auto bad = patch(h, {{"trig_in", "edge"}});
    REQUIRE(bad);
    CHECK(bad->status == 400);
    CHECK_FALSE(patch(h, {{"interlock_fitted", true}}));
    CHECK(h.send(kOn).empty());
    CHECK(channel(h)["output_active"] == true);
    CHECK(channel(h)["state"] == "on");
    CHECK(channel(h)["status"] == 0x1001);
}

} // namespace test_apt_solenoid
