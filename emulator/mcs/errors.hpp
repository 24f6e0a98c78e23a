#pragma once
// MCS error codes (appendix 4.2): the device's vocabulary, shared by the codec that
// encodes them and the channels that raise them.

namespace rigsim::mcs {

/// Error codes of appendix 4.2.
enum class ErrorCode : int {
    None = 0,
    Syntax = 1,
    InvalidCommand = 2,
    Overflow = 3,
    Parse = 4,
    TooFewParameters = 5,
    TooManyParameters = 6,
    InvalidParameter = 7,
    WrongMode = 8,
    NoSensorPresent = 129,
    SensorDisabled = 140,
    CommandOverridden = 141,
    EndStopReached = 142,
    WrongSensorType = 143,
    CouldNotFindReferenceMark = 144,
    WrongEndEffectorType = 145,
    MovementLocked = 146,
    RangeLimitReached = 147,
    PhysicalPositionUnknown = 148,
    CommandNotProcessable = 150,
    WaitingForTrigger = 151,
    CommandNotTriggerable = 152,
    CommandQueueFull = 153,
    InvalidComponent = 154,
    InvalidSubComponent = 155,
    InvalidProperty = 156,
    PermissionDenied = 157,
};

/// Source channel of system errors (manual 1.1).
inline constexpr int kSystem = -1;

} // namespace rigsim::mcs
