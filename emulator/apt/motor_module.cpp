#include "emulator/apt/motor_module.hpp"
#include "emulator/core/log_format.hpp"


namespace rigsim::apt {

namespace {

/// The only channel of a module: P_MOD_CHAN1.

} // namespace

MotorModule::MotorModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address, MotorChannel& channel,
                         spdlog::logger& log, SaveToEeprom save)
    : Module(unit, bay, address, log, std::move(save)), channel_(channel), kcube_(unit.model_name, unit.firmware)
{
}

void MotorModule::finish(const KCubeOutcome& out)
{
    if (!out.ignored.empty())
        return ignore(fmt::format("{}: {}", request_->peer, out.ignored));
    if (out.answer)
        answer(*out.answer);
}

void MotorModule::power_down(bool restore_positions)
{
    channel_.power_up();
    if (restore_positions) {
        channel_.place(channel_.start_position_counts());
        channel_.power_up();   // the counters read 0 where the stage stands
    }
}

msg::DcStatus MotorModule::dc_status() const
{
    return {kChan1, channel_.position(), channel_.velocity_word(), 0, channel_.status_bits()};
}

msg::MotStatus MotorModule::mot_status() const
{
    return {kChan1, channel_.position(), channel_.encoder(), channel_.status_bits()};
}

// ---- Motor family: counters and parameter trios ----

void MotorModule::on(const msg::SetPosCounter& m)
{
    channel_.set_position(m.params.position);
}

void MotorModule::on(const msg::ReqPosCounter&)
{
    answer(msg::GetPosCounter{{kChan1, channel_.position()}});
}

void MotorModule::on(const msg::SetEncCounter& m)
{
    channel_.set_encoder(m.params.encoder_count);
}

void MotorModule::on(const msg::ReqEncCounter&)
{
    answer(msg::GetEncCounter{{kChan1, channel_.encoder()}});
}

void MotorModule::on(const msg::SetVelParams& m)
{
    const auto& p = m.params;
    if (p.min_velocity > p.max_velocity)   // p. 30: the minimum (start) velocity of a ramp up to the maximum
        return ignore(fmt::format("{}: MOT_SET_VELPARAMS with minimum velocity {} above the maximum {}: ignored",
                                  request_->peer, p.min_velocity, p.max_velocity));
    channel_.velocity = {p.min_velocity, p.acceleration, p.max_velocity};
}

void MotorModule::on(const msg::ReqVelParams&)
{
    const auto& v = channel_.velocity;
    answer(msg::GetVelParams{{kChan1, v.min, v.acceleration, v.max}});
}

void MotorModule::on(const msg::SetJogParams& m)
{
    const auto& p = m.params;
    if (p.jog_min_velocity > p.jog_max_velocity)
        return ignore(fmt::format("{}: MOT_SET_JOGPARAMS with jog minimum velocity {} above the maximum {}: ignored",
                                  request_->peer, p.jog_min_velocity, p.jog_max_velocity));
    channel_.jog = {p.jog_mode, p.jog_step_size, {p.jog_min_velocity, p.jog_acceleration, p.jog_max_velocity},
                    p.jog_stop_mode};
}

void MotorModule::on(const msg::ReqJogParams&)
{
    const auto& j = channel_.jog;
    answer(msg::GetJogParams{
        {kChan1, j.mode, j.step_size, j.velocity.min, j.velocity.acceleration, j.velocity.max, j.stop_mode}});
}

void MotorModule::on(const msg::SetGenMoveParams& m)
{
    channel_.backlash = m.params.backlash_distance;
}

void MotorModule::on(const msg::ReqGenMoveParams&)
{
    answer(msg::GetGenMoveParams{{kChan1, channel_.backlash}});
}

void MotorModule::on(const msg::SetMoveRelParams& m)
{
    channel_.relative_distance = m.params.relative_distance;
}

void MotorModule::on(const msg::ReqMoveRelParams&)
{
    answer(msg::GetMoveRelParams{{kChan1, channel_.relative_distance}});
}

