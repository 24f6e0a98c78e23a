// APT piezo units (TPZ001/KPZ101, BPC30x bays; manual p.93-125): the amplifier's clip and slew
// limit, OUTPUTMAXVOLTS, SET_ZERO, smooth mode changes and the closed loop on a BPC bay's strain
// gauge, on a stepped clock. Wire-exact exchanges: transcripts/apt_piezo_tpz001.txt.
#include "apt_harness.hpp"

#include "models/piezo_actuator.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>

namespace test_apt_piezo {

using namespace rigsim::test;

namespace {

/// A BPC303 with three bays of this actuator, strain gauge feedback on each.
rigsim::DeviceConfig bpc303(double creep = 0, double hysteresis = 0, int hardware_max_v = 150)
{
    rigsim::DeviceConfig c;
    c.name = "rack";
    c.protocol = "apt";
    c.model = "BPC303";
    auto& apt = config_of(c);
    apt.hardware_max_voltage_v = hardware_max_v;
    PiezoBayConfig bay;
    bay.actuator.travel_um = 20;
    bay.actuator.max_voltage_v = hardware_max_v;
    bay.actuator.creep = creep;
    bay.actuator.hysteresis = hysteresis;
    bay.actuator.response_ms = 0.1;
    bay.strain_gauge = true;
    apt.piezo_bays.assign(3, bay);
    return c;
}

/// The i16 at data offset 2 (the word after the channel) of a one-frame reply.
std::int32_t word_of(const std::string& reply_hex, bool is_signed)
{
    const auto b = bytes(reply_hex);
    REQUIRE(b.size() >= 10);
    const auto u = get_u16(b, 8);
    return is_signed ? static_cast<std::int16_t>(u) : u;
}

std::uint32_t status_of(AptHarness& h)
{
    const auto b = bytes(h.send("5B 06 01 00 21 01"));
    REQUIRE(b.size() == 12);
    return static_cast<std::uint32_t>(get_i32(b, 8));
}

rigsim::models::PiezoActuator& actuator(AptHarness& h, const std::string& key = "rack/1")
{
    auto* a = h.world().find_as<rigsim::models::PiezoActuator>(key);
    REQUIRE(a != nullptr);
    return *a;
}

} // namespace

TEST_CASE("apt BPC303 bay: OUTPUTMAXVOLTS answers the maximum then the travel, and clips the output",
          "[device][apt][piezo]")
{
    AptHarness h(bpc303());
    // p.121: 100 V of the 150 V amplifier (flags 0x08, D-11), then GET_MAXTRAVEL 20 um = 200.
    CHECK(h.send("80 06 06 00 A1 01 01 00 E8 03 00 00")
          == "82 06 06 00 81 21 01 00 E8 03 08 00 51 06 04 00 81 21 01 00 C8 00");
    CHECK(h.send("81 06 01 00 21 01") == "82 06 06 00 81 21 01 00 E8 03 08 00");
    // Full scale is now 100 V.
    h.send("43 06 04 00 A1 01 01 00 FF 7F");
    h.advance_ms(1);
    CHECK(actuator(h).voltage() == Approx(100.0));
    // A lower maximum clips the output in force (p.121).
    h.send("80 06 06 00 A1 01 01 00 F4 01 00 00");
    h.advance_ms(1);
    CHECK(actuator(h).voltage() == Approx(50.0));
    CHECK(word_of(h.send("44 06 01 00 21 01"), true) == 32767);
    // The other bays keep their own limit (150 V at power-up).
    CHECK(h.send("81 06 01 00 22 01") == "82 06 06 00 81 22 01 00 DC 05 08 00");
}

TEST_CASE("apt BPC bay: OUTPUTMAXVOLTS above the amplifier's hardware maximum is ignored", "[device][apt][piezo]")
{
    AptHarness h(bpc303(0, 0, 100));
    CHECK(h.send("80 06 06 00 A1 01 01 00 B0 04 00 00").empty());   // 120 V on a 100 V amplifier
    CHECK(h.send("81 06 01 00 21 01") == "82 06 06 00 81 21 01 00 E8 03 04 00");
    CHECK((status_of(h) & 0x00007000) == 0x2000);   // p.102: the 100 V hardware bit
}

TEST_CASE("apt piezo slew rate: the output changes no faster than SLEWRATES allows", "[device][apt][piezo]")
{
    AptHarness h(bpc303());
    // p.123: V/ms = value x Vmax / 19000: 1900 at 150 V is 15 V/ms.
    h.send("83 06 06 00 A1 01 01 00 6C 07 00 00");
    h.send("43 06 04 00 A1 01 01 00 FF 7F");   // 150 V
    double last = 0;
    for (int ms = 1; ms <= 12; ++ms) {
        h.advance_ms(1);
        const double v = actuator(h).voltage();
        CHECK(v - last <= 15.0 + 1e-9);
        last = v;
    }
    CHECK(last == Approx(150.0));
    CHECK(word_of(h.send("44 06 01 00 21 01"), true) == 32767);
    // Slew 0: no limit, the next demand is met at once.
    h.send("83 06 06 00 A1 01 01 00 00 00 00 00");
    h.send("43 06 04 00 A1 01 01 00 00 00");
    CHECK(actuator(h).voltage() == 0.0);
}

TEST_CASE("apt BPC bay: the closed loop holds the position against creep, open loop drifts", "[device][apt][piezo]")
{
    const double travel = 20;
    SECTION("open loop drifts by more than 1 % of the travel in 60 s")
    {
        AptHarness h(bpc303(0.02, 0.05));
        h.send("43 06 04 00 A1 01 01 00 00 40");   // half the voltage
        h.advance_ms(200);
        const double start = actuator(h).extension_um();
        h.advance_ms(60'000);
        CHECK(std::abs(actuator(h).extension_um() - start) > 0.01 * travel);
    }
    SECTION("closed loop at 50 % stays within 0.1 % of the travel for 60 s")
    {
        AptHarness h(bpc303(0.02, 0.05));
        CHECK(h.send("40 06 01 02 21 01").empty());
        CHECK(h.send("41 06 01 00 21 01") == "42 06 01 02 01 21");
        h.send("46 06 04 00 A1 01 01 00 00 40");   // 16384: 50 %
        h.advance_ms(1000);
        const double target = 16384.0 / 32767.0 * travel;
        double worst = 0;
        for (int s = 0; s < 60; ++s) {
            h.advance_ms(1000);
            worst = std::max(worst, std::abs(actuator(h).extension_um() - target));
        }
        CHECK(worst < 0.001 * travel);
        CHECK(std::abs(word_of(h.send("47 06 01 00 21 01"), false) - 16384) <= 33);
        // p.101-102: connected, SG feedback, closed loop, 150 V hardware, active, enabled.
        CHECK(status_of(h) == (0x1u | 0x100u | 0x400u | 0x4000u | 0x20000000u | 0x80000000u));
        // p.96: OUTPUTVOLTS is ignored in closed loop.
        const double v = actuator(h).voltage();
        h.send("43 06 04 00 A1 01 01 00 00 00");
        CHECK(actuator(h).voltage() == Approx(v).margin(1.0));
    }
}

TEST_CASE("apt BPC bay: a smooth change to open loop ramps the output over 500 ms", "[device][apt][piezo]")
{
    AptHarness h(bpc303());
    h.send("40 06 01 02 21 01");
    h.send("46 06 04 00 A1 01 01 00 00 40");
    h.advance_ms(1000);
    const double held = actuator(h).voltage();
    REQUIRE(held == Approx(75.0).margin(1.0));
    // Mode 3, open loop smoothed, with the open-loop demand still 0 V (D-18).
    h.send("40 06 01 03 21 01");
    h.advance_ms(250);
    CHECK(actuator(h).voltage() == Approx(held / 2).margin(0.5));
    h.advance_ms(250);
    CHECK(actuator(h).voltage() == Approx(0.0).margin(1e-9));
}

TEST_CASE("apt BPC bay: SET_ZERO zeroes for 2 s at 0 V, then reports zeroed", "[device][apt][piezo]")
{
    AptHarness h(bpc303());
    h.send("43 06 04 00 A1 01 01 00 00 40");
    CHECK(h.send("58 06 01 00 21 01").empty());
    CHECK((status_of(h) & 0x30) == 0x20);   // p.101: zeroing
    CHECK(actuator(h).voltage() == 0.0);
    h.advance_ms(1999);
    CHECK((status_of(h) & 0x30) == 0x20);
    h.advance_ms(1);
    CHECK((status_of(h) & 0x30) == 0x10);   // zeroed
}

TEST_CASE("apt TPZ001: closed loop without a linked gauge is ignored (D-19)", "[device][apt][piezo]")
{
    rigsim::DeviceConfig c;
    c.name = "tpz";
    c.protocol = "apt";
    c.model = "TPZ001";
    config_of(c);   // the default "apt" section: a 20 um, 75 V actuator
    AptHarness h(c);
    h.send("40 06 01 02 50 01");
    CHECK(h.send("41 06 01 00 50 01") == "42 06 01 01 01 50");
    CHECK(h.send("40 06 01 04 50 01").empty());
    CHECK(h.send("41 06 01 00 50 01") == "42 06 01 01 01 50");
    CHECK(h.send("40 06 01 03 50 01").empty());   // open loop smoothed is taken
    CHECK(h.send("41 06 01 00 50 01") == "42 06 01 03 01 50");
}

} // namespace test_apt_piezo
