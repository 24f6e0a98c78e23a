#pragma once
// The codec structs of the Motor Control Messages (Thorlabs APT protocol, issue 3, section
// "Motor Control Messages", p. 28-83): the parameter blocks of the SET/REQ/GET trios (one struct
// each, wrapped by Set<>, Req<> and Get<>), then the messages of one struct each: moves, stops,
// status updates, end-of-move messages.
//
// This header is a part of codec.hpp: codec.hpp includes it after its Set<>, Req<> and Get<>
// templates and message macros, and before its Message variant; include codec.hpp, not this.

namespace rigsim::apt::msg {

// ---- Parameter blocks of the SET/REQ/GET trios (the data packet, channel word first) ----

/// MGMSG_MOT_SET/REQ/GET_POSCOUNTER (p. 28): the 'live' position counter.
struct PosCounter {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_POSCOUNTER;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_POSCOUNTER;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_POSCOUNTER;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::int32_t position = 0;   ///< encoder counts (7.1)
    RIGSIM_APT_FIELDS(s.chan_ident, s.position);
};

/// MGMSG_MOT_SET/REQ/GET_ENCCOUNTER (p. 29).
struct EncCounter {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_ENCCOUNTER;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_ENCCOUNTER;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_ENCCOUNTER;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::int32_t encoder_count = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.encoder_count);
};

/// MGMSG_MOT_SET/REQ/GET_VELPARAMS (p. 30): trapezoidal velocity profile, APT units (7.1).
struct VelParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_VELPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_VELPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_VELPARAMS;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::int32_t min_velocity = 0;
    std::int32_t acceleration = 0;
    std::int32_t max_velocity = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.min_velocity, s.acceleration, s.max_velocity);
    // p. 30: acceleration and maximum velocity are unsigned longs; a zero would never move.
    RIGSIM_APT_RANGES({"minimum velocity", s.min_velocity, 0, kMaxLong}, {"acceleration", s.acceleration, 1, kMaxLong},
                      {"maximum velocity", s.max_velocity, 1, kMaxLong});
};

/// MGMSG_MOT_SET/REQ/GET_JOGPARAMS (p. 32).
struct JogParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_JOGPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_JOGPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_JOGPARAMS;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::uint16_t jog_mode = 0;        ///< 1 continuous, 2 single step
    std::int32_t jog_step_size = 0;    ///< encoder counts
    std::int32_t jog_min_velocity = 0;
    std::int32_t jog_acceleration = 0;
    std::int32_t jog_max_velocity = 0;
    std::uint16_t jog_stop_mode = 0;   ///< 1 immediate, 2 profiled
    RIGSIM_APT_FIELDS(s.chan_ident, s.jog_mode, s.jog_step_size, s.jog_min_velocity, s.jog_acceleration,
                      s.jog_max_velocity, s.jog_stop_mode);
    // p. 32: jog mode 1 continuous, 2 single step; stop mode 1 immediate, 2 profiled.
    RIGSIM_APT_RANGES({"jog mode", s.jog_mode, 1, 2}, {"jog step size", s.jog_step_size, 0, kMaxLong},
                      {"jog minimum velocity", s.jog_min_velocity, 0, kMaxLong},
                      {"jog acceleration", s.jog_acceleration, 1, kMaxLong},
                      {"jog maximum velocity", s.jog_max_velocity, 1, kMaxLong}, {"stop mode", s.jog_stop_mode, 1, 2});
};

/// MGMSG_MOT_SET/REQ/GET_GENMOVEPARAMS (p. 34): the backlash.
struct GenMoveParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_GENMOVEPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_GENMOVEPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_GENMOVEPARAMS;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::int32_t backlash_distance = 0;   ///< encoder counts
    RIGSIM_APT_FIELDS(s.chan_ident, s.backlash_distance);
};

/// MGMSG_MOT_SET/REQ/GET_MOVERELPARAMS (p. 35): the distance of the short MOVE_RELATIVE.
struct MoveRelParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_MOVERELPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_MOVERELPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_MOVERELPARAMS;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::int32_t relative_distance = 0;   ///< encoder counts
    RIGSIM_APT_FIELDS(s.chan_ident, s.relative_distance);
};

