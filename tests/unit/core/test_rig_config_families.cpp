// Core reads rigs through the family registry alone: a made-up family, unknown to the
// daemon, gets its section, its name in messages and its key in the device's allowed keys.
#include "emulator/core/config_reader.hpp"
#include "emulator/core/family_registry.hpp"
#include "emulator/core/rig_config.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <string>

namespace test_rig_config_families {

namespace {

struct LampConfig {
    std::int64_t watts = 5;
};

rigsim::FamilyRegistry lamp_and_fan()
{
    rigsim::FamilyRegistry families;
    families.add({"lamp", "a lamp", [](const rigsim::ConfigReader& r, const nlohmann::json& device,
                                       const std::string& pointer, rigsim::DeviceConfig& config) {
                      const auto& lamp = r.require(device, pointer, "lamp");
                      auto& section = rigsim::section_of<LampConfig>(config);
                      if (const auto* w = r.find(lamp, "watts"))
                          section.watts = r.get_int(*w, rigsim::pointer_to(rigsim::pointer_to(pointer, "lamp"), "watts"), 1, 100);
                  },
                  nullptr});
    families.add({"fan", "a fan", [](const rigsim::ConfigReader&, const nlohmann::json&, const std::string&,
                                     rigsim::DeviceConfig&) {},
                  nullptr});
    return families;
}

std::string error_of(const std::string& text, const rigsim::FamilyRegistry& families)
{
    try {
        rigsim::parse_rig_config(text, "rig.json", families);
    } catch (const rigsim::ConfigError& e) {
        return e.what();
    }
    return "no error";
}

} // namespace

TEST_CASE("rig config: core loads a device's section with the family its protocol names", "[unit][config]")
{
    const auto families = lamp_and_fan();
    const auto rig = rigsim::parse_rig_config(
        R"({"devices":[{"name":"l","protocol":"lamp","model":"E27","lamp":{"watts":60}},{"name":"f","protocol":"fan"}]})",
        "rig.json", families);
    REQUIRE(rig.devices.size() == 2);
    CHECK(rig.devices[0].protocol == "lamp");
    CHECK(rig.devices[0].model == "E27");
    CHECK(rigsim::section_of<LampConfig>(rig.devices[0]).watts == 60);
    CHECK(rig.devices[1].protocol == "fan");
    CHECK_FALSE(rig.devices[1].section.has_value());

    CHECK(error_of(R"({"devices":[{"name":"l","protocol":"mcs"}]})", families)
          == "rig.json: /devices/0/protocol: unknown protocol \"mcs\" (expected \"lamp\" or \"fan\")");
    CHECK(error_of(R"({"devices":[{"name":"l","protocol":"lamp","mcs":{}}]})", families)
          == "rig.json: /devices/0: unknown key \"mcs\" (allowed: name, protocol, model, firmware, tcp_port, "
             "pty, faithful_timing, link, rfc2217_port, lamp, fan)");
    CHECK(error_of(R"({"devices":[{"name":"f","protocol":"fan","lamp":{}}]})", families)
          == "rig.json: /devices/0/lamp: an \"lamp\" object belongs to a lamp, not to protocol \"fan\"");
    CHECK(error_of(R"({"devices":[{"name":"l","protocol":"lamp","lamp":{"watts":0}}]})", families)
          == "rig.json: /devices/0/lamp/watts: expected an integer 1..100, got 0");
}

TEST_CASE("rig config: a family name is registered once", "[unit][config]")
{
    auto families = lamp_and_fan();
    CHECK_THROWS_AS(families.add({"fan", "another fan", nullptr, nullptr}), std::invalid_argument);
    CHECK(families.quoted_names() == "\"lamp\" or \"fan\"");
}

TEST_CASE("rig config: a family's rig-wide check runs once every device is loaded", "[unit][config]")
{
    auto families = lamp_and_fan();
    rigsim::FamilyRegistry checked;
    for (auto family : families.all()) {
        if (family.name == "lamp")
            family.validate_rig = [](const rigsim::ConfigReader& r, const rigsim::RigConfig& rig) {
                bool fan = false;
                for (const auto& d : rig.devices)
                    fan = fan || d.protocol == "fan";
                for (std::size_t i = 0; i < rig.devices.size(); ++i)
                    if (rig.devices[i].protocol == "lamp" && !fan)
                        r.fail(rigsim::pointer_to(rig.devices[i].pointer, "protocol"), "a lamp needs a fan in the rig");
            };
        checked.add(family);
    }
    // The fan comes after the lamp: the check sees it.
    const auto rig = rigsim::parse_rig_config(
        R"({"devices":[{"name":"l","protocol":"lamp","lamp":{}},{"name":"f","protocol":"fan"}]})", "rig.json", checked);
    CHECK(rig.devices[1].pointer == "/devices/1");
    CHECK(rig.devices[1].source == "rig.json");
    CHECK(error_of(R"({"devices":[{"name":"f","protocol":"lamp","lamp":{}}]})", checked) ==
          "rig.json: /devices/0/protocol: a lamp needs a fan in the rig");
    // A device's own errors come first.
    CHECK(error_of(R"({"devices":[{"name":"f","protocol":"lamp","lamp":{"watts":0}}]})", checked) ==
          "rig.json: /devices/0/lamp/watts: expected an integer 1..100, got 0");
}

} // namespace test_rig_config_families
