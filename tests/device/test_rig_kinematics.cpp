// A rig's frames bound to its devices' channels (emulator/daemon/rig_kinematics.cpp and each
// family's ControlSurface::joint): moving a channel on the stepped clock moves its frame and
// everything on it; a channel that cannot drive its joint is a config error when the rig is built
// (and in --check-config), naming the frame's pointer.
#include "emulator/apt/apt_device.hpp"
#include "emulator/daemon/rig.hpp"
#include "emulator/daemon/rig_families.hpp"
#include "emulator/mcs/mcs_device.hpp"
#include "models/axis.hpp"
#include "models/piezo_actuator.hpp"
#include "models/stick_slip.hpp"
#include "tests/support/temp_dir.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <boost/asio/io_context.hpp>

#include <cmath>
#include <memory>
#include <optional>
#include <string>

namespace test_rig_kinematics {

using nlohmann::json;
using namespace rigsim;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// An MCS stack (two linear channels, an end effector, a goniometer, a rotary channel), a KDC101
/// with a PRM1-Z8 rotation stage, a TSC001 solenoid controller, a TPZ001 piezo driver and a
/// TDC001 with a goniometer stage described in the rig.
json devices()
{
    return json::parse(R"([
        {"name": "stack", "protocol": "mcs",
         "mcs": {"channels": [{}, {}, {"kind": "end_effector"}, {"sensor_type": "G605S"}, {"sensor_type": "SR"}]}},
        {"name": "apt_rot", "protocol": "apt", "model": "KDC101", "apt": {"stage": "PRM1-Z8"}},
        {"name": "tsc", "protocol": "apt", "model": "TSC001", "apt": {}},
        {"name": "tpz", "protocol": "apt", "model": "TPZ001", "apt": {}},
        {"name": "apt_gonio", "protocol": "apt", "model": "TDC001",
         "apt": {"stage": {"name": "GONIO-10", "kind": "goniometer", "motor": "dc_servo",
                           "angle_range_deg": [-10, 10], "counts_per_deg": 34304, "max_velocity_deg_s": 2,
                           "acceleration_deg_s2": 2, "home_velocity_deg_s": 1}}}])");
}

/// The table; a rotation stage 50 mm above it turning about z; X on it; a sample 40 mm above X.
json kinematics()
{
    return json::parse(R"({
      "frames": [
        {"name": "table"},
        {"name": "rot", "parent": "table", "offset": {"translation_mm": [0, 0, 50]},
         "axis": {"device": "apt_rot", "channel": 0}, "joint": {"type": "revolute", "axis": [0, 0, 1]}},
        {"name": "x", "parent": "rot", "axis": {"device": "stack", "channel": 0},
         "joint": {"type": "prismatic", "axis": [1, 0, 0]}},
        {"name": "tilt", "parent": "x", "axis": {"device": "stack", "channel": 3},
         "joint": {"type": "goniometer", "axis": [1, 0, 0], "centre_mm": [0, 0, 40]}},
        {"name": "piezo", "parent": "table", "axis": {"device": "tpz", "channel": 0},
         "joint": {"type": "prismatic", "axis": [0, 1, 0]}}
      ],
      "tools": [{"name": "sample", "parent": "x", "offset": {"translation_mm": [0, 0, 40]}}]
    })");
}

RigConfig config_of(const json& k)
{
    return parse_rig_config(json{{"devices", devices()}, {"kinematics", k}}.dump(), "rig.json");
}

/// A rig on a paused clock, its ptys in a fresh directory.
struct Fixture {
    explicit Fixture(const json& k = kinematics()) : config(config_of(k))
    {
        options.pty_dir = dir.path();
        options.ephemeral_ports = true;
        options.paused = true;
        options.log_levels.global = spdlog::level::warn;
    }
    void build() { rig = std::make_unique<Rig>(io, config, options); }
    /// The ConfigError the rig's build throws, or "(no error)".
    std::string build_error()
    {
        try {
            build();
        } catch (const ConfigError& e) {
            return e.what();
        }
        return "(no error)";
    }
    template <class T>
    T& device(const std::string& name)
    {
        for (auto& d : rig->controlled())
            if (d.endpoints.name == name)
                return dynamic_cast<T&>(*d.surface);
        FAIL("no device " << name);
        throw;
    }
    /// Send MCS command `line` to the stack (its answer is dropped).
    void mcs(const std::string& line)
    {
        auto session = device<mcs::McsDevice>("stack").open_session([](std::string_view) {}, "test");
        session->receive(line);
    }
    std::size_t frame(const std::string& name)
    {
        const auto i = rig->kinematics()->find(name);
        REQUIRE(i);
        return *i;
    }