/// MGMSG_MOT_SET/REQ/GET_MOVEABSPARAMS (p. 36): the target of the short MOVE_ABSOLUTE.
struct MoveAbsParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_MOVEABSPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_MOVEABSPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_MOVEABSPARAMS;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::int32_t absolute_position = 0;   ///< encoder counts
    RIGSIM_APT_FIELDS(s.chan_ident, s.absolute_position);
};

/// MGMSG_MOT_SET/REQ/GET_HOMEPARAMS (p. 37).
struct HomeParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_HOMEPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_HOMEPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_HOMEPARAMS;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::uint16_t home_direction = 0;   ///< 1 forward, 2 reverse
    std::uint16_t limit_switch = 0;     ///< 1 hardware reverse, 4 hardware forward
    std::int32_t home_velocity = 0;
    std::int32_t offset_distance = 0;   ///< encoder counts
    RIGSIM_APT_FIELDS(s.chan_ident, s.home_direction, s.limit_switch, s.home_velocity, s.offset_distance);
};

/// MGMSG_MOT_SET/REQ/GET_LIMSWITCHPARAMS (p. 39; 16-byte packet, ERRATA).
struct LimSwitchParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_LIMSWITCHPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_LIMSWITCHPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_LIMSWITCHPARAMS;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::uint16_t cw_hard_limit = 0;    ///< 1..6, optionally | 0x80 (swapped)
    std::uint16_t ccw_hard_limit = 0;
    std::int32_t cw_soft_limit = 0;     ///< position steps
    std::int32_t ccw_soft_limit = 0;
    std::uint16_t soft_limit_mode = 0;  ///< 1 ignore, 2 immediate stop, 3 profiled stop
    RIGSIM_APT_FIELDS(s.chan_ident, s.cw_hard_limit, s.ccw_hard_limit, s.cw_soft_limit, s.ccw_soft_limit,
                      s.soft_limit_mode);
};

/// MGMSG_MOT_SET/REQ/GET_DCPIDPARAMS (p. 51; longs as the field list says, ERRATA).
struct DcPidParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_DCPIDPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_DCPIDPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_DCPIDPARAMS;
    static constexpr Family family = Family::DcServo;
    std::uint16_t chan_ident = 1;
    std::int32_t proportional = 0;
    std::int32_t integral = 0;
    std::int32_t differential = 0;
    std::int32_t integral_limit = 0;
    std::uint16_t filter_control = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.proportional, s.integral, s.differential, s.integral_limit, s.filter_control);
    // p. 51: proportional, integral, differential and integral limit 0..32767.
    RIGSIM_APT_RANGES({"proportional", s.proportional, 0, 32767}, {"integral", s.integral, 0, 32767},
                      {"differential", s.differential, 0, 32767}, {"integral limit", s.integral_limit, 0, 32767});
};

/// MGMSG_MOT_SET/REQ/GET_AVMODES (p. 53): the LED modes.
struct AvModes {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_AVMODES;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_AVMODES;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_AVMODES;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::uint16_t mode_bits = 0;   ///< 1 ident, 2 limit switch, 8 moving
    RIGSIM_APT_FIELDS(s.chan_ident, s.mode_bits);
};

/// MGMSG_MOT_SET/REQ/GET_POTPARAMS (p. 55): windows in ADC counts, velocities in counts/s.
struct PotParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_POTPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_POTPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_POTPARAMS;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::uint16_t zero_wnd = 0;
    std::int32_t vel1 = 0;
    std::uint16_t wnd1 = 0;
    std::int32_t vel2 = 0;
    std::uint16_t wnd2 = 0;
    std::int32_t vel3 = 0;
    std::uint16_t wnd3 = 0;
    std::int32_t vel4 = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.zero_wnd, s.vel1, s.wnd1, s.vel2, s.wnd2, s.vel3, s.wnd3, s.vel4);
};

