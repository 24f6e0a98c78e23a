// The rig keys of the solenoid, piezo and strain gauge units (docs/config.md): every key has
// a default, every refusal names its JSON pointer; the daemon refuses to run the piezo and
// strain gauge units until their modules exist.
#include "emulator/apt/config.hpp"
#include "emulator/core/device.hpp"
#include "emulator/core/family_registry.hpp"
#include "emulator/daemon/rig_families.hpp"
#include "emulator/core/state_store.hpp"
#include "models/clock.hpp"
#include "models/world.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <spdlog/sinks/null_sink.h>
#include <spdlog/spdlog.h>

#include <string>

namespace test_apt_config {

namespace {

using nlohmann::json;
using rigsim::apt::config_of;

json unit(const std::string& name, const std::string& model, json apt)
{
    return {{"name", name}, {"protocol", "apt"}, {"model", model}, {"apt", std::move(apt)}};
}

/// A rig of `devices` (an initializer list, so that one device still makes an array: a json
/// built from `{device}` is that object under clang, an array of it under GCC).
json rig_of(std::initializer_list<json> devices)
{
    json list = json::array();
    for (const auto& device : devices)
        list.push_back(device);
    return {{"devices", list}};
}

std::string error_of(const json& rig)
{
    try {
        rigsim::parse_rig_config(rig.dump(), "rig.json");
    } catch (const rigsim::ConfigError& e) {
        return e.what();
    }
    return "(no error)";
}

/// The "apt" section of a one-device rig.
rigsim::apt::AptConfig apt_of(const std::string& model, json apt)
{
    return config_of(rigsim::parse_rig_config(rig_of({unit("u", model, std::move(apt))}).dump(), "rig.json").devices[0]);
}

} // namespace

TEST_CASE("apt config: every key of the solenoid, piezo and gauge units has its default", "[unit][apt][config]")
{
    for (const char* model : {"TSC001", "KSC101"})
        CHECK(apt_of(model, json::object()).solenoid.interlock_fitted);
    for (const char* model : {"TPZ001", "KPZ101"}) {
        const auto a = apt_of(model, json::object()).actuator;
        CHECK(a.travel_um == 20.0);
        CHECK(a.max_voltage_v == 75);
        CHECK(a.response_ms == 1.0);
        CHECK(a.hysteresis == 0.05);
        CHECK(a.creep == 0.01);
        CHECK(apt_of(model, {{"actuator", json::object()}}).actuator.travel_um == 20.0);
    }
    CHECK(apt_of("BPC301", json::object()).piezo_bays.size() == 1);
    const auto bpc = apt_of("BPC303", json::object());
    CHECK(bpc.hardware_max_voltage_v == 150);
    REQUIRE(bpc.piezo_bays.size() == 3);
    CHECK(bpc.piezo_bays[2].actuator.max_voltage_v == 75);
    CHECK_FALSE(bpc.piezo_bays[2].strain_gauge);
    CHECK(bpc.piezo_bays[2].zero_time_ms == 2000);
    for (const char* model : {"TSG001", "KSG101"}) {
        const auto g = apt_of(model, {{"gauge", json::object()}}).gauge;
        CHECK(g.mounted_on.empty());
        CHECK(g.route == rigsim::apt::GaugeRoute::HubA);
        CHECK(g.noise_um == 0.002);
        CHECK(g.seed == 1);
        CHECK(g.stiffness_n_per_um == 1.0);
        CHECK(g.zero_time_ms == 2000);
    }
    CHECK(apt_of("TSG001", json::object()).serial_number == 0);
}

TEST_CASE("apt config: every key of the solenoid, piezo and gauge units is read", "[unit][apt][config]")
{
    CHECK_FALSE(apt_of("TSC001", {{"solenoid", {{"interlock_fitted", false}}}, {"serial_number", 85000007}})
                    .solenoid.interlock_fitted);
    const auto tpz = apt_of("KPZ101", {{"actuator",
                                            {{"travel_um", 6553.5},
                                             {"max_voltage_v", 150},
                                             {"response_ms", 0.1},
                                             {"hysteresis", 0.3},
                                             {"creep", 0}}},
                                           {"serial_number", 29000002}});
    CHECK(tpz.actuator.travel_um == 6553.5);
    CHECK(tpz.actuator.max_voltage_v == 150);
    CHECK(tpz.actuator.response_ms == 0.1);
    CHECK(tpz.actuator.hysteresis == 0.3);
    CHECK(tpz.actuator.creep == 0.0);
    CHECK(tpz.serial_number == 29000002);
    const auto bpc = apt_of("BPC303", {{"hardware_max_voltage_v", 100},
                                           {"bays", {json::object(), {{"travel_um", 0.1}, {"max_voltage_v", 100},
                                                                      {"strain_gauge", true}, {"zero_time_ms", 0}}}},
                                           {"serial_number", 71281854}});
    CHECK(bpc.hardware_max_voltage_v == 100);
    REQUIRE(bpc.piezo_bays.size() == 2);
    CHECK(bpc.piezo_bays[1].actuator.travel_um == 0.1);
    CHECK(bpc.piezo_bays[1].strain_gauge);
    CHECK(bpc.piezo_bays[1].zero_time_ms == 0);

    // A gauge may come before its piezo in the file (the check runs once every device is read).
    const auto rig = rigsim::parse_rig_config(
        rig_of({unit("g", "KSG101",
                     {{"gauge",
                       {{"mounted_on", "p"}, {"route", "sma"}, {"noise_um", 1}, {"seed", 4294967295LL},
                        {"stiffness_n_per_um", 1e6}, {"zero_time_ms", 60000}}}}),
                unit("p", "TPZ001", json::object())})
            .dump(),
        "rig.json");
    const auto& g = config_of(rig.devices[0]).gauge;
    CHECK(g.mounted_on == "p");
    CHECK(g.route == rigsim::apt::GaugeRoute::Sma);
    CHECK(g.noise_um == 1.0);
    CHECK(g.seed == 4294967295u);
    CHECK(g.stiffness_n_per_um == 1e6);
    CHECK(g.zero_time_ms == 60000);
}

TEST_CASE("apt config: each refusal of the new unit keys names its pointer", "[unit][apt][config]")
{
    struct Row {
        const char* model;
        json apt;
        std::string error;   // after "rig.json: /devices/0/apt"
    };
    const Row rows[]{
        // Keys of another kind of unit.
        {"TPZ001", {{"stage", "MTS50-Z8"}}, "/stage: TPZ001 is a piezo controller: its keys are actuator, serial_number, eeprom"},
        {"TDC001", {{"actuator", json::object()}},
         "/actuator: TDC001 is a motor controller: its keys are stage, bays, serial_number, eeprom"},
        {"BBD203", {{"hardware_max_voltage_v", 150}, {"bays", {"MLS203-X"}}},
         "/hardware_max_voltage_v: BBD203 is a motor rack: its keys are stage, bays, serial_number, eeprom"},
        {"TSC001", {{"gauge", json::object()}}, "/gauge: TSC001 is a solenoid controller: its keys are solenoid, serial_number, eeprom"},
        {"BPC303", {{"actuator", json::object()}},
         "/actuator: BPC303 is a piezo rack: its keys are hardware_max_voltage_v, bays, serial_number"},
        {"KSG101", {{"solenoid", json::object()}}, "/solenoid: KSG101 is a strain gauge reader: its keys are gauge, serial_number, eeprom"},
        {"TPZ001", {{"colour", 1}}, ": unknown key \"colour\" (allowed: actuator, serial_number, eeprom)"},
        // Solenoid.
        {"KSC101", {{"solenoid", {{"interlock_fitted", 1}}}}, "/solenoid/interlock_fitted: expected true or false, got 1"},
        {"KSC101", {{"solenoid", {{"interlock", true}}}}, "/solenoid: unknown key \"interlock\" (allowed: interlock_fitted)"},
        // Actuator ranges.
        {"TPZ001", {{"actuator", {{"travel_mm", 1}}}},
         "/actuator: unknown key \"travel_mm\" (allowed: travel_um, max_voltage_v, response_ms, hysteresis, creep)"},
        {"TPZ001", {{"actuator", {{"travel_um", 0.05}}}}, "/actuator/travel_um: expected a number 0.1..6553.5, got 0.05"},
        {"TPZ001", {{"actuator", {{"travel_um", 6553.6}}}}, "/actuator/travel_um: expected a number 0.1..6553.5, got 6553.6"},
        {"TPZ001", {{"actuator", {{"max_voltage_v", 120}}}}, "/actuator/max_voltage_v: expected 75, 100 or 150, got 120"},
        {"TPZ001", {{"actuator", {{"max_voltage_v", 75.0}}}}, "/actuator/max_voltage_v: expected 75, 100 or 150, got 75.0"},
        {"KPZ101", {{"actuator", {{"response_ms", 0}}}}, "/actuator/response_ms: expected a number 0.1..1000, got 0"},
        {"KPZ101", {{"actuator", {{"hysteresis", 0.31}}}}, "/actuator/hysteresis: expected a number 0..0.3, got 0.31"},
        {"KPZ101", {{"actuator", {{"creep", true}}}}, "/actuator/creep: expected a number 0..0.05, got true"},
        // BPC bays: count per model, hardware maximum.
        {"BPC301", {{"bays", {json::object(), json::object()}}}, "/bays: expected an array of 1 bay, got an array of 2 elements"},
        {"BPC303", {{"bays", json::array()}}, "/bays: expected an array of 1..3 bays, got []"},
        {"BPC303", {{"bays", {json::object(), json::object(), json::object(), json::object()}}},
         "/bays: expected an array of 1..3 bays, got an array of 4 elements"},
        {"BPC303", {{"hardware_max_voltage_v", 200}}, "/hardware_max_voltage_v: expected 75, 100 or 150, got 200"},
        {"BPC303", {{"hardware_max_voltage_v", 100}, {"bays", {json::object(), {{"max_voltage_v", 150}}}}},
         "/bays/1/max_voltage_v: expected at most the rack's hardware_max_voltage_v (100), got 150"},
        {"BPC303", {{"bays", {{{"strain_gauge", "yes"}}}}}, "/bays/0/strain_gauge: expected true or false, got \"yes\""},
        {"BPC303", {{"bays", {{{"zero_time_ms", 60001}}}}}, "/bays/0/zero_time_ms: expected an integer 0..60000, got 60001"},
        {"BPC303", {{"bays", {{{"stage", "DRV001"}}}}},
         "/bays/0: unknown key \"stage\" (allowed: travel_um, max_voltage_v, response_ms, hysteresis, creep, "
         "strain_gauge, zero_time_ms)"},
        // Gauge.
        {"TSG001", {{"gauge", {{"mounted_on", ""}}}},
         "/gauge/mounted_on: expected the name of a TPZ001 or KPZ101 device, got \"\""},
        {"TSG001", {{"gauge", {{"route", "hub_c"}}}}, "/gauge/route: expected \"hub_a\", \"hub_b\" or \"sma\", got \"hub_c\""},
        {"TSG001", {{"gauge", {{"noise_um", 1.5}}}}, "/gauge/noise_um: expected a number 0..1, got 1.5"},
        {"TSG001", {{"gauge", {{"seed", -1}}}}, "/gauge/seed: expected an integer 0..4294967295, got -1"},
        {"TSG001", {{"gauge", {{"stiffness_n_per_um", 0}}}},
         "/gauge/stiffness_n_per_um: expected a number > 0 and <= 1000000, got 0"},
        {"TSG001", {{"gauge", {{"zero_time_ms", -1}}}}, "/gauge/zero_time_ms: expected an integer 0..60000, got -1"},
        // The unit's EEPROM: state file entries (the device checks the rest at power-up).
        {"TDC001", {{"eeprom", 1}}, "/eeprom: expected an object of \"bay<N>/0x<id>\": \"<hex data>\" entries, got 1"},
        {"TDC001", {{"eeprom", {{"bay0/0x413", "00"}}}},
         "/eeprom/bay0~10x413: expected a key bay<N>/0x<4 lower-case hex digits> (a state file's), got \"bay0/0x413\""},
        {"TDC001", {{"eeprom", {{"bay0/0x0413", 5}}}}, "/eeprom/bay0~10x0413: expected a string of hex digits, got 5"},
        {"TDC001", {{"eeprom", {{"bay0/0x0413", "0g"}}}}, "/eeprom/bay0~10x0413: data is not hex (character 2 is 'g')"},
        {"BPC303", {{"eeprom", json::object()}},
         "/eeprom: BPC303 is a piezo rack: its keys are hardware_max_voltage_v, bays, serial_number"},
        // Serial numbers keep the model's prefix (D-1).
        {"TPZ001", {{"serial_number", 29000001}},
         "/serial_number: expected an integer 81000000..81999999 (the model's serial prefix), got 29000001"},
        {"BPC301", {{"serial_number", 71000001}},
         "/serial_number: expected an integer 41000000..41999999 (the model's serial prefix), got 71000001"},
    };
    for (const auto& row : rows) {
        INFO(row.model << " " << row.apt.dump());
        CHECK(error_of(rig_of({unit("u", row.model, row.apt)})) == "rig.json: /devices/0/apt" + row.error);
    }
}

TEST_CASE("apt config: a gauge is mounted on a TPZ001 or KPZ101 of the rig, one gauge per piezo",
          "[unit][apt][config]")
{
    const auto gauge = [](const char* name, const char* piezo) {
        return unit(name, "TSG001", {{"gauge", {{"mounted_on", piezo}}}});
    };
    const std::string at = "rig.json: /devices/1/apt/gauge/mounted_on: ";
    CHECK(error_of(rig_of({unit("p", "TPZ001", json::object()), gauge("g", "nope")})) ==
          at + "no device named \"nope\" in the rig");
    CHECK(error_of(rig_of({unit("b", "BPC303", json::object()), gauge("g", "b")})) ==
          at + "device \"b\" (BPC303) is not a piezo controller (TPZ001, KPZ101)");
    CHECK(error_of(rig_of({unit("p", "TPZ001", json::object()), gauge("g", "g")})) ==
          at + "device \"g\" (TSG001) is not a piezo controller (TPZ001, KPZ101)");
    CHECK(error_of(rig_of({{{"name", "m"}, {"protocol", "mcs"}, {"mcs", {{"channels", {json::object()}}}}},
                           gauge("g", "m")})) == at + "device \"m\" (MCS-3D) is not a piezo controller (TPZ001, KPZ101)");
    CHECK(error_of(rig_of({unit("p", "KPZ101", json::object()), gauge("g1", "p"), gauge("g2", "p")})) ==
          "rig.json: /devices/2/apt/gauge/mounted_on: device \"p\" already has a gauge: /devices/1");
    CHECK(error_of(rig_of({unit("p", "KPZ101", json::object()), unit("q", "TPZ001", json::object()), gauge("g1", "p"),
                           gauge("g2", "q")})) == "(no error)");
}

TEST_CASE("apt config: the daemon runs every APT unit kind: motor, solenoid, piezo and strain gauge units",
          "[unit][apt][config]")
{
    const auto rig = rigsim::parse_rig_config(
        rig_of({unit("m", "TDC001", json::object()), unit("s", "TSC001", json::object()),
                unit("p", "BPC303", json::object()), unit("g", "KSG101", json::object()),
                unit("t", "TPZ001", json::object()),
                unit("tsg", "TSG001", {{"gauge", {{"mounted_on", "t"}}}})})
            .dump(),
        "rig.json");
    rigsim::Clock clock(1000);
    rigsim::models::World world(clock);
    rigsim::StateStore store;
    const rigsim::DeviceContext context{world, std::make_shared<spdlog::logger>("t", std::make_shared<spdlog::sinks::null_sink_st>()),
                                        store};
    const auto& apt = *rigsim::rig_families().find("apt");
    // Once refused with "... is a piezo unit: its keys are valid, but rigsim does not emulate
    // piezo units yet" (and the same for strain gauge units).
    for (const auto& device : rig.devices)
        CHECK(apt.make(device, context) != nullptr);
    world.link_all();   // the TSG001's gauge finds the TPZ001's actuator
}

} // namespace test_apt_config