    test::TempDir dir;
    boost::asio::io_context io;
    RigConfig config;
    RigOptions options;
    std::unique_ptr<Rig> rig;
};

/// The ConfigError of --check-config's device checks for `k`, or "(no error)".
std::string check_error(const json& k)
{
    try {
        check_rig_devices(config_of(k));
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "(no error)";
}

} // namespace

TEST_CASE("rig kinematics: no kinematics key, no frames", "[device][kinematics]")
{
    test::TempDir dir;
    boost::asio::io_context io;
    RigOptions options;
    options.pty_dir = dir.path();
    options.ephemeral_ports = true;
    options.paused = true;
    options.log_levels.global = spdlog::level::warn;
    Rig rig(io, parse_rig_config(json{{"devices", devices()}}.dump(), "rig.json"), options);
    CHECK(rig.kinematics() == nullptr);
    CHECK(rig.joint_bindings().empty());
}

TEST_CASE("rig kinematics: the frames are bound to their channels", "[device][kinematics]")
{
    Fixture f;
    f.build();
    auto* k = f.rig->kinematics();
    REQUIRE(k);
    REQUIRE(k->size() == 6);
    const auto& b = f.rig->joint_bindings();
    REQUIRE(b.size() == k->size());
    CHECK_FALSE(b[f.frame("table")].position);
    CHECK_FALSE(b[f.frame("sample")].position);
    CHECK(k->is_tool(f.frame("sample")));

    const auto& rot = b[f.frame("rot")];
    CHECK(rot.body->kind() == models::BodyKind::Rotary);
    CHECK(rot.body_key == "apt_rot/1");
    const auto& x = b[f.frame("x")];
    CHECK(x.body->kind() == models::BodyKind::Linear);
    CHECK(x.body_key == "stack/0");
    const auto& tilt = b[f.frame("tilt")];
    CHECK(tilt.body->kind() == models::BodyKind::Goniometer);
    CHECK(tilt.body_key == "stack/3");
    const auto& piezo = b[f.frame("piezo")];
    CHECK(piezo.body->kind() == models::BodyKind::PiezoActuator);
    CHECK(piezo.body_key == "tpz/1");
    for (const auto* j : {&rot, &x, &tilt, &piezo}) {
        REQUIRE(j->position);
        REQUIRE(j->drive.velocity);
        CHECK(j->drive.velocity() == 0.0);
    }
    // A collision stops a motor or a stick-slip positioner at an obstacle in joint units; a piezo
    // pushes on (no set_obstacles).
    REQUIRE(rot.drive.set_obstacles);
    REQUIRE(x.drive.set_obstacles);
    REQUIRE(tilt.drive.set_obstacles);
    CHECK_FALSE(piezo.drive.set_obstacles);
    x.drive.set_obstacles(std::nullopt, 1.5);
    const auto* x_body = f.rig->world().find_as<models::StickSlipPositioner>("stack/0");
    REQUIRE(x_body);
    CHECK(x_body->obstacle_max_nm() == Approx(1.5e6).epsilon(1e-15));
    CHECK_FALSE(x_body->obstacle_min_nm());
    x.drive.set_obstacles(std::nullopt, std::nullopt);
    CHECK_FALSE(x_body->obstacle_max_nm());
    // Physical positions: the MCS stages and the piezo start at 0; an APT stage starts in the
    // middle of its travel, where its counters read 0.
    CHECK(x.position() == 0.0);
    CHECK(tilt.position() == 0.0);
    CHECK(piezo.position() == 0.0);
    const auto& channel = f.device<apt::AptDevice>("apt_rot").channel(0);
    const double counts_per_degree = channel.stage().counts_per_mm;   // PRM1-Z8: per degree
    CHECK(counts_per_degree == Approx(1919.64).margin(0.01));
    CHECK(channel.axis().position_counts() != 0.0);
    CHECK(rot.position() == Approx(channel.axis().position_counts() / counts_per_degree).epsilon(1e-15));
    // Independent of the conversion: a rotation stage powers up half a turn from its home
    // switch (180°); the goniometer stage below powers up mid-range (0° of [-10°, 10°]).
    CHECK(rot.position() == Approx(180).margin(1e-9));
    rot.drive.set_obstacles(rot.position() - 10, std::nullopt);
    CHECK(channel.axis().obstacle_min_counts() == Approx(channel.axis().position_counts() - 10 * counts_per_degree));
    rot.drive.set_obstacles(std::nullopt, std::nullopt);
    CHECK_FALSE(channel.axis().obstacle_min_counts());
    CHECK(k->joint_position(f.frame("rot")) == rot.position());

    // The rotary MCS channel is a rotary stage; the APT goniometer stage a goniometer, in degrees.
    std::string sr;
    CHECK_FALSE(f.device<mcs::McsDevice>("stack").axis_body_key(4, sr));
    REQUIRE(f.rig->world().find(sr));
    CHECK(f.rig->world().find(sr)->kind() == models::BodyKind::Rotary);
    std::string gonio_key;
    auto& apt_gonio = f.device<apt::AptDevice>("apt_gonio");
    CHECK_FALSE(apt_gonio.axis_body_key(0, gonio_key));
    CHECK(gonio_key == "apt_gonio/1");
    const models::Body* gonio = f.rig->world().find(gonio_key);
    REQUIRE(gonio);
    CHECK(gonio->kind() == models::BodyKind::Goniometer);
    CHECK(gonio->angle_rad() * 180 / kPi == Approx(apt_gonio.channel(0).axis().position_counts() / 34304).margin(1e-12));
    CHECK(gonio->angle_rad() == Approx(0).margin(1e-9));
}

