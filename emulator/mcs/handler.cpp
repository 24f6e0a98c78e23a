#include "emulator/mcs/handler.hpp"

#include <string>

namespace rigsim::mcs {
namespace {

// A channel index that names no channel is a system error: no channel generated it
// (manual 1.1: "-1 ... the error does not originate from a specific channel").
const Error kNoSuchChannel{kSystem, ErrorCode::InvalidParameter};

std::string join(std::string_view prefix, std::int64_t a)
{
    std::string s(prefix);
    s += std::to_string(a);
    return s;
}

std::string join(std::string_view prefix, std::int64_t a, std::int64_t b)
{
    std::string s = join(prefix, a);
    s += ',';
    s += std::to_string(b);
    return s;
}

} // namespace

Reply Handler::handle(const Command& command)
{
    return std::visit([this](const auto& c) { return on(c); }, command);
}

/// GNC: number of channels (3.1).
Reply Handler::on(const GetNumberOfChannels&)
{
    return Answer{join("N", static_cast<std::int64_t>(controller_.channel_count()))};
}

/// GSI: system id (3.1).
Reply Handler::on(const GetSystemId&)
{
    return Answer{join("ID", controller_.system_id())};
}

/// GIV: interface version, RS232 form `IV<high>,<low>,<update>` (3.1).
Reply Handler::on(const GetInterfaceVersion&)
{
    const auto v = controller_.interface_version();
    return Answer{join("IV", v.high, v.low) + ',' + std::to_string(v.update)};
}

/// GCT<ch>: channel type, 0 positioner, 1 end effector (3.1).
Reply Handler::on(const GetChannelType& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return kNoSuchChannel;
    return Answer{join("CT", c.channel, static_cast<int>(ch->type()))};
}

/// GST<ch>: sensor type code of appendix 4.3 (3.2).
Reply Handler::on(const GetSensorType& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return kNoSuchChannel;
    if (!ch->sensor())
        return Error{c.channel, ErrorCode::NoSensorPresent};
    return Answer{join("ST", c.channel, ch->sensor()->code)};
}

/// SST<ch>,<type>: set sensor type; stops the positioner (3.2).
Reply Handler::on(const SetSensorType& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return kNoSuchChannel;
    if (!ch->sensor())
        return Error{c.channel, ErrorCode::NoSensorPresent};
    if (auto err = ch->set_sensor_type(c.type_code))
        return Error{c.channel, *err};
    return Ack{c.channel};
}

/// GP<ch>: position in nm, linear sensors only (3.4).
Reply Handler::on(const GetPosition& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return kNoSuchChannel;
    if (auto err = ch->check_linear_sensor())
        return Error{c.channel, *err};
    return Answer{join("P", c.channel, ch->position_nm())};
}

/// GS<ch>: channel status code of appendix 4.1 (3.4).
Reply Handler::on(const GetStatus& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return kNoSuchChannel;
    return Answer{join("S", c.channel, static_cast<int>(ch->status()))};
}

/// MPA<ch>,<position_nm>,<hold_ms>: move to position absolute (3.3).
Reply Handler::on(const MovePositionAbsolute& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return kNoSuchChannel;
    if (auto err = ch->move_absolute(c.position_nm, c.hold_ms))
        return Error{c.channel, *err};
    return Ack{c.channel};
}

/// MPR<ch>,<distance_nm>,<hold_ms>: move to position relative (3.3).
Reply Handler::on(const MovePositionRelative& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return kNoSuchChannel;
    if (auto err = ch->move_relative(c.distance_nm, c.hold_ms))
        return Error{c.channel, *err};
    return Ack{c.channel};
}

/// S[<ch>]: stop one channel, or all when the index is omitted (3.3).
Reply Handler::on(const Stop& c)
{
    if (!c.channel) {
        controller_.stop_all();
        return Ack{kSystem};
    }
    auto* ch = controller_.channel(*c.channel);
    if (!ch)
        return kNoSuchChannel;
    ch->stop();
    return Ack{*c.channel};
}

/// SCLS<ch>,<speed>: closed-loop speed; the manual documents the acknowledge as E-1,0 (3.2).
Reply Handler::on(const SetClosedLoopSpeed& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return kNoSuchChannel;
    if (auto err = ch->set_closed_loop_speed(c.speed))
        return Error{c.channel, *err};
    return Ack{kSystem};
}

/// GCLS<ch>: closed-loop speed (3.2).
Reply Handler::on(const GetClosedLoopSpeed& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return kNoSuchChannel;
    return Answer{join("CLS", c.channel, ch->closed_loop_speed())};
}

/// SCLA<ch>,<acceleration>: closed-loop acceleration in µm/s² (3.2).
Reply Handler::on(const SetClosedLoopAcceleration& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return kNoSuchChannel;
    if (auto err = ch->set_closed_loop_acceleration(c.acceleration))
        return Error{c.channel, *err};
    return Ack{c.channel};
}

/// GCLA<ch>: closed-loop acceleration (3.2).
Reply Handler::on(const GetClosedLoopAcceleration& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return kNoSuchChannel;
    return Answer{join("CLA", c.channel, ch->closed_loop_acceleration())};
}

} // namespace rigsim::mcs
