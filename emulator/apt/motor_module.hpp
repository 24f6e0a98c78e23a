#pragma once
// The motor modules of an APT unit (module.hpp): DC servo and stepper here, brushless in
// brushless_module.hpp. Each drives one MotorChannel and acts on the Motor family (and its
// own) through Module's dispatch; messages of the other families (a rack motherboard's, a
// unit's own GETs, the solenoid, piezo and strain gauge ones) are ignored and logged as a
// real unit without that module does.

#include "emulator/apt/kcube_params.hpp"
#include "emulator/apt/module.hpp"
#include "emulator/apt/motor_channel.hpp"

#include <cstdint>
#include <string>
#include <string_view>

namespace rigsim::apt {

/// What the modules of the three motor kinds share: their MotorChannel, the Motor family's
/// handlers, the parameter blocks that do not move the motor, what MOT_SET_EEPROMPARAMS saves.
class MotorModule : public Module {
public:
    /// The parameter SETs MOT_SET_EEPROMPARAMS saves (p. 60): the motor chapter's settings that
    /// rigsim's controllers act on. Not SET_POSCOUNTER or SET_ENCCOUNTER: the 'live' counts
    /// (p. 28), unknown at power-up.
    using Saved = SavedSets<msg::SetVelParams, msg::SetJogParams, msg::SetGenMoveParams, msg::SetMoveRelParams,
                            msg::SetMoveAbsParams, msg::SetHomeParams, msg::SetLimSwitchParams, msg::SetDcPidParams,
                            msg::SetAvModes, msg::SetPotParams, msg::SetButtonParams, msg::SetPmdPositionLoopParams,
                            msg::SetPmdMotorOutputParams, msg::SetPmdTrackSettleParams,
                            msg::SetPmdProfileModeParams, msg::SetPmdCurrentLoopParams,
                            msg::SetPmdSettledCurrentLoopParams, msg::SetPmdStageAxisParams>;

    MotorModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address, MotorChannel& channel,
                spdlog::logger& log, SaveToEeprom save);

    /// The status structure of this kind's update and end-of-move messages (p. 44).
    virtual msg::MotorStatus motor_status() const = 0;

    bool saves(std::uint16_t id) const override { return Saved::saves(id) || kcube_.saves(id); }
    std::size_t fields_read(std::uint16_t id) const override { return kcube_.fields_read(id); }
    std::optional<std::string> saved_data(const msg::Message& m) const override
    {
        return Saved::saves(msg::message_id(m)) ? Saved::data(m) : kcube_.saved_data(m);
    }
    void power_down(bool restore_positions) override;
    bool enabled() const override { return channel_.enabled(); }
    void set_enabled(bool on) override { channel_.set_enabled(on); }

    /// The message that started the channel's last move (HW_RICHRESPONSE's MsgIdent).
    std::uint16_t last_move() const { return last_move_; }

    using Module::on;

    // ---- Motor family: counters and parameter trios ----
    void on(const msg::SetPosCounter& m);      ///< MGMSG_MOT_SET_POSCOUNTER (p. 28)
    void on(const msg::ReqPosCounter& m);      ///< MGMSG_MOT_REQ_POSCOUNTER (p. 28)
    void on(const msg::SetEncCounter& m);      ///< MGMSG_MOT_SET_ENCCOUNTER (p. 29)
    void on(const msg::ReqEncCounter& m);      ///< MGMSG_MOT_REQ_ENCCOUNTER (p. 29)
    void on(const msg::SetVelParams& m);       ///< MGMSG_MOT_SET_VELPARAMS (p. 30)
    void on(const msg::ReqVelParams& m);       ///< MGMSG_MOT_REQ_VELPARAMS (p. 30)
    void on(const msg::SetJogParams& m);       ///< MGMSG_MOT_SET_JOGPARAMS (p. 32)
    void on(const msg::ReqJogParams& m);       ///< MGMSG_MOT_REQ_JOGPARAMS (p. 32)
    void on(const msg::SetGenMoveParams& m);   ///< MGMSG_MOT_SET_GENMOVEPARAMS (p. 34)
    void on(const msg::ReqGenMoveParams& m);   ///< MGMSG_MOT_REQ_GENMOVEPARAMS (p. 34)
    void on(const msg::SetMoveRelParams& m);   ///< MGMSG_MOT_SET_MOVERELPARAMS (p. 35)
    void on(const msg::ReqMoveRelParams& m);   ///< MGMSG_MOT_REQ_MOVERELPARAMS (p. 35)
    void on(const msg::SetMoveAbsParams& m);   ///< MGMSG_MOT_SET_MOVEABSPARAMS (p. 36)
    void on(const msg::ReqMoveAbsParams& m);   ///< MGMSG_MOT_REQ_MOVEABSPARAMS (p. 36)
    void on(const msg::SetHomeParams& m);      ///< MGMSG_MOT_SET_HOMEPARAMS (p. 37)
    void on(const msg::ReqHomeParams& m);      ///< MGMSG_MOT_REQ_HOMEPARAMS (p. 37)
    void on(const msg::SetLimSwitchParams& m); ///< MGMSG_MOT_SET_LIMSWITCHPARAMS (p. 39)
    void on(const msg::ReqLimSwitchParams& m); ///< MGMSG_MOT_REQ_LIMSWITCHPARAMS (p. 39)
    void on(const msg::SetAvModes& m);         ///< MGMSG_MOT_SET_AVMODES (p. 53)
    void on(const msg::ReqAvModes& m);         ///< MGMSG_MOT_REQ_AVMODES (p. 53)
    void on(const msg::SetPotParams& m);       ///< MGMSG_MOT_SET_POTPARAMS (p. 55)
    void on(const msg::ReqPotParams& m);       ///< MGMSG_MOT_REQ_POTPARAMS (p. 55)
    void on(const msg::SetButtonParams& m);    ///< MGMSG_MOT_SET_BUTTONPARAMS (p. 58)
    void on(const msg::ReqButtonParams& m);    ///< MGMSG_MOT_REQ_BUTTONPARAMS (p. 58)
    void on(const msg::SetEepromParams& m);    ///< MGMSG_MOT_SET_EEPROMPARAMS (p. 60)

