#pragma once
// The codec structs of the Generic System Control Messages (Thorlabs APT protocol, issue 3,
// section "Generic System Control Messages", p. 15-27, and the later issues' flash programming
// messages): identify, channel enable state, disconnect, update messages, HW info, rack and hub bays.
//
// This header is a part of codec.hpp: codec.hpp includes it after its Set<>, Req<> and Get<>
// templates and message macros, and before its Message variant; include codec.hpp, not this.

namespace rigsim::apt::msg {

/// MGMSG_MOD_IDENTIFY (p. 16): flash the front panel.
struct ModIdentify {
    RIGSIM_APT_MESSAGE(MGMSG_MOD_IDENTIFY, System);
    std::uint8_t chan_ident = 0;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_MOD_SET_CHANENABLESTATE (p. 17).
struct ModSetChanEnableState {
    RIGSIM_APT_MESSAGE(MGMSG_MOD_SET_CHANENABLESTATE, Bay);
    std::uint8_t chan_ident = 1;
    std::uint8_t enable_state = 1;   ///< 1 enabled, 2 disabled
    RIGSIM_APT_FIELDS(s.chan_ident, s.enable_state);
};
/// MGMSG_MOD_REQ_CHANENABLESTATE (p. 17).
struct ModReqChanEnableState {
    RIGSIM_APT_MESSAGE(MGMSG_MOD_REQ_CHANENABLESTATE, Bay);
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};
/// MGMSG_MOD_GET_CHANENABLESTATE (p. 17).
struct ModGetChanEnableState {
    RIGSIM_APT_MESSAGE(MGMSG_MOD_GET_CHANENABLESTATE, UnitToHost);
    std::uint8_t chan_ident = 1;
    std::uint8_t enable_state = 1;
    RIGSIM_APT_FIELDS(s.chan_ident, s.enable_state);
};
/// MGMSG_HW_DISCONNECT (p. 19).
RIGSIM_APT_BARE_MESSAGE(HwDisconnect, MGMSG_HW_DISCONNECT, System);
/// MGMSG_HW_RESPONSE (p. 19): a fault, header only.
RIGSIM_APT_BARE_MESSAGE(HwResponse, MGMSG_HW_RESPONSE, UnitToHost);
/// MGMSG_HW_RICHRESPONSE (later issues): a fault with its cause.
struct HwRichResponse {
    RIGSIM_APT_MESSAGE(MGMSG_HW_RICHRESPONSE, UnitToHost);
    std::uint16_t msg_ident = 0;   ///< the message that caused it
    std::uint16_t code = 0;
    std::array<char, 64> notes{};
    RIGSIM_APT_FIELDS(s.msg_ident, s.code, s.notes);
};
/// MGMSG_HW_START_UPDATEMSGS (p. 20).
struct HwStartUpdateMsgs {
    RIGSIM_APT_MESSAGE(MGMSG_HW_START_UPDATEMSGS, System);
    std::uint8_t update_rate = 0;   ///< ignored by the units (fixed 10 Hz)
    RIGSIM_APT_FIELDS(s.update_rate);
};
/// MGMSG_HW_STOP_UPDATEMSGS (p. 20; 0x0012, ERRATA).
RIGSIM_APT_BARE_MESSAGE(HwStopUpdateMsgs, MGMSG_HW_STOP_UPDATEMSGS, System);
/// MGMSG_HW_REQ_INFO (p. 21).
RIGSIM_APT_BARE_MESSAGE(HwReqInfo, MGMSG_HW_REQ_INFO, Bay);
/// MGMSG_HW_GET_INFO (p. 21): 84 bytes.
struct HwGetInfo {
    RIGSIM_APT_MESSAGE(MGMSG_HW_GET_INFO, UnitToHost);
    std::uint32_t serial_number = 0;
    std::array<char, 8> model_number{};
    std::uint16_t type = 0;                        ///< 44 brushless card, 45 motherboard, ...
    std::array<char, 4> firmware_version{};        ///< minor, interim, major, unused
    std::array<char, 64> notes{};
    std::uint16_t nchs = 0;                        ///< number of channels
    RIGSIM_APT_FIELDS(s.serial_number, s.model_number, s.type, s.firmware_version, s.notes, s.nchs);
};
/// MGMSG_RACK_REQ_BAYUSED (p. 23).
struct RackReqBayUsed {
    RIGSIM_APT_MESSAGE(MGMSG_RACK_REQ_BAYUSED, Rack);
    std::uint8_t bay_ident = 0;   ///< from 0
    RIGSIM_APT_FIELDS(s.bay_ident);
};
/// MGMSG_RACK_GET_BAYUSED (p. 23).
struct RackGetBayUsed {
    RIGSIM_APT_MESSAGE(MGMSG_RACK_GET_BAYUSED, UnitToHost);
    std::uint8_t bay_ident = 0;
    std::uint8_t bay_state = 0;   ///< 1 occupied, 2 empty
    RIGSIM_APT_FIELDS(s.bay_ident, s.bay_state);
};
/// MGMSG_HUB_REQ_BAYUSED (p. 24).
RIGSIM_APT_BARE_MESSAGE(HubReqBayUsed, MGMSG_HUB_REQ_BAYUSED, Bay);
/// MGMSG_HUB_GET_BAYUSED (p. 24).
struct HubGetBayUsed {
    RIGSIM_APT_MESSAGE(MGMSG_HUB_GET_BAYUSED, UnitToHost);
    std::uint8_t bay_ident = 0;   ///< 0xFF (-1): standalone
    RIGSIM_APT_FIELDS(s.bay_ident);
};
/// MGMSG_RACK_REQ_STATUSBITS (p. 25).
RIGSIM_APT_BARE_MESSAGE(RackReqStatusBits, MGMSG_RACK_REQ_STATUSBITS, Rack);
/// MGMSG_RACK_GET_STATUSBITS (p. 25).
struct RackGetStatusBits {
    RIGSIM_APT_MESSAGE(MGMSG_RACK_GET_STATUSBITS, UnitToHost);
    std::uint32_t status_bits = 0;   ///< digital inputs of the USER IO connector
    RIGSIM_APT_FIELDS(s.status_bits);
};
/// MGMSG_RACK_SET_DIGOUTPUTS (p. 26): header only, the outputs and the bay address.
struct RackSetDigOutputs {
    RIGSIM_APT_MESSAGE(MGMSG_RACK_SET_DIGOUTPUTS, Rack);
    std::uint8_t dig_outputs = 0;   ///< bits 0..3: outputs 1..4
    std::uint8_t bay_ident = 0;     ///< bay address (0x21 + n) or 0: the motherboard
    RIGSIM_APT_FIELDS(s.dig_outputs, s.bay_ident);
};
/// MGMSG_RACK_REQ_DIGOUTPUTS (p. 26).
struct RackReqDigOutputs {
    RIGSIM_APT_MESSAGE(MGMSG_RACK_REQ_DIGOUTPUTS, Rack);
    std::uint8_t dig_outputs = 0;   ///< unused
    std::uint8_t bay_ident = 0;
    RIGSIM_APT_FIELDS(s.dig_outputs, s.bay_ident);
};
/// MGMSG_RACK_GET_DIGOUTPUTS (p. 26).
struct RackGetDigOutputs {
    RIGSIM_APT_MESSAGE(MGMSG_RACK_GET_DIGOUTPUTS, UnitToHost);
    std::uint8_t dig_outputs = 0;
    std::uint8_t bay_ident = 0;
    RIGSIM_APT_FIELDS(s.dig_outputs, s.bay_ident);
};
/// MGMSG_HW_YES_FLASH_PROGRAMMING (later issues).
RIGSIM_APT_BARE_MESSAGE(HwYesFlashProgramming, MGMSG_HW_YES_FLASH_PROGRAMMING, System);
/// MGMSG_HW_NO_FLASH_PROGRAMMING (later issues).
RIGSIM_APT_BARE_MESSAGE(HwNoFlashProgramming, MGMSG_HW_NO_FLASH_PROGRAMMING, System);

} // namespace rigsim::apt::msg
