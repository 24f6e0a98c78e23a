#pragma once
// A TPZ001 "tpz" and the TSG001 "tsg" whose gauge is mounted on its actuator, and the messages
// the gauge-pair device tests send (manual p.94, p.115, p.127): shared by test_apt_gauge_state
// and test_apt_gauge_order.

#include "apt_harness.hpp"

#include "models/piezo_actuator.hpp"

#include <catch2/catch.hpp>

namespace rigsim::test::gauge_pair {

inline constexpr double kTravelUm = 20;

/// A TPZ001 "tpz": a 20 um, 75 V actuator without creep or hysteresis.
inline rigsim::DeviceConfig tpz()
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

/// A TSG001 "tsg" whose noiseless gauge is mounted on "tpz", cabled as `route`.
inline rigsim::DeviceConfig tsg(GaugeRoute route = GaugeRoute::HubA)
{
    rigsim::DeviceConfig c;
    c.name = "tsg";
    c.protocol = "apt";
    c.model = "TSG001";
    auto& g = config_of(c).gauge;
    g.mounted_on = "tpz";
    g.route = route;
    g.noise_um = 0;
    return c;
}

/// The physical extension of the "tpz" actuator, read from the world.
inline double extension_um(AptHarness& h)
{
    auto* a = h.world().find_as<rigsim::models::PiezoActuator>("tpz/1");
    REQUIRE(a != nullptr);
    return a->extension_um();
}

inline constexpr const char* kClosedLoop = "40 06 01 02 50 01";   // PZ_SET_POSCONTROLMODE 2 (p.94)
inline constexpr const char* kReqMode = "41 06 01 00 50 01";
inline constexpr const char* kModeClosed = "42 06 01 02 01 50";
inline constexpr const char* kTpzInput2 = "D4 07 0A 00 D0 01 01 00 01 00 02 00 00 00 00 00";   // 75 V, hub B (p.115)
inline constexpr const char* kTsgOutput1 = "DA 07 0E 00 D0 01 01 00 01 00 01 00 30 75 00 00 00 00 00 00";   // p.127
inline constexpr const char* kTsgOutput2 = "DA 07 0E 00 D0 01 01 00 02 00 01 00 30 75 00 00 00 00 00 00";

} // namespace rigsim::test::gauge_pair
