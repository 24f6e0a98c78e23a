#pragma once
// The codec structs of the Piezo Control Messages (Thorlabs APT protocol, issue 3, section
// "Piezo Control Messages", p. 93-126) and of the TSG001 strain gauge reader (p. 127-129).
//
// This header is a part of codec.hpp: codec.hpp includes it after its Set<>, Req<> and Get<>
// templates and message macros, and before its Message variant; include codec.hpp, not this.

namespace rigsim::apt::msg {

// ---- Piezo Control Messages (p. 93-126) and the TSG001 strain gauge reader (p. 127-129) ----
// PiezoModule (TPZ001, KPZ101, BPC30x bays) and StrainGaugeModule (TSG001, KSG101) act on the
// ones their model's takes lists name (messages.def, catalogue.cpp); the other modules ignore and log them.

/// MGMSG_PZ_SET/REQ/GET_OUTPUTVOLTS (p. 96).
struct PzOutputVolts {
    static constexpr std::uint16_t set_id = MGMSG_PZ_SET_OUTPUTVOLTS;
    static constexpr std::uint16_t req_id = MGMSG_PZ_REQ_OUTPUTVOLTS;
    static constexpr std::uint16_t get_id = MGMSG_PZ_GET_OUTPUTVOLTS;
    static constexpr Family family = Family::Piezo;
    std::uint16_t chan_ident = 1;
    std::int16_t voltage = 0;   ///< -32767..32767: -100..100 % of the maximum output voltage
    RIGSIM_APT_FIELDS(s.chan_ident, s.voltage);
};
/// MGMSG_PZ_SET/REQ/GET_OUTPUTPOS (p. 97).
struct PzOutputPos {
    static constexpr std::uint16_t set_id = MGMSG_PZ_SET_OUTPUTPOS;
    static constexpr std::uint16_t req_id = MGMSG_PZ_REQ_OUTPUTPOS;
    static constexpr std::uint16_t get_id = MGMSG_PZ_GET_OUTPUTPOS;
    static constexpr Family family = Family::Piezo;
    std::uint16_t chan_ident = 1;
    std::uint16_t position_sw = 0;   ///< 0..32767: 0..100 % of the travel (ERRATA)
    RIGSIM_APT_FIELDS(s.chan_ident, s.position_sw);
    // p. 97: 0..32767 = 0..100 % of the travel.
    RIGSIM_APT_RANGES({"PositionSW", s.position_sw, 0, 32767});
};
/// MGMSG_PZ_SET/REQ/GET_INPUTVOLTSSRC (p. 98).
struct PzInputVoltsSrc {
    static constexpr std::uint16_t set_id = MGMSG_PZ_SET_INPUTVOLTSSRC;
    static constexpr std::uint16_t req_id = MGMSG_PZ_REQ_INPUTVOLTSSRC;
    static constexpr std::uint16_t get_id = MGMSG_PZ_GET_INPUTVOLTSSRC;
    static constexpr Family family = Family::Piezo;
    std::uint16_t chan_ident = 1;
    std::uint16_t volt_src = 0;   ///< the SET table's PositionSW (ERRATA)
    RIGSIM_APT_FIELDS(s.chan_ident, s.volt_src);
    // p. 98: software, + external input (1), + potentiometer (2).
    RIGSIM_APT_RANGES({"VoltSrc", s.volt_src, 0, 3});
};
/// MGMSG_PZ_SET/REQ/GET_PICONSTS (p. 100).
struct PzPiConsts {
    static constexpr std::uint16_t set_id = MGMSG_PZ_SET_PICONSTS;
    static constexpr std::uint16_t req_id = MGMSG_PZ_REQ_PICONSTS;
    static constexpr std::uint16_t get_id = MGMSG_PZ_GET_PICONSTS;
    static constexpr Family family = Family::Piezo;
    std::uint16_t chan_ident = 1;
    std::uint16_t prop_const = 0;
    std::uint16_t int_const = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.prop_const, s.int_const);
    // p. 100.
    RIGSIM_APT_RANGES({"PropConst", s.prop_const, 0, 255}, {"IntConst", s.int_const, 0, 255});
};
/// MGMSG_PZ_SET/REQ/GET_OUTPUTLUT (p. 106).
struct PzOutputLut {
    static constexpr std::uint16_t set_id = MGMSG_PZ_SET_OUTPUTLUT;
    static constexpr std::uint16_t req_id = MGMSG_PZ_REQ_OUTPUTLUT;
    static constexpr std::uint16_t get_id = MGMSG_PZ_GET_OUTPUTLUT;
    static constexpr Family family = Family::Piezo;
    std::uint16_t chan_ident = 1;
    std::uint16_t index = 0;
    std::int16_t output = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.index, s.output);
};
/// MGMSG_PZ_SET/REQ/GET_OUTPUTLUTPARAMS (p. 108).
struct PzOutputLutParams {
    static constexpr std::uint16_t set_id = MGMSG_PZ_SET_OUTPUTLUTPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_PZ_REQ_OUTPUTLUTPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_PZ_GET_OUTPUTLUTPARAMS;
    static constexpr Family family = Family::Piezo;
    std::uint16_t chan_ident = 1;
    std::uint16_t mode = 0;
    std::uint16_t cycle_length = 0;
    std::int32_t num_cycles = 0;
    std::int32_t delay_time = 0;
    std::int32_t pre_cycle_rest = 0;
    std::int32_t post_cycle_rest = 0;
    std::uint16_t op_trig_start = 0;
    std::int32_t op_trig_width = 0;
    std::uint16_t trig_repeat_cycle = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.mode, s.cycle_length, s.num_cycles, s.delay_time, s.pre_cycle_rest,
                      s.post_cycle_rest, s.op_trig_start, s.op_trig_width, s.trig_repeat_cycle);
};
/// MGMSG_PZ_SET/REQ/GET_TPZ_DISPSETTINGS (p. 114, no channel word).
struct TpzDispSettings {
    static constexpr std::uint16_t set_id = MGMSG_PZ_SET_TPZ_DISPSETTINGS;
    static constexpr std::uint16_t req_id = MGMSG_PZ_REQ_TPZ_DISPSETTINGS;
    static constexpr std::uint16_t get_id = MGMSG_PZ_GET_TPZ_DISPSETTINGS;
    static constexpr Family family = Family::Piezo;
    std::uint16_t disp_intensity = 0;
    RIGSIM_APT_FIELDS(s.disp_intensity);
    // p. 114.
    RIGSIM_APT_RANGES({"DispIntensity", s.disp_intensity, 0, 255});
};
/// MGMSG_PZ_SET/REQ/GET_TPZ_IOSETTINGS (p. 115).
struct TpzIoSettings {
    static constexpr std::uint16_t set_id = MGMSG_PZ_SET_TPZ_IOSETTINGS;
    static constexpr std::uint16_t req_id = MGMSG_PZ_REQ_TPZ_IOSETTINGS;
    static constexpr std::uint16_t get_id = MGMSG_PZ_GET_TPZ_IOSETTINGS;
    static constexpr Family family = Family::Piezo;
    std::uint16_t chan_ident = 1;
    std::uint16_t voltage_limit = 0;
    std::uint16_t hub_analog_input = 0;
    std::uint16_t future_use1 = 0;
    std::uint16_t future_use2 = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.voltage_limit, s.hub_analog_input, s.future_use1, s.future_use2);
    // p. 115: VoltageLimit 1 75 V, 2 100 V, 3 150 V; HubAnalogInput 1 hub A, 2 hub B, 3 SMA.
    RIGSIM_APT_RANGES({"VoltageLimit", s.voltage_limit, 1, 3}, {"HubAnalogInput", s.hub_analog_input, 1, 3});
};
/// MGMSG_PZ_SET/REQ/GET_IOSETTINGS (p. 119).
struct PzIoSettings {
    static constexpr std::uint16_t set_id = MGMSG_PZ_SET_IOSETTINGS;
    static constexpr std::uint16_t req_id = MGMSG_PZ_REQ_IOSETTINGS;
    static constexpr std::uint16_t get_id = MGMSG_PZ_GET_IOSETTINGS;
    static constexpr Family family = Family::Piezo;
    std::uint16_t chan_ident = 1;
    std::uint16_t amp_current_lim = 0;
    std::uint16_t amp_lp_filter = 0;
    std::uint16_t feedback_sig = 0;
    std::uint16_t bnc_trig_or_lv_out = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.amp_current_lim, s.amp_lp_filter, s.feedback_sig, s.bnc_trig_or_lv_out);
};
/// MGMSG_PZ_SET/REQ/GET_OUTPUTMAXVOLTS (p. 121).
struct PzOutputMaxVolts {
    static constexpr std::uint16_t set_id = MGMSG_PZ_SET_OUTPUTMAXVOLTS;
    static constexpr std::uint16_t req_id = MGMSG_PZ_REQ_OUTPUTMAXVOLTS;
    static constexpr std::uint16_t get_id = MGMSG_PZ_GET_OUTPUTMAXVOLTS;
    static constexpr Family family = Family::Piezo;
    std::uint16_t chan_ident = 1;
    std::uint16_t voltage = 0;   ///< 0.1 V steps
    std::uint16_t flags = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.voltage, s.flags);
    // p. 121: 0.1 V steps, up to 150 V.
    RIGSIM_APT_RANGES({"Voltage", s.voltage, 0, 1500});
};
/// MGMSG_PZ_SET/REQ/GET_TPZ_SLEWRATES (p. 123).
struct TpzSlewRates {
    static constexpr std::uint16_t set_id = MGMSG_PZ_SET_TPZ_SLEWRATES;
    static constexpr std::uint16_t req_id = MGMSG_PZ_REQ_TPZ_SLEWRATES;
    static constexpr std::uint16_t get_id = MGMSG_PZ_GET_TPZ_SLEWRATES;
    static constexpr Family family = Family::Piezo;
    std::uint16_t chan_ident = 1;
    std::uint16_t slew_open = 0;
    std::uint16_t slew_closed = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.slew_open, s.slew_closed);
    // p. 123.
    RIGSIM_APT_RANGES({"SlewOpen", s.slew_open, 0, 32767}, {"SlewClosed", s.slew_closed, 0, 32767});
};
/// MGMSG_PZ_SET/REQ/GET_TSG_IOSETTINGS (p. 127).
struct TsgIoSettings {
    static constexpr std::uint16_t set_id = MGMSG_PZ_SET_TSG_IOSETTINGS;
    static constexpr std::uint16_t req_id = MGMSG_PZ_REQ_TSG_IOSETTINGS;
    static constexpr std::uint16_t get_id = MGMSG_PZ_GET_TSG_IOSETTINGS;
    static constexpr Family family = Family::StrainGauge;
    std::uint16_t chan_ident = 1;
    std::uint16_t hub_analogue_output = 0;
    std::uint16_t display_mode = 0;   ///< 1 position, 2 voltage, 3 force
    std::uint16_t force_calib = 0;   ///< 0.001 N steps
    std::uint16_t future_use1 = 0;
    std::uint16_t future_use2 = 0;
    std::uint16_t future_use3 = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.hub_analogue_output, s.display_mode, s.force_calib, s.future_use1,
                      s.future_use2, s.future_use3);
    // p. 127: HubAnalogueOutput 1 hub A, 2 hub B pairs; DisplayMode 1 position, 2 voltage, 3 force.
    // ForceCalib "between 1 and 1000" N in 0.001 N steps does not fit its word: 1..65535 (D-22).
    RIGSIM_APT_RANGES({"HubAnalogueOutput", s.hub_analogue_output, 1, 2}, {"DisplayMode", s.display_mode, 1, 3},
                      {"ForceCalib", s.force_calib, 1, 65535});
};
/// MGMSG_PZ_SET_POSCONTROLMODE (p. 94).
struct PzSetPosControlMode {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_SET_POSCONTROLMODE, Piezo);
    std::uint8_t chan_ident = 1;
    std::uint8_t mode = 0;   ///< 1: open loop, 2: closed loop, 3/4: smoothed
    RIGSIM_APT_FIELDS(s.chan_ident, s.mode);
};
/// MGMSG_PZ_REQ_POSCONTROLMODE (p. 94).
struct PzReqPosControlMode {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_REQ_POSCONTROLMODE, Piezo);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_PZ_GET_POSCONTROLMODE (p. 94).
struct PzGetPosControlMode {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_GET_POSCONTROLMODE, UnitToHost);
    std::uint8_t chan_ident = 1;
    std::uint8_t mode = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.mode);
};
/// MGMSG_PZ_REQ_PZSTATUSBITS (p. 101).
struct PzReqPzStatusBits {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_REQ_PZSTATUSBITS, Piezo);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_PZ_ACK_PZSTATUSUPDATE (p. 105).
struct PzAckPzStatusUpdate {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_ACK_PZSTATUSUPDATE, Piezo);
    template <class S> static auto fields(S&) { return std::tuple<>(); }
    static constexpr std::string_view field_names = "";
};
/// MGMSG_PZ_START_LUTOUTPUT (p. 112).
struct PzStartLutOutput {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_START_LUTOUTPUT, Piezo);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_PZ_STOP_LUTOUTPUT (p. 112).
struct PzStopLutOutput {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_STOP_LUTOUTPUT, Piezo);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_PZ_SET_ZERO (p. 117).
struct PzSetZero {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_SET_ZERO, Piezo);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_PZ_REQ_MAXTRAVEL (p. 118).
struct PzReqMaxTravel {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_REQ_MAXTRAVEL, Piezo);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_MOT_SET_PZSTAGEPARAMDEFAULTS (p. 125).
struct MotSetPzStageParamDefaults {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_SET_PZSTAGEPARAMDEFAULTS, Piezo);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_PZ_SET_LUTVALUETYPE (p. 126).
struct PzSetLutValueType {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_SET_LUTVALUETYPE, Piezo);
    static constexpr bool no_channel = true;   ///< param1 is the type: the message addresses no channel
    std::uint8_t lut_type = 0;
    RIGSIM_APT_FIELDS(s.lut_type);
};
/// MGMSG_PZ_REQ_TSG_READING (p. 129).
struct TsgReqReading {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_REQ_TSG_READING, StrainGauge);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_PZ_GET_PZSTATUSBITS (p. 101).
struct PzGetPzStatusBits {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_GET_PZSTATUSBITS, UnitToHost);
    std::uint16_t chan_ident = 1;
    std::uint32_t status_bits = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.status_bits);
};
/// PZSTATUSBITS (p. 101-102) that the piezo and the strain gauge units both report.
inline constexpr std::uint32_t kPzConnected = 0x00000001;
inline constexpr std::uint32_t kPzZeroed = 0x00000010;
inline constexpr std::uint32_t kPzZeroing = 0x00000020;
/// Full scale of the piezo units' 16-bit outputs and readings (OUTPUTVOLTS, OUTPUTPOS, readings).
inline constexpr double kPzFullScale = 32767.0;
/// MGMSG_PZ_GET_PZSTATUSUPDATE (p. 103; 10 bytes, ERRATA).
struct PzGetPzStatusUpdate {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_GET_PZSTATUSUPDATE, UnitToHost);
    std::uint16_t chan_ident = 1;
    std::int16_t op_voltage = 0;
    std::int16_t position = 0;
    std::uint32_t status_bits = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.op_voltage, s.position, s.status_bits);
};
/// MGMSG_PZ_SET_EEPROMPARAMS (p. 113).
struct PzSetEepromParams {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_SET_EEPROMPARAMS, Piezo);
    std::uint16_t chan_ident = 1;
    std::uint16_t msg_id = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.msg_id);
};
/// MGMSG_PZ_GET_MAXTRAVEL (p. 118).
struct PzGetMaxTravel {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_GET_MAXTRAVEL, UnitToHost);
    std::uint16_t chan_ident = 1;
    std::uint16_t travel = 0;   ///< 100 nm steps
    RIGSIM_APT_FIELDS(s.chan_ident, s.travel);
};
/// MGMSG_PZ_GET_TSG_READING (p. 129).
struct TsgGetReading {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_GET_TSG_READING, UnitToHost);
    std::uint16_t chan_ident = 1;
    std::int16_t reading = 0;   ///< -32767..32767: -100..100 % of the range
    std::uint16_t smoothed = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.reading, s.smoothed);
};

