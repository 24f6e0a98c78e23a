// The worked example of docs/architecture.md, "A new family": the toy family writes its
// protocol only (toy_family.cpp), and gets from the World what every family gets: a rig JSON
// section, a kinematic joint, collisions, physical faults, the control API's physical state and
// "run until idle", with no code of its own for any of them.

#include "toy_family.hpp"

#include "emulator/control/body_state.hpp"
#include "emulator/control/fault_book.hpp"
#include "emulator/core/event_bus.hpp"
#include "emulator/core/state_store.hpp"
#include "emulator/daemon/rig_kinematics.hpp"
#include "models/world.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <spdlog/logger.h>

#include <memory>
#include <string>

namespace test_toy_family {

using namespace rigsim;
using nlohmann::json;

namespace {

/// A rig of two toy stages: "lift" carries a plate 10 mm wide that "slide" pushes a 10 mm block
/// toward; they collide when the slide passes 35 mm.
const char* const kRig = R"({
  "devices": [
    {"name": "slide", "protocol": "toy", "toy": {"travel_mm": 50}},
    {"name": "lift", "protocol": "toy", "toy": {}}
  ],
  "kinematics": {
    "frames": [
      {"name": "table"},
      {"name": "slide", "parent": "table", "axis": {"device": "slide", "channel": 0},
       "joint": {"type": "prismatic", "axis": [1, 0, 0]},
       "box_mm": {"min": [-5, -5, -5], "max": [5, 5, 5]}},
      {"name": "wall", "parent": "table", "offset": {"translation_mm": [45, 0, 0]},
       "box_mm": {"min": [-5, -5, -5], "max": [5, 5, 5]}}
    ],
    "collisions": [["slide", "wall"]]
  }
})";

struct ToyRig {
    ToyRig()
    {
        families.add(toy::toy_family());
        config = parse_rig_config(kRig, "toy.json", families);
        for (const auto& d : config.devices) {
            const DeviceContext context{world, std::make_shared<spdlog::logger>(d.name), store, &events};
            devices.push_back(families.find(d.protocol)->make(d, context));
        }
        world.link_all();
        built = build_kinematics(*config.kinematics, [this](std::string_view name) { return surface(name); }, world);
        watch_collisions(world, built, *config.kinematics, events);
    }
    ControlSurface* surface(std::string_view name)
    {
        for (std::size_t i = 0; i < devices.size(); ++i)
            if (config.devices[i].name == name)
                return devices[i]->control();
        return nullptr;
    }
    toy::ToyDevice& toy(std::size_t i) { return static_cast<toy::ToyDevice&>(*devices[i]); }

    FamilyRegistry families;
    RigConfig config;
    Clock clock;
    models::World world{clock};
    StateStore store;
    EventBus events;
    std::vector<std::unique_ptr<Device>> devices;
    RigKinematics built;
};

} // namespace

TEST_CASE("toy family: its section is read and refused as every family's", "[device][toy]")
{
    FamilyRegistry families;
    families.add(toy::toy_family());
    const auto config = parse_rig_config(R"({"devices": [{"name": "t", "protocol": "toy", "toy": {}}]})", "r.json", families);
    CHECK(config.devices.at(0).model == "TOY-1");
    CHECK_THROWS_WITH(parse_rig_config(R"({"devices": [{"name": "t", "protocol": "toy", "toy": {"travel_mm": 0}}]})",
                                       "r.json", families),
                      Catch::StartsWith("r.json: /devices/0/toy/travel_mm:"));
}

TEST_CASE("toy family: the protocol moves its body, the rest comes from the world", "[device][toy]")
{
    ToyRig rig;
    auto& slide = rig.toy(0);
    CHECK(slide.handle("POS?") == "POS 25.000");
    CHECK(slide.handle("MOV 30") == "OK");
    CHECK(slide.handle("MOV 99") == "ERR 1");
    CHECK(slide.handle("FLY") == "ERR 0");

    // The control API's physical state: written from the body, not by the toy.
    json state = json::object();
    control::describe_device(slide, &rig.world, state);
    const auto& ch = state["channels"][0];
    CHECK(ch["body"]["key"] == "slide/0");
    CHECK(ch["body"]["kind"] == "linear");
    CHECK(ch["body"]["settling"] == true);
    CHECK(ch["si_unit"] == "m");
    CHECK(ch["position_si"].get<double>() == Approx(0.025));

    // The kinematic joint reads the body in mm.
    rig.clock.advance_ms(2000);
    CHECK(slide.handle("POS?") == "POS 30.000");
    CHECK(rig.built.bindings[1].position() == Approx(30.0));
    CHECK_FALSE(rig.world.settling());

    // A collision: the slide's box meets the wall's at 35 mm and the servo stalls there.
    CHECK(slide.handle("MOV 50") == "OK");
    rig.clock.advance_ms(3000);
    CHECK(slide.handle("STA?") == "STA 2");
    CHECK(rig.built.bindings[1].position() == Approx(35.0).margin(0.02));
}

TEST_CASE("toy family: physical faults act on its body, by its key, with no fault code of its own", "[device][toy]")
{
    ToyRig rig;
    auto& lift = rig.toy(1);
    DeviceFault stall;
    REQUIRE_FALSE(parse_device_fault("stall", json::object(), stall));
    stall.id = 1;
    bool kept = false;
    bool on_body = false;
    REQUIRE_FALSE(control::start_device_fault(lift, &rig.world, stall, &kept, &on_body));
    CHECK(on_body);
    CHECK(lift.handle("MOV 40") == "OK");
    rig.clock.advance_ms(10);
    CHECK(lift.handle("STA?") == "STA 2");   // the servo stalled where it stood
    CHECK(lift.handle("POS?") == "POS 25.000");
    control::end_device_fault(lift, &rig.world, 1, true);
    CHECK(lift.handle("MOV 40") == "OK");
    rig.clock.advance_ms(3000);
    CHECK(lift.handle("POS?") == "POS 40.000");

    // A slip is refused by the body (a servo loses no steps), reference_lost by the toy.
    DeviceFault slip;
    REQUIRE_FALSE(parse_device_fault("slip", json{{"counts", 5}}, slip));
    const auto refused = control::start_device_fault(lift, &rig.world, slip, &kept, &on_body);
    REQUIRE(refused);
    CHECK(refused->message.find("slip: a servo closes its position loop") == 0);
    DeviceFault lost;
    REQUIRE_FALSE(parse_device_fault("reference_lost", json::object(), lost));
    CHECK(control::start_device_fault(lift, &rig.world, lost, &kept, &on_body));
}

} // namespace test_toy_family
