#include "emulator/apt/kcube_params.hpp"

#include <algorithm>
#include <array>
#include <cstdio>

namespace rigsim::apt {

namespace {


/// The blocks of the KCubeMotor family (codec_kcube.hpp).
enum Block : unsigned {
    kPower = 1u << 0,      ///< POWERPARAMS
    kTrigger = 1u << 1,    ///< TRIGGER
    kMmi = 1u << 2,        ///< KCUBEMMIPARAMS
    kTrigIo = 1u << 3,     ///< KCUBETRIGIOCONFIG
    kPosTrig = 1u << 4,    ///< KCUBEPOSTRIGPARAMS
    kKstLoop = 1u << 5,    ///< KCUBEKSTLOOPPARAMS
    kActuator = 1u << 6,   ///< TSTACTUATORTYPE
};

/// The blocks each motor model takes, as the public sources say (docs/protocol/apt.md
/// "Firmware generations"):
/// - POWERPARAMS: the steppers. Issue 16 p. 44 (its example a TST001; its note the BSC20x,
///   TST101 and MST602), the KST101 of yaq's thorlabs_apt_protocol clients.
/// - TRIGGER: the racks. Issue 16 p. 102 ("All benchtop stepper controllers (BSC20x)",
///   "Brushless DC controllers only (BBD20x and TBD001)").
/// - KCUBEMMIPARAMS, KCUBETRIGIOCONFIG, KCUBEPOSTRIGPARAMS: the K-Cube motor controllers
///   (pyLabLib kinesis.py: KDC101, KST101, KBD101; quantumion/thorlabs_cube kcube/kdc.py).
///   pyLabLib does not send TRIGIOCONFIG to a KST101; the messages are the K-Cubes' and
///   a unit answering one a client does not send harms no client: kept for the KST101.
/// - KCUBEKSTLOOPPARAMS: the KST101 (its name); a thorpy example sends it to a BSC20x "as set
///   by APT".
/// - KCUBEMMIPARAMS, KCUBETRIGIOCONFIG also the KSC101 solenoid cube (msl-equipment ksc.py).
/// - TSTACTUATORTYPE: KST101 and BSC20x (MSLNZ/msl-equipment thorlabs/kst.py and bsc.py send
///   it); issue 16 p. 94 names the TST101 only (rigsim has no TST101; not the TST001).
unsigned blocks_of(std::string_view model)
{
    if (model == "TST001")
        return kPower;
    if (model == "KST101")
        return kPower | kMmi | kTrigIo | kPosTrig | kKstLoop | kActuator;
    if (model == "KDC101")
        return kMmi | kTrigIo | kPosTrig;
    if (model == "BSC203")
        return kPower | kTrigger | kKstLoop | kActuator;
    if (model == "BBD203")
        return kTrigger;
    // Issue 37 p. 22, "KBD101 only": the three K-Cube blocks; TRIGGER is the racks' and TBD001's.
    if (model == "KBD101")
        return kMmi | kTrigIo | kPosTrig;
    // Issue 37 p. 15, "Messages applicable to K10CR1 only": TRIGGER; POWERPARAMS as the other
    // Trinamic steppers (Kinesis' defaults give the K10CR1 a MoveFactor and a RestFactor).
    if (model == "K10CR1")
        return kPower | kTrigger;
    // The KSC101's display block and TRIG1/TRIG2 ports (MSLNZ/msl-equipment thorlabs/ksc.py;
    // its solenoid module holds a KCubeParams: docs/protocol/apt.md "K-Cube units").
    if (model == "KSC101")
        return kMmi | kTrigIo;
    return 0;
}

unsigned block_of(std::uint16_t id)
{
    switch (id) {
    case MGMSG_MOT_SET_POWERPARAMS:
    case MGMSG_MOT_REQ_POWERPARAMS:
        return kPower;
    case MGMSG_MOT_SET_TRIGGER:
    case MGMSG_MOT_REQ_TRIGGER:
        return kTrigger;
    case MGMSG_MOT_SET_KCUBEMMIPARAMS:
    case MGMSG_MOT_REQ_KCUBEMMIPARAMS:
        return kMmi;
    case MGMSG_MOT_SET_KCUBETRIGIOCONFIG:
    case MGMSG_MOT_REQ_KCUBETRIGIOCONFIG:
        return kTrigIo;
    case MGMSG_MOT_SET_KCUBEPOSTRIGPARAMS:
    case MGMSG_MOT_REQ_KCUBEPOSTRIGPARAMS:
        return kPosTrig;
    case MGMSG_MOT_SET_KCUBEKSTLOOPPARAMS:
    case MGMSG_MOT_REQ_KCUBEKSTLOOPPARAMS:
        return kKstLoop;
    case MGMSG_MOT_SET_TSTACTUATORTYPE:
        return kActuator;
    default:
        return 0;
    }
}

/// The SETs of the family (saved by EEPROMPARAMS when the unit takes their block).
bool is_set(std::uint16_t id)
{
    return id == MGMSG_MOT_SET_POWERPARAMS || id == MGMSG_MOT_SET_TRIGGER || id == MGMSG_MOT_SET_KCUBEMMIPARAMS
           || id == MGMSG_MOT_SET_KCUBETRIGIOCONFIG || id == MGMSG_MOT_SET_KCUBEPOSTRIGPARAMS
           || id == MGMSG_MOT_SET_KCUBEKSTLOOPPARAMS || id == MGMSG_MOT_SET_TSTACTUATORTYPE;
}

/// Issue 16 p. 94's actuator idents (ZST legacy, ZST, ZFS, DRV013/DRV014), and the BSC20x
/// actuators msl-equipment's bsc.py sets (DRV225 0xB0, DRV250 0xB1, DRV208 0xB2, NRT100 0xB3,
/// NRT150 0xB4).
constexpr std::array<std::uint8_t, 16> kActuators{0x20, 0x21, 0x22, 0x30, 0x31, 0x32, 0x40, 0x41,
                                                  0x42, 0x50, 0x51, 0xB0, 0xB1, 0xB2, 0xB3, 0xB4};

/// The trigger port modes (pyLabLib kinesis.py kcube_trigio_mode; quantumion kdc.py lists
/// 0x00-0x0F): disabled, inputs 0x01-0x04, outputs 0x0A-0x12.
bool trig_mode_known(std::uint16_t mode)
{
    return mode <= 0x04 || (mode >= 0x0A && mode <= 0x12);
}

/// 0x0D-0x0F: pulses at the positions of KCUBEPOSTRIGPARAMS; "Only one Trigger port at a time
/// can be set to this mode" (quantumion kdc.py).
bool position_mode(std::uint16_t mode)
{
    return mode >= 0x0D && mode <= 0x0F;
}

std::string hex_byte(std::uint8_t v)
{
    char text[8];
    std::snprintf(text, sizeof text, "0x%02x", v);
    return text;
}

std::string name_of(std::uint16_t id)
{
    const auto* info = find_message(id);
    return info ? std::string(info->name) : "message";
}

/// The stored form of a parameter SET: its block for channel 1.
template <class P> std::string stored(const msg::Set<P>& m)
{
    auto saved = m;
    saved.params.chan_ident = kChan1;
    return msg::encode_data(saved);
}

} // namespace

KCubeParams::KCubeParams(std::string_view model, Firmware firmware)
    : model_(model), firmware_(firmware), blocks_(firmware == Firmware::Issue3 ? 0u : blocks_of(model)),
      // Issue 16 p. 44: APTServer's ini "typically" sets rest 5 %, move 30 %.
      power_{kChan1, 5, 30},
      // No public source gives the factory values: velocity mode, the rest 0 (in range).
      mmi_{},
      // Both ports disabled, active high (no public factory values).
      trig_io_{},
      // Thorlabs' KBD101 example ("Values are set as default at controller startup"): one pulse
      // each way, 50 us, one cycle.
      pos_trig_{kChan1, 0, 0, 1, 0, 0, 1, 50, 1, {}},
      // The thorpy example's values "as set by APT": open loop.
      kst_loop_{kChan1, 1, 200000, 1000, 100, 100000000, 200, 0}
{
}

bool KCubeParams::takes(std::uint16_t id, KCubeOutcome& out) const
{
    if (firmware_ == Firmware::Issue3) {
        out.ignored = name_of(id) + " is a message of later protocol issues: a " + model_
                      + " of the issue-3 generation (the 2012 manual) does not know it: ignored";
        return false;
    }
    if ((blocks_ & block_of(id)) == 0) {
        out.ignored = name_of(id) + " is not a message a " + model_ + " acts on: ignored";
        return false;
    }
    return true;
}

void KCubeParams::on(const msg::SetPowerParams& m, KCubeOutcome& out)
{
    if (takes(m.id, out))
        power_ = {kChan1, m.params.rest_factor, m.params.move_factor};
}

void KCubeParams::on(const msg::ReqPowerParams& m, KCubeOutcome& out)
{
    if (takes(m.id, out))
        out.answer = msg::GetPowerParams{power_};
}

void KCubeParams::on(const msg::MotSetTstActuatorType& m, KCubeOutcome& out)
{
    if (!takes(m.id, out))
        return;
    const auto ident = m.params.actuator_ident;
    if (std::find(kActuators.begin(), kActuators.end(), ident) == kActuators.end()) {
        out.ignored = "MGMSG_MOT_SET_TSTACTUATORTYPE with actuator " + hex_byte(ident)
                      + " (not a documented actuator): ignored";
        return;
    }
    actuator_ = ident;
}

void KCubeParams::on(const msg::MotSetTrigger& m, KCubeOutcome& out)
{
    // Every bit of the mode byte is documented (issue 16 p. 102-103): any value is taken.
    if (takes(m.id, out))
        trigger_mode_ = m.mode;
}

void KCubeParams::on(const msg::MotReqTrigger& m, KCubeOutcome& out)
{
    if (takes(m.id, out))
        out.answer = msg::MotGetTrigger{static_cast<std::uint8_t>(kChan1), trigger_mode_};
}

void KCubeParams::on(const msg::SetKCubeMmiParams& m, KCubeOutcome& out)
{
    if (!takes(m.id, out))
        return;
    mmi_ = m.params;
    mmi_.chan_ident = kChan1;
}

void KCubeParams::on(const msg::ReqKCubeMmiParams& m, KCubeOutcome& out)
{
    if (takes(m.id, out))
        out.answer = msg::GetKCubeMmiParams{mmi_};
}

void KCubeParams::on(const msg::SetKCubeTrigIoConfig& m, KCubeOutcome& out)
{
    if (!takes(m.id, out))
        return;
    const auto& p = m.params;
    for (const auto mode : {p.trig1_mode, p.trig2_mode})
        if (!trig_mode_known(mode)) {
            out.ignored = "MGMSG_MOT_SET_KCUBETRIGIOCONFIG with trigger mode " + std::to_string(mode)
                          + " (0..4 or 10..18): ignored";
            return;
        }
    if (position_mode(p.trig1_mode) && position_mode(p.trig2_mode)) {
        out.ignored = "MGMSG_MOT_SET_KCUBETRIGIOCONFIG with both ports in a position pulse mode (13..15; one "
                      "port at a time): ignored";
        return;
    }
    trig_io_ = p;
    trig_io_.chan_ident = kChan1;
}

void KCubeParams::on(const msg::ReqKCubeTrigIoConfig& m, KCubeOutcome& out)
{
    if (takes(m.id, out))
        out.answer = msg::GetKCubeTrigIoConfig{trig_io_};
}

void KCubeParams::on(const msg::SetKCubePosTrigParams& m, KCubeOutcome& out)
{
    if (!takes(m.id, out))
        return;
    pos_trig_ = m.params;
    pos_trig_.chan_ident = kChan1;
}

void KCubeParams::on(const msg::ReqKCubePosTrigParams& m, KCubeOutcome& out)
{
    if (takes(m.id, out))
        out.answer = msg::GetKCubePosTrigParams{pos_trig_};
}

void KCubeParams::on(const msg::SetKCubeKstLoopParams& m, KCubeOutcome& out)
{
    if (!takes(m.id, out))
        return;
    kst_loop_ = m.params;
    kst_loop_.chan_ident = kChan1;
}

void KCubeParams::on(const msg::ReqKCubeKstLoopParams& m, KCubeOutcome& out)
{
    if (takes(m.id, out))
        out.answer = msg::GetKCubeKstLoopParams{kst_loop_};
}

std::size_t KCubeParams::fields_read(std::uint16_t id) const
{
    // The wheel and presets of a motor K-Cube's block run to PresetPos3 (data 28) and
    // JSSensitivity (32; quantumion kdc.py, the issue 37 client); a KSC101 has neither and reads
    // the display words at 22..27 (msl-equipment ksc.py "<H20x3H8x"): the table's 28.
    constexpr std::size_t kMotorMmiFields = 34;
    if (id == MGMSG_MOT_SET_KCUBEMMIPARAMS && model_ != "KSC101")
        return kMotorMmiFields;
    const auto* info = find_message(id);
    return info ? info->min_data_length() : 0;
}

bool KCubeParams::saves(std::uint16_t id) const
{
    return is_set(id) && (blocks_ & block_of(id)) != 0;
}

std::optional<std::string> KCubeParams::saved_data(const msg::Message& m) const
{
    if (!saves(msg::message_id(m)))
        return std::nullopt;
    if (const auto* s = msg::get_if<msg::MotSetTstActuatorType>(m))
        return std::string{static_cast<char>(s->params.actuator_ident), '\0'};
    if (const auto* s = msg::get_if<msg::MotSetTrigger>(m))
        return std::string{static_cast<char>(kChan1), static_cast<char>(s->mode)};
    if (const auto* s = msg::get_if<msg::SetPowerParams>(m))
        return stored(*s);
    if (const auto* s = msg::get_if<msg::SetKCubeMmiParams>(m))
        return stored(*s);
    if (const auto* s = msg::get_if<msg::SetKCubeTrigIoConfig>(m))
        return stored(*s);
    if (const auto* s = msg::get_if<msg::SetKCubePosTrigParams>(m))
        return stored(*s);
    if (const auto* s = msg::get_if<msg::SetKCubeKstLoopParams>(m))
        return stored(*s);
    return std::nullopt;
}

} // namespace rigsim::apt
