#pragma once
// The K-Cube piezo driver's and strain gauge reader's own messages (KPZ101, KSG101), and the MFF101/
// MFF102 flipper's (issue 28), which later
// issues of the APT protocol add and the 2012 manual lacks, typed as codec.hpp types the
// manual's: one parameter block per SET/REQ/GET trio, with the field names of the public sources
// (messages.def and docs/protocol/apt.md "K-Cube units" name them), and the header-only
// PZ_REQ_PZSTATUSUPDATE.
//
// This header is a part of codec.hpp: codec.hpp includes it after its Set<>, Req<> and Get<>
// templates and before its Message variant (group KCubeUnitMessage); include codec.hpp, not this.

namespace rigsim::apt::msg {

/// MGMSG_KPZ_SET/REQ/GET_KCUBEMMIPARAMS (later issue, 34 bytes): the KPZ101's wheel and display.
struct KpzMmiParams {
    static constexpr std::uint16_t set_id = MGMSG_KPZ_SET_KCUBEMMIPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_KPZ_REQ_KCUBEMMIPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_KPZ_GET_KCUBEMMIPARAMS;
    static constexpr Family family = Family::Piezo;
    std::uint16_t chan_ident = 1;
    std::uint16_t js_mode = 1;          ///< wheel: 1 move at voltage, 2 jog voltage, 3 go to a preset voltage
    std::uint16_t js_volt_gearbox = 1;  ///< wheel rate: 1 high, 2 medium, 3 low
    std::int32_t js_volt_step = 0;      ///< the jog mode's voltage step
    std::uint16_t dir_sense = 1;        ///< wheel direction: 1 positive, 2 negative (0: as sent by clients)
    std::int32_t preset_volt1 = 0;      ///< the go-to mode's preset voltages
    std::int32_t preset_volt2 = 0;
    std::uint16_t disp_brightness = 0;  ///< display, 0..100 %
    std::uint16_t disp_timeout = 0;     ///< minutes without use before the display dims, 0..480 (0: never)
    std::uint16_t disp_dim_level = 0;   ///< dimmed brightness, 0..10
    std::uint16_t reserved1 = 0;
    std::uint16_t reserved2 = 0;
    std::uint16_t reserved3 = 0;
    std::uint16_t reserved4 = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.js_mode, s.js_volt_gearbox, s.js_volt_step, s.dir_sense, s.preset_volt1,
                      s.preset_volt2, s.disp_brightness, s.disp_timeout, s.disp_dim_level, s.reserved1, s.reserved2,
                      s.reserved3, s.reserved4);
};

/// MGMSG_KPZ_SET/REQ/GET_KCUBETRIGIOCONFIG (later issue, 22 bytes): the KPZ101's TRIG1/TRIG2 ports.
struct KpzTrigIoConfig {
    static constexpr std::uint16_t set_id = MGMSG_KPZ_SET_KCUBETRIGIOCONFIG;
    static constexpr std::uint16_t req_id = MGMSG_KPZ_REQ_KCUBETRIGIOCONFIG;
    static constexpr std::uint16_t get_id = MGMSG_KPZ_GET_KCUBETRIGIOCONFIG;
    static constexpr Family family = Family::Piezo;
    std::uint16_t chan_ident = 1;
    std::uint16_t trig1_mode = 0;       ///< 0 disabled, 1 input (GPI), 2 input: voltage step up, 3 step down, 0x0A output (GPO)
    std::uint16_t trig1_polarity = 1;   ///< 1 active high, 2 active low
    std::uint16_t trig2_mode = 0;
    std::uint16_t trig2_polarity = 1;
    std::uint16_t reserved1 = 0;
    std::uint16_t reserved2 = 0;
    std::uint16_t reserved3 = 0;
    std::uint16_t reserved4 = 0;
    std::uint16_t reserved5 = 0;
    std::uint16_t reserved6 = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.trig1_mode, s.trig1_polarity, s.trig2_mode, s.trig2_polarity, s.reserved1,
                      s.reserved2, s.reserved3, s.reserved4, s.reserved5, s.reserved6);
};

