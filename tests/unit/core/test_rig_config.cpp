#include "emulator/apt/config.hpp"
#include "emulator/daemon/rig_families.hpp"
#include "emulator/mcs/config.hpp"
#include "emulator/mcs2/device.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <iterator>
#include <string>
#include <string_view>

namespace test_rig_config {

using nlohmann::json;
using rigsim::ConfigError;
using rigsim::parse_rig_config;

namespace {

/// The smallest valid rig: one MCS device with one all-default channel.
json minimal_rig()
{
    return json::parse(
        R"({"devices": [{"name": "mcs0", "protocol": "mcs", "mcs": {"channels": [{}]}}]})");
}

/// A valid device named `name`, to append to minimal_rig()["devices"].
json device(const std::string& name)
{
    auto d = minimal_rig()["devices"][0];
    d["name"] = name;
    return d;
}

/// The ConfigError message for `text` named "rig.json", or "(no error)".
std::string error_of_text(std::string_view text)
{
    try {
        parse_rig_config(text, "rig.json");
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "(no error)";
}

/// The ConfigError message for the document `rig`, or "(no error)".
std::string error_of(const json& rig)
{
    return error_of_text(rig.dump());
}

const std::string kDeviceKeys = "(allowed: name, protocol, model, firmware, tcp_port, pty, faithful_timing, link, rfc2217_port, mcs, apt, mcs2)";

} // namespace

TEST_CASE("rig config: a minimal rig gets every default", "[unit][config]")
{
    const auto rig = parse_rig_config(minimal_rig().dump(), "rig.json");
    CHECK(rig.tick_hz == 1000);
    REQUIRE(rig.devices.size() == 1);
    const auto& d = rig.devices[0];
    CHECK(d.name == "mcs0");
    CHECK(d.protocol == "mcs");
    CHECK(d.model == "MCS-3D");
    CHECK(d.tcp_port == 0);
    CHECK(d.pty.empty());
    CHECK(rigsim::mcs::config_of(d).system_id == 1000);
    REQUIRE(rigsim::mcs::config_of(d).channels.size() == 1);
    const auto& c = rigsim::mcs::config_of(d).channels[0];
    CHECK(c.sensor_type == "S");
    CHECK(c.travel_min_nm == -10'500'000);
    CHECK(c.travel_max_nm == 10'500'000);
    CHECK(c.start_position_nm == 0);
    CHECK(c.max_speed_nm_per_s == 10'000'000);
    CHECK(c.closed_loop_speed_nm_per_s == 0);
    CHECK(c.closed_loop_acceleration_um_per_s2 == 0);
}

TEST_CASE("rig config: every key is read", "[unit][config]")
{
    const auto rig = parse_rig_config(R"({
        "tick_hz": 100000,
        "devices": [{
            "name": "Stage_1.x-y",
            "protocol": "mcs",
            "model": "MCS-6D",
            "tcp_port": 65535,
            "pty": "/dev/ttyRIG0",
            "mcs": {
                "system_id": 4294967295,
                "channels": [
                    {"sensor_type": "none", "travel_nm": [-2000000000, 2000000000],
                     "start_position_nm": -2000000000, "max_speed_nm_per_s": 100000000,
                     "closed_loop_speed_nm_per_s": 100000000,
                     "closed_loop_acceleration_um_per_s2": 10000000},
                    {"sensor_type": "SR", "travel_nm": [0, 1], "start_position_nm": 1,
                     "max_speed_nm_per_s": 1}
                ]
            }
        }]
    })", "rig.json");
    CHECK(rig.tick_hz == 100000);
    REQUIRE(rig.devices.size() == 1);
    const auto& d = rig.devices[0];
    CHECK(d.name == "Stage_1.x-y");
    CHECK(d.model == "MCS-6D");
    CHECK(d.tcp_port == 65535);
    CHECK(d.pty == "/dev/ttyRIG0");
    CHECK(rigsim::mcs::config_of(d).system_id == 4294967295u);
    REQUIRE(rigsim::mcs::config_of(d).channels.size() == 2);
    const auto& c0 = rigsim::mcs::config_of(d).channels[0];
    CHECK(c0.sensor_type == "none");
    CHECK(c0.travel_min_nm == -2'000'000'000);
    CHECK(c0.travel_max_nm == 2'000'000'000);
    CHECK(c0.start_position_nm == -2'000'000'000);
    CHECK(c0.max_speed_nm_per_s == 100'000'000);
    CHECK(c0.closed_loop_speed_nm_per_s == 100'000'000);
    CHECK(c0.closed_loop_acceleration_um_per_s2 == 10'000'000);
    const auto& c1 = rigsim::mcs::config_of(d).channels[1];
    CHECK(c1.sensor_type == "SR");
    CHECK(c1.travel_min_nm == 0);
    CHECK(c1.travel_max_nm == 1);
    CHECK(c1.start_position_nm == 1);
    CHECK(c1.max_speed_nm_per_s == 1);
}

TEST_CASE("rig config: config/default.json is the showroom on fixed ports from 40100 and the MCS2 on 55551, control on 40200", "[unit][config]")
{
    const auto rig = rigsim::load_rig_config(RIGSIM_SOURCE_DIR "/config/default.json");
    // The control API on loopback at the port rigsimctl and the Python client ask by default
    // (python/rigsim/control.py DEFAULT_CONTROL), so the README's rig can be steered at once.
    REQUIRE(rig.control);
    CHECK(rig.control->port == 40200);
    REQUIRE(rig.devices.size() == 15);
    // The MCS2 on the unit's own port, 55551 (its drivers often have it fixed), three channels.
    CHECK(rig.devices[14].name == "mcs2");
    CHECK(rig.devices[14].protocol == "mcs2");
    CHECK(rig.devices[14].tcp_port == 55551);
    CHECK(rigsim::mcs2::config_of(rig.devices[14]).channels.size() == 3);
    const auto& d = rig.devices[0];
    CHECK(d.name == "mcs0");
    CHECK(d.protocol == "mcs");
    CHECK(d.tcp_port == 40100);
    CHECK(rigsim::mcs::config_of(d).channels.size() == 3);
    CHECK(rig.devices[1].model == "TDC001");
    CHECK(rig.devices[1].tcp_port == 40101);
    CHECK(rig.devices[2].model == "KDC101");
    CHECK(rig.devices[2].tcp_port == 40102);
    CHECK(rig.devices[3].model == "TST001");
    CHECK(rig.devices[4].model == "KST101");
    CHECK(rig.devices[5].model == "BSC203");
    CHECK(rigsim::apt::config_of(rig.devices[5]).bays.size() == 3);
    CHECK(rig.devices[6].model == "BBD203");
    CHECK(rigsim::apt::config_of(rig.devices[6]).bays.size() == 3);
    // Issue 12's units: each on its own port from 40107, serial <prefix>000001 (D-1 prefixes).
    struct Unit {
        const char* name;
        const char* model;
        int port;
        std::uint32_t serial;
    };
    const Unit units[] = {{"tsc001", "TSC001", 40107, 85000001}, {"ksc101", "KSC101", 40108, 68000001},
                          {"tpz001", "TPZ001", 40109, 81000001}, {"tsg001", "TSG001", 40110, 84000001},
                          {"kpz101", "KPZ101", 40111, 29000001}, {"ksg101", "KSG101", 40112, 59000001},
                          {"bpc303", "BPC303", 40113, 71000001}};
    for (std::size_t k = 0; k < std::size(units); ++k) {
        const auto& dev = rig.devices[7 + k];
        INFO(units[k].name);
        CHECK(dev.name == units[k].name);
        CHECK(dev.protocol == "apt");
        CHECK(dev.model == units[k].model);
        CHECK(dev.tcp_port == units[k].port);
        CHECK(dev.pty.empty());   // its own pty at <pty-dir>/<name>
        CHECK(rigsim::apt::config_of(dev).serial_number == units[k].serial);
    }
    // The gauge readers sit on the piezo drivers' actuators (closed loop possible), and every
    // BPC303 bay has a strain gauge.
    CHECK(rigsim::apt::config_of(rig.devices[10]).gauge.mounted_on == "tpz001");
    CHECK(rigsim::apt::config_of(rig.devices[12]).gauge.mounted_on == "kpz101");
    const auto& bpc = rigsim::apt::config_of(rig.devices[13]);
    REQUIRE(bpc.piezo_bays.size() == 3);
    for (const auto& bay : bpc.piezo_bays)
        CHECK(bay.strain_gauge);
}

TEST_CASE("rig config: an unreadable file names the path and the reason", "[unit][config]")
{
    const std::string missing = RIGSIM_SOURCE_DIR "/config/no-such-rig.json";
    CHECK_THROWS_WITH(rigsim::load_rig_config(missing),
                      missing + ": cannot read: No such file or directory");
    const std::string directory = RIGSIM_SOURCE_DIR "/config";
    CHECK_THROWS_WITH(rigsim::load_rig_config(directory),
                      directory + ": not a regular file (a directory): a rig is read from a JSON file");
}

TEST_CASE("rig config: a load error names the file", "[unit][config]")
{
    CHECK_THROWS_AS(parse_rig_config("{}", "x.json"), ConfigError);
    CHECK_THROWS_WITH(parse_rig_config("{}", "x.json"), "x.json: /devices: required key missing");
}

TEST_CASE("rig config: syntax errors give line and column", "[unit][config]")
{
    CHECK(error_of_text("{\"devices\": [\n  {\"name\": x}]}") ==
          "rig.json: line 2, column 12: syntax error while parsing value - invalid literal; "
          "last read: '\"name\": x'");
    CHECK(error_of_text("") ==
          "rig.json: line 1, column 1: syntax error while parsing value - unexpected end of input; "
          "expected '[', '{', or a literal");
    CHECK(error_of_text("{\n") ==
          "rig.json: line 2, column 1: syntax error while parsing object key - "
          "unexpected end of input; expected string literal");
    // A raw newline inside a string is reported where it is, not at column 0 of the next line.
    CHECK(error_of_text("{\"a\": \"x\ny\"}") ==
          "rig.json: line 1, column 9: syntax error while parsing value - invalid string: control "
          "character U+000A (LF) must be escaped to \\u000A or \\n; last read: '\"x<U+000A>'");
    // Comments are not JSON.
    CHECK(error_of_text("// rig\n{}").rfind("rig.json: line 1, column 1: syntax error", 0) == 0);
}

TEST_CASE("rig config: duplicate keys are errors at the object holding them", "[unit][config]")
{
    CHECK(error_of_text(R"({"tick_hz": 1, "tick_hz": 2})") ==
          "rig.json: /: duplicate key \"tick_hz\"");
    CHECK(error_of_text(R"({"devices": [{"name": "a"}, {"name": "b", "name": "c"}]})") ==
          "rig.json: /devices/1: duplicate key \"name\"");
    CHECK(error_of_text(
              R"({"devices": [[], {"mcs": {"channels": [1, {"travel_nm": [], "travel_nm": []}]}}]})") ==
          "rig.json: /devices/1/mcs/channels/1: duplicate key \"travel_nm\"");
    // RFC 6901: "~" is written "~0" and "/" is written "~1".
    CHECK(error_of_text(R"({"a/b~c": {"x": 1, "x": 2}})") ==
          "rig.json: /a~1b~0c: duplicate key \"x\"");
}

TEST_CASE("rig config: unknown keys are errors at the object holding them", "[unit][config]")
{
    auto rig = minimal_rig();
    SECTION("top level")
    {
        rig["tickhz"] = 1000;
        CHECK(error_of(rig) == "rig.json: /: unknown key \"tickhz\" (allowed: tick_hz, devices, control, clock, kinematics)");
    }
    SECTION("device")
    {
        rig["devices"][0]["colour"] = "red";
        CHECK(error_of(rig) == "rig.json: /devices/0: unknown key \"colour\" " + kDeviceKeys);
    }
    SECTION("mcs")
    {
        rig["devices"][0]["mcs"]["channel"] = json::array();
        CHECK(error_of(rig) ==
              "rig.json: /devices/0/mcs: unknown key \"channel\" (allowed: system_id, interface_version, channels)");
    }
    SECTION("channel")
    {
        rig["devices"][0]["mcs"]["channels"].push_back({{"travel", 1}});
        CHECK(error_of(rig) ==
              "rig.json: /devices/0/mcs/channels/1: unknown key \"travel\" (allowed: kind, "
              "gripper_contact_cv, gripper_stiffness_dun_per_cv, sensor_type, "
              "travel_nm, start_position_nm, max_speed_nm_per_s, closed_loop_speed_nm_per_s, "
              "closed_loop_acceleration_um_per_s2, travel_udeg, reference_position, "
                             "coded_mark_spacing, calibration_ms, step_width_nm, step_jitter_percent, "
                             "scan_range_nm, drift_nm_per_s)");
    }
    SECTION("a key needing escapes is quoted as JSON")
    {
        rig["devices"][0]["a\"b"] = 1;
        CHECK(error_of(rig) == "rig.json: /devices/0: unknown key \"a\\\"b\" " + kDeviceKeys);
    }
}

TEST_CASE("rig config: required keys missing name the key's pointer", "[unit][config]")
{
    auto rig = minimal_rig();
    SECTION("devices")
    {
        rig.erase("devices");
        CHECK(error_of(rig) == "rig.json: /devices: required key missing");
    }
    SECTION("name")
    {
        rig["devices"][0].erase("name");
        CHECK(error_of(rig) == "rig.json: /devices/0/name: required key missing");
    }
    SECTION("protocol")
    {
        rig["devices"][0].erase("protocol");
        CHECK(error_of(rig) == "rig.json: /devices/0/protocol: required key missing");
    }
    SECTION("mcs")
    {
        rig["devices"][0].erase("mcs");
        CHECK(error_of(rig) == "rig.json: /devices/0/mcs: required key missing");
    }
    SECTION("channels")
    {
        rig["devices"][0]["mcs"].erase("channels");
        CHECK(error_of(rig) == "rig.json: /devices/0/mcs/channels: required key missing");
    }
}

TEST_CASE("rig config: objects must be objects", "[unit][config]")
{
    CHECK(error_of_text("[]") == "rig.json: /: expected an object, got []");
    CHECK(error_of_text(R"({"devices": [42]})") ==
          "rig.json: /devices/0: expected an object, got 42");
    auto rig = minimal_rig();
    rig["devices"][0]["mcs"] = "MCS-3D";
    CHECK(error_of(rig) == "rig.json: /devices/0/mcs: expected an object, got \"MCS-3D\"");
    rig = minimal_rig();
    rig["devices"][0]["mcs"]["channels"][0] = json::array({1, 2});
    CHECK(error_of(rig) ==
          "rig.json: /devices/0/mcs/channels/0: expected an object, got an array of 2 elements");
}

TEST_CASE("rig config: devices must be a non-empty array", "[unit][config]")
{
    CHECK(error_of_text(R"({"devices": []})") == "rig.json: /devices: expected a non-empty array");
    CHECK(error_of_text(R"({"devices": {}})") ==
          "rig.json: /devices: expected a non-empty array, got {}");
    CHECK(error_of_text(R"({"devices": null})") ==
          "rig.json: /devices: expected a non-empty array, got null");
}

TEST_CASE("rig config: integers reject wrong types", "[unit][config]")
{
    auto rig = minimal_rig();
    const std::string expected =
        "rig.json: /devices/0/tcp_port: expected an integer 0..65535, got ";
    rig["devices"][0]["tcp_port"] = "abc";
    CHECK(error_of(rig) == expected + "\"abc\"");
    rig["devices"][0]["tcp_port"] = 1.5;
    CHECK(error_of(rig) == expected + "1.5");
    rig["devices"][0]["tcp_port"] = true;
    CHECK(error_of(rig) == expected + "true");
    rig["devices"][0]["tcp_port"] = nullptr;
    CHECK(error_of(rig) == expected + "null");
    rig["devices"][0]["tcp_port"] = json::object();
    CHECK(error_of(rig) == expected + "{}");
    // 1.0 is a float in JSON's grammar, and so is 1e3.
    CHECK(error_of_text(R"({"tick_hz": 1.0, "devices": []})") ==
          "rig.json: /tick_hz: expected an integer 1..100000, got 1.0");
    CHECK(error_of_text(R"({"tick_hz": 1e3, "devices": []})") ==
          "rig.json: /tick_hz: expected an integer 1..100000, got 1000.0");
}

TEST_CASE("rig config: integers reject values out of range", "[unit][config]")
{
    auto rig = minimal_rig();
    auto& dev = rig["devices"][0];
    auto& ch = dev["mcs"]["channels"][0];
    SECTION("tick_hz")
    {
        rig["tick_hz"] = 0;
        CHECK(error_of(rig) == "rig.json: /tick_hz: expected an integer 1..100000, got 0");
        rig["tick_hz"] = 100001;
        CHECK(error_of(rig) == "rig.json: /tick_hz: expected an integer 1..100000, got 100001");
    }
    SECTION("tcp_port")
    {
        dev["tcp_port"] = 70000;
        CHECK(error_of(rig) ==
              "rig.json: /devices/0/tcp_port: expected an integer 0..65535, got 70000");
        dev["tcp_port"] = -1;
        CHECK(error_of(rig) ==
              "rig.json: /devices/0/tcp_port: expected an integer 0..65535, got -1");
    }
    SECTION("system_id")
    {
        dev["mcs"]["system_id"] = 4294967296;
        CHECK(error_of(rig) ==
              "rig.json: /devices/0/mcs/system_id: "
              "expected an integer 0..4294967295, got 4294967296");
    }
    SECTION("integers beyond 64 bits")
    {
        CHECK(error_of_text(R"({"tick_hz": 18446744073709551615})") ==
              "rig.json: /tick_hz: expected an integer 1..100000, got 18446744073709551615");
        CHECK(error_of_text(R"({"tick_hz": -9223372036854775808})") ==
              "rig.json: /tick_hz: expected an integer 1..100000, got -9223372036854775808");
    }
    SECTION("channel speeds")
    {
        const std::string p = "rig.json: /devices/0/mcs/channels/0/";
        ch["max_speed_nm_per_s"] = 0;
        CHECK(error_of(rig) == p + "max_speed_nm_per_s: expected an integer 1..100000000, got 0");
        ch["max_speed_nm_per_s"] = 100000001;
        CHECK(error_of(rig) ==
              p + "max_speed_nm_per_s: expected an integer 1..100000000, got 100000001");
        ch.erase("max_speed_nm_per_s");
        ch["closed_loop_speed_nm_per_s"] = -1;
        CHECK(error_of(rig) ==
              p + "closed_loop_speed_nm_per_s: expected an integer 0..100000000, got -1");
        ch.erase("closed_loop_speed_nm_per_s");
        ch["closed_loop_acceleration_um_per_s2"] = 10000001;
        CHECK(error_of(rig) ==
              p + "closed_loop_acceleration_um_per_s2: "
                  "expected an integer 0..10000000, got 10000001");
    }
}

TEST_CASE("rig config: names are 1..64 characters from A-Z a-z 0-9 _ . -", "[unit][config]")
{
    auto rig = minimal_rig();
    const std::string expected =
        "rig.json: /devices/0/name: expected a name of 1..64 characters [A-Za-z0-9_.-], got ";
    rig["devices"][0]["name"] = "a b";
    CHECK(error_of(rig) == expected + "\"a b\"");
    rig["devices"][0]["name"] = "";
    CHECK(error_of(rig) == expected + "\"\"");
    rig["devices"][0]["name"] = "../x/y";
    CHECK(error_of(rig) == expected + "\"../x/y\"");
    rig["devices"][0]["name"] = 7;
    CHECK(error_of(rig) == expected + "7");
    rig["devices"][0]["name"] = std::string(65, 'x');
    CHECK(error_of(rig) == expected + "\"" + std::string(65, 'x') + "\"");
    rig["devices"][0]["name"] = std::string(64, 'x');
    CHECK(error_of(rig) == "(no error)");
}

TEST_CASE("rig config: protocols are mcs, apt and mcs2, each with its own object", "[unit][config]")
{
    auto rig = minimal_rig();
    rig["devices"][0]["protocol"] = "apt";
    CHECK(error_of(rig) == "rig.json: /devices/0/mcs: an \"mcs\" object belongs to an MCS device, not to protocol \"apt\"");
    rig["devices"][0].erase("mcs");
    CHECK(error_of(rig) == "rig.json: /devices/0/model: expected an APT controller model (TDC001, KDC101, TST001, KST101, BSC203, BBD203, K10CR1, LTS150, LTS300, KBD101, MFF101, MFF102, MPC320, MPC220, KIM101, TIM101, TSC001, KSC101, TPZ001, KPZ101, BPC301, BPC303, MMR601, TSG001, KSG101), got nothing");
    rig["devices"][0]["model"] = "TDC001";
    CHECK(error_of(rig) == "rig.json: /devices/0/apt: required key missing");
    rig["devices"][0]["apt"] = {{"stage", "MTS99"}};
    CHECK(error_of(rig) == "rig.json: /devices/0/apt/stage: unknown stage \"MTS99\" (expected one of DDR25, DDS100, DDS220, DDS300, DDS600, DDSM100, DRV001, DRV014, K10CR1, LTS150, LTS300, MLS203-X, MLS203-Y, MTS25-Z8, MTS50-Z8, PRM1-Z8, Z812B, Z825B, ZST225B, or a stage object)");
    rig["devices"][0]["apt"] = {{"stage", "Z825B"}, {"serial_number", 27000001}};
    CHECK(error_of(rig).find("/devices/0/apt/serial_number: expected an integer 83000000..83999999") != std::string::npos);
    rig["devices"][0]["apt"] = {{"stage", "Z825B"}, {"serial_number", 83123456}};
    const auto ok = rigsim::parse_rig_config(rig.dump(), "rig.json");
    CHECK(ok.devices[0].protocol == "apt");
    CHECK(rigsim::apt::config_of(ok.devices[0]).serial_number == 83123456);
    rig["devices"][0]["model"] = "BBD203";
    rig["devices"][0]["apt"] = {{"stage", "MLS203-X"}};
    CHECK(error_of(rig) == "rig.json: /devices/0/apt/stage: a rack controller names a stage per bay in \"bays\"");
    rig["devices"][0]["apt"] = {{"bays", {"MLS203-X", "MLS203-Y", "MLS203-Y", "MLS203-X"}}};
    CHECK(error_of(rig).find("/devices/0/apt/bays: expected an array of 1..3 stages") != std::string::npos);
    rig["devices"][0]["apt"] = {{"bays", {"MLS203-X", "MLS203-Y"}}};
    CHECK(rigsim::apt::config_of(rigsim::parse_rig_config(rig.dump(), "rig.json").devices[0]).bays.size() == 2);
    rig["devices"][0]["model"] = "TST001";
    rig["devices"][0]["apt"] = json::object();
    CHECK(error_of(rig) == "rig.json: /devices/0/apt/stage: required key missing (the default MTS50-Z8 is not a stage for a TST001)");
    rig["devices"][0]["apt"] = {{"stage", "Z825B"}};
    CHECK(error_of(rig) == "rig.json: /devices/0/apt/stage: stage \"Z825B\" has another kind of motor than a TST001");
    rig["devices"][0]["model"] = "BSC203";
    rig["devices"][0]["apt"] = {{"bays", {"DRV001", "MLS203-X"}}};
    CHECK(error_of(rig) == "rig.json: /devices/0/apt/bays/1: stage \"MLS203-X\" has another kind of motor than a BSC203");
    rig["devices"][0]["protocol"] = "MCS";
    CHECK(error_of(rig) ==
          "rig.json: /devices/0/protocol: unknown protocol \"MCS\" (expected \"mcs\", \"apt\" or \"mcs2\")");
    rig["devices"][0]["protocol"] = 1;
    CHECK(error_of(rig) == "rig.json: /devices/0/protocol: expected a string, got 1");
}

TEST_CASE("rig config: model must be a non-empty string", "[unit][config]")
{
    auto rig = minimal_rig();
    rig["devices"][0]["model"] = "";
    CHECK(error_of(rig) == "rig.json: /devices/0/model: expected a string of 1..64 printable ASCII characters, got \"\"");
    rig["devices"][0]["model"] = json::array();
    CHECK(error_of(rig) == "rig.json: /devices/0/model: expected a string of 1..64 printable ASCII characters, got []");
}

TEST_CASE("rig config: pty must be an absolute path", "[unit][config]")
{
    auto rig = minimal_rig();
    const std::string expected =
        "rig.json: /devices/0/pty: expected an absolute path (starting with '/'), got ";
    rig["devices"][0]["pty"] = "tmp/x";
    CHECK(error_of(rig) == expected + "\"tmp/x\"");
    rig["devices"][0]["pty"] = "";
    CHECK(error_of(rig) == expected + "\"\"");
    rig["devices"][0]["pty"] = false;
    CHECK(error_of(rig) == expected + "false");
}

TEST_CASE("rig config: channels must be 1..255", "[unit][config]")
{
    auto rig = minimal_rig();
    auto& channels = rig["devices"][0]["mcs"]["channels"];
    const std::string expected =
        "rig.json: /devices/0/mcs/channels: expected an array of 1..255 channels, got ";
    channels = json::array();
    CHECK(error_of(rig) == expected + "0 channels");
    channels = json::array();
    for (int i = 0; i < 255; ++i)
        channels.push_back(json::object());
    CHECK(error_of(rig) == "(no error)");
    channels.push_back(json::object());
    CHECK(error_of(rig) == expected + "256 channels");
    channels = json::object();
    CHECK(error_of(rig) == expected + "{}");
}

TEST_CASE("rig config: sensor types come from appendix 4.3 or are none", "[unit][config]")
{
    auto rig = minimal_rig();
    rig["devices"][0]["mcs"]["channels"] = json::array({json::object(), {{"sensor_type", "S9"}}});
    CHECK(error_of(rig) ==
          "rig.json: /devices/0/mcs/channels/1/sensor_type: unknown sensor type \"S9\" "
          "(expected one of S, SR, SP, SC, SR20, M, GD, GE, GF, G605S, G775S, SC500, G955S, "
          "SR77, SD, R20ME, SR2, SCD, SRC, SR36M, SR36ME, SR50M, SR50ME, G1045S, G1395S, MD, "
          "G935M, SHL20, SCT, or \"none\")");
    rig["devices"][0]["mcs"]["channels"][1]["sensor_type"] = "s";
    CHECK_THAT(error_of(rig),
               Catch::StartsWith("rig.json: /devices/0/mcs/channels/1/sensor_type: "
                                 "unknown sensor type \"s\" (expected one of S, SR,"));
    rig["devices"][0]["mcs"]["channels"][1]["sensor_type"] = 1;
    CHECK(error_of(rig) ==
          "rig.json: /devices/0/mcs/channels/1/sensor_type: expected a string, got 1");
    for (const auto* symbol : {"none", "S", "SR", "G605S", "SCT"}) {
        rig["devices"][0]["mcs"]["channels"][1]["sensor_type"] = symbol;
        CHECK(error_of(rig) == "(no error)");
    }
}

TEST_CASE("rig config: travel_nm is [min, max] with min < max", "[unit][config]")
{
    auto rig = minimal_rig();
    auto& travel = rig["devices"][0]["mcs"]["channels"][0]["travel_nm"];
    const std::string p = "rig.json: /devices/0/mcs/channels/0/travel_nm";
    travel = 5;
    CHECK(error_of(rig) == p + ": expected [min, max], two integers, got 5");
    travel = json::array({1, 2, 3});
    CHECK(error_of(rig) == p + ": expected [min, max], two integers, got an array of 3 elements");
    travel = json::array({5, 5});
    CHECK(error_of(rig) == p + ": expected min < max, got [5,5]");
    travel = json::array({6, 5});
    CHECK(error_of(rig) == p + ": expected min < max, got [6,5]");
    travel = json::array({-2000000001, 0});
    CHECK(error_of(rig) == p + "/0: expected an integer -2000000000..2000000000, got -2000000001");
    travel = json::array({0, "1"});
    CHECK(error_of(rig) == p + "/1: expected an integer -2000000000..2000000000, got \"1\"");
}

TEST_CASE("rig config: start_position_nm lies within travel_nm", "[unit][config]")
{
    auto rig = minimal_rig();
    auto& ch = rig["devices"][0]["mcs"]["channels"][0];
    const std::string p = "rig.json: /devices/0/mcs/channels/0/start_position_nm: ";
    ch["start_position_nm"] = 10500001;
    CHECK(error_of(rig) ==
          p + "expected an integer -10500000..10500000 (within travel_nm), got 10500001");
    ch["travel_nm"] = json::array({100, 200});
    ch["start_position_nm"] = 0;
    CHECK(error_of(rig) == p + "expected an integer 100..200 (within travel_nm), got 0");
    ch["start_position_nm"] = 100;
    CHECK(error_of(rig) == "(no error)");
}

TEST_CASE("rig config: device names are unique", "[unit][config]")
{
    auto rig = minimal_rig();
    rig["devices"].push_back(device("mcs1"));
    rig["devices"].push_back(device("mcs0"));
    CHECK(error_of(rig) ==
          "rig.json: /devices/2/name: name \"mcs0\" is already used by /devices/0");
}

TEST_CASE("rig config: a non-zero tcp_port is used once", "[unit][config]")
{
    auto rig = minimal_rig();
    rig["devices"][0]["tcp_port"] = 40100;
    rig["devices"].push_back(device("mcs1"));
    rig["devices"].push_back(device("mcs2"));
    rig["devices"][1]["tcp_port"] = 0;
    rig["devices"][2]["tcp_port"] = 0;
    CHECK(error_of(rig) == "(no error)");
    rig["devices"][2]["tcp_port"] = 40100;
    CHECK(error_of(rig) ==
          "rig.json: /devices/2/tcp_port: port 40100 is already used by /devices/0");
}

TEST_CASE("rig config: the control port is no device's tcp_port", "[unit][config]")
{
    auto rig = minimal_rig();
    rig["devices"][0]["tcp_port"] = 40100;
    rig["control"] = {{"port", 0}};
    CHECK(error_of(rig) == "(no error)");
    rig["control"]["port"] = 40101;
    CHECK(error_of(rig) == "(no error)");
    rig["control"]["port"] = 40100;
    CHECK(error_of(rig) == "rig.json: /control/port: port 40100 is already used by /devices/0");
}

TEST_CASE("rig config: model and firmware are short printable names", "[unit][config]")
{
    auto rig = minimal_rig();
    rig["devices"][0]["model"] = std::string(64, 'M');
    CHECK(error_of(rig) == "(no error)");
    rig["devices"][0]["model"] = std::string(1'000'000, 'M');   // once printed whole on stdout and in every answer
    CHECK(error_of(rig) == "rig.json: /devices/0/model: expected a string of 1..64 printable ASCII characters, got \""
                               + std::string(79, 'M') + "... (1000002 characters)");
    rig["devices"][0]["model"] = "MCS\n3D";
    CHECK(error_of(rig) == "rig.json: /devices/0/model: expected a string of 1..64 printable ASCII characters, got "
                           "\"MCS\\n3D\"");
    rig["devices"][0].erase("model");
    rig["devices"][0]["firmware"] = std::string(65, '1');
    CHECK(error_of(rig).find("rig.json: /devices/0/firmware: expected a string of 1..64 printable ASCII characters")
          == 0);
}

TEST_CASE("rig config: an explicit pty path is used once", "[unit][config]")
{
    auto rig = minimal_rig();
    rig["devices"][0]["pty"] = "/tmp/x";
    rig["devices"].push_back(device("mcs1"));
    rig["devices"][1]["pty"] = "/tmp/x";
    CHECK(error_of(rig) ==
          "rig.json: /devices/1/pty: path \"/tmp/x\" is already used by /devices/0");
}

TEST_CASE("rig config: the daemon's families are \"mcs\", \"apt\" then \"mcs2\"", "[unit][config]")
{
    const auto& families = rigsim::rig_families();
    REQUIRE(families.all().size() == 3);
    CHECK(families.all()[0].name == "mcs");
    CHECK(families.all()[1].name == "apt");
    CHECK(families.all()[2].name == "mcs2");
    CHECK(families.quoted_names() == "\"mcs\", \"apt\" or \"mcs2\"");
    CHECK(families.find("apt") == &families.all()[1]);
    CHECK(families.find("pz") == nullptr);
}

TEST_CASE("rig config: resolved pty paths default to <pty-dir>/<name> and never collide", "[unit][config]")
{
    auto config = rigsim::parse_rig_config(R"({"devices":[
        {"name":"a","protocol":"mcs","mcs":{"channels":[{}]}},
        {"name":"b","protocol":"mcs","pty":"/tmp/x/b-port","mcs":{"channels":[{}]}}]})", "rig.json");
    rigsim::resolve_pty_paths(config, "/tmp/x", "rig.json");
    CHECK(config.devices[0].pty == "/tmp/x/a");
    CHECK(config.devices[1].pty == "/tmp/x/b-port");

    auto clash = rigsim::parse_rig_config(R"({"devices":[
        {"name":"a","protocol":"mcs","pty":"/tmp/x/b","mcs":{"channels":[{}]}},
        {"name":"b","protocol":"mcs","mcs":{"channels":[{}]}}]})", "rig.json");
    try {
        rigsim::resolve_pty_paths(clash, "/tmp/x", "rig.json");
        FAIL("no error");
    } catch (const rigsim::ConfigError& e) {
        CHECK(std::string(e.what())
              == "rig.json: /devices/1/name: pty path \"/tmp/x/b\" is already used by /devices/0 "
                 "(this device's default is <pty-dir>/<name>)");
    }
}