    // ---- Motor family: moves and status ----
    void on(const msg::MoveHome& m);           ///< MGMSG_MOT_MOVE_HOME (p. 41)
    void on(const msg::MoveRelative& m);       ///< MGMSG_MOT_MOVE_RELATIVE (p. 42)
    void on(const msg::MoveAbsolute& m);       ///< MGMSG_MOT_MOVE_ABSOLUTE (p. 45)
    void on(const msg::MoveJog& m);            ///< MGMSG_MOT_MOVE_JOG (p. 47)
    void on(const msg::MoveVelocity& m);       ///< MGMSG_MOT_MOVE_VELOCITY (p. 48)
    void on(const msg::MoveStop& m);           ///< MGMSG_MOT_MOVE_STOP (p. 49)
    void on(const msg::ReqStatusUpdate& m);    ///< MGMSG_MOT_REQ_STATUSUPDATE (p. 78)
    void on(const msg::ReqStatusBits& m);      ///< MGMSG_MOT_REQ_STATUSBITS (p. 81)

    /// The KCubeMotor family (later protocol issues): KCubeParams's handlers.
    template <class T, class = decltype(std::declval<KCubeParams&>().on(std::declval<const T&>(),
                                                                        std::declval<KCubeOutcome&>()))>
    void on(const T& m)
    {
        KCubeOutcome out;
        kcube_.on(m, out);
        finish(out);
    }
    /// The last actuator MOT_SET_TSTACTUATORTYPE set, if any (it has no GET).
    std::optional<std::uint8_t> actuator_ident() const { return kcube_.actuator_ident(); }

protected:
    /// A move: false (and logged) if the channel is disabled; else remembered as the last move.
    bool may_move(std::uint16_t id, std::string_view name);
    /// Send KCubeParams's answer, or log why it ignored the message.
    void finish(const KCubeOutcome& out);
    msg::DcStatus dc_status() const;
    msg::MotStatus mot_status() const;

    MotorChannel& channel_;
    /// p. 37: a brushless (MLS203) channel uses only the homing velocity of HOMEPARAMS.
    bool home_velocity_only_ = false;
    std::uint16_t last_move_ = 0;
    // Parameter blocks that change nothing the emulation models, kept as set (p. 51-58).
    msg::AvModes av_modes_{1, 0x000B};      ///< LED: ident, limit switch, moving
    msg::PotParams pot_params_{};
    msg::ButtonParams button_params_{};
    KCubeParams kcube_;
};

/// A DC motor module (DC servo or brushless): PID parameters and the DC status update.
class DcMotorModule : public MotorModule {
public:
    using MotorModule::MotorModule;
    using MotorModule::on;
    void on(const msg::SetDcPidParams& m);     ///< MGMSG_MOT_SET_DCPIDPARAMS (p. 51)
    void on(const msg::ReqDcPidParams& m);     ///< MGMSG_MOT_REQ_DCPIDPARAMS (p. 51)
    void on(const msg::ReqDcStatusUpdate& m);  ///< MGMSG_MOT_REQ_DCSTATUSUPDATE (p. 80)

    msg::MotorStatus motor_status() const override { return dc_status(); }
    std::string status_update(std::uint8_t host) const override;

protected:
    /// p. 51: the power-up PID of the TDC001 and the BBD203 cards.
    msg::DcPidParams pid_params_{1, 396, 270, 4000, 4860, 15};
};

/// The brushed DC servo module: TDC001, KDC101.
class DcServoModule final : public DcMotorModule {
public:
    using DcMotorModule::DcMotorModule;
    using DcMotorModule::on;
    static constexpr bool handles(msg::Family f)
    {
        return f == msg::Family::Motor || f == msg::Family::DcServo || f == msg::Family::KCubeMotor;
    }
    void handle(const msg::Message& m, Request& r) override;
};

/// The stepper module: TST001, KST101, BSC203 cards. No DC messages.
class StepperModule final : public MotorModule {
public:
    using MotorModule::MotorModule;
    using MotorModule::on;
    static constexpr bool handles(msg::Family f) { return f == msg::Family::Motor || f == msg::Family::KCubeMotor; }
    void handle(const msg::Message& m, Request& r) override;
    msg::MotorStatus motor_status() const override { return mot_status(); }
    std::string status_update(std::uint8_t host) const override;
};

} // namespace rigsim::apt
