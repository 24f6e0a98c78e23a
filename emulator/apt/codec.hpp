#pragma once
// APT codec: one struct per message a motor unit acts on or sends, with the manual's field
// names (Thorlabs APT protocol, issue 3, corrected by the ERRATA), decode(frame) into a
// std::variant and encode(struct, dest, source) back to bytes. It knows no device.
//
// Every struct lists its fields in wire order once, in `fields()`; encode and decode walk
// that list (little-endian, section 6 corrected by the ERRATA). Header-only messages carry
// their fields in the header's param1 and param2 (one byte each). A parameter block shared
// by a SET/REQ/GET trio is one struct (VelParams, ...) wrapped by Set<>, Req<> and Get<>:
// a SET knows its GET through the block's IDs, so no ID arithmetic is needed.
//
// decode() never throws: an ID outside the table, or a packet short of the fields any unit reads
// (messages.hpp fields_length), is an Untyped (ID, params, data); a longer packet's tail is ignored,
// a shorter one's reserved tail read as zeros (codec.cpp as<T>). Same length: encode gives it back.

#include "emulator/apt/frame_framer.hpp"
#include "emulator/apt/messages.hpp"
#include "emulator/apt/wire.hpp"

#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>

namespace rigsim::apt {
/// The typed messages (a namespace of their own: motor_channel.hpp has a JogParams too).
namespace msg {

/// Which module acts on a message; the others ignore it (and log it).
enum class Family {
    System,      ///< the unit shell: identify, disconnect, update messages, end-of-move messages
    Bay,         ///< every module of every kind: channel enable state, info, hub bay
    Rack,        ///< a rack's motherboard
    Motor,       ///< every motor module: counters, moves, trios, status; the solenoid module its
                 ///< AVMODES, BUTTONPARAMS, EEPROMPARAMS (catalogue takes list)
    DcServo,     ///< DC servo and brushless modules (not steppers): PID, DC status
    Pmd,         ///< brushless (PMD) modules: the PMD parameter trios
    Solenoid,    ///< SolenoidModule (TSC001, KSC101)
    Piezo,       ///< PiezoModule (TPZ001, KPZ101, BPC30x bays); StrainGaugeModule its share of the TSG001 list
    StrainGauge, ///< StrainGaugeModule (TSG001, KSG101)
    KCubeMotor,  ///< motor messages of later protocol issues (codec_kcube.hpp): the motor modules' KCubeParams
    UnitToHost,  ///< sent by units (GETs, end-of-move messages): a unit ignores them
    Untyped,     ///< not typed by the codec (unknown ID, or a form its struct does not have)
};

// ---- Parameter blocks of the SET/REQ/GET trios (the data packet, channel word first) ----

/// MGMSG_MOT_SET/REQ/GET_POSCOUNTER (p. 28): the 'live' position counter.
struct PosCounter {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_POSCOUNTER;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_POSCOUNTER;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_POSCOUNTER;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::int32_t position = 0;   ///< encoder counts (7.1)
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.position); }
};

/// MGMSG_MOT_SET/REQ/GET_ENCCOUNTER (p. 29).
struct EncCounter {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_ENCCOUNTER;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_ENCCOUNTER;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_ENCCOUNTER;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::int32_t encoder_count = 0;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.encoder_count); }
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
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.chan_ident, s.min_velocity, s.acceleration, s.max_velocity);
    }
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
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.chan_ident, s.jog_mode, s.jog_step_size, s.jog_min_velocity, s.jog_acceleration,
                        s.jog_max_velocity, s.jog_stop_mode);
    }
};

/// MGMSG_MOT_SET/REQ/GET_GENMOVEPARAMS (p. 34): the backlash.
struct GenMoveParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_GENMOVEPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_GENMOVEPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_GENMOVEPARAMS;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::int32_t backlash_distance = 0;   ///< encoder counts
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.backlash_distance); }
};

/// MGMSG_MOT_SET/REQ/GET_MOVERELPARAMS (p. 35): the distance of the short MOVE_RELATIVE.
struct MoveRelParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_MOVERELPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_MOVERELPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_MOVERELPARAMS;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::int32_t relative_distance = 0;   ///< encoder counts
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.relative_distance); }
};

/// MGMSG_MOT_SET/REQ/GET_MOVEABSPARAMS (p. 36): the target of the short MOVE_ABSOLUTE.
struct MoveAbsParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_MOVEABSPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_MOVEABSPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_MOVEABSPARAMS;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::int32_t absolute_position = 0;   ///< encoder counts
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.absolute_position); }
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
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.chan_ident, s.home_direction, s.limit_switch, s.home_velocity, s.offset_distance);
    }
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
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.chan_ident, s.cw_hard_limit, s.ccw_hard_limit, s.cw_soft_limit, s.ccw_soft_limit,
                        s.soft_limit_mode);
    }
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
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.chan_ident, s.proportional, s.integral, s.differential, s.integral_limit,
                        s.filter_control);
    }
};

/// MGMSG_MOT_SET/REQ/GET_AVMODES (p. 53): the LED modes.
struct AvModes {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_AVMODES;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_AVMODES;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_AVMODES;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;
    std::uint16_t mode_bits = 0;   ///< 1 ident, 2 limit switch, 8 moving
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.mode_bits); }
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
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.chan_ident, s.zero_wnd, s.vel1, s.wnd1, s.vel2, s.wnd2, s.vel3, s.wnd3, s.vel4);
    }
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
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.chan_ident, s.mode, s.position1, s.position2, s.time_out_ms, s.not_used);
    }
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
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.chan_ident, s.kp_pos, s.ki_pos, s.integral_limit, s.kd_pos, s.kd_time_pos, s.kout_pos,
                        s.kvff_pos, s.kaff_pos, s.pos_err_lim, s.not_used1, s.not_used2);
    }
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
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.chan_ident, s.cont_current_lim, s.energy_lim, s.motor_lim, s.motor_bias, s.not_used1,
                        s.not_used2);
    }
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
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.chan_ident, s.time_cycles, s.settle_window, s.track_window, s.not_used1, s.not_used2);
    }
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
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.chan_ident, s.mode, s.jerk, s.not_used1, s.not_used2);
    }
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
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.chan_ident, s.phase, s.kp_current, s.ki_current, s.i_lim_current, s.i_dead_band, s.kff,
                        s.not_used1, s.not_used2);
    }
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
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.chan_ident, s.phase, s.kp_settled, s.ki_settled, s.i_lim_settled, s.i_dead_band_settled,
                        s.kff_settled, s.not_used1, s.not_used2);
    }
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
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.chan_ident, s.stage_id, s.axis_id, s.part_no_axis, s.serial_num, s.cnts_per_unit, s.min_pos,
                        s.max_pos, s.max_accn, s.max_dec, s.max_vel, s.reserved);
    }
};