TEST_CASE("rig config: faithful_timing is a boolean", "[unit][config]")
{
    const auto ok = rigsim::parse_rig_config(R"({"devices":[{"name":"a","protocol":"mcs","faithful_timing":true,"mcs":{"channels":[{}]}}]})", "rig.json");
    CHECK(ok.devices[0].faithful_timing);
    CHECK_FALSE(rigsim::parse_rig_config(R"({"devices":[{"name":"a","protocol":"mcs","mcs":{"channels":[{}]}}]})", "rig.json").devices[0].faithful_timing);
    try {
        rigsim::parse_rig_config(R"({"devices":[{"name":"a","protocol":"mcs","faithful_timing":1,"mcs":{"channels":[{}]}}]})", "rig.json");
        FAIL("no error");
    } catch (const rigsim::ConfigError& e) {
        CHECK(std::string(e.what()) == "rig.json: /devices/0/faithful_timing: expected true or false, got 1");
    }
}

TEST_CASE("rig config: rfc2217_port asks for an RFC 2217 endpoint, 0 an ephemeral one, a port once", "[unit][config]")
{
    const auto none = rigsim::parse_rig_config(R"({"devices":[{"name":"a","protocol":"mcs","mcs":{"channels":[{}]}}]})", "rig.json");
    CHECK_FALSE(none.devices[0].rfc2217_port.has_value());
    const auto some = rigsim::parse_rig_config(
        R"({"devices":[{"name":"a","protocol":"mcs","rfc2217_port":0,"mcs":{"channels":[{}]}},
                       {"name":"b","protocol":"mcs","tcp_port":5000,"rfc2217_port":5001,"mcs":{"channels":[{}]}}]})",
        "rig.json");
    CHECK(some.devices[0].rfc2217_port == std::optional<std::uint16_t>(0));
    CHECK(some.devices[1].rfc2217_port == std::optional<std::uint16_t>(5001));
    CHECK(error_of_text(R"({"devices":[{"name":"a","protocol":"mcs","rfc2217_port":70000,"mcs":{"channels":[{}]}}]})")
          == "rig.json: /devices/0/rfc2217_port: expected an integer 0..65535, got 70000");
    CHECK(error_of_text(R"({"devices":[{"name":"a","protocol":"mcs","tcp_port":5000,"mcs":{"channels":[{}]}},
                                      {"name":"b","protocol":"mcs","rfc2217_port":5000,"mcs":{"channels":[{}]}}]})")
          == "rig.json: /devices/1/rfc2217_port: port 5000 is already used by /devices/0");
}

