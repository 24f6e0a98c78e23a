// The physical face of the world's bodies (models/body.hpp): every body has a kind, and a body
// that moves offers its one degree of freedom in SI units, metres or radians by its kind, while
// it keeps its own resolution inside.

#include "models/axis.hpp"
#include "models/body_joint.hpp"
#include "models/piezo_actuator.hpp"
#include "models/solenoid.hpp"
#include "models/stick_slip.hpp"
#include "models/world.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

namespace test_body_face {

using namespace rigsim;
using namespace rigsim::models;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A servo on a 50 mm stage of 2,000 counts per mm (0.5 µm per count), standing mid-travel.
AxisConfig linear_axis()
{
    AxisConfig c;
    c.drive = Drive::Servo;
    c.kind = BodyKind::Linear;
    c.si_per_count = 0.5e-6;
    c.travel_min_counts = 0;
    c.travel_max_counts = 100'000;
    c.start_position_counts = 50'000;
    return c;
}

} // namespace

TEST_CASE("every kind has its name and its travel", "[body]")
{
    CHECK(body_kind_name(BodyKind::Linear) == "linear");
    CHECK(body_kind_name(BodyKind::PiezoActuator) == "piezo_actuator");
    CHECK(body_kind_name(BodyKind::StrainGauge) == "strain_gauge");
    CHECK(travel_of(BodyKind::Linear) == Travel::Line);
    CHECK(travel_of(BodyKind::PiezoActuator) == Travel::Line);
    CHECK(travel_of(BodyKind::Rotary) == Travel::Angle);
    CHECK(travel_of(BodyKind::Goniometer) == Travel::Angle);
    CHECK(travel_of(BodyKind::Solenoid) == Travel::None);
    CHECK(travel_of(BodyKind::Watch) == Travel::None);
}