/// MGMSG_KSG_SET/REQ/GET_KCUBEMMIPARAMS (later issue, 8 bytes): the KSG101's display.
struct KsgMmiParams {
    static constexpr std::uint16_t set_id = MGMSG_KSG_SET_KCUBEMMIPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_KSG_REQ_KCUBEMMIPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_KSG_GET_KCUBEMMIPARAMS;
    static constexpr Family family = Family::StrainGauge;
    std::uint16_t chan_ident = 1;
    std::uint16_t disp_intensity = 0;   ///< 0..100 %
    std::uint16_t disp_timeout = 0;     ///< minutes, 0..480 (0: never dims)
    std::uint16_t disp_dim_level = 0;   ///< 0..10
    RIGSIM_APT_FIELDS(s.chan_ident, s.disp_intensity, s.disp_timeout, s.disp_dim_level);
};

/// MGMSG_KSG_SET/REQ/GET_KCUBETRIGIOCONFIG (later issue, 22 bytes): the KSG101's TRIG1/TRIG2
/// ports and the reading limits its outputs compare against.
struct KsgTrigIoConfig {
    static constexpr std::uint16_t set_id = MGMSG_KSG_SET_KCUBETRIGIOCONFIG;
    static constexpr std::uint16_t req_id = MGMSG_KSG_REQ_KCUBETRIGIOCONFIG;
    static constexpr std::uint16_t get_id = MGMSG_KSG_GET_KCUBETRIGIOCONFIG;
    static constexpr Family family = Family::StrainGauge;
    std::uint16_t chan_ident = 1;
    std::uint16_t trig1_mode = 0;       ///< 0 disabled, 1 GPI, 0x0A GPO, 0x0B..0x10 output against the limits
    std::uint16_t trig1_polarity = 1;   ///< 1 active high, 2 active low
    std::uint16_t trig2_mode = 0;
    std::uint16_t trig2_polarity = 1;
    std::int32_t lower_lim = 0;         ///< on the reading's scale
    std::int32_t upper_lim = 0;
    std::uint16_t smoothing_samples = 1;
    std::uint16_t reserved = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.trig1_mode, s.trig1_polarity, s.trig2_mode, s.trig2_polarity, s.lower_lim,
                      s.upper_lim, s.smoothing_samples, s.reserved);
};

/// MGMSG_PZ_REQ_PZSTATUSUPDATE (later issue): answered by MGMSG_PZ_GET_PZSTATUSUPDATE.
struct PzReqPzStatusUpdate {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_REQ_PZSTATUSUPDATE, Piezo);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};

using SetKpzMmiParams = Set<KpzMmiParams>;
using ReqKpzMmiParams = Req<KpzMmiParams>;
using GetKpzMmiParams = Get<KpzMmiParams>;
using SetKpzTrigIoConfig = Set<KpzTrigIoConfig>;
using ReqKpzTrigIoConfig = Req<KpzTrigIoConfig>;
using GetKpzTrigIoConfig = Get<KpzTrigIoConfig>;
using SetKsgMmiParams = Set<KsgMmiParams>;
using ReqKsgMmiParams = Req<KsgMmiParams>;
using GetKsgMmiParams = Get<KsgMmiParams>;
using SetKsgTrigIoConfig = Set<KsgTrigIoConfig>;
using ReqKsgTrigIoConfig = Req<KsgTrigIoConfig>;
using GetKsgTrigIoConfig = Get<KsgTrigIoConfig>;

