// The rig JSON's "control" object and the endpoints document's "control" URL.
#include "emulator/daemon/rig.hpp"
#include "emulator/daemon/rig_families.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <string>

namespace test_control_config {

using nlohmann::json;
using rigsim::ConfigError;
using rigsim::parse_rig_config;

namespace {

/// The smallest valid rig, with `control` as its "control" value unless null.
std::string rig_with_control(const json& control)
{
    auto rig = json::parse(R"({"devices": [{"name": "mcs0", "protocol": "mcs", "mcs": {"channels": [{}]}}]})");
    if (!control.is_null())
        rig["control"] = control;
    return rig.dump();
}

std::string error_of(const json& control)
{
    try {
        parse_rig_config(rig_with_control(control), "rig.json");
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "(no error)";
}

} // namespace

TEST_CASE("rig config: control is off unless the rig has a control object", "[unit][config][control]")
{
    CHECK_FALSE(parse_rig_config(rig_with_control(nullptr), "rig.json").control);
    const auto rig = parse_rig_config(rig_with_control(json{{"port", 40200}}), "rig.json");
    REQUIRE(rig.control);
    CHECK(rig.control->port == 40200);
    CHECK(parse_rig_config(rig_with_control(json{{"port", 0}}), "rig.json").control->port == 0);
}

TEST_CASE("rig config: a bad control object names the pointer", "[unit][config][control]")
{
    CHECK(error_of(json{{"port", 40200}, {"bind", "0.0.0.0"}})
          == "rig.json: /control: unknown key \"bind\" (allowed: port)");
    CHECK(error_of(json::object()) == "rig.json: /control/port: required key missing");
    CHECK(error_of(json{{"port", 65536}}).rfind("rig.json: /control/port: expected an integer 0..65535", 0) == 0);
    CHECK(error_of(json{{"port", -1}}).rfind("rig.json: /control/port: expected an integer 0..65535", 0) == 0);
    CHECK(error_of(json{{"port", "80"}}).rfind("rig.json: /control/port:", 0) == 0);
    CHECK(error_of(json(40200)).rfind("rig.json: /control: expected an object", 0) == 0);
}

TEST_CASE("endpoints json: control appears only when the control API is on", "[unit][control]")
{
    const std::vector<rigsim::DeviceEndpoints> devices{{"mcs0", "mcs", "MCS-3D", "127.0.0.1:40100", "/tmp/x/mcs0", "1.2.44", ""}};
    const auto off = json::parse(rigsim::endpoints_json(devices));
    CHECK(off == json{{"devices", json::array({json{{"name", "mcs0"}, {"protocol", "mcs"}, {"model", "MCS-3D"},
                                                      {"tcp", "127.0.0.1:40100"}, {"pty", "/tmp/x/mcs0"}}})}});
    const auto on = json::parse(rigsim::endpoints_json(devices, "http://127.0.0.1:40200"));
    CHECK(on["control"] == "http://127.0.0.1:40200");
    CHECK(on["devices"] == off["devices"]);
    // An RFC 2217 endpoint is listed beside the others, only where there is one.
    const std::vector<rigsim::DeviceEndpoints> with{{"a", "apt", "KDC101", "127.0.0.1:1", "/tmp/x/a", "issue-3", "127.0.0.1:2"},
                                                    {"b", "mcs", "MCS-3D", "127.0.0.1:3", "/tmp/x/b", "1.2.44", ""}};
    const auto listed = json::parse(rigsim::endpoints_json(with));
    CHECK(listed["devices"][0]["rfc2217"] == "127.0.0.1:2");
    CHECK_FALSE(listed["devices"][1].contains("rfc2217"));
}

namespace {

/// The smallest valid rig with `clock` as its "clock" value.
std::string rig_with_clock(const json& clock)
{
    auto rig = json::parse(R"({"devices": [{"name": "mcs0", "protocol": "mcs", "mcs": {"channels": [{}]}}]})");
    rig["clock"] = clock;
    return rig.dump();
}

std::string clock_error_of(const json& clock)
{
    try {
        parse_rig_config(rig_with_clock(clock), "rig.json");
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "(no error)";
}

} // namespace

TEST_CASE("rig config: the clock's start mode, real time unless the rig says otherwise", "[unit][config][control]")
{
    const auto plain = parse_rig_config(rig_with_control(nullptr), "rig.json");
    CHECK(plain.clock.time_scale == 1.0);
    CHECK_FALSE(plain.clock.paused);
    const auto set = parse_rig_config(rig_with_clock(json{{"time_scale", 10}, {"paused", true}}), "rig.json");
    CHECK(set.clock.time_scale == 10.0);
    CHECK(set.clock.paused);
    CHECK(clock_error_of(json{{"time_scale", 0}}) == "rig.json: /clock/time_scale: expected a number 0.001..1000, got 0");
    CHECK(clock_error_of(json{{"paused", "yes"}}) == "rig.json: /clock/paused: expected true or false, got \"yes\"");
    CHECK(clock_error_of(json{{"mode", "fast"}}) == "rig.json: /clock: unknown key \"mode\" (allowed: time_scale, paused)");
}

} // namespace test_control_config
