// The open-loop commands (manual 3.3 MST, MSCA, MSCR; 3.4 GVL): steps and scans of the piezo,
// which run without a sensor (channel_open_loop.cpp is the channel's side).
#include "emulator/mcs/handler.hpp"
#include "emulator/mcs/handler_replies.hpp"

namespace rigsim::mcs {

using replies::join;
using replies::result;

/// MST<ch>,<steps>,<amplitude>,<frequency>: open-loop steps, also without sensor (3.3).
Reply Handler::on(const MoveStep& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return result(ch->move_steps(c.steps, c.amplitude, c.frequency_hz), c.channel, c.channel);
}

/// MSCA<ch>,<target>,<speed>: scan the piezo to a 12-bit level (3.3).
Reply Handler::on(const MoveScanAbsolute& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return result(ch->scan_absolute(c.target, c.speed), c.channel, c.channel);
}

/// MSCR<ch>,<diff>,<speed>: relative scan, stopping at 0 and 4095 (3.3).
Reply Handler::on(const MoveScanRelative& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return result(ch->scan_relative(c.diff, c.speed), c.channel, c.channel);
}

/// GVL<ch>: `VL<ch>,<level>` (3.4).
Reply Handler::on(const GetVoltageLevel& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return Answer{join("VL", c.channel, ch->voltage_level())};
}

} // namespace rigsim::mcs
