// The actuators of the units made after the 2012 manual as joints of a rig's frames: a KIM101's
// channels 0..3 are its four piezo inertia actuators, an MMR601's channel 2 x bay + card channel - 1
// is that card channel's piezo (docs/control-api/apt.md), and the frames API finds the device and
// channel of each joint's body (control::joint_axes), past the channel objects of describe().
#include "emulator/apt/apt_device.hpp"
#include "emulator/control/frame_book.hpp"
#include "emulator/daemon/rig.hpp"
#include "emulator/daemon/rig_families.hpp"
#include "models/inertial_drive.hpp"
#include "models/piezo_actuator.hpp"
#include "tests/support/temp_dir.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <boost/asio/io_context.hpp>

#include <memory>
#include <string>

namespace test_rig_kinematics_units_of_today {

using nlohmann::json;
using namespace rigsim;

namespace {

RigConfig rig_config()
{
    return parse_rig_config(R"({
      "devices": [
        {"name": "kim", "protocol": "apt", "model": "KIM101", "apt": {}},
        {"name": "mmr", "protocol": "apt", "model": "MMR601", "apt": {"bays": [{}, {}]}}],
      "kinematics": {"frames": [
        {"name": "table"},
        {"name": "mirror", "parent": "table", "axis": {"device": "kim", "channel": 2},
         "joint": {"type": "prismatic", "axis": [1, 0, 0]}},
        {"name": "fibre", "parent": "table", "axis": {"device": "mmr", "channel": 3},
         "joint": {"type": "prismatic", "axis": [0, 1, 0]}}]}})",
                            "rig.json");
}

} // namespace

TEST_CASE("rig kinematics: a KIM101 actuator and an MMR601 card channel drive their joints, found by the frames API",
          "[device][kinematics][today]")
{
    test::TempDir dir;
    boost::asio::io_context io;
    RigOptions options;
    options.pty_dir = dir.path();
    options.ephemeral_ports = true;
    options.paused = true;
    options.log_levels.global = spdlog::level::warn;
    Rig rig(io, rig_config(), options);
    const auto& mirror = rig.joint_bindings()[*rig.kinematics()->find("mirror")];
    const auto& fibre = rig.joint_bindings()[*rig.kinematics()->find("fibre")];
    CHECK(mirror.body_key == "kim/3");
    CHECK(fibre.body_key == "mmr/2.2");
    const auto axes = control::joint_axes(rig.joint_bindings(), rig.controlled());
    REQUIRE(axes.size() == 3);
    REQUIRE(axes[1]);
    CHECK((axes[1]->device == "kim" && axes[1]->channel == 2));
    REQUIRE(axes[2]);
    CHECK((axes[2]->device == "mmr" && axes[2]->channel == 3));

    apt::AptDevice* kim = nullptr;
    apt::AptDevice* mmr = nullptr;
    for (auto& d : rig.controlled()) {
        if (d.endpoints.name == "kim")
            kim = dynamic_cast<apt::AptDevice*>(d.surface);
        if (d.endpoints.name == "mmr")
            mmr = dynamic_cast<apt::AptDevice*>(d.surface);
    }
    REQUIRE(kim);
    REQUIRE(mmr);
    // KIM101: channel 3 enabled alone (ChanEnableMode 3), 1000 pulses forward (its bit, 0x04): 20 nm each.
    auto kim_session = kim->open_session([](std::string_view) {}, "test");
    kim_session->receive(std::string("\xC0\x08\x04\x00\xD0\x01\x2B\x00\x03\x00", 10));
    kim_session->receive(std::string("\xD4\x08\x06\x00\xD0\x01\x04\x00\xE8\x03\x00\x00", 12));
    rig.clock().advance_ms(2100);
    CHECK(mirror.position() == Approx(6.5 + 0.02).epsilon(1e-12));
    // MMR601: bay 1's (0x22) channel 2 at half its voltage.
    auto mmr_session = mmr->open_session([](std::string_view) {}, "test");
    mmr_session->receive(std::string("\x43\x06\x04\x00\xA2\x01\x02\x00\x00\x40", 10));
    rig.clock().advance_ms(100);
    const auto* piezo = rig.world().find_as<models::PiezoActuator>("mmr/2.2");
    REQUIRE(piezo);
    CHECK(piezo->extension_um() > 5);
    CHECK(fibre.position() == Approx(piezo->extension_um() / 1000).epsilon(1e-12));
    auto& k = *rig.kinematics();
    k.update();
    CHECK(k.world_pose(*k.find("mirror")).translation().x() == Approx(6.52).margin(1e-9));
}

} // namespace test_rig_kinematics_units_of_today