TEST_CASE("rig kinematics: moving channels on the stepped clock moves the frames", "[device][kinematics]")
{
    Fixture f;
    f.build();
    auto& k = *f.rig->kinematics();
    const auto& b = f.rig->joint_bindings();
    const auto sample = f.frame("sample");
    k.update();
    CHECK(k.world_pose(sample).translation().isApprox(Eigen::Vector3d(0, 0, 90), 1e-12));

    // X to +2 mm (MCS, nm), the rotation stage by 86,384 counts (about 45 degrees) from where
    // its counters read 0.
    const double q_rot_before = b[f.frame("rot")].position();
    f.mcs(":MPA0,2000000,0\n");
    auto& rot = f.device<apt::AptDevice>("apt_rot").channel(0);
    const double counts_per_degree = rot.stage().counts_per_mm;
    rot.move_absolute(86384);
    f.rig->clock().advance_ms(20);
    CHECK(b[f.frame("x")].drive.velocity() > 0);
    CHECK(b[f.frame("rot")].drive.velocity() > 0);
    f.rig->clock().advance_ms(10000);

    const double q_x = b[f.frame("x")].position();
    const double q_rot = b[f.frame("rot")].position();
    CHECK(q_x == Approx(2.0).margin(1e-6));
    CHECK(q_rot - q_rot_before == Approx(86384 / counts_per_degree).margin(1e-9));
    CHECK(b[f.frame("x")].drive.velocity() == 0.0);
    CHECK(b[f.frame("rot")].drive.velocity() == 0.0);

    k.update();
    CHECK(k.joint_position(f.frame("x")) == q_x);
    CHECK(k.joint_position(f.frame("rot")) == q_rot);
    // sample = T(0,0,50) · Rz(q_rot) · T(q_x,0,0) · T(0,0,40)
    const double a = q_rot * kPi / 180;
    const Eigen::Vector3d expected(q_x * std::cos(a), q_x * std::sin(a), 90);
    CHECK((k.world_pose(sample).translation() - expected).norm() < 1e-9);
    const Eigen::Matrix3d rz = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    CHECK((k.world_pose(sample).linear() - rz).norm() < 1e-9);

    // The goniometer: 1 degree (MCS, µ°) about x through (0,0,40) on X: the centre stays put.
    f.mcs(":MAA3,1000000,0,0\n");
    f.rig->clock().advance_ms(10000);
    CHECK(b[f.frame("tilt")].position() == Approx(1.0).margin(1e-9));
    k.update();
    const auto tilt = f.frame("tilt");
    const Eigen::Vector3d centre_world = k.world_pose(tilt) * Eigen::Vector3d(0, 0, 40);
    CHECK((centre_world - expected).norm() < 1e-9);
}

TEST_CASE("rig kinematics: a piezo channel's joint is the actuator's extension in mm", "[device][kinematics]")
{
    Fixture f;
    f.build();
    const auto& piezo = f.rig->joint_bindings()[f.frame("piezo")];
    const auto* actuator = f.rig->world().find_as<models::PiezoActuator>("tpz/1");
    REQUIRE(actuator);
    // PZ_SET_OUTPUTVOLTS (p. 113), channel 1, half of the voltage range.
    const std::string frame{"\x43\x06\x04\x00\xd0\x01\x01\x00\x00\x40", 10};
    auto session = f.device<apt::AptDevice>("tpz").open_session([](std::string_view) {}, "test");
    session->receive(frame);
    f.rig->clock().advance(1);
    CHECK(piezo.drive.velocity() > 0);
    f.rig->clock().advance_ms(100);
    CHECK(actuator->extension_um() > 5);
    CHECK(piezo.position() == Approx(actuator->extension_um() / 1000).epsilon(1e-15));
    auto& k = *f.rig->kinematics();
    k.update();
    CHECK(k.world_pose(f.frame("piezo")).translation().y() == Approx(piezo.position()).margin(1e-12));
}

