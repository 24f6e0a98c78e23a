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

constexpr std::array<ControllerModel, 2> kControllers{{
    // 2.2: "83xxxxxx DC servo driver T-Cube TDC001"; Thorlabs' K-Cube DC servo: 27xxxxxx.
    {"TDC001", 83, 31, MotorKind::DcServo, "APT DC Motor Controller", kDcVelocity, kDcAcceleration},
    {"KDC101", 27, 31, MotorKind::DcServo, "Brushed Motor Controller", kDcVelocity, kDcAcceleration},
}};

// Z8 actuators: 512-count encoder, 67.49:1 gearbox, 1 mm lead screw: 34,304 counts per mm
// (34,555 in some documents; Thorlabs' APT software uses 34,304).
constexpr std::array<StageModel, 3> kStages{{
    {"MTS50-Z8", MotorKind::DcServo, 50.0, 34'304.0, 2.4, 1.5, 1.0, 0.3},
    {"MTS25-Z8", MotorKind::DcServo, 25.0, 34'304.0, 2.4, 1.5, 1.0, 0.3},
    {"Z825B", MotorKind::DcServo, 25.0, 34'304.0, 2.6, 4.0, 1.0, 0.3},
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
    return "TDC001, KDC101";
}

std::string_view stage_names()
{
    return "MTS50-Z8, MTS25-Z8, Z825B";
}

} // namespace rigsim::apt