/// SET of a parameter trio: the host sets the block.
template <class P> struct Set {
    static constexpr std::uint16_t id = P::set_id;
    static constexpr bool header_only = false;
    static constexpr Family family = P::family;
    using Params = P;
    P params;
    template <class S> static auto fields(S& s) { return P::fields(s.params); }
};

/// REQ of a parameter trio: header only, the channel in param1.
template <class P> struct Req {
    static constexpr std::uint16_t id = P::req_id;
    static constexpr bool header_only = true;
    static constexpr Family family = P::family;
    using Params = P;
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};

/// GET of a parameter trio: the unit's answer to the REQ.
template <class P> struct Get {
    static constexpr std::uint16_t id = P::get_id;
    static constexpr bool header_only = false;
    static constexpr Family family = Family::UnitToHost;
    using Params = P;
    P params;
    template <class S> static auto fields(S& s) { return P::fields(s.params); }
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

/// Declares the ID, form and family of a message struct.
#define RIGSIM_APT_MESSAGE(ID, HEADER_ONLY, FAMILY)                                                                   \
    static constexpr std::uint16_t id = ID;                                                                           \
    static constexpr bool header_only = HEADER_ONLY;                                                                  \
    static constexpr Family family = Family::FAMILY

/// A header-only message without parameters.
#define RIGSIM_APT_BARE_MESSAGE(NAME, ID, FAMILY)                                                                     \
    struct NAME {                                                                                                     \
        RIGSIM_APT_MESSAGE(ID, true, FAMILY);                                                                         \
        template <class S> static auto fields(S&) { return std::tuple<>(); }                                          \
    }

/// MGMSG_MOD_IDENTIFY (p. 16): flash the front panel.
struct ModIdentify {
    RIGSIM_APT_MESSAGE(MGMSG_MOD_IDENTIFY, true, System);
    std::uint8_t chan_ident = 0;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_MOD_SET_CHANENABLESTATE (p. 17).
struct ModSetChanEnableState {
    RIGSIM_APT_MESSAGE(MGMSG_MOD_SET_CHANENABLESTATE, true, Bay);
    std::uint8_t chan_ident = 1;
    std::uint8_t enable_state = 1;   ///< 1 enabled, 2 disabled
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.enable_state); }
};
/// MGMSG_MOD_REQ_CHANENABLESTATE (p. 17).
struct ModReqChanEnableState {
    RIGSIM_APT_MESSAGE(MGMSG_MOD_REQ_CHANENABLESTATE, true, Bay);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_MOD_GET_CHANENABLESTATE (p. 17).
struct ModGetChanEnableState {
    RIGSIM_APT_MESSAGE(MGMSG_MOD_GET_CHANENABLESTATE, true, UnitToHost);
    std::uint8_t chan_ident = 1;
    std::uint8_t enable_state = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.enable_state); }
};
/// MGMSG_HW_DISCONNECT (p. 19).
RIGSIM_APT_BARE_MESSAGE(HwDisconnect, MGMSG_HW_DISCONNECT, System);
/// MGMSG_HW_RESPONSE (p. 19): a fault, header only.
RIGSIM_APT_BARE_MESSAGE(HwResponse, MGMSG_HW_RESPONSE, UnitToHost);
/// MGMSG_HW_RICHRESPONSE (later issues): a fault with its cause.
struct HwRichResponse {
    RIGSIM_APT_MESSAGE(MGMSG_HW_RICHRESPONSE, false, UnitToHost);
    std::uint16_t msg_ident = 0;   ///< the message that caused it
    std::uint16_t code = 0;
    std::array<char, 64> notes{};
    template <class S> static auto fields(S& s) { return std::tie(s.msg_ident, s.code, s.notes); }
};
/// MGMSG_HW_START_UPDATEMSGS (p. 20).
struct HwStartUpdateMsgs {
    RIGSIM_APT_MESSAGE(MGMSG_HW_START_UPDATEMSGS, true, System);
    std::uint8_t update_rate = 0;   ///< ignored by the units (fixed 10 Hz)
    template <class S> static auto fields(S& s) { return std::tie(s.update_rate); }
};
/// MGMSG_HW_STOP_UPDATEMSGS (p. 20; 0x0012, ERRATA).
RIGSIM_APT_BARE_MESSAGE(HwStopUpdateMsgs, MGMSG_HW_STOP_UPDATEMSGS, System);
/// MGMSG_HW_REQ_INFO (p. 21).
RIGSIM_APT_BARE_MESSAGE(HwReqInfo, MGMSG_HW_REQ_INFO, Bay);
/// MGMSG_HW_GET_INFO (p. 21): 84 bytes.
struct HwGetInfo {
    RIGSIM_APT_MESSAGE(MGMSG_HW_GET_INFO, false, UnitToHost);
    std::uint32_t serial_number = 0;
    std::array<char, 8> model_number{};
    std::uint16_t type = 0;                        ///< 44 brushless card, 45 motherboard, ...
    std::array<char, 4> firmware_version{};        ///< minor, interim, major, unused
    std::array<char, 64> notes{};
    std::uint16_t nchs = 0;                        ///< number of channels
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.serial_number, s.model_number, s.type, s.firmware_version, s.notes, s.nchs);
    }
};
/// MGMSG_RACK_REQ_BAYUSED (p. 23).
struct RackReqBayUsed {
    RIGSIM_APT_MESSAGE(MGMSG_RACK_REQ_BAYUSED, true, Rack);
    std::uint8_t bay_ident = 0;   ///< from 0
    template <class S> static auto fields(S& s) { return std::tie(s.bay_ident); }
};
/// MGMSG_RACK_GET_BAYUSED (p. 23).
struct RackGetBayUsed {
    RIGSIM_APT_MESSAGE(MGMSG_RACK_GET_BAYUSED, true, UnitToHost);
    std::uint8_t bay_ident = 0;
    std::uint8_t bay_state = 0;   ///< 1 occupied, 2 empty
    template <class S> static auto fields(S& s) { return std::tie(s.bay_ident, s.bay_state); }
};
/// MGMSG_HUB_REQ_BAYUSED (p. 24).
RIGSIM_APT_BARE_MESSAGE(HubReqBayUsed, MGMSG_HUB_REQ_BAYUSED, Bay);
/// MGMSG_HUB_GET_BAYUSED (p. 24).
struct HubGetBayUsed {
    RIGSIM_APT_MESSAGE(MGMSG_HUB_GET_BAYUSED, true, UnitToHost);
    std::uint8_t bay_ident = 0;   ///< 0xFF (-1): standalone
    template <class S> static auto fields(S& s) { return std::tie(s.bay_ident); }
};
/// MGMSG_RACK_REQ_STATUSBITS (p. 25).
RIGSIM_APT_BARE_MESSAGE(RackReqStatusBits, MGMSG_RACK_REQ_STATUSBITS, Rack);
/// MGMSG_RACK_GET_STATUSBITS (p. 25).
struct RackGetStatusBits {
    RIGSIM_APT_MESSAGE(MGMSG_RACK_GET_STATUSBITS, false, UnitToHost);
    std::uint32_t status_bits = 0;   ///< digital inputs of the USER IO connector
    template <class S> static auto fields(S& s) { return std::tie(s.status_bits); }
};
/// MGMSG_RACK_SET_DIGOUTPUTS (p. 26): header only, the outputs and the bay address.
struct RackSetDigOutputs {
    RIGSIM_APT_MESSAGE(MGMSG_RACK_SET_DIGOUTPUTS, true, Rack);
    std::uint8_t dig_outputs = 0;   ///< bits 0..3: outputs 1..4
    std::uint8_t bay_ident = 0;     ///< bay address (0x21 + n) or 0: the motherboard
    template <class S> static auto fields(S& s) { return std::tie(s.dig_outputs, s.bay_ident); }
};
/// MGMSG_RACK_REQ_DIGOUTPUTS (p. 26).
struct RackReqDigOutputs {
    RIGSIM_APT_MESSAGE(MGMSG_RACK_REQ_DIGOUTPUTS, true, Rack);
    std::uint8_t dig_outputs = 0;   ///< unused
    std::uint8_t bay_ident = 0;
    template <class S> static auto fields(S& s) { return std::tie(s.dig_outputs, s.bay_ident); }
};
/// MGMSG_RACK_GET_DIGOUTPUTS (p. 26).
struct RackGetDigOutputs {
    RIGSIM_APT_MESSAGE(MGMSG_RACK_GET_DIGOUTPUTS, true, UnitToHost);
    std::uint8_t dig_outputs = 0;
    std::uint8_t bay_ident = 0;
    template <class S> static auto fields(S& s) { return std::tie(s.dig_outputs, s.bay_ident); }
};
/// MGMSG_HW_YES_FLASH_PROGRAMMING (later issues).
RIGSIM_APT_BARE_MESSAGE(HwYesFlashProgramming, MGMSG_HW_YES_FLASH_PROGRAMMING, System);
/// MGMSG_HW_NO_FLASH_PROGRAMMING (later issues).
RIGSIM_APT_BARE_MESSAGE(HwNoFlashProgramming, MGMSG_HW_NO_FLASH_PROGRAMMING, System);