TEST_CASE("rig kinematics: a joint that does not suit its stage is a config error at build", "[device][kinematics]")
{
    auto k = kinematics();
    k["frames"][2]["joint"] = json{{"type", "revolute"}, {"axis", {0, 0, 1}}};
    Fixture f(k);
    CHECK(f.build_error() == "rig.json: /kinematics/frames/2/joint/type: a revolute joint on a linear stage (stack channel 0)");
    // Nothing opened: no pty symlink left.
    CHECK(f.dir.entries().empty());
    CHECK(check_error(k) == "rig.json: /kinematics/frames/2/joint/type: a revolute joint on a linear stage (stack channel 0)");

    k = kinematics();
    k["frames"][1]["joint"] = json{{"type", "prismatic"}, {"axis", {0, 0, 1}}};
    CHECK(check_error(k) ==
          "rig.json: /kinematics/frames/1/joint/type: a prismatic joint on a rotary stage (apt_rot channel 0)");
    k = kinematics();
    k["frames"][1]["joint"] = json{{"type", "goniometer"}, {"axis", {0, 0, 1}}, {"centre_mm", {0, 0, 1}}};
    CHECK(check_error(k) ==
          "rig.json: /kinematics/frames/1/joint/type: a goniometer joint on a rotary stage (apt_rot channel 0)");
    k = kinematics();
    k["frames"][3]["joint"] = json{{"type", "prismatic"}, {"axis", {0, 0, 1}}};
    CHECK(check_error(k) ==
          "rig.json: /kinematics/frames/3/joint/type: a prismatic joint on a goniometer stage (stack channel 3)");
    // An APT goniometer stage: a goniometer or revolute joint, nothing else.
    k = kinematics();
    k["frames"][4] = json::parse(R"({"name": "g", "parent": "table", "axis": {"device": "apt_gonio", "channel": 0},
                                    "joint": {"type": "goniometer", "axis": [1, 0, 0], "centre_mm": [0, 0, 20]}})");
    CHECK(check_error(k) == "(no error)");
    k["frames"][4]["joint"] = json{{"type", "prismatic"}, {"axis", {0, 0, 1}}};
    CHECK(check_error(k) ==
          "rig.json: /kinematics/frames/4/joint/type: a prismatic joint on a goniometer stage (apt_gonio channel 0)");
    // A goniometer may drive a revolute joint; a piezo a prismatic one.
    k = kinematics();
    k["frames"][3]["joint"] = json{{"type", "revolute"}, {"axis", {1, 0, 0}}};
    CHECK(check_error(k) == "(no error)");
    k["frames"][4]["joint"] = json{{"type", "revolute"}, {"axis", {1, 0, 0}}};
    CHECK(check_error(k) == "rig.json: /kinematics/frames/4/joint/type: a revolute joint on a linear stage (tpz channel 0)");
}

TEST_CASE("rig kinematics: a channel out of range or that moves nothing is a config error at build",
          "[device][kinematics]")
{
    auto k = kinematics();
    k["frames"][2]["axis"]["channel"] = 9;
    Fixture f(k);
    CHECK(f.build_error() == "rig.json: /kinematics/frames/2/axis/channel: device \"stack\": no channel 9 (the device has 5)");
    CHECK(check_error(k) == "rig.json: /kinematics/frames/2/axis/channel: device \"stack\": no channel 9 (the device has 5)");

    k = kinematics();
    k["frames"][2]["axis"]["channel"] = 2;
    CHECK(check_error(k) == "rig.json: /kinematics/frames/2/axis: device \"stack\": channel 2 is an end effector "
                            "(gripper, force sensor): it moves nothing");
    k = kinematics();
    k["frames"][1]["axis"]["channel"] = 1;
    CHECK(check_error(k) ==
          "rig.json: /kinematics/frames/1/axis/channel: device \"apt_rot\": no channel 1: the KDC101 has channel 0 only");
    k = kinematics();
    k["frames"][4]["axis"]["device"] = "tsc";
    CHECK(check_error(k) == "rig.json: /kinematics/frames/4/axis: device \"tsc\": channel 0 of the TSC001 (a solenoid "
                            "controller) moves nothing");
    CHECK(check_error(kinematics()) == "(no error)");
}

} // namespace test_rig_kinematics
