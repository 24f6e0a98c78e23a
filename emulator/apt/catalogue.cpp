#include "emulator/apt/catalogue.hpp"

#include <array>

namespace rigsim::apt {
namespace {

// DC servo T-Cube/K-Cube: a 6 MHz clock, 2048-cycle sample interval T = 2048 / 6e6 s;
// velocity = counts/s × T × 65536, acceleration = counts/s² × T² × 65536 (Thorlabs' APT
// scaling; with 34,304 counts/mm: 767,367 per mm/s and 261.93 per mm/s²).
constexpr double kDcT = 2048.0 / 6e6;
constexpr double kDcVelocity = kDcT * 65536.0;
constexpr double kDcAcceleration = kDcT * kDcT * 65536.0;

// Stepper controllers: VELPARAMS are "in encoder counts/sec ... For stepper controllers the
// position steps are in micro-steps" (p. 29), i.e. microsteps/s and microsteps/s².
constexpr std::array<ControllerModel, 6> kControllers{{
    // 2.2: "80xxxxxx Stepper Driver T-Cube TST001"; Thorlabs' K-Cube stepper: 26xxxxxx.
    {"TST001", 80, 31, MotorKind::Stepper, "APT Stepper Motor Controller", 1.0, 1.0},
    {"KST101", 26, 31, MotorKind::Stepper, "Stepper Motor Controller", 1.0, 1.0, false, 1, 0, 0, 0, true},
    // 2.2: "83xxxxxx DC servo driver T-Cube TDC001"; Thorlabs' K-Cube DC servo: 27xxxxxx.
    {"TDC001", 83, 31, MotorKind::DcServo, "APT DC Motor Controller", kDcVelocity, kDcAcceleration},
    {"KDC101", 27, 31, MotorKind::DcServo, "Brushed Motor Controller", kDcVelocity, kDcAcceleration, false, 1, 0, 0,
     0, true},
    // 2.2: "73xxxxxx Brushless DC motherboard BBD102/BBD103", "94xxxxxx Brushless DC motor
    // card"; HW_GET_INFO types 45 (motherboard) and 44 (brushless card). Scaling: 7.1.
    // 2.2: "70xxxxxx Three channel card slot stepper driver BSC103"; its successor BSC203 keeps
    // the card-slot scheme. The manual names no HW type for stepper cards: 45 for both.
    {"BSC203", 70, 45, MotorKind::Stepper, "Stepper Motor Controller", 1.0, 1.0, true, 3, 45, 70},
    // 7.1 gives the MLS203 figures per mm at 20,000 counts/mm; per count they hold for any
    // stage the PMD processor drives (DDSM100 at 2,000 counts/mm: 13,421.8 per mm/s).
    {"BBD203", 73, 45, MotorKind::Brushless, "Brushless DC Motor Controller", 134'218.0 / 20'000.0,
     13.7439 / 20'000.0, true, 3, 44, 94, 92.2337 / 20'000.0},
}};

// Z8 actuators: 512-count encoder, 67.49:1 gearbox, 1 mm lead screw: 34,304 counts per mm
// (34,555 in some documents; Thorlabs' APT software uses 34,304).
constexpr std::array<StageModel, 11> kStages{{
    // Stepper actuators: 25,600 microsteps per mm ("In the APT Stepper Motor controllers the
    // encoder resolution is 25,600 counts per mm", p. 77).
    {"DRV001", MotorKind::Stepper, 13.0, 25'600.0, 2.0, 4.0, 1.0, 0.5},
    {"ZST225B", MotorKind::Stepper, 25.0, 25'600.0, 2.0, 4.0, 1.0, 0.5},
    // DRV014: 50 mm of travel on the same 1 mm lead screw and motor as the DRV001.
    {"DRV014", MotorKind::Stepper, 50.0, 25'600.0, 2.0, 4.0, 1.0, 0.5},
    {"MTS50-Z8", MotorKind::DcServo, 50.0, 34'304.0, 2.4, 1.5, 1.0, 0.3},
    {"MTS25-Z8", MotorKind::DcServo, 25.0, 34'304.0, 2.4, 1.5, 1.0, 0.3},
    {"Z825B", MotorKind::DcServo, 25.0, 34'304.0, 2.6, 4.0, 1.0, 0.3},
    {"Z812B", MotorKind::DcServo, 12.0, 34'304.0, 2.6, 4.0, 1.0, 0.3},
    // PRM1-Z8 rotation stage: the Z8 motor through a 1:20.145 worm, 1,919.64 counts per degree;
    // continuous rotation, a home switch; APT defaults 10 deg/s, 10 deg/s², home offset 4 deg.
    {"PRM1-Z8", MotorKind::DcServo, 360.0, 1'919.6418, 10.0, 10.0, 10.0, 4.0, 0, 0, true},
    // MLS203 (7.1): 20,000 counts/mm; X 110 mm, Y 75 mm of travel.
    // p. 76's example: part number "MLS203 Y Axis", MaxAccn 27,488 (2,000 mm/s²), MaxVel
    // 26,843,546 (200 mm/s).
    {"MLS203-X", MotorKind::Brushless, 110.0, 20'000.0, 100.0, 500.0, 10.0, 1.0, 134'218.0, 13.7439, false, 0x10,
     "MLS203 X Axis", 26'843'546, 27'488},
    {"MLS203-Y", MotorKind::Brushless, 75.0, 20'000.0, 100.0, 500.0, 10.0, 1.0, 134'218.0, 13.7439, false, 0x11,
     "MLS203 Y Axis", 26'843'546, 27'488},
    // DDSM100 direct-drive stage: 100 mm, 0.5 µm encoder (2,000 counts/mm), 500 mm/s, 5,000 mm/s².
    {"DDSM100", MotorKind::Brushless, 100.0, 2'000.0, 500.0, 5'000.0, 5.0, 0.5},
}};

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
