#include "emulator/apt/catalogue.hpp"

#include "emulator/apt/messages.hpp"

#include <array>
#include <utility>

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

// The Trinamic-driven steppers (KST101, BSC20x; also TST101, K10CR1, LTS in pyLabLib's list):
// 2048 microsteps per full step where the manual's (TST001, BSC10x) count 128, velocity
// 53.68 APT units per microstep/s and acceleration 53.68 × 204.94e-6 per microstep/s²
// (AlexShkarin/pyLabLib, pylablib/devices/Thorlabs/kinesis.py, KinesisMotor._calculate_scale
// and _get_step_scale). The DC servo cubes keep T = 2048 / 6e6 s and the brushless racks
// 102.4 µs there: the manual's figures.
constexpr double kTrinamicVelocity = 53.68;
constexpr double kTrinamicAcceleration = 53.68 * 204.94e-6;
constexpr double kTrinamicMicrosteps = 2048.0 / 128.0;

// ---- Units made after the 2012 manual (issue 28; docs/protocol/apt.md "Units of today") ----
// Sources: Thorlabs' "Motion Controllers Host-Controller Communications Protocol", issue 37
// (22 May 2023; a copy in amsikking/thorlabs_MFF101), cited "issue 37 p. N"; Kinesis' default
// settings file (ThorlabsDefaultSettings.xml in Thorlabs/Motion_Control_Examples), cited "Kinesis'
// defaults". Each exists in the later generation only.

/// A Trinamic-driven integrated stepper unit: its built-in stage counts its 2048 microsteps per
/// full step (issue 37 p. 41: velocity = microsteps/s x 53.68, acceleration = microsteps/s² / 90.9).
constexpr ControllerModel integrated_stepper(std::string_view name, std::uint32_t serial_prefix,
                                             std::string_view notes, std::uint16_t hardware_version)
{
    auto c = stepper_cube(name, serial_prefix, notes);
    c.velocity_per_count_s = kTrinamicVelocity;
    c.acceleration_per_count_s2 = kTrinamicAcceleration;
    c.built_in_stage = name;
    c.later_only = true;
    c.rich_fault_reports = true;
    c.hardware_version = hardware_version;
    return c;
}

// K10CR1 cage rotator: prefix 55 (issue 37 p. 33; Kinesis' DeviceType 55 "Cage Rotator", hardware
// revision 3). No public HW_GET_INFO of a real unit gives its type or firmware: type 31 and
// 1.0.3 as the other cubes.
constexpr ControllerModel k10cr1()
{
    return integrated_stepper("K10CR1", 55, "Cage Rotator", 3);
}

// LTS150/LTS300 long-travel stages: prefix 45 (issue 37 p. 33; Kinesis' DeviceType 45
// "LTS(Integrated)"). The ones sold today are the "HS" revisions (Kinesis' hardware revisions 3
// and 4), which count 2048 microsteps per full step (MSLNZ/msl-equipment thorlabs/lts.py: 2048
// when the hardware version is 3 or more, else 128): hardware version 3.
constexpr ControllerModel lts(std::string_view name)
{
    return integrated_stepper(name, 45, "LTS(Integrated)", 3);
}

// KBD101 K-Cube brushless: prefix 28 (issue 37 p. 32); firmware 2.0.8 (amsikking/thorlabs_DDS100
// asserts 131080 from a tested unit); type 44, issue 37 p. 53's "brushless DC controller" (no
// public reading of a real unit's type). The brushless scaling of the BBD203: T = 102.4 us
// (issue 37 p. 39), the same per count for every stage.
constexpr ControllerModel kbd101()
{
    auto c = cube("KBD101", 28, MotorKind::Brushless, "Brushless Motor Controller");
    c.hw_type = 44;
    c.firmware_version = 0x00020008;
    c.velocity_per_count_s = 134'218.0 / 20'000.0;
    c.acceleration_per_count_s2 = 13.7439 / 20'000.0;
    c.jerk_per_count_s3 = 92.2337 / 20'000.0;
    c.later_only = true;
    c.rich_fault_reports = true;
    return c;
}

// ---- Solenoid, piezo and strain-gauge units ----
// Their message sets are takes lists of messages.def (its last column: the manual's cross-reference
// tables, p. 132-138, without the generic messages, with the choices of docs/protocol/errata.md; the
// K-Cubes take their T-Cube's list, and with the later generation their own messages beyond it).