/// MGMSG_MOT_SET/REQ/GET_BUTTONPARAMS (p. 58; 16-byte packet, ERRATA).
struct ButtonParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_BUTTONPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_BUTTONPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_BUTTONPARAMS;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::uint16_t mode = 0;          ///< 1 jog, 2 go to position
    std::int32_t position1 = 0;      ///< encoder counts
    std::int32_t position2 = 0;
    std::uint16_t time_out_ms = 0;
    std::uint16_t not_used = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.mode, s.position1, s.position2, s.time_out_ms, s.not_used);
    // p. 58: mode 1 jog, 2 go to position.
    RIGSIM_APT_RANGES({"mode", s.mode, 1, 2});
};

/// MGMSG_MOT_SET/REQ/GET_PMDPOSITIONLOOPPARAMS (p. 61).
struct PmdPositionLoopParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_PMDPOSITIONLOOPPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_PMDPOSITIONLOOPPARAMS;
    static constexpr Family family = Family::Pmd;
    std::uint16_t chan_ident = 1;
    std::uint16_t kp_pos = 0;
    std::uint16_t ki_pos = 0;
    std::uint32_t integral_limit = 0;
    std::uint16_t kd_pos = 0;
    std::uint16_t kd_time_pos = 0;
    std::uint16_t kout_pos = 0;
    std::uint16_t kvff_pos = 0;
    std::uint16_t kaff_pos = 0;
    std::uint32_t pos_err_lim = 0;
    std::uint16_t not_used1 = 0;
    std::uint16_t not_used2 = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.kp_pos, s.ki_pos, s.integral_limit, s.kd_pos, s.kd_time_pos, s.kout_pos,
                      s.kvff_pos, s.kaff_pos, s.pos_err_lim, s.not_used1, s.not_used2);
    // p. 61. The PosErrLim text says "0 to 7FFFFFF" (seven Fs); the dword's other limit
    // field, Integral Limit, says 7FFFFFFF: taken for both.
    RIGSIM_APT_RANGES({"Kp", s.kp_pos, 0, 32767}, {"Ki", s.ki_pos, 0, 32767},
                      {"integral limit", s.integral_limit, 0, kMaxLong}, {"Kd", s.kd_pos, 0, 32767},
                      {"KdTimePos", s.kd_time_pos, 1, 32767}, {"KvffPos", s.kvff_pos, 0, 32767},
                      {"KaffPos", s.kaff_pos, 0, 32767}, {"PosErrLim", s.pos_err_lim, 0, kMaxLong});
};

/// MGMSG_MOT_SET/REQ/GET_PMDMOTOROUTPUTPARAMS (p. 64).
struct PmdMotorOutputParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_PMDMOTOROUTPUTPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_PMDMOTOROUTPUTPARAMS;
    static constexpr Family family = Family::Pmd;
    std::uint16_t chan_ident = 1;
    std::uint16_t cont_current_lim = 0;
    std::uint16_t energy_lim = 0;
    std::uint16_t motor_lim = 0;
    std::int16_t motor_bias = 0;
    std::uint16_t not_used1 = 0;
    std::uint16_t not_used2 = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.cont_current_lim, s.energy_lim, s.motor_lim, s.motor_bias, s.not_used1,
                      s.not_used2);
    // p. 63-64: MotorBias "-32767 to 32768" in a signed word: -32767..32767.
    RIGSIM_APT_RANGES({"ContCurrentLim", s.cont_current_lim, 0, 32767}, {"EnergyLim", s.energy_lim, 0, 32767},
                      {"MotorLim", s.motor_lim, 0, 32767}, {"MotorBias", s.motor_bias, -32767, 32767});
};

