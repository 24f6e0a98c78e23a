#pragma once
// The KIM101/TIM101 piezo motor controllers' messages (MGMSG_PZMOT_*, Thorlabs' "Motion
// Controllers Host-Controller Communications Protocol" issue 37 p. 370-406), which the 2012
// manual lacks.
//
// PZMOT_SET_PARAMS and PZMOT_GET_PARAMS carry one sub-message each (p. 371): the first data word
// names the block (SubMsgID), the block's fields follow. Each block is a struct of its own
// (`sub_id`, its fields after SubMsgID); PzmotBlock is their variant, and the two messages hold
// one. PZMOT_REQ_PARAMS is header-only: param1 the SubMsgID, param2 the channel (p. 372; every
// public driver sends it so: pyLabLib kinesis.py, InstrumentKit thorlabsapt.py, yaq's
// thorlabs-apt-protocol). The channel word is a bit (1, 2, 4, 8 for channels 1 to 4) everywhere
// the data carries one (p. 372-405); PZMOT_MOVE_JOG's param1 is the channel (docs/protocol/
// errata.md "Units of today" for which numbering).
//
// This header is a part of codec.hpp: codec.hpp includes it after the chapters and before its
// Message variant (group PzmotMessage); include codec.hpp, not this.

namespace rigsim::apt::msg {

// ---- The sub-message blocks (p. 372-401) ----

/// 0x05 PosCounts (p. 372): the position counter, in steps.
struct PzmotPosCounts {
    static constexpr std::uint16_t sub_id = 0x05;
    static constexpr std::string_view sub_name = "PosCounts";
    std::uint16_t chan_ident = 1;
    std::int32_t position = 0;
    std::int32_t enc_count = 0;   ///< not used
    RIGSIM_APT_FIELDS(s.chan_ident, s.position, s.enc_count);
};

/// 0x07 DriveOPParams (p. 374): the drive of MOVE_ABSOLUTE.
struct PzmotDriveOpParams {
    static constexpr std::uint16_t sub_id = 0x07;
    static constexpr std::string_view sub_name = "DriveOPParams";
    std::uint16_t chan_ident = 1;
    std::uint16_t max_voltage = 110;   ///< V, 85..125
    std::int32_t step_rate = 500;      ///< steps/s, 1..2000
    std::int32_t step_accn = 100'000;  ///< steps/s², 1..100,000
    RIGSIM_APT_FIELDS(s.chan_ident, s.max_voltage, s.step_rate, s.step_accn);
    RIGSIM_APT_RANGES({"MaxVoltage", s.max_voltage, 85, 125}, {"StepRate", s.step_rate, 1, 2000},
                      {"StepAccn", s.step_accn, 1, 100'000});
};

/// 0x09 TIM_JogParams (p. 376, TIM101 only): the jog of MOVE_JOG.
struct PzmotTimJogParams {
    static constexpr std::uint16_t sub_id = 0x09;
    static constexpr std::string_view sub_name = "TIM_JogParams";
    std::uint16_t chan_ident = 1;
    std::uint16_t jog_mode = 2;         ///< 1 continuous, 2 single step
    std::int32_t jog_step_size = 250;   ///< steps, 1..2000
    std::int32_t jog_step_rate = 500;   ///< steps/s, 1..2000
    std::int32_t jog_step_accn = 100'000;
    RIGSIM_APT_FIELDS(s.chan_ident, s.jog_mode, s.jog_step_size, s.jog_step_rate, s.jog_step_accn);
    RIGSIM_APT_RANGES({"JogMode", s.jog_mode, 1, 2}, {"JogStepSize", s.jog_step_size, 1, 2000},
                      {"JogStepRate", s.jog_step_rate, 1, 2000}, {"JogStepAccn", s.jog_step_accn, 1, 100'000});
};

/// 0x11 TIM_PotParams (p. 378, TIM101 only): the top panel slider's top speed.
struct PzmotTimPotParams {
    static constexpr std::uint16_t sub_id = 0x11;
    static constexpr std::string_view sub_name = "TIM_PotParams";
    std::uint16_t chan_ident = 1;
    std::int32_t max_step_rate = 1000;   ///< steps/s, 1..2000
    RIGSIM_APT_FIELDS(s.chan_ident, s.max_step_rate);
    RIGSIM_APT_RANGES({"MaxStepRate", s.max_step_rate, 1, 2000});
};

/// 0x13 TIM_ButtonParams (p. 379, TIM101 only): the top panel buttons.
struct PzmotTimButtonParams {
    static constexpr std::uint16_t sub_id = 0x13;
    static constexpr std::string_view sub_name = "TIM_ButtonParams";
    std::uint16_t chan_ident = 1;
    std::uint16_t mode = 1;   ///< 1 jog, 2 go to position
    std::int32_t position1 = 0;
    std::int32_t position2 = 0;
    std::uint16_t time_out1 = 0;
    std::uint16_t time_out2 = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.mode, s.position1, s.position2, s.time_out1, s.time_out2);
    RIGSIM_APT_RANGES({"Mode", s.mode, 1, 2});
};

/// 0x0B LimSwitchParams (p. 381, KIM101): issue 37 says the unit does not act on it yet: stored and answered.
struct PzmotLimSwitchParams {
    static constexpr std::uint16_t sub_id = 0x0B;
    static constexpr std::string_view sub_name = "LimSwitchParams";
    std::uint16_t chan_ident = 1;
    std::uint16_t fwd_hard_limit = 1;   ///< 1..5 as MOT_SET_LIMSWITCHPARAMS' (1: ignored)
    std::uint16_t rev_hard_limit = 1;
    std::uint16_t stage_id = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.fwd_hard_limit, s.rev_hard_limit, s.stage_id);
    RIGSIM_APT_RANGES({"FwdHardLimit", s.fwd_hard_limit, 1, 5}, {"RevHardLimit", s.rev_hard_limit, 1, 5});
};

/// 0x0F HomeParams (p. 383, KIM101, REQ/GET only): "for future use".
struct PzmotHomeParams {
    static constexpr std::uint16_t sub_id = 0x0F;
    static constexpr std::string_view sub_name = "HomeParams";
    std::uint16_t chan_ident = 1;
    std::uint16_t home_direction = 2;   ///< 1 forward, 2 reverse
    std::uint16_t home_lim_switch = 1;  ///< 1 forward, 4 reverse switch
    std::int32_t home_step_rate = 500;
    std::int32_t home_offset_dist = 0;  ///< steps, 0..10,000
    RIGSIM_APT_FIELDS(s.chan_ident, s.home_direction, s.home_lim_switch, s.home_step_rate, s.home_offset_dist);
};

/// 0x15 KCubeMMIParams (p. 385, KIM101): the joystick and display (24 data bytes: the structure's
/// and every driver's; the example header's 0x1C is 4 too many).
struct PzmotKCubeMmiParams {
    static constexpr std::uint16_t sub_id = 0x15;
    static constexpr std::string_view sub_name = "KCubeMMIParams";
    std::uint16_t chan_ident = 1;
    std::uint16_t js_mode = 1;          ///< 1 velocity, 2 jog, 3 go to position
    std::int32_t js_max_step_rate = 2000;   ///< steps/s, 1..2000
    std::uint16_t js_dir_sense = 1;     ///< 1 normal, 2 reversed
    std::int32_t preset_pos1 = 0;
    std::int32_t preset_pos2 = 0;
    std::uint16_t disp_brightness = 100;   ///< 0..100 %
    std::uint16_t reserved = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.js_mode, s.js_max_step_rate, s.js_dir_sense, s.preset_pos1, s.preset_pos2,
                      s.disp_brightness, s.reserved);
    RIGSIM_APT_RANGES({"JSMode", s.js_mode, 1, 3}, {"JSMaxStepRate", s.js_max_step_rate, 1, 2000},
                      {"JSDirSense", s.js_dir_sense, 0, 2}, {"DispBrightness", s.disp_brightness, 0, 100});
};

/// 0x17 TrigIOConfig (p. 387, KIM101): the two trigger ports, each tied to a channel (no channel
/// word of its own).
struct PzmotTrigIoConfig {
    static constexpr std::uint16_t sub_id = 0x17;
    static constexpr std::string_view sub_name = "TrigIOConfig";
    std::uint16_t trig_channel1 = 1;   ///< the channel TRIG1 acts on (1, 2, 4, 8)
    std::uint16_t trig_channel2 = 1;
    std::uint16_t trig1_mode = 0;      ///< 0 disabled, 1 GPI, 2-4 input moves, 0x0A-0x12 outputs
    std::uint16_t trig1_polarity = 1;  ///< 1 active high, 2 active low
    std::uint16_t trig2_mode = 0;
    std::uint16_t trig2_polarity = 1;
    std::uint16_t reserved1 = 0;
    std::uint16_t reserved2 = 0;
    std::uint16_t reserved3 = 0;
    std::uint16_t reserved4 = 0;
    std::uint16_t reserved5 = 0;
    std::uint16_t reserved6 = 0;
    RIGSIM_APT_FIELDS(s.trig_channel1, s.trig_channel2, s.trig1_mode, s.trig1_polarity, s.trig2_mode,
                      s.trig2_polarity, s.reserved1, s.reserved2, s.reserved3, s.reserved4, s.reserved5,
                      s.reserved6);
    RIGSIM_APT_RANGES({"Trig1Mode", s.trig1_mode, 0, 0x12}, {"Trig1Polarity", s.trig1_polarity, 1, 2},
                      {"Trig2Mode", s.trig2_mode, 0, 0x12}, {"Trig2Polarity", s.trig2_polarity, 1, 2});
};

/// 0x19 TrigParams (p. 391, KIM101): the position trigger outputs.
struct PzmotTrigParams {
    static constexpr std::uint16_t sub_id = 0x19;
    static constexpr std::string_view sub_name = "TrigParams";
    std::uint16_t chan_ident = 1;
    std::int32_t start_pos_fwd = 0;
    std::int32_t interval_fwd = 0;
    std::int32_t num_pulses_fwd = 0;
    std::int32_t start_pos_rev = 0;
    std::int32_t interval_rev = 0;
    std::int32_t num_pulses_rev = 0;
    std::int32_t pulse_width = 10;   ///< µs, 1..100,000
    std::int32_t num_cycles = 1;
    RIGSIM_APT_FIELDS(s.chan_ident, s.start_pos_fwd, s.interval_fwd, s.num_pulses_fwd, s.start_pos_rev,
                      s.interval_rev, s.num_pulses_rev, s.pulse_width, s.num_cycles);
    RIGSIM_APT_RANGES({"PulseWidth", s.pulse_width, 1, 100'000});
};

/// 0x2B ChanEnableMode (p. 394, KIM101): which channels are enabled (no channel word).
struct PzmotChanEnableMode {
    static constexpr std::uint16_t sub_id = 0x2B;
    static constexpr std::string_view sub_name = "ChanEnableMode";
    std::uint16_t mode = 1;   ///< 0 none, 1-4 that channel, 5 channels 1 and 2, 6 channels 3 and 4
    RIGSIM_APT_FIELDS(s.mode);
    RIGSIM_APT_RANGES({"Mode", s.mode, 0, 6});
};

/// 0x2D KCubeJogParams (p. 396, KIM101): the jog of MOVE_JOG, a step count for each direction.
struct PzmotKCubeJogParams {
    static constexpr std::uint16_t sub_id = 0x2D;
    static constexpr std::string_view sub_name = "KCubeJogParams";
    std::uint16_t chan_ident = 1;
    std::uint16_t jog_mode = 2;             ///< 1 continuous, 2 single step
    std::int32_t jog_step_size_fwd = 250;   ///< steps, 1..2000
    std::int32_t jog_step_size_rev = 260;
    std::int32_t jog_step_rate = 500;       ///< steps/s, 1..2000
    std::int32_t jog_step_accn = 100'000;   ///< steps/s², 1..100,000
    RIGSIM_APT_FIELDS(s.chan_ident, s.jog_mode, s.jog_step_size_fwd, s.jog_step_size_rev, s.jog_step_rate,
                      s.jog_step_accn);
    RIGSIM_APT_RANGES({"JogMode", s.jog_mode, 1, 2}, {"JogStepSizeFwd", s.jog_step_size_fwd, 1, 2000},
                      {"JogStepSizeRev", s.jog_step_size_rev, 1, 2000}, {"JogStepRate", s.jog_step_rate, 1, 2000},
                      {"JogStepAccn", s.jog_step_accn, 1, 100'000});
};

/// 0x30 KCubeFeedbackSigParams (p. 398, KIM101): the feedback input ("encoder: future").
struct PzmotFeedbackSigParams {
    static constexpr std::uint16_t sub_id = 0x30;
    static constexpr std::string_view sub_name = "KCubeFeedbackSigParams";
    std::uint16_t chan_ident = 1;
    std::uint16_t fb_signal_mode = 0;   ///< 0 disabled, 1 limit switch, 2 encoder
    std::int32_t encoder_const = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.fb_signal_mode, s.encoder_const);
    RIGSIM_APT_RANGES({"FBSignalMode", s.fb_signal_mode, 0, 2});
};

/// 0x32 KCubeMoveRelativeParams (p. 400, KIM101): the distance of a trigger input's relative move.
struct PzmotMoveRelativeParams {
    static constexpr std::uint16_t sub_id = 0x32;
    static constexpr std::string_view sub_name = "KCubeMoveRelativeParams";
    std::uint16_t chan_ident = 1;
    std::int32_t rel_distance = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.rel_distance);
};

/// 0x34 KCubeMoveAbsoluteParams (p. 401, KIM101): the target of a trigger input's absolute move.
struct PzmotMoveAbsoluteParams {
    static constexpr std::uint16_t sub_id = 0x34;
    static constexpr std::string_view sub_name = "KCubeMoveAbsoluteParams";
    std::uint16_t chan_ident = 1;
    std::int32_t abs_distance = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.abs_distance);
};

/// One sub-message block of PZMOT_SET/GET_PARAMS.
using PzmotBlock =
    std::variant<PzmotPosCounts, PzmotDriveOpParams, PzmotTimJogParams, PzmotTimPotParams, PzmotTimButtonParams,
                 PzmotLimSwitchParams, PzmotHomeParams, PzmotKCubeMmiParams, PzmotTrigIoConfig, PzmotTrigParams,
                 PzmotChanEnableMode, PzmotKCubeJogParams, PzmotFeedbackSigParams, PzmotMoveRelativeParams,
                 PzmotMoveAbsoluteParams>;

/// The block's SubMsgID.
inline std::uint16_t sub_id_of(const PzmotBlock& b)
{
    return std::visit([](const auto& s) { return std::decay_t<decltype(s)>::sub_id; }, b);
}

/// The block's channel word (1, 2, 4, 8), or 0 for a block without one (ChanEnableMode, TrigIOConfig).
inline std::uint16_t channel_of(const PzmotBlock& b)
{
    return std::visit(
        [](const auto& s) -> std::uint16_t {
            if constexpr (std::is_same_v<std::decay_t<decltype(s)>, PzmotChanEnableMode>
                          || std::is_same_v<std::decay_t<decltype(s)>, PzmotTrigIoConfig>)
                return 0;
            else
                return s.chan_ident;
        },
        b);
}

// ---- The messages (p. 371-406) ----

/// MGMSG_PZMOT_SET_PARAMS (p. 371): one sub-message block.
struct PzmotSetParams {
    RIGSIM_APT_MESSAGE(MGMSG_PZMOT_SET_PARAMS, PzMotor);
    PzmotBlock block;
    RIGSIM_APT_FIELDS(s.block);
};
/// MGMSG_PZMOT_REQ_PARAMS (p. 372): header-only, param1 the SubMsgID, param2 the channel.
struct PzmotReqParams {
    RIGSIM_APT_MESSAGE(MGMSG_PZMOT_REQ_PARAMS, PzMotor);
    std::uint8_t sub_msg_id = 0x05;
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.sub_msg_id, s.chan_ident);
};
/// MGMSG_PZMOT_GET_PARAMS (p. 373): the unit's answer, the block asked for.
struct PzmotGetParams {
    RIGSIM_APT_MESSAGE(MGMSG_PZMOT_GET_PARAMS, UnitToHost);
    PzmotBlock block;
    RIGSIM_APT_FIELDS(s.block);
};
/// MGMSG_PZMOT_MOVE_ABSOLUTE (p. 402; its contents list types 0x04D8): to a step count from zero.
struct PzmotMoveAbsolute {
    RIGSIM_APT_MESSAGE(MGMSG_PZMOT_MOVE_ABSOLUTE, PzMotor);
    std::uint16_t chan_ident = 1;
    std::int32_t abs_position = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.abs_position);
};
/// MGMSG_PZMOT_MOVE_COMPLETED (p. 403): a move or jog ended.
struct PzmotMoveCompleted {
    RIGSIM_APT_MESSAGE(MGMSG_PZMOT_MOVE_COMPLETED, UnitToHost);
    std::uint16_t chan_ident = 1;
    std::int32_t abs_position = 0;
    std::int32_t enc_count = 0;      ///< not used
    std::uint32_t status_bits = 0;   ///< not used
    RIGSIM_APT_FIELDS(s.chan_ident, s.abs_position, s.enc_count, s.status_bits);
};
/// MGMSG_PZMOT_MOVE_JOG (p. 404): header-only, param1 the channel, param2 1 forward, 2 reverse.
struct PzmotMoveJog {
    RIGSIM_APT_MESSAGE(MGMSG_PZMOT_MOVE_JOG, PzMotor);
    std::uint8_t chan_ident = 1;
    std::uint8_t jog_dir = 1;
    RIGSIM_APT_FIELDS(s.chan_ident, s.jog_dir);
};
/// MGMSG_PZMOT_REQ_STATUSUPDATE (p. 405): header-only; answered by GET_STATUSUPDATE.
struct PzmotReqStatusUpdate {
    RIGSIM_APT_MESSAGE(MGMSG_PZMOT_REQ_STATUSUPDATE, PzMotor);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_PZMOT_GET_STATUSUPDATE (p. 405): the four channels' counters and status bits.
struct PzmotGetStatusUpdate {
    RIGSIM_APT_MESSAGE(MGMSG_PZMOT_GET_STATUSUPDATE, UnitToHost);
    std::uint16_t chan_ident1 = 1;
    std::int32_t position1 = 0;
    std::int32_t enc_count1 = 0;
    std::uint32_t status_bits1 = 0;
    std::uint16_t chan_ident2 = 2;
    std::int32_t position2 = 0;
    std::int32_t enc_count2 = 0;
    std::uint32_t status_bits2 = 0;
    std::uint16_t chan_ident3 = 4;
    std::int32_t position3 = 0;
    std::int32_t enc_count3 = 0;
    std::uint32_t status_bits3 = 0;
    std::uint16_t chan_ident4 = 8;
    std::int32_t position4 = 0;
    std::int32_t enc_count4 = 0;
    std::uint32_t status_bits4 = 0;
    RIGSIM_APT_FIELDS(s.chan_ident1, s.position1, s.enc_count1, s.status_bits1, s.chan_ident2, s.position2,
                      s.enc_count2, s.status_bits2, s.chan_ident3, s.position3, s.enc_count3, s.status_bits3,
                      s.chan_ident4, s.position4, s.enc_count4, s.status_bits4);
};
/// MGMSG_PZMOT_ACK_STATUSUPDATE (p. 406): the host's "server alive" (the unit shell takes it).
RIGSIM_APT_BARE_MESSAGE(PzmotAckStatusUpdate, MGMSG_PZMOT_ACK_STATUSUPDATE, PzMotor);

/// The KIM101/TIM101 messages (later protocol issues).
struct PzmotMessage
    : std::variant<PzmotSetParams, PzmotReqParams, PzmotGetParams, PzmotMoveAbsolute, PzmotMoveCompleted,
                   PzmotMoveJog, PzmotReqStatusUpdate, PzmotGetStatusUpdate, PzmotAckStatusUpdate> {
    using variant::variant;
};

} // namespace rigsim::apt::msg
