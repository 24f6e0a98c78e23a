// Sensors on moved frames (issue 13: "a strain gauge or a sensor mounted on a moved frame reads the
// world"): a TSG001 on a TPZ001 that a KDC101 carries reads the actuator's own extension in the
// world, whatever the coarse stage under it does, while the frames follow both; a stepper's lost
// microsteps move its counters, not its frame.
#include "emulator/daemon/rig.hpp"
#include "emulator/daemon/rig_families.hpp"
#include "models/axis.hpp"
#include "models/piezo_actuator.hpp"
#include "models/strain_gauge.hpp"
#include "tests/support/temp_dir.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <boost/asio/io_context.hpp>

#include <memory>
#include <string>

namespace test_rig_kinematics_sensors {

using nlohmann::json;
using namespace rigsim;

namespace {

/// A KDC101 (Z825B, 34,304 counts/mm) carrying a TPZ001 whose actuator pushes a holder along x, a
/// noiseless TSG001 on that actuator, and a TST001 (DRV001 stepper) driving a separate y frame.
json rig_json()
{
    return json::parse(R"({
      "devices": [
        {"name": "coarse", "protocol": "apt", "model": "KDC101", "apt": {"stage": "Z825B"}},
        {"name": "fine", "protocol": "apt", "model": "TPZ001",
         "apt": {"actuator": {"travel_um": 20, "hysteresis": 0, "creep": 0}}},
        {"name": "gauge", "protocol": "apt", "model": "TSG001",
         "apt": {"gauge": {"mounted_on": "fine", "noise_um": 0}}},
        {"name": "side", "protocol": "apt", "model": "TST001", "apt": {"stage": "DRV001"}}
      ],
      "kinematics": {
        "frames": [
          {"name": "table"},
          {"name": "coarse", "parent": "table", "axis": {"device": "coarse", "channel": 0},
           "joint": {"type": "prismatic", "axis": [1, 0, 0]}},
          {"name": "fine", "parent": "coarse", "offset": {"translation_mm": [0, 0, 10]},
           "axis": {"device": "fine", "channel": 0}, "joint": {"type": "prismatic", "axis": [1, 0, 0]}},
          {"name": "side", "parent": "table", "axis": {"device": "side", "channel": 0},
           "joint": {"type": "prismatic", "axis": [0, 1, 0]}}
        ],
        "tools": [{"name": "tip", "parent": "fine", "offset": {"translation_mm": [25, 0, 0]}}]
      }
    })");
}

struct Fixture {
    Fixture() : config(parse_rig_config(rig_json().dump(), "rig.json"))
    {
        options.pty_dir = dir.path();
        options.ephemeral_ports = true;
        options.paused = true;
        options.log_levels.global = spdlog::level::warn;
        rig = std::make_unique<Rig>(io, config, options);
    }
    /// World x of frame `name` after an update.
    double x(const std::string& name)
    {
        auto& k = *rig->kinematics();
        k.update();
        return k.world_pose(*k.find(name)).translation().x();
    }
    double y(const std::string& name)
    {
        auto& k = *rig->kinematics();
        k.update();
        return k.world_pose(*k.find(name)).translation().y();
    }

    test::TempDir dir;
    boost::asio::io_context io;
    RigConfig config;
    RigOptions options;
    std::unique_ptr<Rig> rig;
};

} // namespace

TEST_CASE("rig kinematics sensors: a gauge on a moved frame reads its actuator, not the stage under it",
          "[device][kinematics]")
{
    Fixture f;
    auto* actuator = f.rig->world().find_as<models::PiezoActuator>("fine/1");
    auto* gauge = f.rig->world().find_as<models::StrainGauge>("gauge/1");
    auto* coarse = f.rig->world().find_as<models::Axis>("coarse/1");
    REQUIRE(actuator);
    REQUIRE(gauge);
    REQUIRE(coarse);

    // The piezo at half its voltage: about 10 µm out; let it settle.
    actuator->set_voltage(37.5);
    f.rig->clock().advance_ms(200);
    const double extension_um = actuator->extension_um();
    REQUIRE(extension_um == Approx(10).margin(0.01));
    const double reading_before = gauge->reading_um(f.rig->clock().now());
    CHECK(reading_before == Approx(extension_um).margin(1e-9));
    const double tip_before = f.x("tip");
    CHECK(tip_before == Approx(12.5 + extension_um / 1000 + 25).epsilon(0).margin(1e-9));

    // The coarse stage moves 3 mm (34,304 counts per mm) under the piezo.
    coarse->move_to(coarse->position_counts() + 3 * 34304.0, 2 * 34304.0, 4 * 34304.0);
    f.rig->clock().advance_ms(5000);
    REQUIRE_FALSE(coarse->moving());
    CHECK(f.x("coarse") == Approx(15.5).epsilon(0).margin(1e-9));
    CHECK(f.x("tip") == Approx(tip_before + 3).epsilon(0).margin(1e-9));
    // The gauge measures the actuator's extension: the frame it rides on moved, the reading did not.
    CHECK(gauge->reading_um(f.rig->clock().now()) == Approx(reading_before).margin(1e-9));

    // The piezo extends: the gauge and the tip see the same micrometres.
    actuator->set_voltage(75);
    f.rig->clock().advance_ms(200);
    const double moved_um = actuator->extension_um() - extension_um;
    REQUIRE(moved_um == Approx(10).margin(0.02));
    CHECK(gauge->reading_um(f.rig->clock().now()) - reading_before == Approx(moved_um).margin(1e-9));
    CHECK((f.x("tip") - tip_before - 3) * 1000 == Approx(moved_um).margin(1e-6));
}

TEST_CASE("rig kinematics sensors: a stepper's lost microsteps move its counters, not its frame",
          "[device][kinematics]")
{
    Fixture f;
    auto* side = f.rig->world().find_as<models::Axis>("side/1");
    REQUIRE(side);
    const double start_mm = f.y("side");
    // Half of every move's microsteps are lost: the motor (and so the counters) reach the target,
    // the carriage, which the frame follows, only half way.
    side->set_slip(0, 0.5);
    const double counts_per_mm = 51200;   // the DRV001 on a TST001
    side->move_to(side->position_counts() + 2 * counts_per_mm, counts_per_mm, 2 * counts_per_mm);
    f.rig->clock().advance_ms(10000);
    REQUIRE_FALSE(side->moving());
    CHECK(side->motor_position_counts() - side->position_counts() == Approx(counts_per_mm).margin(1e-6));
    CHECK(f.y("side") == Approx(start_mm + 1).epsilon(0).margin(1e-9));
}

} // namespace test_rig_kinematics_sensors
