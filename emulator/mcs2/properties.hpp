#pragma once
// Every MCS2 ASCII command and property (SmarAct MCS2 Programmer's Guide 1.0.6: Tables 6.1-6.3 with
// the definitions of chapter 4, which win where they disagree, and sections 6.3.8, 6.4, 6.5), as one
// table: its path as the guide prints it, what it is attached to (device, module, channel), its type,
// access, range and power-up default, and whether it is kept in non-volatile memory. The command tree
// is built from these paths; the controller reads, writes and range-checks the stored properties by
// the table and computes the live ones (state words, positions, errors) by their id.

#include "emulator/mcs2/command_tree.hpp"

#include <cstdint>
#include <limits>
#include <array>
#include <string_view>

namespace rigsim::mcs2 {

/// Every row of the table, in its order.
enum class Id : std::int16_t {
    // Common commands (Table 6.1).
    Cls, Ese, Esr, Idn, Opc, Rst, Sre, Stb, Tst, Wai,
    // System, command groups, streaming (6.3.8, 6.4, 6.5).
    ErrCount, ErrNext,
    CgrOpen, CgrClose, CgrAbort, CgrFinished, CgrValues,
    StrOpen, StrFree, StrFrame, StrClose, StrAbort,
    // Movement commands (Table 6.2).
    Move, Stop, Calibrate, Reference,
    // Device properties.
    DevChannels, DevModules, DevState, DevSerial, DevName, DevEstopMode, DevDiscoverMode,
    DevStreamBaseRate, DevStreamSyncRate, DevStreamOptions, DevHmLock, DevHmLockDefault,
    DevTriggerMode, DevTriggerCondition,
    // Module properties.
    ModPower, ModState, ModChannels, ModTemperature, ModIoOptions, ModIoVoltage, ModAinRange,
    ModDin, ModDout, ModDoutSet, ModDoutClear, ModAout,
    // Channel properties.
    Amplifier, ControlOptions, ActuatorMode, LoopInput, SensorInputSelect, SensorValue, AuxValue,
    PositionerType, PositionerTypeName, MoveMode, State, Position, TargetPosition, ScanPosition,
    MeanShift, ScanVelocity, HoldTime, Velocity, Acceleration, MaxFrequency, MaxFrequencyDefault,
    StepFrequency, StepAmplitude, FollowingErrorLimit, BroadcastStop, SensorPowerMode, PowerSaveDelay,
    SafeDirection, TtzThreshold, ScaleOffset, ScaleInversion, RangeMin, RangeMax, CalibrationOptions,
    CorrectionOptions, ReferencingOptions, DistanceToMark, DistanceCodeInverted, ChannelError,
    ChannelTemperature, TriggerMode, TriggerPolarity, TriggerPulseWidth, CompareThreshold,
    CompareIncrement, CompareDirection, CompareLimitMin, CompareLimitMax, AuxPositionerType,
    AuxPositionerTypeName, AuxInputSelect, AuxInputIndex, AuxInputValue, AuxDirectionInversion,
    // Tuning (4.8): R(W) behind the write protection.
    TunMovementType, TunCustom, TunBaseUnit, TunBaseResolution, TunHeadType, TunReferenceType, TunGainP,
    TunGainI, TunGainD, TunGainShift, TunAntiWindup, TunEsdDistance, TunEsdCounter, TunTargetReached,
    TunTargetHold, TunSave, TunWriteProtection,
    // Keywords of later firmware (public drivers, not guide 1.0.6): firmware-dependent.
    SensorModeAlias, SensorDelayAlias, ModuleStateAlias, FollowingError,
};

/// What the row's indices address.
enum class Scope : std::uint8_t { Common, System, Group, Stream, Command, Device, Module, Channel };
enum class Type : std::uint8_t { None, I32, I64, String };
/// R(W) is Tuning: readable, writable once the write protection is lifted (4.8).
enum class Access : std::uint8_t { R, W, RW, Tuning };
/// Stored: read and written by the table alone (range-checked, kept per device, module or channel);
/// Live: the controller computes it or acts on it.
enum class Kind : std::uint8_t { Stored, Live };

struct Property {
    Id id;
    std::string_view path;   ///< as the guide prints it: "[:PROPerty]:CHANnel#:VELocity"
    Scope scope;
    Type type;
    Access access;
    Kind kind;
    std::int64_t min = 0;
    std::int64_t max = 0;
    std::int64_t initial = 0;   ///< power-up (or factory) value of a stored property
    bool nonvolatile = false;
    bool groupable = true;      ///< may stand in a command group (column CG)
    std::string_view section;   ///< the guide's section: "4.4.15"
};

inline constexpr std::size_t kPropertyCount = static_cast<std::size_t>(Id::FollowingError) + 1;
/// The table, in Id order (table()[static_cast<size_t>(id)].id == id).
const std::array<Property, kPropertyCount>& table();
inline const Property& property(Id id) { return table()[static_cast<std::size_t>(id)]; }
/// The command tree of the table; node_property(node) is the row of a command's node.
const CommandTree& command_tree();
/// The row a resolved node stands for, or nullptr.
const Property* node_property(int node);

/// Hold Time's SA_CTL_INFINITE (0xffffffff, written -1 or 4294967295: errata).
inline constexpr std::int64_t kInfinite = 0xffffffffLL;
/// The key that lifts the tuning write protection (4.8.17): 0x534D4152, "SMAR".
inline constexpr std::int64_t kTuningKey = 0x534D4152;

} // namespace rigsim::mcs2
