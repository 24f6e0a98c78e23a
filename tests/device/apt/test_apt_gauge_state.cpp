// A TPZ001 piezo driver with the TSG001 strain gauge reader mounted on its actuator, across
// power-ups and through the reader's own settings (manual p.94, p.103-105, p.113, p.115,
// p.117, p.127-129): a saved closed loop comes back at power-up, the reader's zero goes with
// its power, its status update's Position stays in 0..32767, its HubAnalogueOutput picks the
// hub channel, a closed loop resumes bumpless when its input comes back, and its status
// updates stop after 50 without PZ_ACK_PZSTATUSUPDATE.
#include "gauge_pair.hpp"
#include "tests/support/temp_dir.hpp"

#include "models/piezo_actuator.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <string>

namespace test_apt_gauge_state {

using namespace rigsim::test;
using namespace rigsim::test::gauge_pair;

namespace {

constexpr const char* kModeOpen = "42 06 01 01 01 50";
constexpr const char* kTpzInput1 = "D4 07 0A 00 D0 01 01 00 01 00 01 00 00 00 00 00";   // 75 V, hub A (p.115)

/// TSG_READING's Reading word of device `d` (p.129).
std::int16_t reading(AptHarness& h, std::size_t d)
{
    const auto b = bytes(h.send("DD 07 01 00 50 01", d));
    REQUIRE(b.size() == 12);
    return static_cast<std::int16_t>(get_u16(b, 8));
}

/// PZ_GET_OUTPUTVOLTS of device `d` in volts of the 75 V limit (p.96).
double output_v(AptHarness& h, std::size_t d = 0)
{
    const auto b = bytes(h.send("44 06 01 00 50 01", d));
    REQUIRE(b.size() == 10);
    return static_cast<std::int16_t>(get_u16(b, 8)) / 32767.0 * 75.0;
}

} // namespace

TEST_CASE("apt gauge state: a TPZ001's saved closed loop comes back at power-up on its TSG001, the entry kept",
          "[device][apt][gauge][eeprom]")
{
    TempDir dir;
    const auto state_path = dir.file("state.json");
    const bool hub_b = GENERATE(false, true);
    INFO((hub_b ? "hub B: TPZ_IOSETTINGS input 2 saved too (0x07D4 replays before 0x0640)" : "hub A"));
    {
        rigsim::StateStore store(state_path);
        AptHarness h({tpz(), tsg(hub_b ? GaugeRoute::HubB : GaugeRoute::HubA)}, &store);
        if (hub_b) {
            h.send(kTpzInput2);
            h.send("D0 07 04 00 D0 01 01 00 D4 07");   // PZ_SET_EEPROMPARAMS TPZ_IOSETTINGS (p.113)
        }
        h.send(kClosedLoop);
        REQUIRE(h.send(kReqMode) == kModeClosed);
        h.send("D0 07 04 00 D0 01 01 00 40 06");       // PZ_SET_EEPROMPARAMS POSCONTROLMODE
        REQUIRE(store.get("tpz", "bay0/0x0640") != nullptr);
    }
    rigsim::StateStore reloaded(state_path);          // the daemon restarts on the same file
    AptHarness h({tpz(), tsg(hub_b ? GaugeRoute::HubB : GaugeRoute::HubA)}, &reloaded);
    CHECK(h.send(kReqMode) == kModeClosed);
    CHECK(reloaded.get("tpz", "bay0/0x0640") != nullptr);
    if (hub_b)
        CHECK(reloaded.get("tpz", "bay0/0x07d4") != nullptr);
    // And the loop runs: OUTPUTPOS 50 % is reached on the gauge.
    h.send("46 06 04 00 D0 01 01 00 00 40");
    h.advance_ms(500);
    CHECK(extension_um(h) == Approx(16384.0 / 32767.0 * kTravelUm).margin(0.01));
}

TEST_CASE("apt harness: a TSG001 added before its TPZ001 finds it (the world links once both exist)",
          "[device][apt][gauge]")
{
    AptHarness h(tsg());
    REQUIRE(h.add_device(tpz()) == 1);
    h.send(kClosedLoop, 1);
    CHECK(h.send(kReqMode, 1) == kModeClosed);
    CHECK(h.send("50 06 01 00 50 01", 0) == "51 06 04 00 81 50 01 00 C8 00");   // MAXTRAVEL 20 um (p.118)
}

TEST_CASE("apt TPZ001: after a power cycle its closed loop still reads its gauge", "[device][apt][gauge]")
{
    AptHarness h(tpz());
    h.add_device(tsg());
    h.device(0).power_cycle(rigsim::PowerCycle{});
    h.send(kClosedLoop);
    CHECK(h.send(kReqMode) == kModeClosed);
}

TEST_CASE("apt TSG001: the zero is lost with the power, as the zeroed bit is", "[device][apt][gauge]")
{
    AptHarness h(tpz());
    h.add_device(tsg());
    h.send("43 06 04 00 D0 01 01 00 77 77");   // 70 V of 75 V (p.96)
    h.advance_ms(100);
    const std::int16_t raw = reading(h, 1);
    REQUIRE(raw == 0x7777);
    h.send("58 06 01 00 50 01", 1);            // PZ_SET_ZERO (p.117, D-13: 2 s)
    h.advance_ms(2100);
    REQUIRE(std::abs(reading(h, 1)) <= 1);
    SECTION("power cycle")
    {
        h.device(1).power_cycle(rigsim::PowerCycle{});
    }
    SECTION("POST /api/reset")
    {
        h.device(1).power_cycle(rigsim::PowerCycle{true, true});
    }
    CHECK(reading(h, 1) == raw);
    h.send("11 00 00 00 50 01", 1);            // the status update's bits: 0x1 only, not zeroed (0x10)
    h.advance_ms(100);
    CHECK(h.take(1) == "61 06 0A 00 81 50 01 00 00 00 77 77 01 00 00 00");
}

TEST_CASE("apt TSG001: below its zero the status update's Position is 0, TSG_READING keeps the sign",
          "[device][apt][gauge]")
{
    AptHarness h(tpz());
    h.add_device(tsg());
    h.send("43 06 04 00 D0 01 01 00 77 77");   // 70 V
    h.advance_ms(100);
    h.send("58 06 01 00 50 01", 1);            // zero at 70 V
    h.advance_ms(2100);
    h.send("43 06 04 00 D0 01 01 00 BB 3B");   // 35 V: below the zero
    h.advance_ms(100);
    CHECK(reading(h, 1) < -10000);             // p.129: +-32767
    h.send("11 00 00 00 50 01", 1);
    h.advance_ms(100);
    const auto update = bytes(h.take(1));
    REQUIRE(update.size() == 16);
    CHECK(get_u16(update, 0) == 0x0661);
    CHECK(get_u16(update, 10) == 0);           // p.103: Position 0..32767
    CHECK(get_u32(update, 12) == 0x11);        // linked, zeroed
}

TEST_CASE("apt TSG001: its HubAnalogueOutput picks the hub channel the TPZ001's input reads",
          "[device][apt][gauge]")
{
    SECTION("hub A cabling: TSG output 2 + TPZ input 2 closes the loop")
    {
        AptHarness h(tpz());
        h.add_device(tsg(GaugeRoute::HubA));
        h.send(kTsgOutput2, 1);
        h.send(kTpzInput2);
        h.send(kClosedLoop);
        CHECK(h.send(kReqMode) == kModeClosed);
    }
    SECTION("hub A cabling: TSG output 1 + TPZ input 2 is refused (D-19)")
    {
        AptHarness h(tpz());
        h.add_device(tsg(GaugeRoute::HubA));
        h.send(kTsgOutput1, 1);
        h.send(kTpzInput2);
        h.send(kClosedLoop);
        CHECK(h.send(kReqMode) == kModeOpen);
    }
    SECTION("hub B cabling: the reader powers up with output 2")
    {
        AptHarness h(tpz());
        h.add_device(tsg(GaugeRoute::HubB));
        CHECK(h.send("DB 07 01 00 50 01", 1) == "DC 07 0E 00 81 50 01 00 02 00 01 00 30 75 00 00 00 00 00 00");
        h.send(kClosedLoop);
        CHECK(h.send(kReqMode) == kModeOpen);   // the TPZ reads input 1 at power-up
        h.send(kTpzInput2);
        h.send(kClosedLoop);
        CHECK(h.send(kReqMode) == kModeClosed);
    }
    SECTION("SMA cabling: input 3, whatever the hub output")
    {
        AptHarness h(tpz());
        h.add_device(tsg(GaugeRoute::Sma));
        h.send(kTsgOutput2, 1);
        h.send(kClosedLoop);
        CHECK(h.send(kReqMode) == kModeOpen);
        h.send("D4 07 0A 00 D0 01 01 00 01 00 03 00 00 00 00 00");
        h.send(kClosedLoop);
        CHECK(h.send(kReqMode) == kModeClosed);
    }
}

TEST_CASE("apt TPZ001 closed loop: when its input comes back after 5 s away it resumes without a jump",
          "[device][apt][piezo][gauge]")
{
    AptHarness h(tpz());
    h.add_device(tsg());
    h.send(kClosedLoop);
    REQUIRE(h.send(kReqMode) == kModeClosed);
    h.send("46 06 04 00 D0 01 01 00 66 26");   // 30 % (p.97)
    h.advance_ms(1000);
    REQUIRE(extension_um(h) == Approx(0.3 * kTravelUm).margin(0.02));
    h.send(kTpzInput2);                        // the feedback switched away: the loop idles
    h.send("46 06 04 00 D0 01 01 00 CC 4C");   // 60 %, taken in closed loop
    h.advance_ms(5000);
    const double before_v = output_v(h);
    h.send(kTpzInput1);                        // the input comes back
    CHECK(output_v(h) == Approx(before_v).margin(1e-9));
    h.advance_ms(1);
    // One 1 ms tick of the 4 kHz loop: Prop 100/255 x the error's change (the output has not
    // moved) plus Int 4 x 15 /s x 30 % x 1 ms = 1.8 % of 75 V = 1.35 V.
    const double step_v = output_v(h) - before_v;
    INFO("first tick's output change " << step_v << " V");
    CHECK(std::abs(step_v) < 2.0);
    h.advance_ms(2000);
    CHECK(extension_um(h) == Approx(0.6 * kTravelUm).margin(0.02));
}

TEST_CASE("apt TSG001: status updates stop after 50 without PZ_ACK_PZSTATUSUPDATE, 0x0662 resumes them",
          "[device][apt][gauge]")
{
    AptHarness h(tpz());
    h.add_device(tsg());
    CHECK(h.send("11 00 00 00 50 01", 1).empty());   // HW_START_UPDATEMSGS
    h.advance_ms(99);
    CHECK(h.take(1).empty());
    h.advance_ms(1);
    CHECK(h.take(1) == "61 06 0A 00 81 50 01 00 00 00 00 00 01 00 00 00");   // p.103-104
    h.advance_ms(4900);                              // 50 in all (p.105)
    CHECK(h.take(1).size() == 49 * 16 * 3 - 1);
    h.advance_ms(1000);
    CHECK(h.take(1).empty());
    CHECK(h.send("92 04 00 00 50 01", 1).empty());   // the motors' MOT_ACK_DCSTATUSUPDATE: not the TSG's
    h.advance_ms(200);
    CHECK(h.take(1).empty());
    CHECK(h.send("62 06 00 00 50 01", 1).empty());   // PZ_ACK_PZSTATUSUPDATE (p.105)
    h.advance_ms(200);
    CHECK(h.take(1).size() == 2 * 16 * 3 - 1);
    CHECK(h.send("12 00 00 00 50 01", 1).empty());   // HW_STOP_UPDATEMSGS
    h.advance_ms(1000);
    CHECK(h.take(1).empty());
}

} // namespace test_apt_gauge_state
