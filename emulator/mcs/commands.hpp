#pragma once
// The typed MCS commands and answers (manual chapter 3): what the codec decodes and
// encodes, what the handler executes and the command queue (2.4.5) holds. No wire text here.

#include "emulator/mcs/errors.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <variant>

namespace rigsim::mcs {

// ---- Commands (one struct per command of chapter 3 that rigsim implements) ----
// Parameters keep the manual's names and units; every value arrives as a signed 32-bit
// number except where a command documents a wider range (MSCA/MSCR speed).

struct GetCommunicationMode {};                                   ///< GCM
struct SetCommunicationMode { std::int32_t mode; };               ///< SCM
struct GetNumberOfChannels {};                                    ///< GNC
struct GetSystemId {};                                            ///< GSI
struct GetInterfaceVersion {};                                    ///< GIV
struct Reset {};                                                  ///< R
struct SetHcmEnabled { std::int32_t mode; };                      ///< SHE
struct GetChannelType { std::int32_t channel; };                  ///< GCT
struct GetSensorEnabled {};                                       ///< GSE
struct SetSensorEnabled { std::int32_t mode; };                   ///< SSE
struct GetSensorType { std::int32_t channel; };                   ///< GST
struct SetSensorType { std::int32_t channel; std::int32_t type_code; };  ///< SST
struct GetPosition { std::int32_t channel; };                     ///< GP
struct GetStatus { std::int32_t channel; };                       ///< GS
struct GetPhysicalPositionKnown { std::int32_t channel; };        ///< GPPK
struct MovePositionAbsolute { std::int32_t channel; std::int32_t position_nm; std::int32_t hold_ms; };  ///< MPA
struct MovePositionRelative { std::int32_t channel; std::int32_t distance_nm; std::int32_t hold_ms; };  ///< MPR
struct Stop { std::optional<std::int32_t> channel; };             ///< S (no channel: all)
struct SetClosedLoopSpeed { std::int32_t channel; std::int32_t speed; };            ///< SCLS
struct GetClosedLoopSpeed { std::int32_t channel; };              ///< GCLS
struct SetClosedLoopAcceleration { std::int32_t channel; std::int32_t acceleration; };  ///< SCLA
struct GetClosedLoopAcceleration { std::int32_t channel; };       ///< GCLA
struct SetClosedLoopMaxFrequency { std::int32_t channel; std::int32_t frequency_hz; };  ///< SCLF
struct SetAccumulateRelativePositions { std::int32_t channel; std::int32_t accumulate; };  ///< SARP
struct SetPosition { std::int32_t channel; std::int32_t position; };  ///< SP
struct SetZeroPosition { std::int32_t channel; };                 ///< SZP
struct SetScale { std::int32_t channel; std::int32_t scale; std::int32_t inverted; };  ///< SSC
struct GetScale { std::int32_t channel; };                        ///< GSC
struct SetSafeDirection { std::int32_t channel; std::int32_t direction; };  ///< SSD
struct GetSafeDirection { std::int32_t channel; };                ///< GSD
struct SetStepWhileScan { std::int32_t channel; std::int32_t step; };  ///< SSWS
struct SetReportOnComplete { std::int32_t channel; std::int32_t report; };  ///< SRC
struct KeepAlive { std::optional<std::int32_t> delay_ms; };       ///< K (no delay: reset the timer)
struct ConfigureBaudrate { std::int32_t baudrate; };              ///< CB
struct GetSerialNumber { std::int32_t channel; };                 ///< GSN
struct GetFirmwareVersion { std::int32_t channel; };              ///< GFV
struct GetFeaturePermissions { std::int32_t channel; std::int32_t byte_index; };  ///< GFP
struct FindReferenceMark { std::int32_t channel; std::int32_t direction; std::int32_t hold_ms; std::int32_t auto_zero; };  ///< FRM
struct CalibrateSensor { std::int32_t channel; };                 ///< CS
struct MoveAngleAbsolute { std::int32_t channel; std::int32_t angle_udeg; std::int32_t revolution; std::int32_t hold_ms; };  ///< MAA
struct MoveAngleRelative { std::int32_t channel; std::int32_t angle_udeg; std::int32_t revolution; std::int32_t hold_ms; };  ///< MAR
struct GetAngle { std::int32_t channel; };                        ///< GA
struct SetPositionLimit { std::int32_t channel; std::int32_t min_nm; std::int32_t max_nm; };  ///< SPL
struct GetPositionLimit { std::int32_t channel; };                ///< GPL
struct SetAngleLimit { std::int32_t channel; std::int32_t min_angle_udeg; std::int32_t min_revolution;
                       std::int32_t max_angle_udeg; std::int32_t max_revolution; };  ///< SAL
struct GetAngleLimit { std::int32_t channel; };                   ///< GAL
struct MoveStep { std::int32_t channel; std::int32_t steps; std::int32_t amplitude; std::int32_t frequency_hz; };  ///< MST
struct MoveScanAbsolute { std::int32_t channel; std::int32_t target; std::int64_t speed; };  ///< MSCA
struct MoveScanRelative { std::int32_t channel; std::int32_t diff; std::int64_t speed; };    ///< MSCR
struct GetVoltageLevel { std::int32_t channel; };                 ///< GVL
struct GetChannelProperty { std::int32_t channel; std::int32_t key; };  ///< GCP
struct SetChannelProperty { std::int32_t channel; std::int32_t key; std::int32_t value; };  ///< SCP
struct GetEmergencyStopMode {};                                   ///< GESM
struct SetEmergencyStopMode { std::int32_t mode; };               ///< SESM
struct AppendTriggeredCommand { std::int32_t channel; std::int32_t trigger_source; };  ///< ATC
struct ClearTriggeredCommandQueue { std::int32_t channel; };      ///< CTCQ
struct TriggerCommand { std::int32_t trigger_index; };            ///< TC
struct SetReportOnTriggered { std::int32_t channel; std::int32_t report; };  ///< SRT
struct GetCaptureBuffer { std::int32_t channel; std::int32_t buffer; };  ///< GB
struct SetEndEffectorType { std::int32_t channel; std::int32_t type; std::int32_t param1; std::int32_t param2; };  ///< SEET
struct GetEndEffectorType { std::int32_t channel; };              ///< GEET
struct MoveGripperOpeningAbsolute { std::int32_t channel; std::int32_t opening_cv; std::int32_t speed_v_per_s; };  ///< MGOA
struct MoveGripperOpeningRelative { std::int32_t channel; std::int32_t diff_cv; std::int32_t speed_v_per_s; };  ///< MGOR
struct MoveGripperForceAbsolute { std::int32_t channel; std::int32_t force_dun; std::int32_t speed_v_per_s; std::int32_t hold_ms; };  ///< MGFA
struct GetGripperOpening { std::int32_t channel; };               ///< GGO
struct GetForce { std::int32_t channel; };                        ///< GF
struct SetZeroForce { std::int32_t channel; };                    ///< SZF

using Command = std::variant<
    GetCommunicationMode, SetCommunicationMode, GetNumberOfChannels, GetSystemId,
    GetInterfaceVersion, Reset, SetHcmEnabled, GetChannelType, GetSensorEnabled,
    SetSensorEnabled, GetSensorType, SetSensorType, GetPosition, GetStatus,
    GetPhysicalPositionKnown, MovePositionAbsolute, MovePositionRelative, Stop,
    SetClosedLoopSpeed, GetClosedLoopSpeed, SetClosedLoopAcceleration, GetClosedLoopAcceleration,
    SetClosedLoopMaxFrequency, SetAccumulateRelativePositions, SetPosition, SetZeroPosition,
    SetScale, GetScale, SetSafeDirection, GetSafeDirection, SetStepWhileScan, SetReportOnComplete,
    KeepAlive, ConfigureBaudrate, GetSerialNumber, GetFirmwareVersion, GetFeaturePermissions,
    FindReferenceMark, CalibrateSensor, MoveAngleAbsolute, MoveAngleRelative, GetAngle,
    SetPositionLimit, GetPositionLimit, SetAngleLimit, GetAngleLimit, MoveStep, MoveScanAbsolute,
    MoveScanRelative, GetVoltageLevel, GetChannelProperty, SetChannelProperty, GetEmergencyStopMode,
    SetEmergencyStopMode, AppendTriggeredCommand, ClearTriggeredCommandQueue, TriggerCommand,
    SetReportOnTriggered, GetCaptureBuffer, SetEndEffectorType, GetEndEffectorType,
    MoveGripperOpeningAbsolute, MoveGripperOpeningRelative, MoveGripperForceAbsolute,
    GetGripperOpening, GetForce, SetZeroForce>;

// ---- Answers ----

/// `E<channel>,0`
struct Ack { int channel; };
/// `E<channel>,<code>`
struct Error { int channel; ErrorCode code; };
/// Any other answer string, without ':' and '\n' (e.g. `P0,2000000`).
struct Answer { std::string text; };
/// No answer at all (async-only commands such as SRC; acknowledges in async mode).
struct Silent {};

using Reply = std::variant<Ack, Error, Answer, Silent>;

} // namespace rigsim::mcs
