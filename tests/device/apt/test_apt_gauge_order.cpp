// A TPZ001 and the TSG001 reading its actuator, when the reader itself moves the signal
// (TSG_IOSETTINGS HubAnalogueOutput, p.127): at power-up the reader restores its hub output
// before the driver replays its saved closed loop, whichever the rig lists first; a closed
// loop whose reader switched its output away and back resumes without a jump (p.94, p.115).
#include "gauge_pair.hpp"
#include "tests/support/temp_dir.hpp"

#include "models/piezo_actuator.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <string>

namespace test_apt_gauge_order {

using namespace rigsim::test;
using namespace rigsim::test::gauge_pair;

/// PZ_GET_OUTPUTVOLTS of the TPZ in volts of the 75 V limit (p.96).
double output_v(AptHarness& h)
{
    const auto b = bytes(h.send("44 06 01 00 50 01"));
    REQUIRE(b.size() == 10);
    return static_cast<std::int16_t>(get_u16(b, 8)) / 32767.0 * 75.0;
}

TEST_CASE("apt gauge order: a TPZ001 listed before its TSG001 replays its closed loop on the reader's saved hub "
          "output, both entries kept",
          "[device][apt][gauge][eeprom]")
{
    TempDir dir;
    const auto state_path = dir.file("state.json");
    {
        rigsim::StateStore store(state_path);
        AptHarness h({tpz(), tsg()}, &store);
        h.send(kTsgOutput2, 1);
        h.send("D0 07 04 00 D0 01 01 00 DA 07", 1);   // PZ_SET_EEPROMPARAMS TSG_IOSETTINGS (p.113)
        h.send(kTpzInput2);
        h.send("D0 07 04 00 D0 01 01 00 D4 07");      // ... TPZ_IOSETTINGS
        h.send(kClosedLoop);
        REQUIRE(h.send(kReqMode) == kModeClosed);
        h.send("D0 07 04 00 D0 01 01 00 40 06");      // ... POSCONTROLMODE
        REQUIRE(store.get("tsg", "bay0/0x07da") != nullptr);
        REQUIRE(store.get("tpz", "bay0/0x0640") != nullptr);
    }
    rigsim::StateStore reloaded(state_path);         // the daemon restarts on the same file
    AptHarness h({tpz(), tsg()}, &reloaded);
    CHECK(h.send(kReqMode) == kModeClosed);
    CHECK(reloaded.get("tpz", "bay0/0x0640") != nullptr);
    CHECK(reloaded.get("tpz", "bay0/0x07d4") != nullptr);
    CHECK(reloaded.get("tsg", "bay0/0x07da") != nullptr);
}

TEST_CASE("apt TPZ001 closed loop: when its TSG001 switches its hub output away 5 s and back it resumes "
          "without a jump",
          "[device][apt][piezo][gauge]")
{
    AptHarness h(tpz());
    h.add_device(tsg());
    h.send(kClosedLoop);
    REQUIRE(h.send(kReqMode) == kModeClosed);
    h.send("46 06 04 00 D0 01 01 00 66 26");   // 30 % (p.97)
    h.advance_ms(1000);
    REQUIRE(extension_um(h) == Approx(0.3 * kTravelUm).margin(0.02));
    h.send(kTsgOutput2, 1);                    // the reader's signal goes to hub B: the loop holds
    h.send("46 06 04 00 D0 01 01 00 CC 4C");   // 60 %, taken in closed loop
    h.advance_ms(5000);
    const double before_v = output_v(h);
    CHECK(extension_um(h) == Approx(0.3 * kTravelUm).margin(0.02));
    h.send(kTsgOutput1, 1);                    // and back
    h.advance_ms(1);
    // As through TPZ_IOSETTINGS (test_apt_gauge_state.cpp): one 1 ms tick of the 4 kHz loop
    // moves the output about 1.35 V, not the 5 s of integration.
    const double step_v = output_v(h) - before_v;
    INFO("first tick's output change " << step_v << " V");
    CHECK(std::abs(step_v) < 2.0);
    h.advance_ms(2000);
    CHECK(extension_um(h) == Approx(0.6 * kTravelUm).margin(0.02));
}

} // namespace test_apt_gauge_order