/// MGMSG_MOT_SET/REQ/GET_PMDTRACKSETTLEPARAMS (p. 66).
struct PmdTrackSettleParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_PMDTRACKSETTLEPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_PMDTRACKSETTLEPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_PMDTRACKSETTLEPARAMS;
    static constexpr Family family = Family::Pmd;
    std::uint16_t chan_ident = 1;
    std::uint16_t time_cycles = 0;     ///< settle time, servo cycles
    std::uint16_t settle_window = 0;   ///< encoder counts
    std::uint16_t track_window = 0;
    std::uint16_t not_used1 = 0;
    std::uint16_t not_used2 = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.time_cycles, s.settle_window, s.track_window, s.not_used1, s.not_used2);
    // p. 66: settle time 0..32767 cycles; both windows 0..65535 (any word).
    RIGSIM_APT_RANGES({"settle time", s.time_cycles, 0, 32767});
};

/// MGMSG_MOT_SET/REQ/GET_PMDPROFILEMODEPARAMS (p. 69).
struct PmdProfileModeParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_PMDPROFILEMODEPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_PMDPROFILEMODEPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_PMDPROFILEMODEPARAMS;
    static constexpr Family family = Family::Pmd;
    std::uint16_t chan_ident = 1;
    std::uint16_t mode = 0;      ///< 0 trapezoidal, 2 S-curve
    std::uint32_t jerk = 0;      ///< PMD jerk units (7.1)
    std::uint16_t not_used1 = 0;
    std::uint16_t not_used2 = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.mode, s.jerk, s.not_used1, s.not_used2);
    // p. 69: mode 0 trapezoidal, 2 S-curve (1 is no mode); jerk 0..4294967295 (any dword).
    RIGSIM_APT_RANGES({"mode", s.mode, 0, 2});
};

/// MGMSG_MOT_SET/REQ/GET_PMDCURRENTLOOPPARAMS (p. 71).
struct PmdCurrentLoopParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_PMDCURRENTLOOPPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_PMDCURRENTLOOPPARAMS;
    static constexpr Family family = Family::Pmd;
    std::uint16_t chan_ident = 1;
    std::uint16_t phase = 0;   ///< 0 A, 1 B, 2 A and B
    std::uint16_t kp_current = 0;
    std::uint16_t ki_current = 0;
    std::uint16_t i_lim_current = 0;
    std::uint16_t i_dead_band = 0;
    std::uint16_t kff = 0;
    std::uint16_t not_used1 = 0;
    std::uint16_t not_used2 = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.phase, s.kp_current, s.ki_current, s.i_lim_current, s.i_dead_band, s.kff,
                      s.not_used1, s.not_used2);
    // p. 71: phase 0 A, 1 B, 2 A and B; gains, limit, dead band, feed-forward 0..32767.
    RIGSIM_APT_RANGES({"phase", s.phase, 0, 2}, {"KpCurrent", s.kp_current, 0, 32767},
                      {"KiCurrent", s.ki_current, 0, 32767},
                      {"ILimCurrent", s.i_lim_current, 0, 32767}, {"IDeadBand", s.i_dead_band, 0, 32767},
                      {"Kff", s.kff, 0, 32767});
};

/// MGMSG_MOT_SET/REQ/GET_PMDSETTLEDCURRENTLOOPPARAMS (p. 73).
struct PmdSettledCurrentLoopParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_PMDSETTLEDCURRENTLOOPPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_PMDSETTLEDCURRENTLOOPPARAMS;
    static constexpr Family family = Family::Pmd;
    std::uint16_t chan_ident = 1;
    std::uint16_t phase = 0;
    std::uint16_t kp_settled = 0;
    std::uint16_t ki_settled = 0;
    std::uint16_t i_lim_settled = 0;
    std::uint16_t i_dead_band_settled = 0;
    std::uint16_t kff_settled = 0;
    std::uint16_t not_used1 = 0;
    std::uint16_t not_used2 = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.phase, s.kp_settled, s.ki_settled, s.i_lim_settled, s.i_dead_band_settled,
                      s.kff_settled, s.not_used1, s.not_used2);
    // p. 73: as the current loop's.
    RIGSIM_APT_RANGES({"phase", s.phase, 0, 2}, {"KpSettled", s.kp_settled, 0, 32767},
                      {"KiSettled", s.ki_settled, 0, 32767},
                      {"ILimSettled", s.i_lim_settled, 0, 32767}, {"IDeadBandSettled", s.i_dead_band_settled, 0, 32767},
                      {"KffSettled", s.kff_settled, 0, 32767});
};

