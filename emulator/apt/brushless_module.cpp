#include "emulator/apt/brushless_module.hpp"

#include <spdlog/spdlog.h>

namespace rigsim::apt {

namespace {


/// Parameters as the module keeps them: for its channel 1, whatever channel word came.
template <class P> P for_chan1(P p)
{
    p.chan_ident = kChan1;
    return p;
}

} // namespace

BrushlessModule::BrushlessModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address,
                                 MotorChannel& channel, spdlog::logger& log, SaveToEeprom save)
    : DcMotorModule(unit, bay, address, channel, log, std::move(save))
{
    // p. 37: on a brushless (MLS203) channel only the homing velocity of HOMEPARAMS counts.
    home_velocity_only_ = true;
}

void BrushlessModule::handle(const msg::Message& m, Request& r)
{
    visit_as(*this, m, r);
}

void BrushlessModule::on(const msg::SetPmdPositionLoopParams& m)
{
    position_loop_ = for_chan1(m.params);
}

void BrushlessModule::on(const msg::ReqPmdPositionLoopParams&)
{
    answer(msg::GetPmdPositionLoopParams{position_loop_});
}

void BrushlessModule::on(const msg::SetPmdMotorOutputParams& m)
{
    motor_output_ = for_chan1(m.params);
}

void BrushlessModule::on(const msg::ReqPmdMotorOutputParams&)
{
    answer(msg::GetPmdMotorOutputParams{motor_output_});
}

void BrushlessModule::on(const msg::SetPmdTrackSettleParams& m)
{
    track_settle_ = for_chan1(m.params);
}

void BrushlessModule::on(const msg::ReqPmdTrackSettleParams&)
{
    answer(msg::GetPmdTrackSettleParams{track_settle_});
}

void BrushlessModule::on(const msg::SetPmdProfileModeParams& m)
{
    // p. 69: mode 0 trapezoidal, 2 S-curve; jerk in PMD jerk units (7.1).
    const auto& p = m.params;
    if (p.mode != 0 && p.mode != 2)
        return ignore(fmt::format("MOT_SET_PMDPROFILEMODEPARAMS mode {} (0 trapezoidal, 2 S-curve): ignored", p.mode));
    channel_.profile_mode = p.mode;
    channel_.jerk = p.jerk;
    profile_mode_ = for_chan1(p);
}

void BrushlessModule::on(const msg::ReqPmdProfileModeParams&)
{
    answer(msg::GetPmdProfileModeParams{profile_mode_});
}

void BrushlessModule::on(const msg::SetPmdCurrentLoopParams& m)
{
    current_loop_ = for_chan1(m.params);
}

void BrushlessModule::on(const msg::ReqPmdCurrentLoopParams&)
{
    answer(msg::GetPmdCurrentLoopParams{current_loop_});
}

void BrushlessModule::on(const msg::SetPmdSettledCurrentLoopParams& m)
{
    settled_current_loop_ = for_chan1(m.params);
}

void BrushlessModule::on(const msg::ReqPmdSettledCurrentLoopParams&)
{
    answer(msg::GetPmdSettledCurrentLoopParams{settled_current_loop_});
}

void BrushlessModule::on(const msg::SetPmdStageAxisParams& m)
{
    // "can only be used to increase the Minimum position value and decrease the Maximum
    // position value": the travel narrows, nothing else changes (p. 75).
    if (channel_.stage().kind == StageKind::Rotary)   // a DDR25: nothing to narrow
        return ignore(fmt::format("MOT_SET_PMDSTAGEAXISPARAMS on the rotation stage {}: it turns without end, no "
                                  "travel to narrow: ignored",
                                  channel_.stage().name));
    const auto min_position = m.params.min_pos, max_position = m.params.max_pos;
    if (min_position >= max_position || min_position < channel_.min_position()
        || max_position > channel_.max_position())
        return ignore(fmt::format("MOT_SET_PMDSTAGEAXISPARAMS travel {}..{} is not within {}..{}: ignored",
                                  min_position, max_position, channel_.min_position(), channel_.max_position()));
    channel_.narrow_travel(min_position, max_position);
}

void BrushlessModule::on(const msg::ReqPmdStageAxisParams&)
{
    answer(msg::GetPmdStageAxisParams{stage_axis_params()});
}

msg::PmdStageAxisParams BrushlessModule::stage_axis_params() const
{
    // p. 75: stage ID (MLS203 X 0x10, Y 0x11; 0 for stages the manual does not list), axis
    // ID, part number, serial, counts per unit, travel, maximum acceleration, deceleration
    // and velocity; the reserved tail zero.
    const auto& stage = channel_.stage();
    msg::PmdStageAxisParams p;
    p.stage_id = stage.pmd_stage_id;
    const auto part = stage.pmd_part_number.empty() ? stage.name : stage.pmd_part_number;
    part.substr(0, p.part_no_axis.size()).copy(p.part_no_axis.data(), p.part_no_axis.size());
    p.serial_num = unit_.serial % 1'000'000 * 10 + static_cast<std::uint32_t>(bay_);
    p.cnts_per_unit = static_cast<std::uint32_t>(stage.counts_per_mm);
    p.min_pos = channel_.min_position();
    p.max_pos = channel_.max_position();
    // "inherent in the design of the stage and cannot be altered" (p. 75): not VELPARAMS.
    const auto& design = channel_.design_velocity();
    p.max_accn = stage.pmd_max_acceleration > 0 ? stage.pmd_max_acceleration : design.acceleration;
    p.max_dec = p.max_accn;
    p.max_vel = stage.pmd_max_velocity > 0 ? stage.pmd_max_velocity : design.max;
    return p;
}

} // namespace rigsim::apt
