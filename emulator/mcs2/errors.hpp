#pragma once
// SmarActControl error codes (MCS2 Programmer's Guide 1.0.6, appendix A.1, Table A.1) that the MCS2
// reports: through a channel's Channel Error property (4.10.1) and, on the ASCII interface, through
// the error queue as `<code>,"<text>"` with the code in decimal (the guide gives no base; every other
// number of the interface is decimal) and the table's description as the text.

#include <cstdint>
#include <string_view>

namespace rigsim::mcs2 {

enum class Error : std::int32_t {
    None = 0x0000,
    InvalidParameter = 0x0013,
    InvalidDataType = 0x0016,
    Aborted = 0x0019,
    InvalidModuleIndex = 0x0021,
    InvalidChannelIndex = 0x0022,
    PermissionDenied = 0x0023,
    CommandNotGroupable = 0x0024,
    MovementLocked = 0x0025,
    InvalidArraySize = 0x0027,
    InvalidConfiguration = 0x0029,
    BufferUnderflow = 0x000c,
    BufferOverflow = 0x000d,
    NoHmPresent = 0x0100,
    NoIomPresent = 0x0101,
    NoSensorPresent = 0x0103,
    SensorDisabled = 0x0104,
    PowerSupplyDisabled = 0x0105,
    AmplifierDisabled = 0x0106,
    InvalidSensorMode = 0x0107,
    InvalidActuatorMode = 0x0108,
    InvalidInputTrigMode = 0x0109,
    NotCalibrated = 0x0111,
    NotReferenced = 0x0112,
    ControlLoopInputDisabled = 0x0115,
    InvalidControlLoopInput = 0x0116,
    BusyMoving = 0x0150,
    BusyCalibrating = 0x0151,
    BusyReferencing = 0x0152,
    EndStopReached = 0x0200,
    FollowingErrorLimit = 0x0201,
    RangeLimitReached = 0x0202,
    InvalidStreamHandle = 0x0300,
    InsufficientFrames = 0x0302,
    BusyStreaming = 0x0303,
    FeatureNotSupported = 0x7ffd,
};

/// Table A.1's description of `code` (a SmarActControl code), or "Unknown error".
std::string_view error_text(std::int32_t code);

} // namespace rigsim::mcs2