void MotorModule::on(const msg::SetMoveAbsParams& m)
{
    channel_.absolute_position = m.params.absolute_position;
}

void MotorModule::on(const msg::ReqMoveAbsParams&)
{
    answer(msg::GetMoveAbsParams{{kChan1, channel_.absolute_position}});
}

void MotorModule::on(const msg::SetHomeParams& m)
{
    const auto& p = m.params;
    // p. 37: on a brushless (MLS203) channel only the homing velocity counts; the other
    // fields are kept as sent and ignored.
    const bool others_ok = (p.home_direction == 1 || p.home_direction == 2)
                           && (p.limit_switch == 1 || p.limit_switch == 4) && p.offset_distance >= 0;
    if (p.home_velocity <= 0 || (!home_velocity_only_ && !others_ok))
        return ignore(fmt::format("{}: MOT_SET_HOMEPARAMS out of range: ignored", request_->peer));
    channel_.home_params = {p.home_direction, p.limit_switch, p.home_velocity, p.offset_distance};
}

void MotorModule::on(const msg::ReqHomeParams&)
{
    const auto& h = channel_.home_params;
    answer(msg::GetHomeParams{{kChan1, h.direction, h.limit_switch, h.velocity, h.offset}});
}

void MotorModule::on(const msg::SetLimSwitchParams& m)
{
    const auto& p = m.params;
    // p. 39: hardware modes 1..6 and software modes 1..3, each possibly with 0x80.
    const auto hard_ok = [](std::uint16_t mode) { return (mode & ~0x80u) >= 1 && (mode & ~0x80u) <= 6; };
    const auto soft = p.soft_limit_mode & ~0x80u;
    if (!hard_ok(p.cw_hard_limit) || !hard_ok(p.ccw_hard_limit) || soft < 1 || soft > 3)
        return ignore(fmt::format("{}: MOT_SET_LIMSWITCHPARAMS modes {}, {} (1..6) and {} (1..3): ignored",
                                  request_->peer, p.cw_hard_limit, p.ccw_hard_limit, p.soft_limit_mode));
    channel_.limit_switch = {p.cw_hard_limit, p.ccw_hard_limit, p.cw_soft_limit, p.ccw_soft_limit,
                             p.soft_limit_mode};
}

void MotorModule::on(const msg::ReqLimSwitchParams&)
{
    const auto& l = channel_.limit_switch;
    answer(msg::GetLimSwitchParams{{kChan1, l.cw_hard, l.ccw_hard, l.cw_soft, l.ccw_soft, l.mode}});
}

void MotorModule::on(const msg::SetAvModes& m)
{
    // p. 52-53: mode bits 1 (ident), 2 (limit switch), 8 (moving); no others.
    if ((m.params.mode_bits & ~0x000Bu) != 0)
        return ignore(fmt::format("{}: MOT_SET_AVMODES mode bits 0x{:04x} (bits of 0x000b only): ignored",
                                  request_->peer, m.params.mode_bits));
    av_modes_ = m.params;
    av_modes_.chan_ident = kChan1;
}

void MotorModule::on(const msg::ReqAvModes&)
{
    answer(msg::GetAvModes{av_modes_});
}

void MotorModule::on(const msg::SetPotParams& m)
{
    // p. 55-57: windows in ADC counts up to 127, each from the previous one on, and "Wnd3
    // must be greater than Wnd2"; velocities in encoder counts/s.
    const auto& p = m.params;
    const bool velocities_ok = p.vel1 >= 0 && p.vel2 >= 0 && p.vel3 >= 0 && p.vel4 >= 0;
    if (!(p.zero_wnd <= p.wnd1 && p.wnd1 <= p.wnd2 && p.wnd2 < p.wnd3 && p.wnd3 <= 127) || !velocities_ok)
        return ignore(fmt::format(
            "{}: MOT_SET_POTPARAMS windows {}, {}, {}, {} (rising to 127) or a negative velocity: ignored",
            request_->peer, p.zero_wnd, p.wnd1, p.wnd2, p.wnd3));
    pot_params_ = p;
    pot_params_.chan_ident = kChan1;
}

