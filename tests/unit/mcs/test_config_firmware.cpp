// MCS firmware generations in the rig: "firmware" picks the generation (the manual's without it);
// "mcs.interface_version" given beside it must belong to it (docs/config.md).
#include "emulator/daemon/rig_families.hpp"
#include "emulator/mcs/config.hpp"
#include "emulator/mcs/firmware.hpp"

#include <catch2/catch.hpp>

#include <string>

namespace test_config_firmware {

using rigsim::mcs::Firmware;

namespace {

/// A rig with one MCS device; `firmware` and `version` are left out when empty.
std::string rig(const std::string& firmware, const std::string& version)
{
    std::string device = R"({"name":"a","protocol":"mcs",)";
    if (!firmware.empty())
        device += R"("firmware":")" + firmware + R"(",)";
    device += R"("mcs":{)";
    if (!version.empty())
        device += R"("interface_version":")" + version + R"(",)";
    device += R"("channels":[{}]}})";
    return R"({"devices":[)" + device + "]}";
}

struct Loaded {
    std::string firmware_name;
    Firmware firmware;
    std::string giv;   ///< "<high>.<low>.<update>"
};

Loaded load(const std::string& firmware, const std::string& version)
{
    const auto config = rigsim::parse_rig_config(rig(firmware, version), "rig.json");
    const auto& mcs = rigsim::mcs::config_of(config.devices.at(0));
    const auto& v = mcs.interface_version;
    return {config.devices[0].firmware, mcs.firmware,
            std::to_string(v.high) + "." + std::to_string(v.low) + "." + std::to_string(v.update)};
}

std::string error_of(const std::string& firmware, const std::string& version)
{
    try {
        rigsim::parse_rig_config(rig(firmware, version), "rig.json");
    } catch (const rigsim::ConfigError& e) {
        return e.what();
    }
    return "no error";
}

} // namespace

TEST_CASE("mcs firmware: the generations, their names and versions", "[unit][mcs][firmware]")
{
    CHECK(rigsim::mcs::firmware_name(Firmware::V1_2_44) == "1.2.44");
    CHECK(rigsim::mcs::firmware_name(Firmware::V2_0_1) == "2.0.1");
    CHECK(rigsim::mcs::find_firmware("2.0.1") == Firmware::V2_0_1);
    CHECK_FALSE(rigsim::mcs::find_firmware("2.0"));
    CHECK(rigsim::mcs::firmware_names() == "\"1.2.44\", \"2.0.1\"");
    CHECK(rigsim::mcs::firmware_version(Firmware::V2_0_1) == std::array<std::int64_t, 3>{2, 0, 1});
    // The newest generation whose version is not above it; below every one: the manual's.
    CHECK(rigsim::mcs::firmware_of_version({1, 0, 0}) == Firmware::V1_2_44);
    CHECK(rigsim::mcs::firmware_of_version({1, 2, 44}) == Firmware::V1_2_44);
    CHECK(rigsim::mcs::firmware_of_version({1, 5, 0}) == Firmware::V1_2_44);
    CHECK(rigsim::mcs::firmware_of_version({2, 0, 0}) == Firmware::V1_2_44);
    CHECK(rigsim::mcs::firmware_of_version({2, 0, 1}) == Firmware::V2_0_1);
    CHECK(rigsim::mcs::firmware_of_version({3, 0, 0}) == Firmware::V2_0_1);
}

TEST_CASE("mcs firmware: FRM directions per generation", "[unit][mcs][firmware]")
{
    using rigsim::mcs::frm_direction;
    CHECK(frm_direction(Firmware::V1_2_44, 0));
    CHECK(frm_direction(Firmware::V1_2_44, 1)->backward);
    for (int d : {-1, 2, 3, 4, 7, 8})
        CHECK_FALSE(frm_direction(Firmware::V1_2_44, d));
    for (int d : {-1, 8, 100})
        CHECK_FALSE(frm_direction(Firmware::V2_0_1, d));
    const bool backward[] = {false, true, false, true, false, true, false, true};
    for (int d = 0; d < 8; ++d) {
        INFO("direction " << d);
        const auto r = frm_direction(Firmware::V2_0_1, d);
        REQUIRE(r);
        CHECK(r->backward == backward[d]);
        CHECK(r->abort_on_end_stop == (d >= 4));
    }
}

TEST_CASE("mcs firmware: neither key gives the manual's generation and GIV 1.2.44", "[unit][mcs][firmware][config]")
{
    const auto l = load("", "");
    CHECK(l.firmware_name == "1.2.44");
    CHECK(l.firmware == Firmware::V1_2_44);
    CHECK(l.giv == "1.2.44");
}

TEST_CASE("mcs firmware: the firmware alone sets GIV's default", "[unit][mcs][firmware][config]")
{
    const auto later = load("2.0.1", "");
    CHECK(later.firmware == Firmware::V2_0_1);
    CHECK(later.giv == "2.0.1");
    CHECK(load("1.2.44", "").giv == "1.2.44");
}

TEST_CASE("mcs firmware: without a firmware the device is the manual's, whatever GIV answers", "[unit][mcs][firmware][config]")
{
    const auto old = load("", "1.5.0");
    CHECK(old.firmware_name == "1.2.44");
    CHECK(old.firmware == Firmware::V1_2_44);
    CHECK(old.giv == "1.5.0");
    // The interface version alone keeps its meaning (the GIV answer): no later behaviour.
    const auto later = load("", "2.3.7");
    CHECK(later.firmware_name == "1.2.44");   // the name the control API reports
    CHECK(later.firmware == Firmware::V1_2_44);
    CHECK(later.giv == "2.3.7");
    CHECK(load("", "1.0.0").firmware == Firmware::V1_2_44);
}

TEST_CASE("mcs firmware: both keys must agree, else the interface version is refused", "[unit][mcs][firmware][config]")
{
    CHECK(load("2.0.1", "2.0.1").giv == "2.0.1");
    CHECK(load("2.0.1", "4.1.0").giv == "4.1.0");
    CHECK(load("1.2.44", "1.9.9").giv == "1.9.9");
    CHECK(error_of("2.0.1", "1.2.44")
          == "rig.json: /devices/0/mcs/interface_version: interface version \"1.2.44\" belongs to firmware generation "
             "\"1.2.44\" (the newest whose version is not above it), but \"firmware\" is \"2.0.1\"");
    CHECK(error_of("1.2.44", "2.0.1")
          == "rig.json: /devices/0/mcs/interface_version: interface version \"2.0.1\" belongs to firmware generation "
             "\"2.0.1\" (the newest whose version is not above it), but \"firmware\" is \"1.2.44\"");
    // An unknown generation is named first, at its own key.
    CHECK(error_of("1.3", "2.0.1")
          == "rig.json: /devices/0/firmware: unknown MCS firmware generation \"1.3\" (expected \"1.2.44\", \"2.0.1\")");
}

} // namespace test_config_firmware