/// The messages on takes list `List` (messages.def's last column).
template <TakesLists List> constexpr MessageSet listed()
{
    return MessageSet{kIdsOnList<List>.data(), kIdsOnList<List>.size()};
}

/// A cube (HW_GET_INFO type 31) driving something else than a motor.
constexpr ControllerModel unit_cube(std::string_view name, std::uint32_t serial_prefix, UnitKind kind,
                                    MessageSet takes, std::string_view notes)
{
    auto c = cube(name, serial_prefix, MotorKind::DcServo, notes);
    c.kind = kind;
    c.takes = takes;
    if (kind != UnitKind::Solenoid)
        c.ack_id = MGMSG_PZ_ACK_PZSTATUSUPDATE;
    c.mmi_wheel = kind != UnitKind::Solenoid;
    return c;
}

// MFF101/MFF102 motorised flip mounts (issue 28): prefix 37 (issue 37 p. 32, "MFF10X"); the unit
// reports its model as "MFF002" (amsikking/thorlabs_MFF101 asserts it of an MFF101; no reading of
// an MFF102, whose controller is the same: the same name) and firmware 1.0.3 (that driver asserts
// 65539). HW_GET_INFO type not published: 31 as the other cubes. Its messages: list kMff.
constexpr ControllerModel mff(std::string_view name)
{
    auto c = unit_cube(name, 37, UnitKind::Flipper, listed<kMff>(), "MFF Filter Flipper");
    c.reported_name = "MFF002";
    c.later_only = true;
    c.ack_id = MGMSG_MOT_ACK_DCSTATUSUPDATE;
    c.mmi_wheel = false;
    return c;
}

// MPC320/MPC220 motorised polarisation controllers (issue 28): prefix 38 (Thorlabs/Motion_Control_
// Examples 38000001, PnPQ's hardware test 38454784; not in issue 37's table); three or two paddles.
// No public HW_GET_INFO of a unit: type 31, firmware 1.0.3 as the other cubes. Its messages: kMpc.
constexpr ControllerModel mpc(std::string_view name, int paddles)
{
    auto c = unit_cube(name, 38, UnitKind::Polariser, listed<kMpc>(), "Polarization Controller");
    c.paddles = paddles;
    c.later_only = true;
    c.ack_id = MGMSG_MOT_ACK_DCSTATUSUPDATE;
    c.mmi_wheel = false;
    return c;
}

// KIM101 (K-Cube) and TIM101 (T-Cube) piezo inertia motor controllers (issue 28): four channels,
// each a PIA actuator. Prefixes: KIM101 97 (Thorlabs/Motion_Control_Examples C#/KCube/KIM101
// 97000001, its MATLAB example 97100058; not in issue 37's table), TIM101 65 (issue 37 p. 33, "T-Cube
// Inertial Piezo Driver TIM001", pyLabLib's 65:"TIM001"). No public HW_GET_INFO of a unit: type 31,
// firmware 1.0.3 as the other cubes. Its messages: kPzmot; its updates stop after 10 without
// PZMOT_ACK_STATUSUPDATE (issue 37 p. 406).
constexpr ControllerModel pzmot(std::string_view name, std::uint32_t serial_prefix, std::string_view notes)
{
    auto c = unit_cube(name, serial_prefix, UnitKind::PiezoMotor, listed<kPzmot>(), notes);
    c.pzmot_channels = 4;
    c.later_only = true;
    c.ack_id = MGMSG_PZMOT_ACK_STATUSUPDATE;
    c.updates_without_ack = 10;
    c.mmi_wheel = false;
    return c;
}