using SetPzOutputVolts = Set<PzOutputVolts>;
using ReqPzOutputVolts = Req<PzOutputVolts>;
using GetPzOutputVolts = Get<PzOutputVolts>;
using SetPzOutputPos = Set<PzOutputPos>;
using ReqPzOutputPos = Req<PzOutputPos>;
using GetPzOutputPos = Get<PzOutputPos>;
using SetPzInputVoltsSrc = Set<PzInputVoltsSrc>;
using ReqPzInputVoltsSrc = Req<PzInputVoltsSrc>;
using GetPzInputVoltsSrc = Get<PzInputVoltsSrc>;
using SetPzPiConsts = Set<PzPiConsts>;
using ReqPzPiConsts = Req<PzPiConsts>;
using GetPzPiConsts = Get<PzPiConsts>;
using SetPzOutputLut = Set<PzOutputLut>;
using ReqPzOutputLut = Req<PzOutputLut>;
using GetPzOutputLut = Get<PzOutputLut>;
using SetPzOutputLutParams = Set<PzOutputLutParams>;
using ReqPzOutputLutParams = Req<PzOutputLutParams>;
using GetPzOutputLutParams = Get<PzOutputLutParams>;
using SetTpzDispSettings = Set<TpzDispSettings>;
using ReqTpzDispSettings = Req<TpzDispSettings>;
using GetTpzDispSettings = Get<TpzDispSettings>;
using SetTpzIoSettings = Set<TpzIoSettings>;
using ReqTpzIoSettings = Req<TpzIoSettings>;
using GetTpzIoSettings = Get<TpzIoSettings>;
using SetPzIoSettings = Set<PzIoSettings>;
using ReqPzIoSettings = Req<PzIoSettings>;
using GetPzIoSettings = Get<PzIoSettings>;
using SetPzOutputMaxVolts = Set<PzOutputMaxVolts>;
using ReqPzOutputMaxVolts = Req<PzOutputMaxVolts>;
using GetPzOutputMaxVolts = Get<PzOutputMaxVolts>;
using SetTpzSlewRates = Set<TpzSlewRates>;
using ReqTpzSlewRates = Req<TpzSlewRates>;
using GetTpzSlewRates = Get<TpzSlewRates>;
using SetTsgIoSettings = Set<TsgIoSettings>;
using ReqTsgIoSettings = Req<TsgIoSettings>;
using GetTsgIoSettings = Get<TsgIoSettings>;

} // namespace rigsim::apt::msg
