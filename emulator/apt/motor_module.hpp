#pragma once
// The module of one channel of an APT unit: a T-/K-Cube's only channel or a rack bay's card.
// It acts on the typed messages (codec.hpp) addressed to it, through a msg::visit over an
// overload set with one on() per message: a message of a family the module kind acts on
// (Family) without its on() does not compile. Messages of the other families (another
// module kind's, a rack motherboard's, a unit's own GETs, the untyped piezo and solenoid
// ones) are ignored and logged as a real unit without that module does.
//
// The unit shell (AptDevice) handles the System family before a module sees a message, and
// keeps what MOT_SET_EEPROMPARAMS saves: every SET a module does not mark ignored.

#include "emulator/apt/catalogue.hpp"
#include "emulator/apt/codec.hpp"
#include "emulator/apt/motor_channel.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace spdlog {
class logger;
}

namespace rigsim::apt {

/// One message being handled: where it came from and where the answer goes.
struct Request {
    const Frame& frame;
    std::string_view peer;
    std::string& reply;
    std::uint8_t host;       ///< where answers go (the requester's source)
    bool ignored = false;    ///< the module ignored it (a SET: MOT_SET_EEPROMPARAMS must not save it)
    std::string why{};       ///< why it was ignored (the warning without the peer)
};

/// What every module knows of the unit it sits in.
struct UnitIdentity {
    std::string model_name;        ///< as configured ("TDC001"), for HW_GET_INFO and logs
    const ControllerModel& model;
    std::uint32_t serial;
    std::size_t built_in_bays;     ///< a rack's bays with a card (its motherboard's channel count)
};

/// HW_GET_INFO (p. 21) of a unit or motherboard (no bay) or of a rack bay's card.
msg::HwGetInfo hw_get_info(const UnitIdentity& unit, std::optional<std::size_t> bay);

/// What the modules of the three motor kinds share: addressing checks, the Bay and Motor
/// families' handlers, the parameter blocks that do not move the motor.
class MotorModule {
public:
    /// MOT_SET_EEPROMPARAMS: ask the unit shell to save the last SET of message `id`.
    using SaveToEeprom = std::function<void(std::uint16_t id, std::string_view peer)>;

    MotorModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address, MotorChannel& channel,
                spdlog::logger& log, SaveToEeprom save);
    virtual ~MotorModule() = default;
    MotorModule(const MotorModule&) = delete;
    MotorModule& operator=(const MotorModule&) = delete;

    /// Act on a message addressed to this module (not a System one: the shell took those).
    virtual void handle(const msg::Message& m, Request& r) = 0;
    /// The status structure of this kind's update and end-of-move messages (p. 44).
    virtual msg::MotorStatus motor_status() const = 0;
    /// The periodic status update of this kind: GET_STATUSUPDATE or GET_DCSTATUSUPDATE.
    virtual std::string status_update(std::uint8_t host) const = 0;

    /// The message that started the channel's last move (HW_RICHRESPONSE's MsgIdent).
    std::uint16_t last_move() const { return last_move_; }
    std::uint8_t address() const { return address_; }

    // ---- Bay family ----
    /// MGMSG_MOD_SET_CHANENABLESTATE (p. 17).
    void on(const msg::ModSetChanEnableState& m);
    /// MGMSG_MOD_REQ_CHANENABLESTATE (p. 17): answers MGMSG_MOD_GET_CHANENABLESTATE.
    void on(const msg::ModReqChanEnableState& m);
    /// MGMSG_HW_REQ_INFO (p. 21): answers MGMSG_HW_GET_INFO.
    void on(const msg::HwReqInfo& m);
    /// MGMSG_HUB_REQ_BAYUSED (p. 24): a cube answers it stands alone; a rack bay ignores it.
    void on(const msg::HubReqBayUsed& m);

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

protected:
    /// The visit of a module kind `Self`: System messages were the shell's; Bay messages go
    /// to their handler; the others are checked for channel 1 and the SET's field ranges,
    /// then go to Self's handler if Self acts on their family, else are ignored and logged.
    template <class Self, class T> void dispatch(Self& self, const T& m);

    /// Log warning `text` and mark the message ignored (a SET is then not saved by EEPROMPARAMS).
    void ignore(const std::string& text);
    /// "<name> is not a message a <model> acts on: ignored".
    void not_mine();
    /// The channel the message addresses (a cube's channel 0 read as 1).
    std::uint16_t channel() const;
    /// Log and ignore a message for another channel than 1.
    void wrong_channel();
    /// The channel the message addresses is this module's; else logged and ignored.
    bool channel_ok();
    /// Every field of the SET being handled is within the manual's range; else logged and ignored.
    bool in_range();
    /// Reply with message `m` from this module.
    template <class T> void answer(const T& m);
    /// A move: false (and logged) if the channel is disabled; else remembered as the last move.
    bool may_move(std::uint16_t id, std::string_view name);
    msg::DcStatus dc_status() const;
    msg::MotStatus mot_status() const;
    void begin(Request& r, const msg::Message& m)
    {
        request_ = &r;
        message_ = &m;
    }

    const UnitIdentity& unit_;
    std::size_t bay_;
    std::uint8_t address_;
    MotorChannel& channel_;
    spdlog::logger& log_;
    SaveToEeprom save_to_eeprom_;
    Request* request_ = nullptr;           ///< the message being handled
    const msg::Message* message_ = nullptr;
    /// p. 37: a brushless (MLS203) channel uses only the homing velocity of HOMEPARAMS.
    bool home_velocity_only_ = false;
    std::uint16_t last_move_ = 0;
    // Parameter blocks that change nothing the emulation models, kept as set (p. 51-58).
    msg::AvModes av_modes_{1, 0x000B};      ///< LED: ident, limit switch, moving
    msg::PotParams pot_params_{};
    msg::ButtonParams button_params_{};
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
    static constexpr bool handles(msg::Family f) { return f == msg::Family::Motor || f == msg::Family::DcServo; }
    void handle(const msg::Message& m, Request& r) override;
};

/// The stepper module: TST001, KST101, BSC203 cards. No DC messages.
class StepperModule final : public MotorModule {
public:
    using MotorModule::MotorModule;
    using MotorModule::on;
    static constexpr bool handles(msg::Family f) { return f == msg::Family::Motor; }
    void handle(const msg::Message& m, Request& r) override;
    msg::MotorStatus motor_status() const override { return mot_status(); }
    std::string status_update(std::uint8_t host) const override;
};

// ---- templates ----

template <class T> void MotorModule::answer(const T& m)
{
    request_->reply += msg::encode(m, request_->host, address_);
}

template <class Self, class T> void MotorModule::dispatch(Self& self, const T& m)
{
    constexpr msg::Family family = T::family;
    if constexpr (family == msg::Family::System) {
        return;   // the unit shell acted on it before
    } else if constexpr (family == msg::Family::Bay) {
        self.on(m);
    } else {
        if (!channel_ok() || !in_range())
            return;
        if constexpr (Self::handles(family))
            self.on(m);
        else
            not_mine();
    }
}

} // namespace rigsim::apt