// MMR601 modular rack ("Midi Rack") with MPZ601 piezo modules (issue 28). The rack's own HW_GET_INFO,
// read from a unit (AlexShkarin/pyLabLib issue 97): serial 75000000 (issue 37 p. 33 lists 48 for "MMR
// series Midi Rack bay serial number"), model "MMR601", type 3, firmware 1.0.2, hardware version 3,
// 6 channels, notes "MMR601 Rack USB Communications Board (Issue 3)". Its bays: MPZ601 cards, serial
// prefix 51 (issue 37 p. 33; Kinesis shows the same unit's bays as 511xxxxx), two channels each
// (Thorlabs/Motion_Control_Examples MMR601: "Piezo and StepperMotor have 2"); no public HW_GET_INFO of
// a card: type 45 as the BPC cards. Their messages: issue 37 p. 7's list (kMpz); their LUT and loop
// as a BPC bay's (no public figure). Addressed as a single unit, it freezes (pyLabLib issue 81).
constexpr ControllerModel mmr601()
{
    ControllerModel c;
    c.name = "MMR601";
    c.kind = UnitKind::Piezo;
    c.takes = listed<kMpz>();
    c.ack_id = MGMSG_PZ_ACK_PZSTATUSUPDATE;
    c.lut_max_index = 7'999;
    c.lut_base_interval_us = 1'000;
    c.loop_rate_hz = 1'000;
    c.serial_prefix = 75;
    c.hw_type = 3;
    c.firmware_version = 0x00010002;
    c.hardware_version = 3;
    c.notes = "MMR601 Rack USB Communications Board (Issue 3)";
    c.rack = true;
    c.max_bays = 6;
    c.bay_hw_type = 45;
    c.bay_serial_prefix = 51;
    c.bay_model_name = "MPZ601";
    c.bay_channels = 2;
    c.later_only = true;
    c.wrong_address_freezes = true;
    return c;
}

// Serial prefixes: the manual lists none for these units (2.2); Thorlabs' own (D-1).
constexpr ControllerModel solenoid_cube(std::string_view name, std::uint32_t serial_prefix, std::string_view notes)
{
    return unit_cube(name, serial_prefix, UnitKind::Solenoid, listed<kTsc>(), notes);
}

// TPZ001 LUT: indices 0..512 (p. 106), timing in 250 µs samples (p. 109); its loop runs at
// that 4 kHz rate.
constexpr ControllerModel piezo_cube(std::string_view name, std::uint32_t serial_prefix, std::string_view notes)
{
    auto c = unit_cube(name, serial_prefix, UnitKind::Piezo, listed<kTpz>(), notes);
    c.lut_max_index = 512;
    c.lut_base_interval_us = 250;
    c.loop_rate_hz = 4'000;
    return c;
}

constexpr ControllerModel gauge_cube(std::string_view name, std::uint32_t serial_prefix, std::string_view notes)
{
    return unit_cube(name, serial_prefix, UnitKind::StrainGauge, listed<kTsg>(), notes);
}

constexpr ControllerModel rich(ControllerModel c)
{
    c.rich_fault_reports = true;
    return c;
}

/// A unit that takes `later` beyond its set with the later firmware generation (a K-Cube's own
/// messages; a T-Cube's status request).
constexpr ControllerModel later_unit(ControllerModel c, MessageSet later)
{
    c.later_takes = later;
    return c;
}

// BPC30x piezo racks: a motherboard at 0x11 and a card per channel (HW_GET_INFO 45 both,
// D-20; cards carry the rack's prefix). LUT: indices 0..7999 (p. 106), 1 ms samples (p. 109);
// the loop at that 1 kHz rate.
constexpr ControllerModel bpc(std::string_view name, std::uint32_t serial_prefix, int bays)
{
    ControllerModel c;
    c.name = name;
    c.kind = UnitKind::Piezo;
    c.takes = listed<kBpc>();
    c.ack_id = MGMSG_PZ_ACK_PZSTATUSUPDATE;
    c.lut_max_index = 7'999;
    c.lut_base_interval_us = 1'000;
    c.loop_rate_hz = 1'000;
    c.serial_prefix = serial_prefix;
    c.hw_type = 45;
    c.notes = "Piezo Controller";
    c.rack = true;
    c.max_bays = bays;
    c.bay_hw_type = 45;
    c.bay_serial_prefix = serial_prefix;
    return c;
}

