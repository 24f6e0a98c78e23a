// The "mcs2" section of the rig JSON (docs/config.md): defaults, and each bad value named by its
// JSON pointer.

#include "emulator/daemon/rig_families.hpp"
#include "emulator/mcs2/device.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <string>

namespace test_mcs2_config {

using nlohmann::json;

namespace {

json rig()
{
    return json::parse(R"({"devices": [{"name": "m2", "protocol": "mcs2", "mcs2": {"channels": [{}]}}]})");
}

std::string error_of(const json& r)
{
    try {
        rigsim::parse_rig_config(r.dump(), "rig.json");
    } catch (const rigsim::ConfigError& e) {
        return e.what();
    }
    return "(no error)";
}

} // namespace

TEST_CASE("mcs2 config: defaults: model MCS2, firmware current, serial MCS2-00001234, type 300", "[unit][mcs2][config]")
{
    const auto config = rigsim::parse_rig_config(rig().dump(), "rig.json");
    const auto& d = config.devices.at(0);
    CHECK(d.model == "MCS2");
    CHECK(d.firmware == "current");
    const auto& s = rigsim::mcs2::config_of(d);
    CHECK(s.firmware == rigsim::mcs2::Firmware::Current);
    CHECK(s.serial_number == "MCS2-00001234");
    REQUIRE(s.channels.size() == 1);
    CHECK(s.channels[0].positioner_type == 300);
    CHECK(!s.channels[0].travel_min);
}

TEST_CASE("mcs2 config: bad values are named by their JSON pointer", "[unit][mcs2][config]")
{
    auto r = rig();
    r["devices"][0]["firmware"] = "2.0";
    CHECK(error_of(r) == "rig.json: /devices/0/firmware: unknown MCS2 firmware generation \"2.0\" (expected \"1.0.6\" or \"current\")");
    r = rig();
    r["devices"][0]["firmware"] = "1.0.6";
    CHECK(error_of(r) == "(no error)");
    r = rig();
    r["devices"][0]["mcs2"]["channels"][0]["positioner_type"] = 305;
    CHECK(error_of(r).find("rig.json: /devices/0/mcs2/channels/0/positioner_type: unknown positioner type 305 (expected one of 300, 301,") == 0);
    r = rig();
    r["devices"][0]["mcs2"]["channels"][0]["travel"] = json::array({5, 5});
    CHECK(error_of(r) == "rig.json: /devices/0/mcs2/channels/0/travel: expected min < max, got [5,5]");
    r = rig();
    r["devices"][0]["mcs2"]["channels"][0]["travel"] = json::array({0, 100});
    r["devices"][0]["mcs2"]["channels"][0]["start_position"] = 200;
    CHECK(error_of(r) == "rig.json: /devices/0/mcs2/channels/0/start_position: expected a position within \"travel\", got 200");
    r = rig();
    r["devices"][0]["mcs2"]["channels"] = json::array();
    CHECK(error_of(r) == "rig.json: /devices/0/mcs2/channels: expected an array of 1..24 channels, got 0 channels");
    r = rig();
    r["devices"][0]["mcs2"]["colour"] = 1;
    CHECK(error_of(r).find("rig.json: /devices/0/mcs2: unknown key \"colour\"") == 0);
    r = rig();
    r["devices"][0]["mcs2"]["serial_number"] = "a\"b";
    CHECK(error_of(r).find("rig.json: /devices/0/mcs2/serial_number: expected printable ASCII without quotes") == 0);
    r = rig();
    r["devices"][0]["mcs2"]["channels"][0]["sensor"] = 1;
    CHECK(error_of(r) == "rig.json: /devices/0/mcs2/channels/0/sensor: expected true or false, got 1");
    r = rig();
    r["devices"][0].erase("mcs2");
    CHECK(error_of(r) == "rig.json: /devices/0/mcs2: required key missing");
}

} // namespace test_mcs2_config