/// MGMSG_MOT_MOVE_HOME (p. 41).
struct MoveHome {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_MOVE_HOME, true, Motor);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_MOT_MOVE_HOMED (p. 41).
struct MoveHomed {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_MOVE_HOMED, true, UnitToHost);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_MOT_MOVE_RELATIVE (p. 42): the short form (no distance) moves by MOVERELPARAMS.
struct MoveRelative {
    static constexpr std::uint16_t id = MGMSG_MOT_MOVE_RELATIVE;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;                     ///< param1 in the short form
    std::optional<std::int32_t> relative_distance;   ///< encoder counts; the long form only
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.relative_distance); }
};
/// MGMSG_MOT_MOVE_ABSOLUTE (p. 45): the short form (no position) moves to MOVEABSPARAMS.
struct MoveAbsolute {
    static constexpr std::uint16_t id = MGMSG_MOT_MOVE_ABSOLUTE;
    static constexpr Family family = Family::Motor;
    std::uint16_t chan_ident = 1;                     ///< param1 in the short form
    std::optional<std::int32_t> absolute_distance;   ///< encoder counts; the long form only
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.absolute_distance); }
};
/// MGMSG_MOT_MOVE_JOG (p. 47).
struct MoveJog {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_MOVE_JOG, true, Motor);
    std::uint8_t chan_ident = 1;
    std::uint8_t direction = 1;   ///< 1 forward, 2 reverse
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.direction); }
};
/// MGMSG_MOT_MOVE_VELOCITY (p. 48).
struct MoveVelocity {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_MOVE_VELOCITY, true, Motor);
    std::uint8_t chan_ident = 1;
    std::uint8_t direction = 1;   ///< 1 forward, 2 reverse
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.direction); }
};
/// MGMSG_MOT_MOVE_STOP (p. 49).
struct MoveStop {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_MOVE_STOP, true, Motor);
    std::uint8_t chan_ident = 1;
    std::uint8_t stop_mode = 2;   ///< 1 immediate, 2 profiled
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.stop_mode); }
};

/// The 14-byte status of MOT_GET_STATUSUPDATE (p. 77): steppers.
struct MotStatus {
    std::uint16_t chan_ident = 1;
    std::int32_t position = 0;
    std::int32_t enc_count = 0;
    std::uint32_t status_bits = 0;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.position, s.enc_count, s.status_bits); }
};
/// The 14-byte status of MOT_GET_DCSTATUSUPDATE (p. 79): DC servo and brushless units.
struct DcStatus {
    std::uint16_t chan_ident = 1;
    std::int32_t position = 0;
    std::int16_t velocity = 0;   ///< APT velocity units / 65536 (a word, signed by direction)
    std::uint16_t reserved = 0;
    std::uint32_t status_bits = 0;
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.chan_ident, s.position, s.velocity, s.reserved, s.status_bits);
    }
};
/// What MOVE_COMPLETED and MOVE_STOPPED carry (p. 44, ERRATA): the status structure of the
/// unit's own update message. decode() reads it as DcStatus (the bytes alone cannot tell).
using MotorStatus = std::variant<DcStatus, MotStatus>;

