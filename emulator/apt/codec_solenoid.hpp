#pragma once
// The codec structs of the Solenoid Control Messages (Thorlabs APT protocol, issue 3, section
// "Solenoid Control Messages", p. 84-92): the MOT_ messages of the TSC001 solenoid driver.
//
// This header is a part of codec.hpp: codec.hpp includes it after its Set<>, Req<> and Get<>
// templates and message macros, and before its Message variant; include codec.hpp, not this.

namespace rigsim::apt::msg {

// ---- Solenoid Control Messages (p. 84-92): MOT_ messages of the TSC001 solenoid driver ----
// SolenoidModule (TSC001, KSC101) acts on them; every other module ignores and logs them.

/// MGMSG_MOT_SET_SOL_OPERATINGMODE (p. 85).
struct SolSetOperatingMode {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_SET_SOL_OPERATINGMODE, Solenoid);
    std::uint8_t chan_ident = 1;
    std::uint8_t operating_mode = 1;   ///< 1 manual, 2 single, 3 auto, 4 triggered
    RIGSIM_APT_FIELDS(s.chan_ident, s.operating_mode);
};
/// MGMSG_MOT_REQ_SOL_OPERATINGMODE (p. 85).
struct SolReqOperatingMode {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_REQ_SOL_OPERATINGMODE, Solenoid);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_MOT_GET_SOL_OPERATINGMODE (p. 85).
struct SolGetOperatingMode {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_GET_SOL_OPERATINGMODE, UnitToHost);
    std::uint8_t chan_ident = 1;
    std::uint8_t operating_mode = 1;   ///< 1 manual, 2 single, 3 auto, 4 triggered
    RIGSIM_APT_FIELDS(s.chan_ident, s.operating_mode);
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
    RIGSIM_APT_FIELDS(s.chan_ident, s.on_time_250us, s.off_time_250us, s.num_cycles);
    // p. 87: OnTime and OffTime in 250 us steps, 100 ms..10,000 s; NumCycles 0 (forever)..1,000,000.
    RIGSIM_APT_RANGES({"OnTime", s.on_time_250us, 400, 40'000'000}, {"OffTime", s.off_time_250us, 400, 40'000'000},
                      {"NumCycles", s.num_cycles, 0, 1'000'000});
};

/// MGMSG_MOT_SET_SOL_INTERLOCKMODE (p. 89).
struct SolSetInterlockMode {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_SET_SOL_INTERLOCKMODE, Solenoid);
    std::uint8_t chan_ident = 1;
    std::uint8_t interlock_mode = 1;   ///< 1 enabled (the interlock plug is required), 2 disabled
    RIGSIM_APT_FIELDS(s.chan_ident, s.interlock_mode);
};
/// MGMSG_MOT_REQ_SOL_INTERLOCKMODE (p. 89).
struct SolReqInterlockMode {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_REQ_SOL_INTERLOCKMODE, Solenoid);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_MOT_GET_SOL_INTERLOCKMODE (p. 89).
struct SolGetInterlockMode {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_GET_SOL_INTERLOCKMODE, UnitToHost);
    std::uint8_t chan_ident = 1;
    std::uint8_t interlock_mode = 1;   ///< 1 enabled, 2 disabled
    RIGSIM_APT_FIELDS(s.chan_ident, s.interlock_mode);
};

/// MGMSG_MOT_SET_SOL_STATE (p. 91): overrides the operating mode.
struct SolSetState {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_SET_SOL_STATE, Solenoid);
    std::uint8_t chan_ident = 1;
    // The data structure table labels param2 "Interlock Mode" (copied from p. 89); the
    // header diagram and the values name it the state.
    std::uint8_t state = 2;   ///< 1 on (solenoid active), 2 off
    RIGSIM_APT_FIELDS(s.chan_ident, s.state);
};
/// MGMSG_MOT_REQ_SOL_STATE (p. 91).
struct SolReqState {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_REQ_SOL_STATE, Solenoid);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_MOT_GET_SOL_STATE (p. 91).
struct SolGetState {
    RIGSIM_APT_MESSAGE(MGMSG_MOT_GET_SOL_STATE, UnitToHost);
    std::uint8_t chan_ident = 1;
    std::uint8_t state = 2;   ///< 1 on, 2 off
    RIGSIM_APT_FIELDS(s.chan_ident, s.state);
};

using SetSolCycleParams = Set<SolCycleParams>;
using ReqSolCycleParams = Req<SolCycleParams>;
using GetSolCycleParams = Get<SolCycleParams>;

} // namespace rigsim::apt::msg