constexpr std::array<ControllerModel, 25> kControllers{
    tst001(), kst101(), tdc001(), kdc101(), bsc203(), bbd203(), k10cr1(), lts("LTS150"), lts("LTS300"), kbd101(),
    mff("MFF101"), mff("MFF102"), mpc("MPC320", 3), mpc("MPC220", 2),
    pzmot("KIM101", 97, "Inertial Piezo Motor Controller"), pzmot("TIM101", 65, "T-Cube Inertial Piezo Driver"),
    solenoid_cube("TSC001", 85, "APT Solenoid Controller"),
    later_unit(rich(solenoid_cube("KSC101", 68, "Solenoid Controller")), listed<kKscLater>()),
    later_unit(piezo_cube("TPZ001", 81, "APT Piezo Driver"), listed<kTCubeLater>()),
    later_unit(rich(piezo_cube("KPZ101", 29, "Piezo Controller")), listed<kKpzLater>()),
    // BPC303: Thorlabs' prefix 71; BPC301: 41 after the 40/70 single/three-channel pattern of
    // 2.2 (the least certain of D-1).
    bpc("BPC301", 41, 1),
    bpc("BPC303", 71, 3),
    mmr601(),
    later_unit(gauge_cube("TSG001", 84, "APT Strain Gauge Reader"), listed<kTCubeLater>()),
    later_unit(rich(gauge_cube("KSG101", 59, "Strain Gauge Reader")), listed<kKsgLater>()),
};

// ---- The later generation ("issue-44.1"; docs/protocol/apt.md, "Firmware generations") ----


constexpr bool trinamic_stepper(std::string_view name)
{
    return name == "KST101" || name == "BSC203";
}

/// `c` as the later generation shapes it.
constexpr ControllerModel later(ControllerModel c)
{
    c.firmware = Firmware::Issue44_1;
    // amsikking/thorlabs_KSC101 thorlabs_KSC101.py, written against a unit: its HW_GET_INFO
    // firmware dword is 65542 (asserted at start-up): 1.0.6. No public source gives another
    // model's later firmware: they keep 1.0.3.
    if (c.name == "KSC101")
        c.firmware_version = 0x00010006;
    c.later_info_fields = true;
    c.reports_stage_type = c.kind == UnitKind::Motor && c.motor == MotorKind::DcServo && !c.rack;
    if (trinamic_stepper(c.name)) {
        c.velocity_per_count_s = kTrinamicVelocity;
        c.acceleration_per_count_s2 = kTrinamicAcceleration;
        c.counts_per_stage_count = kTrinamicMicrosteps;
    }
    return c;
}

template <std::size_t N>
constexpr std::array<ControllerModel, N> later_all(const std::array<ControllerModel, N>& manual)
{
    std::array<ControllerModel, N> out{};
    for (std::size_t i = 0; i < N; ++i)
        out[i] = later(manual[i]);
    return out;
}

constexpr auto kLaterControllers = later_all(kControllers);

// HW_GET_INFO's stage type word of a DC servo cube (pyLabLib's KinesisMotor._autodetect_stage
// reads data bytes 76-77 of a KDC101/TDC001; yaq-project/thorlabs-apt-protocol parsing.py
// hw_get_info reads the same byte as "stage_info"). The "B" actuators are the same motor and
// encoder (34,304 counts/mm) as the Z812/Z825 of that table.
constexpr std::pair<std::string_view, std::uint16_t> kDcStageTypes[]{
    {"PRM1-Z8", 6}, {"MTS25-Z8", 7}, {"MTS50-Z8", 8}, {"Z825B", 9}, {"Z812B", 10},
};

} // namespace

const ControllerModel* find_controller(std::string_view name, Firmware firmware)
{
    for (const auto& c : kLaterControllers)
        if (c.name == name && (c.later_only || firmware != Firmware::Issue3))
            return &c;
    for (const auto& c : kControllers)
        if (c.name == name)
            return &c;
    return nullptr;
}

const ControllerModel* built_into(std::string_view stage)
{
    for (const auto& c : kLaterControllers)
        if (!c.built_in_stage.empty() && c.built_in_stage == stage)
            return &c;
    return nullptr;
}

StageModel driven_stage(const ControllerModel& controller, StageModel stage)
{
    stage.counts_per_mm *= controller.counts_per_stage_count;
    return stage;
}

std::uint16_t dc_stage_type(std::string_view name)
{
    for (const auto& [stage, type] : kDcStageTypes)
        if (stage == name)
            return type;
    return 0;
}

std::string_view controller_names()
{
    return "TDC001, KDC101, TST001, KST101, BSC203, BBD203, K10CR1, LTS150, LTS300, KBD101, MFF101, MFF102, MPC320, "
           "MPC220, KIM101, TIM101, TSC001, KSC101, TPZ001, KPZ101, BPC301, BPC303, MMR601, TSG001, KSG101";
}

} // namespace rigsim::apt