/// MGMSG_MOT_MOVE_COMPLETED (p. 44): 14 bytes of status (ERRATA).
struct MoveCompleted {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_MOVE_COMPLETED, false, UnitToHost);
    MotorStatus status;
    template <class S> static auto fields(S& s) { return std::tie(s.status); }
};
/// MGMSG_MOT_MOVE_STOPPED (p. 50): 14 bytes of status (ERRATA).
struct MoveStopped {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_MOVE_STOPPED, false, UnitToHost);
    MotorStatus status;
    template <class S> static auto fields(S& s) { return std::tie(s.status); }
};
/// MGMSG_MOT_SET_EEPROMPARAMS (p. 60): save the parameters of message msg_id.
struct SetEepromParams {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_SET_EEPROMPARAMS, false, Motor);
    std::uint16_t chan_ident = 1;
    std::uint16_t msg_id = 0;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.msg_id); }
};
/// MGMSG_MOT_REQ_STATUSUPDATE (p. 78).
struct ReqStatusUpdate {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_REQ_STATUSUPDATE, true, Motor);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_MOT_GET_STATUSUPDATE (p. 77).
struct GetStatusUpdate {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_GET_STATUSUPDATE, false, UnitToHost);
    MotStatus status;
    template <class S> static auto fields(S& s) { return MotStatus::fields(s.status); }
};
/// MGMSG_MOT_REQ_DCSTATUSUPDATE (p. 80).
struct ReqDcStatusUpdate {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_REQ_DCSTATUSUPDATE, true, DcServo);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_MOT_GET_DCSTATUSUPDATE (p. 79).
struct GetDcStatusUpdate {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_GET_DCSTATUSUPDATE, false, UnitToHost);
    DcStatus status;
    template <class S> static auto fields(S& s) { return DcStatus::fields(s.status); }
};
/// MGMSG_MOT_ACK_DCSTATUSUPDATE (p. 80): "server alive" (0x0492, ERRATA).
RIGSIM_APT_BARE_MESSAGE(AckDcStatusUpdate, MGMSG_MOT_ACK_DCSTATUSUPDATE, System);
/// MGMSG_MOT_REQ_STATUSBITS (p. 81).
struct ReqStatusBits {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_REQ_STATUSBITS, true, Motor);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_MOT_GET_STATUSBITS (p. 81).
struct GetStatusBits {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_GET_STATUSBITS, false, UnitToHost);
    std::uint16_t chan_ident = 1;
    std::uint32_t status_bits = 0;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.status_bits); }
};
/// MGMSG_MOT_SUSPEND_ENDOFMOVEMSGS (p. 82).
RIGSIM_APT_BARE_MESSAGE(SuspendEndOfMoveMsgs, MGMSG_MOT_SUSPEND_ENDOFMOVEMSGS, System);
/// MGMSG_MOT_RESUME_ENDOFMOVEMSGS (p. 83).
RIGSIM_APT_BARE_MESSAGE(ResumeEndOfMoveMsgs, MGMSG_MOT_RESUME_ENDOFMOVEMSGS, System);

// ---- Solenoid Control Messages (p. 84-92): MOT_ messages of the TSC001 solenoid driver ----
// SolenoidModule (TSC001, KSC101) acts on them; every other module ignores and logs them.

/// MGMSG_MOT_SET_SOL_OPERATINGMODE (p. 85).
struct SolSetOperatingMode {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_SET_SOL_OPERATINGMODE, true, Solenoid);
    std::uint8_t chan_ident = 1;
    std::uint8_t operating_mode = 1;   ///< 1 manual, 2 single, 3 auto, 4 triggered
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.operating_mode); }
};
/// MGMSG_MOT_REQ_SOL_OPERATINGMODE (p. 85).
struct SolReqOperatingMode {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_REQ_SOL_OPERATINGMODE, true, Solenoid);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_MOT_GET_SOL_OPERATINGMODE (p. 85).
struct SolGetOperatingMode {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_GET_SOL_OPERATINGMODE, true, UnitToHost);
    std::uint8_t chan_ident = 1;
    std::uint8_t operating_mode = 1;   ///< 1 manual, 2 single, 3 auto, 4 triggered
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.operating_mode); }
};

/// MGMSG_MOT_SET/REQ/GET_SOL_CYCLEPARAMS (p. 87): the on/off cycle of the non-manual modes.
struct SolCycleParams {
    static constexpr std::uint16_t set_id = MGMSG_MOT_SET_SOL_CYCLEPARAMS;
    static constexpr std::uint16_t req_id = MGMSG_MOT_REQ_SOL_CYCLEPARAMS;
    static constexpr std::uint16_t get_id = MGMSG_MOT_GET_SOL_CYCLEPARAMS;
    static constexpr Family family = Family::Solenoid;
    std::uint16_t chan_ident = 1;       ///< always 1 on a TSC001
    std::int32_t on_time_250us = 0;     ///< OnTime: 250 us steps, 100 ms..10,000 s (4000 = 1 s)
    std::int32_t off_time_250us = 0;    ///< OffTime: 250 us steps, 100 ms..10,000 s
    std::int32_t num_cycles = 0;        ///< 'Auto' mode only: 0..1,000,000, 0 cycles indefinitely
    template <class S> static auto fields(S& s)
    {
        return std::tie(s.chan_ident, s.on_time_250us, s.off_time_250us, s.num_cycles);
    }
};

/// MGMSG_MOT_SET_SOL_INTERLOCKMODE (p. 89).
struct SolSetInterlockMode {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_SET_SOL_INTERLOCKMODE, true, Solenoid);
    std::uint8_t chan_ident = 1;
    std::uint8_t interlock_mode = 1;   ///< 1 enabled (the interlock plug is required), 2 disabled
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.interlock_mode); }
};
/// MGMSG_MOT_REQ_SOL_INTERLOCKMODE (p. 89).
struct SolReqInterlockMode {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_REQ_SOL_INTERLOCKMODE, true, Solenoid);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_MOT_GET_SOL_INTERLOCKMODE (p. 89).
struct SolGetInterlockMode {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_GET_SOL_INTERLOCKMODE, true, UnitToHost);
    std::uint8_t chan_ident = 1;
    std::uint8_t interlock_mode = 1;   ///< 1 enabled, 2 disabled
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.interlock_mode); }
};

