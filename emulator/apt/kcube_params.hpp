#pragma once
// The motor parameter blocks of later protocol issues (codec_kcube.hpp) that a motor module of
// the "issue-44.1" generation stores and answers: a stepper's power factors, a rack's trigger
// byte, the K-Cube wheel/display, trigger port, position trigger and KST loop blocks, the
// stepper's actuator type. Which model takes which block, the ranges and the public source of
// each: kcube_params.cpp and docs/protocol/apt.md ("Firmware generations").
//
// rigsim models none of their physics (no phase current, no trigger ports, no wheel, no
// encoder loop of a stepper, no far-end homing): a unit keeps what it was sent, answers it
// back, and EEPROMPARAMS saves it. A unit of the manual's generation ("issue-3", the 2012
// units) does not know these messages: it ignores and logs them, as the real one does.

#include "emulator/apt/codec.hpp"
#include "emulator/apt/firmware.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace rigsim::apt {

/// What KCubeParams makes of one message: the answer to send, or why the unit ignores it.
struct KCubeOutcome {
    std::optional<msg::Message> answer;
    std::string ignored;   ///< non-empty: logged and ignored (a SET is then not saved)
};

/// One motor module's blocks of the KCubeMotor family (one channel: P_MOD_CHAN1).
class KCubeParams {
public:
    /// The blocks `model` takes under `firmware` (none under Firmware::Issue3), at their power-up values.
    KCubeParams(std::string_view model, Firmware firmware);

    void on(const msg::SetPowerParams& m, KCubeOutcome& out);          ///< MGMSG_MOT_SET_POWERPARAMS
    void on(const msg::ReqPowerParams& m, KCubeOutcome& out);          ///< MGMSG_MOT_REQ_POWERPARAMS
    void on(const msg::MotSetTstActuatorType& m, KCubeOutcome& out);   ///< MGMSG_MOT_SET_TSTACTUATORTYPE
    void on(const msg::MotSetTrigger& m, KCubeOutcome& out);           ///< MGMSG_MOT_SET_TRIGGER
    void on(const msg::MotReqTrigger& m, KCubeOutcome& out);           ///< MGMSG_MOT_REQ_TRIGGER
    void on(const msg::SetKCubeMmiParams& m, KCubeOutcome& out);       ///< MGMSG_MOT_SET_KCUBEMMIPARAMS
    void on(const msg::ReqKCubeMmiParams& m, KCubeOutcome& out);       ///< MGMSG_MOT_REQ_KCUBEMMIPARAMS
    void on(const msg::SetKCubeTrigIoConfig& m, KCubeOutcome& out);    ///< MGMSG_MOT_SET_KCUBETRIGIOCONFIG
    void on(const msg::ReqKCubeTrigIoConfig& m, KCubeOutcome& out);    ///< MGMSG_MOT_REQ_KCUBETRIGIOCONFIG
    void on(const msg::SetKCubePosTrigParams& m, KCubeOutcome& out);   ///< MGMSG_MOT_SET_KCUBEPOSTRIGPARAMS
    void on(const msg::ReqKCubePosTrigParams& m, KCubeOutcome& out);   ///< MGMSG_MOT_REQ_KCUBEPOSTRIGPARAMS
    void on(const msg::SetKCubeKstLoopParams& m, KCubeOutcome& out);   ///< MGMSG_MOT_SET_KCUBEKSTLOOPPARAMS
    void on(const msg::ReqKCubeKstLoopParams& m, KCubeOutcome& out);   ///< MGMSG_MOT_REQ_KCUBEKSTLOOPPARAMS

    /// Whether MOT_SET_EEPROMPARAMS saves SET `id` here: a SET of a block this unit takes.
    bool saves(std::uint16_t id) const;
    /// The stored form of `m` if saves() it: a data packet for channel 1, or a header-only
    /// SET's param1 and param2 (TSTACTUATORTYPE: the actuator; TRIGGER: channel 1, the mode).
    std::optional<std::string> saved_data(const msg::Message& m) const;

    /// The data bytes of message `id` this model reads (Module::fields_read): a motor K-Cube
    /// reads KCUBEMMIPARAMS up to JSSensitivity, a KSC101 its display words only (the table's).
    std::size_t fields_read(std::uint16_t id) const;

    /// The last actuator TSTACTUATORTYPE set (it has no GET), or nothing.
    std::optional<std::uint8_t> actuator_ident() const { return actuator_; }

private:
    /// Whether this unit acts on message `id`; else `out.ignored` says why.
    bool takes(std::uint16_t id, KCubeOutcome& out) const;

    std::string model_;
    Firmware firmware_;
    unsigned blocks_;   ///< kcube_params.cpp's Block bits
    msg::PowerParams power_;
    std::uint8_t trigger_mode_ = 0;
    msg::KCubeMmiParams mmi_;
    msg::KCubeTrigIoConfig trig_io_;
    msg::KCubePosTrigParams pos_trig_;
    msg::KCubeKstLoopParams kst_loop_;
    std::optional<std::uint8_t> actuator_;
};

} // namespace rigsim::apt