TEST_CASE("an axis shows its counts in metres and is placed and stopped in metres", "[body]")
{
    Clock clock;
    World world(clock);
    auto& axis = world.emplace<Axis>("kdc/1", clock, linear_axis());
    const Body& body = axis;
    CHECK(body.kind() == BodyKind::Linear);
    CHECK(body.position_m() == Approx(0.025));
    CHECK(body.travel_m().min == 0.0);
    CHECK(body.travel_m().max == Approx(0.05));
    CHECK_THROWS_AS(body.angle_rad(), std::logic_error);
    CHECK_FALSE(body.settling());

    axis.place_m(0.01);
    CHECK(axis.position_counts() == Approx(20'000));
    axis.place_m(1.0);   // clamped to the end stop
    CHECK(axis.position_counts() == Approx(100'000));

    // Moving down at 10,000 counts/s = 5 mm/s, an obstacle at 45 mm stops it there (a servo stalls).
    axis.move_to(0, 10'000, 1e9);
    clock.advance(1);
    CHECK(body.settling());
    CHECK(body.velocity_m_per_s() == Approx(-0.005));
    CHECK(body.stoppable());
    axis.set_obstacles_m(0.045, std::nullopt);
    clock.advance(2'000);
    CHECK_FALSE(body.settling());
    CHECK(body.position_m() == Approx(0.045));
    CHECK(axis.position_counts() == Approx(90'000));
}

TEST_CASE("a rotation stage turns in radians and has no end stops", "[body]")
{
    Clock clock;
    World world(clock);
    AxisConfig c = linear_axis();
    c.kind = BodyKind::Rotary;
    c.rotary = true;
    c.si_per_count = kPi / 180.0 / 1'000;   // 1,000 counts per degree
    c.travel_min_counts = -1e9;
    c.travel_max_counts = 1e9;
    c.start_position_counts = 90'000;
    auto& axis = world.emplace<Axis>("tdc/1", clock, c);
    CHECK(axis.angle_rad() == Approx(kPi / 2));
    CHECK(std::isinf(axis.travel_rad().min));
    CHECK(std::isinf(axis.travel_rad().max));
    CHECK_THROWS_AS(axis.position_m(), std::logic_error);
    axis.place_rad(kPi);
    CHECK(axis.position_counts() == Approx(180'000));
}

TEST_CASE("an axis refuses a kind that disagrees with it", "[body]")
{
    Clock clock;
    AxisConfig c = linear_axis();
    c.rotary = true;   // no end stops, yet said to be linear
    CHECK_THROWS_AS(Axis(clock, c), std::invalid_argument);
    c = linear_axis();
    c.kind = BodyKind::Solenoid;
    CHECK_THROWS_AS(Axis(clock, c), std::invalid_argument);
    c = linear_axis();
    c.si_per_count = -1;
    CHECK_THROWS_AS(Axis(clock, c), std::invalid_argument);
    // A bare axis (a test's, without a scale) has no face.
    c = linear_axis();
    c.si_per_count = 0;
    const Axis bare(clock, c);
    CHECK_THROWS_AS(bare.position_m(), std::logic_error);
}

TEST_CASE("a stick-slip positioner keeps nm or µ° inside and shows metres or radians", "[body]")
{
    Clock clock;
    World world(clock);
    StickSlipConfig linear;
    linear.start_position_nm = 1'500'000;
    linear.travel_min_nm = -5e6;
    linear.travel_max_nm = 5e6;
    auto& stage = world.emplace<StickSlipPositioner>("mcs/0", clock, linear);
    CHECK(stage.kind() == BodyKind::Linear);
    CHECK(stage.position_m() == Approx(1.5e-3));
    CHECK(stage.travel_m().max == Approx(5e-3));
    stage.place_m(-1.0);   // clamped to the end stop
    CHECK(stage.position_nm() == Approx(-5e6));

    StickSlipConfig gonio;
    gonio.kind = BodyKind::Goniometer;
    gonio.start_position_nm = 2e6;   // µ°: 2°
    auto& cradle = world.emplace<StickSlipPositioner>("mcs/1", clock, gonio);
    CHECK(cradle.angle_rad() == Approx(2.0 * kPi / 180.0));
    cradle.place_rad(-kPi / 180.0);
    CHECK(cradle.position_nm() == Approx(-1e6));
    CHECK_THROWS_AS(cradle.position_m(), std::logic_error);

    // An obstacle in radians stops a closed-loop move there.
    cradle.move_to(10e6, 1e6, 0);
    cradle.set_obstacles_rad(std::nullopt, 0.0);
    clock.advance(20'000);
    CHECK(cradle.position_nm() == Approx(0.0).margin(1e-6));
    CHECK_FALSE(cradle.settling());
}

TEST_CASE("a piezo actuator shows its extension in metres and pushes on against an obstacle", "[body]")
{
    Clock clock;
    World world(clock);
    PiezoActuatorConfig c;
    c.travel_um = 20;
    c.max_voltage_v = 75;
    c.response_ms = 1.0;
    auto& piezo = world.emplace<PiezoActuator>("tpz/1", clock, c);
    CHECK(piezo.kind() == BodyKind::PiezoActuator);
    CHECK(piezo.position_m() == Approx(0.0).margin(1e-12));
    CHECK(piezo.travel_m().max == Approx(20e-6));
    CHECK_FALSE(piezo.stoppable());
    CHECK_THROWS_AS(piezo.set_obstacles_m(0.0, std::nullopt), std::logic_error);
    CHECK_THROWS_AS(piezo.place_m(1e-6), std::logic_error);
    piezo.set_voltage(75);
    CHECK(piezo.settling());
    CHECK(piezo.velocity_m_per_s() > 0.0);
    clock.advance(100);
    CHECK(piezo.position_m() == Approx(piezo.extension_um() * 1e-6));
}

TEST_CASE("a body without travel has a kind and no position", "[body]")
{
    Clock clock;
    World world(clock);
    auto& solenoid = world.emplace<Solenoid>("tsc/1");
    CHECK(solenoid.kind() == BodyKind::Solenoid);
    CHECK(solenoid.travel() == Travel::None);
    CHECK_FALSE(solenoid.stoppable());
    CHECK_THROWS_AS(solenoid.position_m(), std::logic_error);
    CHECK_THROWS_AS(solenoid.angle_rad(), std::logic_error);
}

TEST_CASE("a body as a joint: mm or degrees from its face, obstacles back through it", "[body]")
{
    CHECK(body_suits(BodyKind::Linear, JointType::Prismatic));
    CHECK(body_suits(BodyKind::PiezoActuator, JointType::Prismatic));
    CHECK_FALSE(body_suits(BodyKind::Linear, JointType::Revolute));
    CHECK(body_suits(BodyKind::Rotary, JointType::Revolute));
    CHECK_FALSE(body_suits(BodyKind::Rotary, JointType::Goniometer));
    CHECK(body_suits(BodyKind::Goniometer, JointType::Goniometer));
    CHECK(body_suits(BodyKind::Goniometer, JointType::Revolute));
    CHECK_FALSE(body_suits(BodyKind::Solenoid, JointType::Prismatic));

    Clock clock;
    World world(clock);
    auto& axis = world.emplace<Axis>("kdc/1", clock, linear_axis());
    const JointReader q = joint_reader(axis);
    CHECK(q() == Approx(25.0));   // mm
    JointDrive drive = joint_drive(axis);
    CHECK(drive.body_key == "kdc/1");
    REQUIRE(drive.set_obstacles);
    drive.set_obstacles(std::nullopt, 30.0);   // mm
    REQUIRE(axis.obstacle_max_counts());
    CHECK(*axis.obstacle_max_counts() == Approx(60'000));
    axis.move_to(100'000, 10'000, 1e9);
    clock.advance(1);
    CHECK(drive.velocity() == Approx(5.0));   // mm/s

    StickSlipConfig gonio;
    gonio.kind = BodyKind::Goniometer;
    gonio.start_position_nm = 3e6;   // µ°
    auto& cradle = world.emplace<StickSlipPositioner>("mcs/3", clock, gonio);
    CHECK(joint_reader(cradle)() == Approx(3.0));   // degrees
    joint_drive(cradle).set_obstacles(-2.0, std::nullopt);
    REQUIRE(cradle.obstacle_min_nm());
    CHECK(*cradle.obstacle_min_nm() == Approx(-2e6));

    PiezoActuatorConfig pc;
    auto& piezo = world.emplace<PiezoActuator>("tpz/1", clock, pc);
    CHECK_FALSE(joint_drive(piezo).set_obstacles);   // it pushes on
    auto& solenoid = world.emplace<Solenoid>("tsc/1");
    CHECK_THROWS_AS(joint_reader(solenoid), std::invalid_argument);
    CHECK_THROWS_AS(joint_drive(solenoid), std::invalid_argument);
}

TEST_CASE("physical faults act on a body by its key, combined, and end one by one", "[body][faults]")
{
    Clock clock;
    World world(clock);
    AxisConfig c = linear_axis();
    c.drive = Drive::Stepper;
    auto& axis = world.emplace<Axis>("bsc/1", clock, c);

    BodyFault slip{PhysicalFault::Slip, 10.0, 0.5, 0};
    world.add_fault(1, "bsc/1", slip);
    BodyFault slip2{PhysicalFault::Slip, 5.0, 0.5, 0};
    world.add_fault(2, "bsc/1", slip2);
    CHECK(axis.faults().slip_steps == 15.0);
    CHECK(axis.faults().slip_fraction == 0.75);   // the second takes half of what the first left
    world.add_fault(3, "bsc/1", BodyFault{PhysicalFault::LimitSwitch, {}, {}, +1});
    world.add_fault(4, "bsc/1", BodyFault{PhysicalFault::LimitSwitch, {}, {}, -1});
    CHECK(axis.switch_pressed() == -1);   // the newest switch
    CHECK(world.fault_body(4) == &axis);
    CHECK(world.remove_fault(4));
    CHECK(axis.switch_pressed() == +1);
    CHECK_FALSE(world.remove_fault(4));
    CHECK(world.fault_body(4) == nullptr);

    // A switch held by hand (a test's set-up) reads pressed once no fault presses one.
    axis.set_switch_held(-1);
    CHECK(axis.switch_pressed() == +1);
    world.remove_fault(3);
    CHECK(axis.switch_pressed() == -1);
    axis.set_switch_held(0);
    CHECK(axis.switch_pressed() == 0);

    world.add_fault(5, "bsc/1", BodyFault{PhysicalFault::Stall, {}, {}, 0});
    CHECK(axis.jammed());
    world.add_fault(6, "bsc/1", BodyFault{PhysicalFault::SensorFailure, {}, {}, 0});
    CHECK(axis.faults().sensor_failed);
    world.remove_fault(5);
    CHECK_FALSE(axis.jammed());
    axis.set_loop_open(true);   // the device's: a servo without its encoder
    CHECK(axis.jammed());
    axis.set_loop_open(false);
    CHECK_FALSE(axis.jammed());

    CHECK_THROWS_WITH(world.add_fault(1, "bsc/1", BodyFault{}), "fault 1 is active already");
    CHECK_THROWS_WITH(world.add_fault(7, "nope/0", BodyFault{}), "the world has no body \"nope/0\"");
}

TEST_CASE("a body refuses the faults it cannot suffer, in the API's words", "[body][faults]")
{
    Clock clock;
    World world(clock);
    world.emplace<Axis>("kdc/1", clock, linear_axis());   // a servo
    CHECK_THROWS_WITH(world.add_fault(1, "kdc/1", BodyFault{PhysicalFault::Slip, 10.0, {}, 0}),
                      Catch::StartsWith("slip: a servo closes its position loop on the encoder"));
    AxisConfig c = linear_axis();
    c.drive = Drive::Stepper;
    world.emplace<Axis>("bsc/1", clock, c);
    CHECK_THROWS_WITH(world.add_fault(2, "bsc/1", BodyFault{PhysicalFault::Slip, {}, {}, 0}),
                      Catch::StartsWith("slip needs \"counts\""));

    auto& stage = world.emplace<StickSlipPositioner>("mcs/0", clock, StickSlipConfig{});
    CHECK_THROWS_WITH(world.add_fault(3, "mcs/0", BodyFault{PhysicalFault::LimitSwitch, {}, {}, 1}),
                      Catch::StartsWith("\"kind\": limit_switch: a stick-slip positioner has no limit switches"));
    CHECK_THROWS_WITH(world.add_fault(4, "mcs/0", BodyFault{PhysicalFault::Slip, 3.0, {}, 0}),
                      Catch::StartsWith("counts: a stick-slip positioner slips by a fraction"));
    CHECK_THROWS_WITH(world.add_fault(5, "mcs/0", BodyFault{PhysicalFault::Slip, {}, 1.0, 0}),
                      Catch::StartsWith("fraction: a number from 0 up to (not including) 1"));
    world.add_fault(6, "mcs/0", BodyFault{PhysicalFault::Slip, {}, {}, 0});
    CHECK(stage.slip() == 0.5);   // half of each step when no fraction is given
    world.add_fault(7, "mcs/0", BodyFault{PhysicalFault::Stall, {}, {}, 0});
    CHECK(stage.blocked());

    world.emplace<Solenoid>("tsc/1");
    CHECK_THROWS_WITH(world.add_fault(8, "tsc/1", BodyFault{PhysicalFault::Stall, {}, {}, 0}),
                      "\"kind\": stall: a solenoid (tsc/1) has no such fault");
    CHECK(world.fault_body(8) == nullptr);
}

} // namespace test_body_face