/// MGMSG_MOT_SET_SOL_STATE (p. 91): overrides the operating mode.
struct SolSetState {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_SET_SOL_STATE, true, Solenoid);
    std::uint8_t chan_ident = 1;
    // The data structure table labels param2 "Interlock Mode" (copied from p. 89); the
    // header diagram and the values name it the state.
    std::uint8_t state = 2;   ///< 1 on (solenoid active), 2 off
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.state); }
};
/// MGMSG_MOT_REQ_SOL_STATE (p. 91).
struct SolReqState {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_REQ_SOL_STATE, true, Solenoid);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_MOT_GET_SOL_STATE (p. 91).
struct SolGetState {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_GET_SOL_STATE, true, UnitToHost);
    std::uint8_t chan_ident = 1;
    std::uint8_t state = 2;   ///< 1 on, 2 off
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.state); }
};

using SetSolCycleParams = Set<SolCycleParams>;
using ReqSolCycleParams = Req<SolCycleParams>;
using GetSolCycleParams = Get<SolCycleParams>;

// ---- Piezo Control Messages (p. 93-126) and the TSG001 strain gauge reader (p. 127-129) ----
// PiezoModule (TPZ001, KPZ101, BPC30x bays) and StrainGaugeModule (TSG001, KSG101) act on the
// ones their model's takes list names (catalogue.cpp); the other modules ignore and log them.

/// MGMSG_PZ_SET/REQ/GET_OUTPUTVOLTS (p. 96).
struct PzOutputVolts {
    static constexpr std::uint16_t set_id = MGMSG_PZ_SET_OUTPUTVOLTS;
    static constexpr std::uint16_t req_id = MGMSG_PZ_REQ_OUTPUTVOLTS;
    static constexpr std::uint16_t get_id = MGMSG_PZ_GET_OUTPUTVOLTS;
    static constexpr Family family = Family::Piezo;
    std::uint16_t chan_ident = 1;
    std::int16_t voltage = 0;   ///< -32767..32767: -100..100 % of the maximum output voltage
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.voltage); }
};
/// MGMSG_PZ_SET/REQ/GET_OUTPUTPOS (p. 97).
struct PzOutputPos {
    static constexpr std::uint16_t set_id = MGMSG_PZ_SET_OUTPUTPOS;
    static constexpr std::uint16_t req_id = MGMSG_PZ_REQ_OUTPUTPOS;
    static constexpr std::uint16_t get_id = MGMSG_PZ_GET_OUTPUTPOS;
    static constexpr Family family = Family::Piezo;
    std::uint16_t chan_ident = 1;
    std::uint16_t position_sw = 0;   ///< 0..32767: 0..100 % of the travel (ERRATA)
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.position_sw); }
};
/// MGMSG_PZ_SET/REQ/GET_INPUTVOLTSSRC (p. 98).
struct PzInputVoltsSrc {
    static constexpr std::uint16_t set_id = MGMSG_PZ_SET_INPUTVOLTSSRC;
    static constexpr std::uint16_t req_id = MGMSG_PZ_REQ_INPUTVOLTSSRC;
    static constexpr std::uint16_t get_id = MGMSG_PZ_GET_INPUTVOLTSSRC;
    static constexpr Family family = Family::Piezo;
    std::uint16_t chan_ident = 1;
    std::uint16_t volt_src = 0;   ///< the SET table's PositionSW (ERRATA)
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.volt_src); }
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
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.prop_const, s.int_const); }
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
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.index, s.output); }
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
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.mode, s.cycle_length, s.num_cycles, s.delay_time, s.pre_cycle_rest, s.post_cycle_rest, s.op_trig_start, s.op_trig_width, s.trig_repeat_cycle); }
};
/// MGMSG_PZ_SET/REQ/GET_TPZ_DISPSETTINGS (p. 114, no channel word).
struct TpzDispSettings {
    static constexpr std::uint16_t set_id = MGMSG_PZ_SET_TPZ_DISPSETTINGS;
    static constexpr std::uint16_t req_id = MGMSG_PZ_REQ_TPZ_DISPSETTINGS;
    static constexpr std::uint16_t get_id = MGMSG_PZ_GET_TPZ_DISPSETTINGS;
    static constexpr Family family = Family::Piezo;
    std::uint16_t disp_intensity = 0;
    template <class S> static auto fields(S& s) { return std::tie(s.disp_intensity); }
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
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.voltage_limit, s.hub_analog_input, s.future_use1, s.future_use2); }
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
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.amp_current_lim, s.amp_lp_filter, s.feedback_sig, s.bnc_trig_or_lv_out); }
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
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.voltage, s.flags); }
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
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.slew_open, s.slew_closed); }
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
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.hub_analogue_output, s.display_mode, s.force_calib, s.future_use1, s.future_use2, s.future_use3); }
};
/// MGMSG_PZ_SET_POSCONTROLMODE (p. 94).
struct PzSetPosControlMode {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_SET_POSCONTROLMODE, true, Piezo);
    std::uint8_t chan_ident = 1;
    std::uint8_t mode = 0;   ///< 1: open loop, 2: closed loop, 3/4: smoothed
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.mode); }
};
/// MGMSG_PZ_REQ_POSCONTROLMODE (p. 94).
struct PzReqPosControlMode {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_REQ_POSCONTROLMODE, true, Piezo);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_PZ_GET_POSCONTROLMODE (p. 94).
struct PzGetPosControlMode {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_GET_POSCONTROLMODE, true, UnitToHost);
    std::uint8_t chan_ident = 1;
    std::uint8_t mode = 0;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.mode); }
};
/// MGMSG_PZ_REQ_PZSTATUSBITS (p. 101).
struct PzReqPzStatusBits {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_REQ_PZSTATUSBITS, true, Piezo);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_PZ_ACK_PZSTATUSUPDATE (p. 105).
struct PzAckPzStatusUpdate {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_ACK_PZSTATUSUPDATE, true, Piezo);
    template <class S> static auto fields(S&) { return std::tuple<>(); }
};
/// MGMSG_PZ_START_LUTOUTPUT (p. 112).
struct PzStartLutOutput {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_START_LUTOUTPUT, true, Piezo);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_PZ_STOP_LUTOUTPUT (p. 112).
struct PzStopLutOutput {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_STOP_LUTOUTPUT, true, Piezo);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_PZ_SET_ZERO (p. 117).
struct PzSetZero {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_SET_ZERO, true, Piezo);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_PZ_REQ_MAXTRAVEL (p. 118).
struct PzReqMaxTravel {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_REQ_MAXTRAVEL, true, Piezo);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_MOT_SET_PZSTAGEPARAMDEFAULTS (p. 125).
struct MotSetPzStageParamDefaults {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_SET_PZSTAGEPARAMDEFAULTS, true, Piezo);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_PZ_SET_LUTVALUETYPE (p. 126).
struct PzSetLutValueType {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_SET_LUTVALUETYPE, true, Piezo);
    std::uint8_t lut_type = 0;
    template <class S> static auto fields(S& s) { return std::tie(s.lut_type); }
};
/// MGMSG_PZ_REQ_TSG_READING (p. 129).
struct TsgReqReading {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_REQ_TSG_READING, true, StrainGauge);
    std::uint8_t chan_ident = 1;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident); }
};
/// MGMSG_PZ_GET_PZSTATUSBITS (p. 101).
struct PzGetPzStatusBits {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_GET_PZSTATUSBITS, false, UnitToHost);
    std::uint16_t chan_ident = 1;
    std::uint32_t status_bits = 0;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.status_bits); }
};
/// PZSTATUSBITS (p. 101-102) that the piezo and the strain gauge units both report.
inline constexpr std::uint32_t kPzConnected = 0x00000001;
inline constexpr std::uint32_t kPzZeroed = 0x00000010;
inline constexpr std::uint32_t kPzZeroing = 0x00000020;
/// Full scale of the piezo units' 16-bit outputs and readings (OUTPUTVOLTS, OUTPUTPOS, readings).
inline constexpr double kPzFullScale = 32767.0;
/// MGMSG_PZ_GET_PZSTATUSUPDATE (p. 103; 10 bytes, ERRATA).
struct PzGetPzStatusUpdate {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_GET_PZSTATUSUPDATE, false, UnitToHost);
    std::uint16_t chan_ident = 1;
    std::int16_t op_voltage = 0;
    std::int16_t position = 0;
    std::uint32_t status_bits = 0;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.op_voltage, s.position, s.status_bits); }
};
/// MGMSG_PZ_SET_EEPROMPARAMS (p. 113).
struct PzSetEepromParams {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_SET_EEPROMPARAMS, false, Piezo);
    std::uint16_t chan_ident = 1;
    std::uint16_t msg_id = 0;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.msg_id); }
};
/// MGMSG_PZ_GET_MAXTRAVEL (p. 118).
struct PzGetMaxTravel {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_GET_MAXTRAVEL, false, UnitToHost);
    std::uint16_t chan_ident = 1;
    std::uint16_t travel = 0;   ///< 100 nm steps
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.travel); }
};
/// MGMSG_PZ_GET_TSG_READING (p. 129).
struct TsgGetReading {
    RIGSIM_APT_MESSAGE(MGMSG_PZ_GET_TSG_READING, false, UnitToHost);
    std::uint16_t chan_ident = 1;
    std::int16_t reading = 0;   ///< -32767..32767: -100..100 % of the range
    std::uint16_t smoothed = 0;
    template <class S> static auto fields(S& s) { return std::tie(s.chan_ident, s.reading, s.smoothed); }
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

} // namespace msg
} // namespace rigsim::apt
// The K-Cube piezo driver's and strain gauge reader's own messages (later protocol issues).
#include "emulator/apt/codec_kcube_units.hpp"
namespace rigsim::apt {
namespace msg {

#undef RIGSIM_APT_BARE_MESSAGE
#undef RIGSIM_APT_MESSAGE

/// A message the codec does not type (an ID outside the table), or whose data packet has another length than
/// its struct's: kept whole.
struct Untyped {
    static constexpr Family family = Family::Untyped;
    std::uint16_t id = 0;
    std::uint8_t param1 = 0;
    std::uint8_t param2 = 0;
    bool has_data = false;
    std::string data;   ///< the data packet
    template <class S> static auto fields(S& s) { return std::tie(s.id, s.param1, s.param2, s.has_data, s.data); }
};

} // namespace msg
} // namespace rigsim::apt

