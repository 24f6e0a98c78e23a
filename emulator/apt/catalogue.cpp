#include "emulator/apt/catalogue.hpp"

#include <array>

namespace rigsim::apt {
namespace {

// Each model is a constexpr function that sets its fields by name on the defaults of
// catalogue.hpp; models of one family start from the family's function.

// DC servo T-Cube/K-Cube: a 6 MHz clock, 2048-cycle sample interval T = 2048 / 6e6 s;
// velocity = counts/s × T × 65536, acceleration = counts/s² × T² × 65536 (Thorlabs' APT
// scaling; with 34,304 counts/mm: 767,367 per mm/s and 261.93 per mm/s²).
constexpr double kDcT = 2048.0 / 6e6;
constexpr double kDcVelocity = kDcT * 65536.0;
constexpr double kDcAcceleration = kDcT * kDcT * 65536.0;

/// A single-unit controller (T-Cube, K-Cube) of HW_GET_INFO type 31.
constexpr ControllerModel cube(std::string_view name, std::uint32_t serial_prefix, MotorKind motor,
                               std::string_view notes)
{
    ControllerModel c;
    c.name = name;
    c.serial_prefix = serial_prefix;
    c.hw_type = 31;
    c.motor = motor;
    c.notes = notes;
    return c;
}

// Stepper controllers: VELPARAMS are "in encoder counts/sec ... For stepper controllers the
// position steps are in micro-steps" (p. 29), i.e. microsteps/s and microsteps/s².
constexpr ControllerModel stepper_cube(std::string_view name, std::uint32_t serial_prefix, std::string_view notes)
{
    auto c = cube(name, serial_prefix, MotorKind::Stepper, notes);
    c.velocity_per_count_s = 1.0;
    c.acceleration_per_count_s2 = 1.0;
    return c;
}

constexpr ControllerModel dc_servo_cube(std::string_view name, std::uint32_t serial_prefix, std::string_view notes)
{
    auto c = cube(name, serial_prefix, MotorKind::DcServo, notes);
    c.velocity_per_count_s = kDcVelocity;
    c.acceleration_per_count_s2 = kDcAcceleration;
    return c;
}

// 2.2: "80xxxxxx Stepper Driver T-Cube TST001"; Thorlabs' K-Cube stepper: 26xxxxxx.
constexpr ControllerModel tst001()
{
    return stepper_cube("TST001", 80, "APT Stepper Motor Controller");
}

constexpr ControllerModel kst101()
{
    auto c = stepper_cube("KST101", 26, "Stepper Motor Controller");
    c.rich_fault_reports = true;
    return c;
}

// 2.2: "83xxxxxx DC servo driver T-Cube TDC001"; Thorlabs' K-Cube DC servo: 27xxxxxx.
constexpr ControllerModel tdc001()
{
    return dc_servo_cube("TDC001", 83, "APT DC Motor Controller");
}

constexpr ControllerModel kdc101()
{
    auto c = dc_servo_cube("KDC101", 27, "Brushed Motor Controller");
    c.rich_fault_reports = true;
    return c;
}

// 2.2: "70xxxxxx Three channel card slot stepper driver BSC103"; its successor BSC203 keeps
// the card-slot scheme. The manual names no HW type for stepper cards: 45 for both.
constexpr ControllerModel bsc203()
{
    ControllerModel c;
    c.name = "BSC203";
    c.serial_prefix = 70;
    c.hw_type = 45;
    c.motor = MotorKind::Stepper;
    c.notes = "Stepper Motor Controller";
    c.velocity_per_count_s = 1.0;
    c.acceleration_per_count_s2 = 1.0;
    c.rack = true;
    c.max_bays = 3;
    c.bay_hw_type = 45;
    c.bay_serial_prefix = 70;
    return c;
}

// 2.2: "73xxxxxx Brushless DC motherboard BBD102/BBD103", "94xxxxxx Brushless DC motor
// card"; HW_GET_INFO types 45 (motherboard) and 44 (brushless card). Scaling: 7.1 gives the
// MLS203 figures per mm at 20,000 counts/mm; per count they hold for any stage the PMD
// processor drives (DDSM100 at 2,000 counts/mm: 13,421.8 per mm/s).
constexpr ControllerModel bbd203()
{
    ControllerModel c;
    c.name = "BBD203";
    c.serial_prefix = 73;
    c.hw_type = 45;
    c.motor = MotorKind::Brushless;
    c.notes = "Brushless DC Motor Controller";
    c.velocity_per_count_s = 134'218.0 / 20'000.0;
    c.acceleration_per_count_s2 = 13.7439 / 20'000.0;
    c.rack = true;
    c.max_bays = 3;
    c.bay_hw_type = 44;
    c.bay_serial_prefix = 94;
    c.jerk_per_count_s3 = 92.2337 / 20'000.0;
    return c;
}

constexpr std::array<ControllerModel, 6> kControllers{tst001(), kst101(), tdc001(), kdc101(), bsc203(), bbd203()};

/// A stage: its name, motor and travel.
constexpr StageModel stage(std::string_view name, MotorKind motor, double travel_mm)
{
    StageModel s;
    s.name = name;
    s.motor = motor;
    s.travel_mm = travel_mm;
    return s;
}

// Stepper actuators on a 1 mm lead screw: 25,600 microsteps per mm ("In the APT Stepper Motor
// controllers the encoder resolution is 25,600 counts per mm", p. 77).
constexpr StageModel stepper_actuator(std::string_view name, double travel_mm)
{
    auto s = stage(name, MotorKind::Stepper, travel_mm);
    s.counts_per_mm = 25'600.0;
    s.max_velocity_mm_s = 2.0;
    s.acceleration_mm_s2 = 4.0;
    s.home_velocity_mm_s = 1.0;
    s.home_offset_mm = 0.5;
    return s;
}

// Z8 actuators: 512-count encoder, 67.49:1 gearbox, 1 mm lead screw: 34,304 counts per mm
// (34,555 in some documents; Thorlabs' APT software uses 34,304).
constexpr StageModel z8_actuator(std::string_view name, double travel_mm, double max_velocity_mm_s,
                                 double acceleration_mm_s2)
{
    auto s = stage(name, MotorKind::DcServo, travel_mm);
    s.counts_per_mm = 34'304.0;
    s.max_velocity_mm_s = max_velocity_mm_s;
    s.acceleration_mm_s2 = acceleration_mm_s2;
    s.home_velocity_mm_s = 1.0;
    s.home_offset_mm = 0.3;
    return s;
}

// PRM1-Z8 rotation stage: the Z8 motor through a 1:20.145 worm, 1,919.64 counts per degree;
// continuous rotation, a home switch; APT defaults 10 deg/s, 10 deg/s², home offset 4 deg.
constexpr StageModel prm1_z8()
{
    auto s = stage("PRM1-Z8", MotorKind::DcServo, 360.0);
    s.counts_per_mm = 1'919.6418;
    s.max_velocity_mm_s = 10.0;
    s.acceleration_mm_s2 = 10.0;
    s.home_velocity_mm_s = 10.0;
    s.home_offset_mm = 4.0;
    s.rotary = true;
    return s;
}

// MLS203 (7.1): 20,000 counts/mm; X 110 mm, Y 75 mm of travel. p. 76's example: part number
// "MLS203 Y Axis", MaxAccn 27,488 (2,000 mm/s²), MaxVel 26,843,546 (200 mm/s).
constexpr StageModel mls203_axis(std::string_view name, double travel_mm, std::uint16_t pmd_stage_id,
                                 std::string_view pmd_part_number)
{
    auto s = stage(name, MotorKind::Brushless, travel_mm);
    s.counts_per_mm = 20'000.0;
    s.max_velocity_mm_s = 100.0;
    s.acceleration_mm_s2 = 500.0;
    s.home_velocity_mm_s = 10.0;
    s.home_offset_mm = 1.0;
    s.velocity_per_mm_s = 134'218.0;
    s.acceleration_per_mm_s2 = 13.7439;
    s.pmd_stage_id = pmd_stage_id;
    s.pmd_part_number = pmd_part_number;
    s.pmd_max_velocity = 26'843'546;
    s.pmd_max_acceleration = 27'488;
    return s;
}

// DDSM100 direct-drive stage: 100 mm, 0.5 µm encoder (2,000 counts/mm), 500 mm/s, 5,000 mm/s².
constexpr StageModel ddsm100()
{
    auto s = stage("DDSM100", MotorKind::Brushless, 100.0);
    s.counts_per_mm = 2'000.0;
    s.max_velocity_mm_s = 500.0;
    s.acceleration_mm_s2 = 5'000.0;
    s.home_velocity_mm_s = 5.0;
    s.home_offset_mm = 0.5;
    return s;
}

constexpr std::array<StageModel, 11> kStages{
    stepper_actuator("DRV001", 13.0),
    stepper_actuator("ZST225B", 25.0),
    // DRV014: 50 mm of travel on the same 1 mm lead screw and motor as the DRV001.
    stepper_actuator("DRV014", 50.0),
    z8_actuator("MTS50-Z8", 50.0, 2.4, 1.5),
    z8_actuator("MTS25-Z8", 25.0, 2.4, 1.5),
    z8_actuator("Z825B", 25.0, 2.6, 4.0),
    z8_actuator("Z812B", 12.0, 2.6, 4.0),
    prm1_z8(),
    mls203_axis("MLS203-X", 110.0, 0x10, "MLS203 X Axis"),
    mls203_axis("MLS203-Y", 75.0, 0x11, "MLS203 Y Axis"),
    ddsm100(),
};

} // namespace

const ControllerModel* find_controller(std::string_view name)
{
    for (const auto& c : kControllers)
        if (c.name == name)
            return &c;
    return nullptr;
}

const StageModel* find_stage(std::string_view name)
{
    for (const auto& s : kStages)
        if (s.name == name)
            return &s;
    return nullptr;
}

std::string_view controller_names()
{
    return "TDC001, KDC101, TST001, KST101, BSC203, BBD203";
}

std::string_view stage_names()
{
    return "DRV001, ZST225B, DRV014, MTS50-Z8, MTS25-Z8, Z825B, Z812B, PRM1-Z8, MLS203-X, MLS203-Y, DDSM100";
}

} // namespace rigsim::apt