/// MGMSG_MOT_SET/REQ/GET_PMDSTAGEAXISPARAMS (p. 75): 74 bytes; the field list omits the
/// channel word and garbles the reserved tail, which is 24 bytes by the stated length.
struct PmdStageAxisParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_PMDSTAGEAXISPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_PMDSTAGEAXISPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_PMDSTAGEAXISPARAMS;
    static constexpr Family family = Family::Pmd;
    std::uint16_t chan_ident = 1;
    std::uint16_t stage_id = 0;   ///< 0x10 MLS203 X, 0x11 MLS203 Y
    std::uint16_t axis_id = 0;
    std::array<char, 16> part_no_axis{};
    std::uint32_t serial_num = 0;
    std::uint32_t cnts_per_unit = 0;   ///< encoder counts per mm or degree
    std::int32_t min_pos = 0;          ///< encoder counts
    std::int32_t max_pos = 0;
    std::int32_t max_accn = 0;         ///< PMD units (7.1)
    std::int32_t max_dec = 0;
    std::int32_t max_vel = 0;
    std::array<char, 24> reserved{};
    RIGSIM_APT_FIELDS(s.chan_ident, s.stage_id, s.axis_id, s.part_no_axis, s.serial_num, s.cnts_per_unit, s.min_pos,
                      s.max_pos, s.max_accn, s.max_dec, s.max_vel, s.reserved);
};


using SetPosCounter = Set<PosCounter>;
using ReqPosCounter = Req<PosCounter>;
using GetPosCounter = Get<PosCounter>;
using SetEncCounter = Set<EncCounter>;
using ReqEncCounter = Req<EncCounter>;
using GetEncCounter = Get<EncCounter>;
using SetVelParams = Set<VelParams>;
using ReqVelParams = Req<VelParams>;
using GetVelParams = Get<VelParams>;
using SetJogParams = Set<JogParams>;
using ReqJogParams = Req<JogParams>;
using GetJogParams = Get<JogParams>;
using SetGenMoveParams = Set<GenMoveParams>;
using ReqGenMoveParams = Req<GenMoveParams>;
using GetGenMoveParams = Get<GenMoveParams>;
using SetMoveRelParams = Set<MoveRelParams>;
using ReqMoveRelParams = Req<MoveRelParams>;
using GetMoveRelParams = Get<MoveRelParams>;
using SetMoveAbsParams = Set<MoveAbsParams>;
using ReqMoveAbsParams = Req<MoveAbsParams>;
using GetMoveAbsParams = Get<MoveAbsParams>;
using SetHomeParams = Set<HomeParams>;
using ReqHomeParams = Req<HomeParams>;
using GetHomeParams = Get<HomeParams>;
using SetLimSwitchParams = Set<LimSwitchParams>;
using ReqLimSwitchParams = Req<LimSwitchParams>;
using GetLimSwitchParams = Get<LimSwitchParams>;
using SetDcPidParams = Set<DcPidParams>;
using ReqDcPidParams = Req<DcPidParams>;
using GetDcPidParams = Get<DcPidParams>;
using SetAvModes = Set<AvModes>;
using ReqAvModes = Req<AvModes>;
using GetAvModes = Get<AvModes>;
using SetPotParams = Set<PotParams>;
using ReqPotParams = Req<PotParams>;
using GetPotParams = Get<PotParams>;
using SetButtonParams = Set<ButtonParams>;
using ReqButtonParams = Req<ButtonParams>;
using GetButtonParams = Get<ButtonParams>;
using SetPmdPositionLoopParams = Set<PmdPositionLoopParams>;
using ReqPmdPositionLoopParams = Req<PmdPositionLoopParams>;
using GetPmdPositionLoopParams = Get<PmdPositionLoopParams>;
using SetPmdMotorOutputParams = Set<PmdMotorOutputParams>;
using ReqPmdMotorOutputParams = Req<PmdMotorOutputParams>;
using GetPmdMotorOutputParams = Get<PmdMotorOutputParams>;
using SetPmdTrackSettleParams = Set<PmdTrackSettleParams>;
using ReqPmdTrackSettleParams = Req<PmdTrackSettleParams>;
using GetPmdTrackSettleParams = Get<PmdTrackSettleParams>;
using SetPmdProfileModeParams = Set<PmdProfileModeParams>;
using ReqPmdProfileModeParams = Req<PmdProfileModeParams>;
using GetPmdProfileModeParams = Get<PmdProfileModeParams>;
using SetPmdCurrentLoopParams = Set<PmdCurrentLoopParams>;
using ReqPmdCurrentLoopParams = Req<PmdCurrentLoopParams>;
using GetPmdCurrentLoopParams = Get<PmdCurrentLoopParams>;
using SetPmdSettledCurrentLoopParams = Set<PmdSettledCurrentLoopParams>;
using ReqPmdSettledCurrentLoopParams = Req<PmdSettledCurrentLoopParams>;
using GetPmdSettledCurrentLoopParams = Get<PmdSettledCurrentLoopParams>;
using SetPmdStageAxisParams = Set<PmdStageAxisParams>;
using ReqPmdStageAxisParams = Req<PmdStageAxisParams>;
using GetPmdStageAxisParams = Get<PmdStageAxisParams>;

