// The end effector's commands (manual sections 3.2 to 3.4: SEET, GEET, MGOA, MGOR, MGFA, GGO,
// GF, SZF): the gripper and the force sensor of a channel that has one (end_effector.hpp).
#include "emulator/mcs/handler.hpp"
#include "emulator/mcs/handler_replies.hpp"

namespace rigsim::mcs {

using replies::join;
using replies::result;

/// SEET<ch>,<type>,<param1>,<param2>: acknowledged as E-1,0 per the manual (3.2).
Reply Handler::on(const SetEndEffectorType& c)
{
    auto* ee = controller_.effector(c.channel);
    if (!ee)
        return missing(c.channel);
    return result(ee->set_type(c.type, c.param1, c.param2), c.channel, kSystem);
}

/// GEET<ch>: `EET<ch>,<type>,<param1>,<param2>` (3.2).
Reply Handler::on(const GetEndEffectorType& c)
{
    const auto* ee = controller_.effector(c.channel);
    if (!ee)
        return missing(c.channel);
    return Answer{join("EET", c.channel, static_cast<int>(ee->type())) + "," + std::to_string(ee->param1()) + ","
                  + std::to_string(ee->param2())};
}

/// MGOA<ch>,<opening>,<speed>: gripper voltage in 1/100 V at V/s; status 8 (3.3).
Reply Handler::on(const MoveGripperOpeningAbsolute& c)
{
    auto* ee = controller_.effector(c.channel);
    if (!ee)
        return missing(c.channel);
    return result(ee->move_opening_absolute(c.opening_cv, c.speed_v_per_s), c.channel, c.channel);
}

/// MGOR<ch>,<diff>,<speed>: relative gripper voltage (3.3).
Reply Handler::on(const MoveGripperOpeningRelative& c)
{
    auto* ee = controller_.effector(c.channel);
    if (!ee)
        return missing(c.channel);
    return result(ee->move_opening_relative(c.diff_cv, c.speed_v_per_s), c.channel, c.channel);
}

/// MGFA<ch>,<force>,<speed>,<hold>: grip with a force in 1/10 µN; status 4, then 3 (3.3).
Reply Handler::on(const MoveGripperForceAbsolute& c)
{
    auto* ee = controller_.effector(c.channel);
    if (!ee)
        return missing(c.channel);
    return result(ee->move_force_absolute(c.force_dun, c.speed_v_per_s, c.hold_ms), c.channel, c.channel);
}

/// GGO<ch>: `GO<ch>,<opening>` in 1/100 V (3.4).
Reply Handler::on(const GetGripperOpening& c)
{
    const auto* ee = controller_.effector(c.channel);
    if (!ee)
        return missing(c.channel);
    std::int32_t value = 0;
    if (auto err = ee->opening_cv(value))
        return Error{c.channel, *err};
    return Answer{join("GO", c.channel, value)};
}

/// GF<ch>: `F<ch>,<force>` in 1/10 µN (3.4).
Reply Handler::on(const GetForce& c)
{
    const auto* ee = controller_.effector(c.channel);
    if (!ee)
        return missing(c.channel);
    std::int32_t value = 0;
    if (auto err = ee->force_dun(value))
        return Error{c.channel, *err};
    return Answer{join("F", c.channel, value)};
}

/// SZF<ch>: zero the force sensor; status 6 for about a second (3.2).
Reply Handler::on(const SetZeroForce& c)
{
    auto* ee = controller_.effector(c.channel);
    if (!ee)
        return missing(c.channel);
    return result(ee->zero_force(), c.channel, c.channel);
}

} // namespace rigsim::mcs