#include "emulator/apt/codec_kcube.hpp"

namespace rigsim::apt {
namespace msg {

// ---- The decoded message: a variant of the manual's chapters, each a variant of its messages ----
//
// One flat std::variant of all 166 messages would cost minutes of compile time and hundreds of
// megabytes of debug information per file that visits it (libstdc++ instantiates its storage and
// accessors per alternative, each named after all 166 types). Two levels, each a struct with a short
// name, cost a few percent of that. msg::visit() walks both levels; get_if<T>() and holds<T>() find
// one message.

/// Generic System Control Messages (p. 15-26).
struct GenericMessage : std::variant<ModIdentify, ModSetChanEnableState, ModReqChanEnableState, ModGetChanEnableState,
                                     HwDisconnect, HwResponse, HwRichResponse, HwStartUpdateMsgs, HwStopUpdateMsgs,
                                     HwReqInfo, HwGetInfo, RackReqBayUsed, RackGetBayUsed, HubReqBayUsed,
                                     HubGetBayUsed, RackReqStatusBits, RackGetStatusBits, RackSetDigOutputs,
                                     RackReqDigOutputs, RackGetDigOutputs, HwYesFlashProgramming,
                                     HwNoFlashProgramming> {
    using variant::variant;
};
/// The motor parameter trios (p. 27-60).
struct MotorTrioMessage
    : std::variant<SetPosCounter, ReqPosCounter, GetPosCounter, SetEncCounter, ReqEncCounter, GetEncCounter,
                   SetVelParams, ReqVelParams, GetVelParams, SetJogParams, ReqJogParams, GetJogParams,
                   SetGenMoveParams, ReqGenMoveParams, GetGenMoveParams, SetMoveRelParams, ReqMoveRelParams,
                   GetMoveRelParams, SetMoveAbsParams, ReqMoveAbsParams, GetMoveAbsParams, SetHomeParams,
                   ReqHomeParams, GetHomeParams, SetLimSwitchParams, ReqLimSwitchParams, GetLimSwitchParams,
                   SetDcPidParams, ReqDcPidParams, GetDcPidParams, SetAvModes, ReqAvModes, GetAvModes, SetPotParams,
                   ReqPotParams, GetPotParams, SetButtonParams, ReqButtonParams, GetButtonParams> {
    using variant::variant;
};
/// The brushless (PMD) parameter trios (p. 61-76).
struct PmdTrioMessage
    : std::variant<SetPmdPositionLoopParams, ReqPmdPositionLoopParams, GetPmdPositionLoopParams,
                   SetPmdMotorOutputParams, ReqPmdMotorOutputParams, GetPmdMotorOutputParams,
                   SetPmdTrackSettleParams, ReqPmdTrackSettleParams, GetPmdTrackSettleParams,
                   SetPmdProfileModeParams, ReqPmdProfileModeParams, GetPmdProfileModeParams,
                   SetPmdCurrentLoopParams, ReqPmdCurrentLoopParams, GetPmdCurrentLoopParams,
                   SetPmdSettledCurrentLoopParams, ReqPmdSettledCurrentLoopParams, GetPmdSettledCurrentLoopParams,
                   SetPmdStageAxisParams, ReqPmdStageAxisParams, GetPmdStageAxisParams> {
    using variant::variant;
};
/// Moves, end-of-move and status messages (p. 41-83).
struct MoveStatusMessage
    : std::variant<MoveHome, MoveHomed, MoveRelative, MoveAbsolute, MoveJog, MoveVelocity, MoveStop, MoveCompleted,
                   MoveStopped, SetEepromParams, ReqStatusUpdate, GetStatusUpdate, ReqDcStatusUpdate,
                   GetDcStatusUpdate, AckDcStatusUpdate, ReqStatusBits, GetStatusBits, SuspendEndOfMoveMsgs,
                   ResumeEndOfMoveMsgs> {
    using variant::variant;
};
/// Solenoid Control Messages (p. 84-92).
struct SolenoidMessage
    : std::variant<SolSetOperatingMode, SolReqOperatingMode, SolGetOperatingMode, SetSolCycleParams,
                   ReqSolCycleParams, GetSolCycleParams, SolSetInterlockMode, SolReqInterlockMode,
                   SolGetInterlockMode, SolSetState, SolReqState, SolGetState> {
    using variant::variant;
};
/// The piezo and strain gauge parameter trios (p. 93-129).
struct PiezoTrioMessage
    : std::variant<SetPzOutputVolts, ReqPzOutputVolts, GetPzOutputVolts, SetPzOutputPos, ReqPzOutputPos,
                   GetPzOutputPos, SetPzInputVoltsSrc, ReqPzInputVoltsSrc, GetPzInputVoltsSrc, SetPzPiConsts,
                   ReqPzPiConsts, GetPzPiConsts, SetPzOutputLut, ReqPzOutputLut, GetPzOutputLut, SetPzOutputLutParams,
                   ReqPzOutputLutParams, GetPzOutputLutParams, SetTpzDispSettings, ReqTpzDispSettings,
                   GetTpzDispSettings, SetTpzIoSettings, ReqTpzIoSettings, GetTpzIoSettings, SetPzIoSettings,
                   ReqPzIoSettings, GetPzIoSettings, SetPzOutputMaxVolts, ReqPzOutputMaxVolts, GetPzOutputMaxVolts,
                   SetTpzSlewRates, ReqTpzSlewRates, GetTpzSlewRates, SetTsgIoSettings, ReqTsgIoSettings,
                   GetTsgIoSettings> {
    using variant::variant;
};
/// The other piezo and strain gauge messages (p. 93-129).
struct PiezoMessage
    : std::variant<PzSetPosControlMode, PzReqPosControlMode, PzGetPosControlMode, PzReqPzStatusBits,
                   PzAckPzStatusUpdate, PzStartLutOutput, PzStopLutOutput, PzSetZero, PzReqMaxTravel,
                   MotSetPzStageParamDefaults, PzSetLutValueType, TsgReqReading, PzGetPzStatusBits,
                   PzGetPzStatusUpdate, PzSetEepromParams, PzGetMaxTravel, TsgGetReading> {
    using variant::variant;
};

namespace codec_detail {
template <class T, class V> struct IsIn : std::false_type {};
template <class T, class... Ts> struct IsIn<T, std::variant<Ts...>> : std::disjunction<std::is_same<T, Ts>...> {};
/// The chapter (Group) whose variant holds message T; no `type` if none does.
template <class T, class... Groups> struct GroupOf {};
template <class T, class G, class... Groups>
struct GroupOf<T, G, Groups...>
    : std::conditional_t<IsIn<T, typename G::variant>::value, std::common_type<G>, GroupOf<T, Groups...>> {};
} // namespace codec_detail

/// Every chapter, in the order of Message's alternatives.
using Chapters = std::tuple<GenericMessage, MotorTrioMessage, PmdTrioMessage, MoveStatusMessage, SolenoidMessage,
                            PiezoTrioMessage, PiezoMessage, KCubeMotorMessage, KCubeUnitMessage>;

namespace codec_detail {
template <class T, class C> struct GroupOfIn;
template <class T, class... G> struct GroupOfIn<T, std::tuple<G...>> : GroupOf<T, G...> {};
} // namespace codec_detail

/// The chapter of typed message T (GenericMessage, ...).
template <class T> using GroupOf = typename codec_detail::GroupOfIn<T, Chapters>::type;

/// Every message decode() can return: a chapter's message, or an Untyped.
struct Message : std::variant<GenericMessage, MotorTrioMessage, PmdTrioMessage, MoveStatusMessage, SolenoidMessage,
                              PiezoTrioMessage, PiezoMessage, KCubeMotorMessage, KCubeUnitMessage, Untyped> {
    Message() = default;
    /// Typed message `m`, in its chapter.
    template <class T, class G = GroupOf<T>>
    Message(T m) : variant(std::in_place_type<G>, std::in_place_type<T>, std::move(m))
    {
    }
    Message(Untyped m) : variant(std::in_place_type<Untyped>, std::move(m)) {}
};

/// Calls f with the typed message (or Untyped) `m` holds; f returns one type for all.
template <class F> decltype(auto) visit(F&& f, const Message& m)
{
    return std::visit(
        [&f](const auto& group) -> decltype(auto) {
            if constexpr (std::is_same_v<std::decay_t<decltype(group)>, Untyped>)
                return f(group);
            else
                return std::visit(f, static_cast<const typename std::decay_t<decltype(group)>::variant&>(group));
        },
        static_cast<const Message::variant&>(m));
}

/// The message T that `m` holds, or nullptr.
template <class T> const T* get_if(const Message& m)
{
    if constexpr (std::is_same_v<T, Untyped>) {
        return std::get_if<Untyped>(&static_cast<const Message::variant&>(m));
    } else {
        using G = GroupOf<T>;
        const auto* group = std::get_if<G>(&static_cast<const Message::variant&>(m));
        return group ? std::get_if<T>(&static_cast<const typename G::variant&>(*group)) : nullptr;
    }
}

/// Whether `m` holds message T.
template <class T> bool holds(const Message& m) { return get_if<T>(m) != nullptr; }

/// The typed message of a frame (an Untyped if the codec has no struct for it).
Message decode(const Frame& frame);

// ---- Encoding ----

namespace codec_detail {

inline void put(std::string& out, std::uint8_t v) { put_u8(out, v); }
inline void put(std::string& out, std::uint16_t v) { put_u16(out, v); }
inline void put(std::string& out, std::int16_t v) { put_i16(out, v); }
inline void put(std::string& out, std::uint32_t v) { put_u32(out, v); }
inline void put(std::string& out, std::int32_t v) { put_i32(out, v); }
template <std::size_t N> void put(std::string& out, const std::array<char, N>& v) { out.append(v.data(), N); }
inline void put(std::string& out, const MotorStatus& v)
{
    std::visit([&](const auto& s) { std::apply([&](const auto&... f) { (put(out, f), ...); }, s.fields(s)); }, v);
}
inline void put(std::string& out, const std::optional<std::int32_t>& v)
{
    if (v)
        put_i32(out, *v);
}

template <class T> std::uint8_t param_byte(const T& v) { return static_cast<std::uint8_t>(v); }

} // namespace codec_detail

/// The data packet of message `m` (empty for a header-only message).
template <class T> std::string encode_data(const T& m)
{
    std::string out;
    std::apply([&](const auto&... f) { (codec_detail::put(out, f), ...); }, T::fields(m));
    return out;
}

namespace codec_detail {
/// A frame being written: a buffer of the largest frame, copied into a string once (status
/// updates and GETs are the hot path; byte-wise string appends cost more than the handler).
struct FrameBuffer {
    std::array<char, kMaxFrameSize> bytes;
    std::size_t size = 0;
    void append(const char* p, std::size_t n)
    {
        std::memcpy(bytes.data() + size, p, n);
        size += n;
    }
};
inline void put(FrameBuffer& out, std::uint8_t v)
{
    const char c = static_cast<char>(v);
    out.append(&c, 1);
}
inline void put(FrameBuffer& out, std::uint16_t v)
{
    const char b[2] = {static_cast<char>(v & 0xFF), static_cast<char>(v >> 8)};
    out.append(b, 2);
}
inline void put(FrameBuffer& out, std::int16_t v) { put(out, static_cast<std::uint16_t>(v)); }
inline void put(FrameBuffer& out, std::uint32_t v)
{
    const char b[4] = {static_cast<char>(v & 0xFF), static_cast<char>((v >> 8) & 0xFF),
                       static_cast<char>((v >> 16) & 0xFF), static_cast<char>(v >> 24)};
    out.append(b, 4);
}
inline void put(FrameBuffer& out, std::int32_t v) { put(out, static_cast<std::uint32_t>(v)); }
template <std::size_t N> void put(FrameBuffer& out, const std::array<char, N>& v) { out.append(v.data(), N); }
inline void put(FrameBuffer& out, const MotorStatus& v)
{
    std::visit([&](const auto& s) { std::apply([&](const auto&... f) { (put(out, f), ...); }, s.fields(s)); }, v);
}
inline void put(FrameBuffer& out, const std::optional<std::int32_t>& v)
{
    if (v)
        put(out, *v);
}

/// The frame of `m` with its data packet: the header (length patched in at the end), then the fields.
template <class T> std::string encode_frame_with_data(const T& m, std::uint8_t dest, std::uint8_t source)
{
    FrameBuffer out;
    put(out, T::id);
    put(out, std::uint16_t{0});
    put(out, static_cast<std::uint8_t>(dest | kDataFlag));
    put(out, source);
    std::apply([&](const auto&... f) { (put(out, f), ...); }, T::fields(m));
    const auto length = static_cast<std::uint16_t>(out.size - kHeaderSize);
    out.bytes[2] = static_cast<char>(length & 0xFF);
    out.bytes[3] = static_cast<char>(length >> 8);
    return std::string(out.bytes.data(), out.size);
}
} // namespace codec_detail

/// Message `m` as a frame from `source` to `dest` (without the data flag).
template <class T> std::string encode(const T& m, std::uint8_t dest, std::uint8_t source)
{
    if constexpr (std::is_same_v<T, MoveRelative> || std::is_same_v<T, MoveAbsolute>) {
        const auto& distance = std::get<1>(T::fields(m));
        if (!distance)
            return encode_header_only(T::id, static_cast<std::uint8_t>(m.chan_ident), 0, dest, source);
        return codec_detail::encode_frame_with_data(m, dest, source);
    } else if constexpr (std::is_same_v<T, Untyped>) {
        return m.has_data ? encode_with_data(m.id, dest, source, m.data)
                          : encode_header_only(m.id, m.param1, m.param2, dest, source);
    } else if constexpr (T::header_only) {
        std::uint8_t params[2] = {0, 0};
        std::size_t i = 0;
        std::apply([&](const auto&... f) { ((params[i++] = codec_detail::param_byte(f)), ...); }, T::fields(m));
        return encode_header_only(T::id, params[0], params[1], dest, source);
    } else {
        return codec_detail::encode_frame_with_data(m, dest, source);
    }
}

/// Any decoded message back to its frame.
std::string encode(const Message& m, std::uint8_t dest, std::uint8_t source);

/// The message ID of a decoded message.
std::uint16_t message_id(const Message& m);

/// Field-by-field equality of two messages of one type (the round-trip tests use it).
template <class T, class = decltype(T::fields(std::declval<const T&>()))>
bool operator==(const T& a, const T& b)
{
    return T::fields(a) == T::fields(b);
}
template <class T, class = decltype(T::fields(std::declval<const T&>()))>
bool operator!=(const T& a, const T& b)
{
    return !(a == b);
}

} // namespace msg
} // namespace rigsim::apt
