#pragma once
// The codec structs of the motor messages that later protocol issues add (messages.def,
// "Later protocol issues"): the stepper power factors, the rack trigger byte, the K-Cube
// wheel/display, trigger port, position trigger and KST loop blocks, the TST actuator type.
// Same pattern as codec.hpp (fields() in wire order; Set<>/Req<>/Get<> trios). Their family,
// KCubeMotor, is acted on by the motor modules through KCubeParams (kcube_params.hpp).
//
// codec.hpp includes this file where Set<>, Req<> and Get<> are defined: include codec.hpp,
// not this file.

namespace rigsim::apt::msg {

/// MGMSG_MOT_SET/REQ/GET_POWERPARAMS (issue 16 p. 44): a stepper's phase power at rest and
/// while moving, in % of full power.
struct PowerParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_POWERPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_POWERPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_POWERPARAMS;
    static constexpr Family family = Family::KCubeMotor;
    std::uint16_t chan_ident = 1;
    std::uint16_t rest_factor = 0;   ///< 1..100 %
    std::uint16_t move_factor = 0;   ///< 1..100 %
    RIGSIM_APT_FIELDS(s.chan_ident, s.rest_factor, s.move_factor);
    // Issue 16 p. 44: "in the range 1 to 100 (i.e. 1% to 100% of full power)".
    RIGSIM_APT_RANGES({"RestFactor", s.rest_factor, 1, 100}, {"MoveFactor", s.move_factor, 1, 100});
};

/// MGMSG_MOT_SET/REQ/GET_KCUBEMMIPARAMS: the K-Cube's top-panel wheel and display.
struct KCubeMmiParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_KCUBEMMIPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_KCUBEMMIPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_KCUBEMMIPARAMS;
    static constexpr Family family = Family::KCubeMotor;
    std::uint16_t chan_ident = 1;
    std::uint16_t js_mode = 1;          ///< 1 velocity, 2 jog, 3 go to position
    std::int32_t js_max_vel = 0;
    std::int32_t js_accn = 0;
    std::uint16_t dir_sense = 0;        ///< 0 wheel moves disabled, 1 up = forward, 2 up = reverse
    std::int32_t preset_pos1 = 0;
    std::int32_t preset_pos2 = 0;
    std::uint16_t disp_brightness = 0;  ///< 0..100
    std::uint16_t disp_timeout = 0;     ///< minutes, 0 (never dimmed)..480
    std::uint16_t disp_dim_level = 0;   ///< 0..10
    std::int32_t preset_pos3 = 0;
    std::uint16_t js_sensitivity = 0;
    std::uint16_t reserved = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.js_mode, s.js_max_vel, s.js_accn, s.dir_sense, s.preset_pos1, s.preset_pos2,
                      s.disp_brightness, s.disp_timeout, s.disp_dim_level, s.preset_pos3, s.js_sensitivity,
                      s.reserved);
    // quantumion/thorlabs_cube kdc.py (and the issue 37 client's checks): JSMode 1 velocity, 2 jog,
    // 3 go to position; DirSense 0..2; DispBrightness 0..100; DispTimeout 0..480 minutes; DispDimLevel 0..10.
    // The wheel's words are the motor cubes'. A KSC101 has no wheel: Kinesis' KSC_MMIParams calls the ten
    // words before the display "unused", and MSLNZ/msl-equipment thorlabs/ksc.py sends them as 0 (JSMode 0),
    // which the unit takes.
    RIGSIM_APT_RANGES({"JSMode", s.js_mode, 1, 3, ReadBy::WheelUnit},
                      {"DirSense", s.dir_sense, 0, 2, ReadBy::WheelUnit},
                      {"DispBrightness", s.disp_brightness, 0, 100}, {"DispTimeout", s.disp_timeout, 0, 480},
                      {"DispDimLevel", s.disp_dim_level, 0, 10});
};

