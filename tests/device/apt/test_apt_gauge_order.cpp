// A TPZ001 and the TSG001 reading its actuator, when the reader itself moves the signal
// (TSG_IOSETTINGS HubAnalogueOutput, p.127): at power-up the reader restores its hub output
// before the driver replays its saved closed loop, whichever the rig lists first; a closed
// loop whose reader switched its output away and back resumes without a jump (p.94, p.115).
#include "apt_harness.hpp"

#include "models/piezo_actuator.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace test_apt_gauge_order {

using namespace rigsim::test;

constexpr double kTravelUm = 20;

/// A TPZ001 "tpz": a 20 um, 75 V actuator without creep or hysteresis.
rigsim::DeviceConfig tpz()
{
    rigsim::DeviceConfig c;
    c.name = "tpz";
    c.protocol = "apt";
    c.model = "TPZ001";
    auto& a = config_of(c).actuator;
    a.travel_um = kTravelUm;
    a.max_voltage_v = 75;
    a.creep = 0;
    a.hysteresis = 0;
    a.response_ms = 1;
    return c;
}

/// A TSG001 "tsg" whose noiseless gauge is mounted on "tpz", cabled to hub channel A.
rigsim::DeviceConfig tsg()
{
    rigsim::DeviceConfig c;
    c.name = "tsg";
    c.protocol = "apt";
    c.model = "TSG001";
    auto& g = config_of(c).gauge;
    g.mounted_on = "tpz";
    g.route = GaugeRoute::HubA;
    g.noise_um = 0;
    return c;
}

/// A state file in a fresh directory, removed with its directory at the end.
class StateFile {
public:
    StateFile()
    {
        char dir_template[] = "/tmp/rigsim-gauge-order-XXXXXX";
        REQUIRE(::mkdtemp(dir_template));
        dir_ = dir_template;
        path_ = dir_ + "/state.json";
    }
    ~StateFile()
    {
        std::remove(path_.c_str());
        ::rmdir(dir_.c_str());
    }
    const std::string& path() const { return path_; }

private:
    std::string dir_;
    std::string path_;
};

constexpr const char* kClosedLoop = "40 06 01 02 50 01";          // PZ_SET_POSCONTROLMODE 2 (p.94)
constexpr const char* kReqMode = "41 06 01 00 50 01";
constexpr const char* kModeClosed = "42 06 01 02 01 50";
constexpr const char* kTpzInput2 = "D4 07 0A 00 D0 01 01 00 01 00 02 00 00 00 00 00";   // 75 V, hub B (p.115)
constexpr const char* kTsgOutput1 = "DA 07 0E 00 D0 01 01 00 01 00 01 00 30 75 00 00 00 00 00 00";   // p.127
constexpr const char* kTsgOutput2 = "DA 07 0E 00 D0 01 01 00 02 00 01 00 30 75 00 00 00 00 00 00";

/// PZ_GET_OUTPUTVOLTS of the TPZ in volts of the 75 V limit (p.96).
double output_v(AptHarness& h)
{
    const auto b = bytes(h.send("44 06 01 00 50 01"));
    REQUIRE(b.size() == 10);
    return static_cast<std::int16_t>(get_u16(b, 8)) / 32767.0 * 75.0;
}

double extension_um(AptHarness& h)
{
    auto* a = h.world().find_as<rigsim::models::PiezoActuator>("tpz/1");
    REQUIRE(a != nullptr);
    return a->extension_um();
}

TEST_CASE("apt gauge order: a TPZ001 listed before its TSG001 replays its closed loop on the reader's saved hub "
          "output, both entries kept",
          "[device][apt][gauge][eeprom]")
{
    StateFile file;
    {
        rigsim::StateStore store(file.path());
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
    rigsim::StateStore reloaded(file.path());         // the daemon restarts on the same file
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