// ---- Messages of one struct each ----

/// MGMSG_MOT_MOVE_HOME (p. 41).
struct MoveHome {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_MOVE_HOME, Motor);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_MOT_MOVE_HOMED (p. 41).
struct MoveHomed {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_MOVE_HOMED, UnitToHost);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_MOT_MOVE_RELATIVE (p. 42): the short form (no distance) moves by MOVERELPARAMS.
struct MoveRelative {
    static constexpr std::uint16_t id = MGMSG_MOT_MOVE_RELATIVE;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;                     ///< param1 in the short form
    std::optional<std::int32_t> relative_distance;   ///< encoder counts; the long form only
    RIGSIM_APT_FIELDS(s.chan_ident, s.relative_distance);
};
/// MGMSG_MOT_MOVE_ABSOLUTE (p. 45): the short form (no position) moves to MOVEABSPARAMS.
struct MoveAbsolute {
    static constexpr std::uint16_t id = MGMSG_MOT_MOVE_ABSOLUTE;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;                     ///< param1 in the short form
    std::optional<std::int32_t> absolute_distance;   ///< encoder counts; the long form only
    RIGSIM_APT_FIELDS(s.chan_ident, s.absolute_distance);
};
/// MGMSG_MOT_MOVE_JOG (p. 47).
struct MoveJog {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_MOVE_JOG, Motor);
    std::uint8_t chan_ident = 1;
    std::uint8_t direction = 1;   ///< 1 forward, 2 reverse
    RIGSIM_APT_FIELDS(s.chan_ident, s.direction);
};
/// MGMSG_MOT_MOVE_VELOCITY (p. 48).
struct MoveVelocity {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_MOVE_VELOCITY, Motor);
    std::uint8_t chan_ident = 1;
    std::uint8_t direction = 1;   ///< 1 forward, 2 reverse
    RIGSIM_APT_FIELDS(s.chan_ident, s.direction);
};
/// MGMSG_MOT_MOVE_STOP (p. 49).
struct MoveStop {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_MOVE_STOP, Motor);
    std::uint8_t chan_ident = 1;
    std::uint8_t stop_mode = 2;   ///< 1 immediate, 2 profiled
    RIGSIM_APT_FIELDS(s.chan_ident, s.stop_mode);
};

