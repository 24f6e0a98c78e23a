#pragma once
// One function per MCS command (manual chapter 3): call the controller, return the answer.
// std::visit dispatch, so a command without a handler fails to compile.

#include "emulator/mcs/codec.hpp"
#include "emulator/mcs/controller.hpp"

namespace rigsim::mcs {

class Handler {
public:
    explicit Handler(Controller& controller) : controller_(controller) {}

    Reply handle(const Command& command);

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

private:
    Controller& controller_;
};

} // namespace rigsim::mcs