/// MGMSG_MOT_SET/REQ/GET_KCUBETRIGIOCONFIG: what the TRIG1 and TRIG2 ports do.
struct KCubeTrigIoConfig {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_KCUBETRIGIOCONFIG;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_KCUBETRIGIOCONFIG;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_KCUBETRIGIOCONFIG;
    static constexpr Family family = Family::KCubeMotor;
    std::uint16_t chan_ident = 1;
    std::uint16_t trig1_mode = 0;       ///< 0 disabled, 0x01-0x04 inputs, 0x0A-0x12 outputs
    std::uint16_t trig1_polarity = 1;   ///< 1 active high, 2 active low
    std::uint16_t trig2_mode = 0;
    std::uint16_t trig2_polarity = 1;
    std::array<char, 12> reserved{};
    RIGSIM_APT_FIELDS(s.chan_ident, s.trig1_mode, s.trig1_polarity, s.trig2_mode, s.trig2_polarity, s.reserved);
    // Polarity 1 active high, 2 active low (Kinesis' KMOT_TRIG_POLHIGH / KMOT_TRIG_POLLOW). The modes
    // are a set, not a range: KCubeParams checks them.
    RIGSIM_APT_RANGES({"Trig1Polarity", s.trig1_polarity, 1, 2}, {"Trig2Polarity", s.trig2_polarity, 1, 2});
};

/// MGMSG_MOT_SET/REQ/GET_KCUBEPOSTRIGPARAMS: the output pulses at positions of a trigger port
/// set to a position mode.
struct KCubePosTrigParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_KCUBEPOSTRIGPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_KCUBEPOSTRIGPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_KCUBEPOSTRIGPARAMS;
    static constexpr Family family = Family::KCubeMotor;
    std::uint16_t chan_ident = 1;
    std::int32_t start_pos_fwd = 0;     ///< position counts
    std::int32_t interval_fwd = 0;
    std::int32_t num_pulses_fwd = 0;
    std::int32_t start_pos_rev = 0;
    std::int32_t interval_rev = 0;
    std::int32_t num_pulses_rev = 0;
    std::int32_t pulse_width = 0;       ///< us, 1..1,000,000
    std::int32_t num_cycles = 0;
    std::array<char, 12> reserved{};
    RIGSIM_APT_FIELDS(s.chan_ident, s.start_pos_fwd, s.interval_fwd, s.num_pulses_fwd, s.start_pos_rev,
                      s.interval_rev, s.num_pulses_rev, s.pulse_width, s.num_cycles, s.reserved);
    // quantumion kdc.py: pulse width "from 1 us to 1000000 us"; counts of pulses and cycles.
    RIGSIM_APT_RANGES({"NumPulsesFwd", s.num_pulses_fwd, 0, kMaxLong}, {"NumPulsesRev", s.num_pulses_rev, 0, kMaxLong},
                      {"PulseWidth", s.pulse_width, 1, 1'000'000}, {"NumCycles", s.num_cycles, 0, kMaxLong});
};

/// MGMSG_MOT_SET/REQ/GET_KCUBEKSTLOOPPARAMS: a KST101's position loop (encoded stages).
struct KCubeKstLoopParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_KCUBEKSTLOOPPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_KCUBEKSTLOOPPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_KCUBEKSTLOOPPARAMS;
    static constexpr Family family = Family::KCubeMotor;
    std::uint16_t chan_ident = 1;
    std::uint16_t loop_mode = 1;        ///< 1 open loop, 2 closed loop
    std::int32_t prop = 0;
    std::int32_t integral = 0;
    std::int32_t diff = 0;
    std::int32_t pid_clip = 0;
    std::int32_t pid_tol = 0;
    std::uint32_t encoder_const = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.loop_mode, s.prop, s.integral, s.diff, s.pid_clip, s.pid_tol, s.encoder_const);
    // KMOT_KST_OPENLOOP 1, KMOT_KST_CLOSEDLOOP 2.
    RIGSIM_APT_RANGES({"LoopMode", s.loop_mode, 1, 2});
};