TEST_CASE("rig config: link is the link model, every key optional and checked", "[unit][config]")
{
    const auto none = rigsim::parse_rig_config(R"({"devices":[{"name":"a","protocol":"mcs","mcs":{"channels":[{}]}}]})", "rig.json");
    CHECK_FALSE(none.devices[0].link.has_value());
    const auto dflt = rigsim::parse_rig_config(R"({"devices":[{"name":"a","protocol":"mcs","link":{},"mcs":{"channels":[{}]}}]})", "rig.json");
    REQUIRE(dflt.devices[0].link.has_value());
    CHECK(dflt.devices[0].link->latency_timer_ms == 16);
    CHECK(dflt.devices[0].link->packet_bytes == 62);
    CHECK(dflt.devices[0].link->usb_frame_us == 1000);
    CHECK(dflt.devices[0].link->processing_us == 0);
    CHECK_FALSE(dflt.devices[0].link->tcp);
    const auto set = rigsim::parse_rig_config(
        R"({"devices":[{"name":"a","protocol":"apt","model":"KDC101","link":{"latency_timer_ms":2,"packet_bytes":510,"usb_frame_us":125,"processing_us":300,"tcp":true},"apt":{"serial_number":27000001}}]})",
        "rig.json");
    REQUIRE(set.devices[0].link.has_value());
    CHECK(set.devices[0].link->latency_timer_ms == 2);
    CHECK(set.devices[0].link->packet_bytes == 510);
    CHECK(set.devices[0].link->usb_frame_us == 125);
    CHECK(set.devices[0].link->processing_us == 300);
    CHECK(set.devices[0].link->tcp);
    const std::pair<const char*, const char*> bad[] = {
        {R"(true)", "/devices/0/link: expected an object, got true"},
        {R"({"latency_timer_ms":0})", "/devices/0/link/latency_timer_ms: expected an integer 1..255, got 0"},
        {R"({"latency_timer_ms":256})", "/devices/0/link/latency_timer_ms: expected an integer 1..255, got 256"},
        {R"({"packet_bytes":0})", "/devices/0/link/packet_bytes: expected an integer 1..4096, got 0"},
        {R"({"usb_frame_us":100})", "/devices/0/link/usb_frame_us: expected an integer 125..1000, got 100"},
        {R"({"processing_us":-1})", "/devices/0/link/processing_us: expected an integer 0..10000000, got -1"},
        {R"({"tcp":"yes"})", "/devices/0/link/tcp: expected true or false, got \"yes\""},
        {R"({"latency":16})", "/devices/0/link: unknown key \"latency\" (allowed: latency_timer_ms, packet_bytes, usb_frame_us, processing_us, tcp)"},
    };
    for (const auto& [link, message] : bad) {
        INFO(link);
        CHECK(error_of_text(std::string(R"({"devices":[{"name":"a","protocol":"apt","model":"KDC101","link":)") + link + R"(,"apt":{"serial_number":27000001}}]})") ==
              std::string("rig.json: ") + message);
    }
}

