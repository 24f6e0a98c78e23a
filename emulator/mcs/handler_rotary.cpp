// The commands of rotary positioners (manual 2.3.1: a logical angle in µ° and a revolution
// count; 3.2 SAL/GAL, 3.3 MAA/MAR, 3.4 GA).
#include "emulator/mcs/handler.hpp"
#include "emulator/mcs/handler_replies.hpp"

#include <cstdint>
#include <string>

namespace rigsim::mcs {

using replies::join;
using replies::result;

namespace {

constexpr std::int64_t kFullTurn_udeg = 360'000'000;   ///< 2.3.1

/// A logical angle in µ° as `<angle>,<revolution>` (angle 0..359,999,999).
std::string angle_text(std::int64_t udeg)
{
    std::int64_t revolution = udeg / kFullTurn_udeg;
    std::int64_t angle = udeg % kFullTurn_udeg;
    if (angle < 0) {
        angle += kFullTurn_udeg;
        --revolution;
    }
    return std::to_string(angle) + "," + std::to_string(revolution);
}

} // namespace

/// MAA<ch>,<angle>,<revolution>,<hold>: angle 0..359,999,999 µ°, revolution
/// -32768..32767 (3.3, 2.3.1).
Reply Handler::on(const MoveAngleAbsolute& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (auto err = ch->check_angular_sensor())
        return Error{c.channel, *err};
    if (c.angle_udeg < 0 || c.angle_udeg >= kFullTurn_udeg || c.revolution < -32768 || c.revolution > 32767)
        return Error{c.channel, ErrorCode::InvalidParameter};
    return result(ch->move_angle_absolute(c.revolution * kFullTurn_udeg + c.angle_udeg, c.hold_ms),
                  c.channel, c.channel);
}

/// MAR<ch>,<angle>,<revolution>,<hold>: angle -359,999,999..359,999,999 µ° (3.3).
Reply Handler::on(const MoveAngleRelative& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (auto err = ch->check_angular_sensor())
        return Error{c.channel, *err};
    if (c.angle_udeg <= -kFullTurn_udeg || c.angle_udeg >= kFullTurn_udeg || c.revolution < -32768
        || c.revolution > 32767)
        return Error{c.channel, ErrorCode::InvalidParameter};
    return result(ch->move_angle_relative(c.revolution * kFullTurn_udeg + c.angle_udeg, c.hold_ms),
                  c.channel, c.channel);
}

/// GA<ch>: `A<ch>,<angle>,<revolution>` (3.4).
Reply Handler::on(const GetAngle& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (auto err = ch->check_angular_sensor())
        return Error{c.channel, *err};
    return Answer{join("A", c.channel) + "," + angle_text(ch->position())};
}

/// SAL<ch>,<minAngle>,<minRev>,<maxAngle>,<maxRev>: rotary software range limit (3.2).
Reply Handler::on(const SetAngleLimit& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (auto err = ch->check_angular_sensor())
        return Error{c.channel, *err};
    auto valid_angle = [](std::int32_t a) { return a >= 0 && a < kFullTurn_udeg; };
    auto valid_rev = [](std::int32_t r) { return r >= -32768 && r <= 32767; };
    if (!valid_angle(c.min_angle_udeg) || !valid_angle(c.max_angle_udeg) || !valid_rev(c.min_revolution)
        || !valid_rev(c.max_revolution))
        return Error{c.channel, ErrorCode::InvalidParameter};
    return result(ch->set_range_limit(c.min_revolution * kFullTurn_udeg + c.min_angle_udeg,
                                      c.max_revolution * kFullTurn_udeg + c.max_angle_udeg),
                  c.channel, c.channel);
}

/// GAL<ch>: `AL<ch>,<minAngle>,<minRev>,<maxAngle>,<maxRev>` (3.2).
Reply Handler::on(const GetAngleLimit& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (auto err = ch->check_angular_sensor())
        return Error{c.channel, *err};
    const auto [lo, hi] = ch->range_limit();
    return Answer{join("AL", c.channel) + "," + angle_text(lo) + "," + angle_text(hi)};
}

} // namespace rigsim::mcs
