// MCS2 channels as joints of the rig's frames: their bodies are the World's stick-slip positioners,
// so a client's move over the MCS2 protocol moves the frame, and the frames API finds the device and
// channel of each joint (control::joint_axes), as for the other families.
#include "emulator/control/frame_book.hpp"
#include "emulator/daemon/rig.hpp"
#include "emulator/daemon/rig_families.hpp"
#include "emulator/mcs2/device.hpp"
#include "tests/support/temp_dir.hpp"

#include <catch2/catch.hpp>

#include <boost/asio/io_context.hpp>

#include <cmath>
#include <string>

namespace test_mcs2_kinematics {

using namespace rigsim;

TEST_CASE("MCS2 kinematics: a linear and a rotary channel drive their joints, found by the frames API",
          "[device][kinematics][mcs2]")
{
    test::TempDir dir;
    boost::asio::io_context io;
    RigOptions options;
    options.pty_dir = dir.path();
    options.ephemeral_ports = true;
    options.paused = true;
    options.log_levels.global = spdlog::level::warn;
    Rig rig(io, parse_rig_config(R"({
      "devices": [{"name": "m2", "protocol": "mcs2",
                   "mcs2": {"channels": [{"positioner_type": 300}, {"positioner_type": 312}]}}],
      "kinematics": {"frames": [
        {"name": "table"},
        {"name": "x", "parent": "table", "axis": {"device": "m2", "channel": 0},
         "joint": {"type": "prismatic", "axis": [1, 0, 0]}},
        {"name": "rot", "parent": "x", "axis": {"device": "m2", "channel": 1},
         "joint": {"type": "revolute", "axis": [0, 0, 1]}}]}})",
                                 "rig.json"),
            options);
    const auto& x = rig.joint_bindings()[*rig.kinematics()->find("x")];
    const auto& rot = rig.joint_bindings()[*rig.kinematics()->find("rot")];
    CHECK(x.body_key == "m2/0");
    CHECK(rot.body_key == "m2/1");
    const auto axes = control::joint_axes(rig.joint_bindings(), rig.controlled());
    REQUIRE(axes.size() == 3);
    REQUIRE(axes[1]);
    CHECK((axes[1]->device == "m2" && axes[1]->channel == 0));
    REQUIRE(axes[2]);
    CHECK((axes[2]->device == "m2" && axes[2]->channel == 1));

    mcs2::Mcs2Device* m2 = nullptr;
    for (auto& d : rig.controlled())
        if (d.endpoints.name == "m2")
            m2 = dynamic_cast<mcs2::Mcs2Device*>(d.surface);
    REQUIRE(m2);
    auto session = m2->open_session([](std::string_view) {}, "test");
    session->receive(":MOVE0 1000000000\r\n");    // 1 mm (pm)
    session->receive(":MOVE1 90000000000\r\n");   // 90° (n°)
    rig.clock().advance_ms(10'000);
    CHECK(x.position() == Approx(1.0).epsilon(1e-12));   // mm
    auto& k = *rig.kinematics();
    k.update();
    CHECK(k.world_pose(*k.find("x")).translation().x() == Approx(1.0).margin(1e-9));
    CHECK(rot.position() == Approx(90.0).epsilon(1e-9));   // degrees
}

} // namespace test_mcs2_kinematics
