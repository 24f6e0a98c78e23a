#pragma once
// One function per MCS command (manual chapter 3): call the controller, return the answer.
// std::visit dispatch, so a command without a handler fails to compile.

#include "emulator/mcs/codec.hpp"
#include "emulator/mcs/controller.hpp"

namespace rigsim::mcs {

class Handler {
public:
    explicit Handler(Controller& controller) : controller_(controller) {}

    /// A command from a client: through the command queue checks (2.4.5), then its handler.
    Reply handle(const Command& command);
    /// A queued command whose trigger arrived: straight to its handler.
    Reply execute(const Command& command);

    Reply on(const GetCommunicationMode& c);
    Reply on(const SetCommunicationMode& c);
    Reply on(const Reset& c);
    Reply on(const SetHcmEnabled& c);
    Reply on(const GetSensorEnabled& c);
    Reply on(const SetSensorEnabled& c);
    Reply on(const GetPhysicalPositionKnown& c);
    Reply on(const SetClosedLoopMaxFrequency& c);
    Reply on(const SetAccumulateRelativePositions& c);
    Reply on(const SetPosition& c);
    Reply on(const SetZeroPosition& c);
    Reply on(const SetScale& c);
    Reply on(const GetScale& c);
    Reply on(const SetSafeDirection& c);
    Reply on(const GetSafeDirection& c);
    Reply on(const SetStepWhileScan& c);
    Reply on(const SetReportOnComplete& c);
    Reply on(const KeepAlive& c);
    Reply on(const ConfigureBaudrate& c);
    Reply on(const GetSerialNumber& c);
    Reply on(const GetFirmwareVersion& c);
    Reply on(const GetFeaturePermissions& c);
    Reply on(const FindReferenceMark& c);
    Reply on(const CalibrateSensor& c);
    Reply on(const MoveAngleAbsolute& c);
    Reply on(const MoveAngleRelative& c);
    Reply on(const GetAngle& c);
    Reply on(const SetPositionLimit& c);
    Reply on(const GetPositionLimit& c);
    Reply on(const SetAngleLimit& c);
    Reply on(const GetAngleLimit& c);
    Reply on(const MoveStep& c);
    Reply on(const MoveScanAbsolute& c);
    Reply on(const MoveScanRelative& c);
    Reply on(const GetVoltageLevel& c);
    Reply on(const GetChannelProperty& c);
    Reply on(const SetChannelProperty& c);
    Reply on(const GetEmergencyStopMode& c);
    Reply on(const SetEmergencyStopMode& c);
    Reply on(const AppendTriggeredCommand& c);
    Reply on(const ClearTriggeredCommandQueue& c);
    Reply on(const TriggerCommand& c);
    Reply on(const SetReportOnTriggered& c);
    Reply on(const GetCaptureBuffer& c);
    Reply on(const SetEndEffectorType& c);
    Reply on(const GetEndEffectorType& c);
    Reply on(const MoveGripperOpeningAbsolute& c);
    Reply on(const MoveGripperOpeningRelative& c);
    Reply on(const MoveGripperForceAbsolute& c);
    Reply on(const GetGripperOpening& c);
    Reply on(const GetForce& c);
    Reply on(const SetZeroForce& c);
    Reply on(const GetNumberOfChannels& c);
    Reply on(const GetSystemId& c);
    Reply on(const GetInterfaceVersion& c);
    Reply on(const GetChannelType& c);
    Reply on(const GetSensorType& c);
    Reply on(const SetSensorType& c);
    Reply on(const GetPosition& c);
    Reply on(const GetStatus& c);
    Reply on(const MovePositionAbsolute& c);
    Reply on(const MovePositionRelative& c);
    Reply on(const Stop& c);
    Reply on(const SetClosedLoopSpeed& c);
    Reply on(const GetClosedLoopSpeed& c);
    Reply on(const SetClosedLoopAcceleration& c);
    Reply on(const GetClosedLoopAcceleration& c);

    /// R was handled: the device resets the controller after the acknowledge has been sent.
    bool take_reset_request();

private:
    /// The answer for an index without a channel of the right kind.
    Error missing(std::int32_t index) const;

    Controller& controller_;
    bool reset_requested_ = false;
};

} // namespace rigsim::mcs