void MotorModule::on(const msg::ReqPotParams&)
{
    answer(msg::GetPotParams{pot_params_});
}

void MotorModule::on(const msg::SetButtonParams& m)
{
    button_params_ = m.params;
    button_params_.chan_ident = kChan1;
}

void MotorModule::on(const msg::ReqButtonParams&)
{
    answer(msg::GetButtonParams{button_params_});
}

void MotorModule::on(const msg::SetEepromParams& m)
{
    save_to_eeprom_(m.msg_id, request_->peer);
}

// ---- Motor family: moves and status ----

bool MotorModule::may_move(std::uint16_t id, std::string_view name)
{
    if (!channel_.enabled()) {
        ignore(fmt::format("{}: {} while channel 1 is disabled: it does not move", request_->peer, name));
        return false;
    }
    last_move_ = id;
    return true;
}

void MotorModule::on(const msg::MoveHome& m)
{
    // Drivers re-send MOVE_HOME every 0.5-3 s while they wait for MOVE_HOMED: a unit
    // that is homing keeps homing rather than starting over.
    if (channel_.enabled() && channel_.homing())
        return log_.info("{}: MOT_MOVE_HOME while homing: homing goes on", request_->peer);
    if (may_move(m.id, request_->frame.info->name))
        channel_.home();
}

void MotorModule::on(const msg::MoveRelative& m)
{
    if (may_move(m.id, request_->frame.info->name))
        channel_.move_relative(m.relative_distance.value_or(channel_.relative_distance));
}

void MotorModule::on(const msg::MoveAbsolute& m)
{
    if (may_move(m.id, request_->frame.info->name))
        channel_.move_absolute(m.absolute_distance.value_or(channel_.absolute_position));
}

void MotorModule::on(const msg::MoveJog& m)
{
    if (!may_move(m.id, request_->frame.info->name))
        return;
    if (m.direction != 1 && m.direction != 2)
        return ignore(fmt::format("{}: MOT_MOVE_JOG direction {}: ignored", request_->peer, m.direction));
    channel_.jog_move(m.direction == 1);
}

void MotorModule::on(const msg::MoveVelocity& m)
{
    if (!may_move(m.id, request_->frame.info->name))
        return;
    if (m.direction != 1 && m.direction != 2)
        return ignore(fmt::format("{}: MOT_MOVE_VELOCITY direction {}: ignored", request_->peer, m.direction));
    channel_.move_velocity(m.direction == 1);
}

void MotorModule::on(const msg::MoveStop& m)
{
    channel_.stop(m.stop_mode == 1);
}

void MotorModule::on(const msg::ReqStatusUpdate&)
{
    answer(msg::GetStatusUpdate{mot_status()});
}

void MotorModule::on(const msg::ReqStatusBits&)
{
    answer(msg::GetStatusBits{kChan1, channel_.status_bits()});
}

// ---- DC motor modules ----

void DcMotorModule::on(const msg::SetDcPidParams& m)
{
    pid_params_ = m.params;
    pid_params_.chan_ident = kChan1;
}

void DcMotorModule::on(const msg::ReqDcPidParams&)
{
    answer(msg::GetDcPidParams{pid_params_});
}

void DcMotorModule::on(const msg::ReqDcStatusUpdate&)
{
    answer(msg::GetDcStatusUpdate{dc_status()});
}

std::string DcMotorModule::status_update(std::uint8_t host) const
{
    return msg::encode(msg::GetDcStatusUpdate{dc_status()}, host, address_);
}

void DcServoModule::handle(const msg::Message& m, Request& r)
{
    visit_as(*this, m, r);
}

// ---- Stepper modules ----

std::string StepperModule::status_update(std::uint8_t host) const
{
    return msg::encode(msg::GetStatusUpdate{mot_status()}, host, address_);
}

void StepperModule::handle(const msg::Message& m, Request& r)
{
    visit_as(*this, m, r);
}

} // namespace rigsim::apt