using SetPowerParams = Set<PowerParams>;
using ReqPowerParams = Req<PowerParams>;
using GetPowerParams = Get<PowerParams>;
using SetKCubeMmiParams = Set<KCubeMmiParams>;
using ReqKCubeMmiParams = Req<KCubeMmiParams>;
using GetKCubeMmiParams = Get<KCubeMmiParams>;
using SetKCubeTrigIoConfig = Set<KCubeTrigIoConfig>;
using ReqKCubeTrigIoConfig = Req<KCubeTrigIoConfig>;
using GetKCubeTrigIoConfig = Get<KCubeTrigIoConfig>;
using SetKCubePosTrigParams = Set<KCubePosTrigParams>;
using ReqKCubePosTrigParams = Req<KCubePosTrigParams>;
using GetKCubePosTrigParams = Get<KCubePosTrigParams>;
using SetKCubeKstLoopParams = Set<KCubeKstLoopParams>;
using ReqKCubeKstLoopParams = Req<KCubeKstLoopParams>;
using GetKCubeKstLoopParams = Get<KCubeKstLoopParams>;

/// MGMSG_MOT_SET_TRIGGER (issue 16 p. 102): a rack's trigger mode bits, header only.
struct MotSetTrigger {
    static constexpr std::uint16_t id = MGMSG_MOT_SET_TRIGGER;
    static constexpr bool header_only = header_only_in_table(id);
    static constexpr Family family = Family::KCubeMotor;
    std::uint8_t chan_ident = 1;
    std::uint8_t mode = 0;   ///< bits 0-7 (their meaning differs for brushless and stepper racks)
    RIGSIM_APT_FIELDS(s.chan_ident, s.mode);
};
/// MGMSG_MOT_REQ_TRIGGER (issue 16 p. 103).
struct MotReqTrigger {
    static constexpr std::uint16_t id = MGMSG_MOT_REQ_TRIGGER;
    static constexpr bool header_only = header_only_in_table(id);
    static constexpr Family family = Family::KCubeMotor;
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_MOT_GET_TRIGGER (issue 16 p. 103).
struct MotGetTrigger {
    static constexpr std::uint16_t id = MGMSG_MOT_GET_TRIGGER;
    static constexpr bool header_only = header_only_in_table(id);
    static constexpr Family family = Family::UnitToHost;
    std::uint8_t chan_ident = 1;
    std::uint8_t mode = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.mode);
};
/// MGMSG_MOT_SET_TSTACTUATORTYPE (issue 16 p. 94): the actuator a stepper drives, header only:
/// param1 is the actuator, not a channel. Its fields are a block without a channel word (as
/// PZ_SET_TPZ_DISPSETTINGS's), so the module does not read param1 as a channel.
struct MotSetTstActuatorType {
    static constexpr std::uint16_t id = MGMSG_MOT_SET_TSTACTUATORTYPE;
    static constexpr bool header_only = header_only_in_table(id);
    static constexpr Family family = Family::KCubeMotor;
    struct Params {
        std::uint8_t actuator_ident = 0;   ///< 0x20-0x22 ZST legacy, 0x30-0x32 ZST, 0x40-0x42 ZFS, ...
        std::uint8_t unused = 0;
    } params;
    RIGSIM_APT_FIELDS(s.params.actuator_ident, s.params.unused);
};

/// The motor messages of later protocol issues (after the manual's chapters).
struct KCubeMotorMessage
    : std::variant<SetPowerParams, ReqPowerParams, GetPowerParams, MotSetTstActuatorType, MotSetTrigger,
                   MotReqTrigger, MotGetTrigger, SetKCubeMmiParams, ReqKCubeMmiParams, GetKCubeMmiParams,
                   SetKCubeTrigIoConfig, ReqKCubeTrigIoConfig, GetKCubeTrigIoConfig, SetKCubePosTrigParams,
                   ReqKCubePosTrigParams, GetKCubePosTrigParams, SetKCubeKstLoopParams, ReqKCubeKstLoopParams,
                   GetKCubeKstLoopParams> {
    using variant::variant;
};

} // namespace rigsim::apt::msg