TEST_CASE("rig config: mcs interface_version is \"<high>.<low>.<update>\", default 1.2.44", "[unit][config]")
{
    const auto dflt = rigsim::parse_rig_config(R"({"devices":[{"name":"a","protocol":"mcs","mcs":{"channels":[{}]}}]})", "rig.json");
    CHECK(rigsim::mcs::config_of(dflt.devices[0]).interface_version.high == 1);
    CHECK(rigsim::mcs::config_of(dflt.devices[0]).interface_version.low == 2);
    CHECK(rigsim::mcs::config_of(dflt.devices[0]).interface_version.update == 44);
    const auto ok = rigsim::parse_rig_config(
        R"({"devices":[{"name":"a","protocol":"mcs","mcs":{"interface_version":"1.5.0","channels":[{}]}}]})", "rig.json");
    CHECK(rigsim::mcs::config_of(ok.devices[0]).interface_version.high == 1);
    CHECK(rigsim::mcs::config_of(ok.devices[0]).interface_version.low == 5);
    CHECK(rigsim::mcs::config_of(ok.devices[0]).interface_version.update == 0);
    for (const char* bad : {R"("1.2")", R"("1.2.3.4")", R"("1..2")", R"("a.b.c")", R"("1.2.65536")", R"("")", R"(" 1.2.3")",
                            R"("1.2.")", "[1,2,44]", "1"}) {
        INFO(bad);
        try {
            rigsim::parse_rig_config(std::string(R"({"devices":[{"name":"a","protocol":"mcs","mcs":{"interface_version":)") + bad
                                         + R"(,"channels":[{}]}}]})",
                                     "rig.json");
            FAIL("no error");
        } catch (const rigsim::ConfigError& e) {
            CHECK(std::string(e.what()).rfind("rig.json: /devices/0/mcs/interface_version: expected a version \"<high>.<low>.<update>\" of three numbers 0..65535, got ", 0) == 0);
        }
    }
}