/// The 14-byte status of MOT_GET_STATUSUPDATE (p. 77): steppers.
struct MotStatus {
    std::uint16_t chan_ident = 1;
    std::int32_t position = 0;
    std::int32_t enc_count = 0;
    std::uint32_t status_bits = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.position, s.enc_count, s.status_bits);
};
/// The 14-byte status of MOT_GET_DCSTATUSUPDATE (p. 79): DC servo and brushless units.
struct DcStatus {
    std::uint16_t chan_ident = 1;
    std::int32_t position = 0;
    std::int16_t velocity = 0;   ///< APT velocity units / 65536 (a word, signed by direction)
    std::uint16_t reserved = 0;
    std::uint32_t status_bits = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.position, s.velocity, s.reserved, s.status_bits);
};
/// What MOVE_COMPLETED and MOVE_STOPPED carry (p. 44, ERRATA): the status structure of the
/// unit's own update message. decode() reads it as DcStatus (the bytes alone cannot tell).
using MotorStatus = std::variant<DcStatus, MotStatus>;

/// MGMSG_MOT_MOVE_COMPLETED (p. 44): 14 bytes of status (ERRATA).
struct MoveCompleted {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_MOVE_COMPLETED, UnitToHost);
    MotorStatus status;
    RIGSIM_APT_FIELDS(s.status);
};
/// MGMSG_MOT_MOVE_STOPPED (p. 50): 14 bytes of status (ERRATA).
struct MoveStopped {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_MOVE_STOPPED, UnitToHost);
    MotorStatus status;
    RIGSIM_APT_FIELDS(s.status);
};
/// MGMSG_MOT_SET_EEPROMPARAMS (p. 60): save the parameters of message msg_id.
struct SetEepromParams {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_SET_EEPROMPARAMS, Motor);
    std::uint16_t chan_ident = 1;
    std::uint16_t msg_id = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.msg_id);
};
/// MGMSG_MOT_REQ_STATUSUPDATE (p. 78).
struct ReqStatusUpdate {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_REQ_STATUSUPDATE, Motor);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_MOT_GET_STATUSUPDATE (p. 77).
struct GetStatusUpdate {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_GET_STATUSUPDATE, UnitToHost);
    MotStatus status;
    template <class S> static auto fields(S& s) { return MotStatus::fields(s.status); }
    static constexpr std::string_view field_names = MotStatus::field_names;
};
/// MGMSG_MOT_REQ_DCSTATUSUPDATE (p. 80).
struct ReqDcStatusUpdate {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_REQ_DCSTATUSUPDATE, DcServo);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_MOT_GET_DCSTATUSUPDATE (p. 79).
struct GetDcStatusUpdate {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_GET_DCSTATUSUPDATE, UnitToHost);
    DcStatus status;
    template <class S> static auto fields(S& s) { return DcStatus::fields(s.status); }
    static constexpr std::string_view field_names = DcStatus::field_names;
};
/// MGMSG_MOT_ACK_DCSTATUSUPDATE (p. 80): "server alive" (0x0492, ERRATA).
RIGSIM_APT_BARE_MESSAGE(AckDcStatusUpdate, MGMSG_MOT_ACK_DCSTATUSUPDATE, System);
/// MGMSG_MOT_REQ_STATUSBITS (p. 81).
struct ReqStatusBits {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_REQ_STATUSBITS, Motor);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_MOT_GET_STATUSBITS (p. 81).
struct GetStatusBits {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_GET_STATUSBITS, UnitToHost);
    std::uint16_t chan_ident = 1;
    std::uint32_t status_bits = 0;
    RIGSIM_APT_FIELDS(s.chan_ident, s.status_bits);
};
/// MGMSG_MOT_SUSPEND_ENDOFMOVEMSGS (p. 82).
RIGSIM_APT_BARE_MESSAGE(SuspendEndOfMoveMsgs, MGMSG_MOT_SUSPEND_ENDOFMOVEMSGS, System);
/// MGMSG_MOT_RESUME_ENDOFMOVEMSGS (p. 83).
RIGSIM_APT_BARE_MESSAGE(ResumeEndOfMoveMsgs, MGMSG_MOT_RESUME_ENDOFMOVEMSGS, System);

} // namespace rigsim::apt::msg