/// MGMSG_MOT_SET/REQ/GET_MFF_OPERPARAMS (issue 37 p. 182-185, 34 bytes): the MFF101/MFF102 flipper's
/// transit time and its two digital I/O ports.
struct MffOperParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_MFF_OPERPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_MFF_OPERPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_MFF_OPERPARAMS;
    static constexpr Family family = Family::Flipper;
    std::uint16_t chan_ident = 1;
    std::int32_t transit_time = 500;        ///< ms from one position to the other, 300..2800
    std::int32_t transit_time_adc = 508;    ///< 10,000,000 × TransitTime^-1.591, as the client computes it
    std::uint16_t dig_io1_oper_mode = 1;    ///< 1 input: toggle, 2 input: go to position, 3 output: at position, 4 output: moving
    std::uint16_t dig_io1_sig_mode = 1;     ///< 0x01 button, 0x02 logic edge, 0x04 swap (OR), 0x10 level out, 0x20 pulse out, 0x40 invert (OR)
    std::int32_t dig_io1_pulse_width = 200; ///< ms, 10..200
    std::uint16_t dig_io2_oper_mode = 1;
    std::uint16_t dig_io2_sig_mode = 1;
    std::int32_t dig_io2_pulse_width = 200;
    std::int32_t not_used1 = 0;
    std::uint32_t not_used2 = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.transit_time, s.transit_time_adc, s.dig_io1_oper_mode, s.dig_io1_sig_mode,
                      s.dig_io1_pulse_width, s.dig_io2_oper_mode, s.dig_io2_sig_mode, s.dig_io2_pulse_width,
                      s.not_used1, s.not_used2);
    // Issue 37 p. 183-184 and Kinesis' FilterFlipper.h: transit 300..2800 ms, pulses 10..200 ms,
    // operating modes 1..4.
    RIGSIM_APT_RANGES({"TransitTime", s.transit_time, 300, 2800}, {"DigIO1OperMode", s.dig_io1_oper_mode, 1, 4},
                      {"DigIO1PulseWidth", s.dig_io1_pulse_width, 10, 200}, {"DigIO2OperMode", s.dig_io2_oper_mode, 1, 4},
                      {"DigIO2PulseWidth", s.dig_io2_pulse_width, 10, 200});
};

using SetMffOperParams = Set<MffOperParams>;
using ReqMffOperParams = Req<MffOperParams>;
using GetMffOperParams = Get<MffOperParams>;

/// MGMSG_MOT_SET/REQ/GET_POLPARAMS (issue 37 p. 408-409, 12 bytes): the MPC320/MPC220's velocity,
/// home position and each paddle's jog step (one set for the unit: no channel word).
struct PolParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_POLPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_POLPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_POLPARAMS;
    static constexpr Family family = Family::Polariser;
    std::uint16_t not_used = 0;
    std::uint16_t velocity = 50;       ///< % of 400 deg/s, 10..100
    std::uint16_t home_position = 0;   ///< counts, 0..1370 (0..170 deg)
    std::uint16_t jog_step1 = 25;      ///< counts, paddle 1
    std::uint16_t jog_step2 = 25;
    std::uint16_t jog_step3 = 25;
    RIGSIM_APT_FIELDS(s.not_used, s.velocity, s.home_position, s.jog_step1, s.jog_step2, s.jog_step3);
    RIGSIM_APT_RANGES({"Velocity", s.velocity, 10, 100}, {"HomePosition", s.home_position, 0, 1370},
                      {"JogStep1", s.jog_step1, 0, 1370}, {"JogStep2", s.jog_step2, 0, 1370},
                      {"JogStep3", s.jog_step3, 0, 1370});
};

using SetPolParams = Set<PolParams>;
using ReqPolParams = Req<PolParams>;
using GetPolParams = Get<PolParams>;

/// The K-Cube piezo driver's and strain gauge reader's own messages, the flipper's and the polarisation controller's (later
/// protocol issues).
struct KCubeUnitMessage
    : std::variant<SetKpzMmiParams, ReqKpzMmiParams, GetKpzMmiParams, SetKpzTrigIoConfig, ReqKpzTrigIoConfig,
                   GetKpzTrigIoConfig, SetKsgMmiParams, ReqKsgMmiParams, GetKsgMmiParams, SetKsgTrigIoConfig,
                   ReqKsgTrigIoConfig, GetKsgTrigIoConfig, PzReqPzStatusUpdate, SetMffOperParams, ReqMffOperParams,
                   GetMffOperParams, SetPolParams, ReqPolParams, GetPolParams> {
    using variant::variant;
};

} // namespace rigsim::apt::msg