TEST_CASE("rig config: a device's firmware names a generation of its family, the manual's by default", "[unit][config]")
{
    const auto mcs = R"({"name":"m","protocol":"mcs","mcs":{"channels":[{}]}})";
    const auto apt = R"({"name":"k","protocol":"apt","model":"KDC101","apt":{}})";
    auto rig = json::parse(std::string(R"({"devices":[)") + mcs + "," + apt + "]}");
    const auto dflt = parse_rig_config(rig.dump(), "rig.json");
    CHECK(dflt.devices[0].firmware == "1.2.44");
    CHECK(rigsim::mcs::config_of(dflt.devices[0]).firmware == rigsim::mcs::Firmware::V1_2_44);
    CHECK(dflt.devices[1].firmware == "issue-3");
    CHECK(rigsim::apt::config_of(dflt.devices[1]).firmware == rigsim::apt::Firmware::Issue3);

    rig["devices"][1]["firmware"] = "issue-44.1";
    const auto later = parse_rig_config(rig.dump(), "rig.json");
    CHECK(later.devices[1].firmware == "issue-44.1");
    CHECK(rigsim::apt::config_of(later.devices[1]).firmware == rigsim::apt::Firmware::Issue44_1);

    rig["devices"][1]["firmware"] = "1.2.44";
    CHECK(error_of(rig) == "rig.json: /devices/1/firmware: unknown APT firmware generation \"1.2.44\" "
                           "(expected \"issue-3\", \"issue-44.1\")");
    rig["devices"][1]["firmware"] = "issue-3";
    rig["devices"][0]["firmware"] = "issue-3";
    CHECK(error_of(rig).rfind("rig.json: /devices/0/firmware: unknown MCS firmware generation \"issue-3\" (expected "
                              "\"1.2.44\"",
                              0) == 0);
    rig["devices"][0]["firmware"] = "";
    CHECK(error_of(rig) == "rig.json: /devices/0/firmware: expected a string of 1..64 printable ASCII characters, got \"\"");
    rig["devices"][0]["firmware"] = 3;
    CHECK(error_of(rig) == "rig.json: /devices/0/firmware: expected a string of 1..64 printable ASCII characters, got 3");
}

TEST_CASE("rig config: drift_nm_per_s is a signed channel integer, 0 by default", "[unit][config]")
{
    auto rig = minimal_rig();
    CHECK(rigsim::mcs::config_of(parse_rig_config(rig.dump(), "rig.json").devices[0]).channels[0].drift_nm_per_s == 0);
    rig["devices"][0]["mcs"]["channels"][0]["drift_nm_per_s"] = -250;
    CHECK(rigsim::mcs::config_of(parse_rig_config(rig.dump(), "rig.json").devices[0]).channels[0].drift_nm_per_s
          == -250);
    const std::string expected =
        "rig.json: /devices/0/mcs/channels/0/drift_nm_per_s: expected an integer -1000000..1000000, got ";
    rig["devices"][0]["mcs"]["channels"][0]["drift_nm_per_s"] = "fast";
    CHECK(error_of(rig) == expected + "\"fast\"");
    rig["devices"][0]["mcs"]["channels"][0]["drift_nm_per_s"] = 0.5;
    CHECK(error_of(rig) == expected + "0.5");
    rig["devices"][0]["mcs"]["channels"][0]["drift_nm_per_s"] = 1'000'001;
    CHECK(error_of(rig) == expected + "1000001");
}

} // namespace test_rig_config
