#include "emulator/apt/messages.hpp"

#include <array>
#include <limits>

namespace rigsim::apt {

namespace {

// The constant and its spelling, so a name can never drift from its ID.
#define RIGSIM_APT_MSG(constant) constant, std::string_view(#constant)

constexpr std::int16_t H = -1;   // header-only
constexpr Group G = Group::Generic;
constexpr Group M = Group::Motor;
constexpr Group P = Group::Piezo;
constexpr Group S = Group::StrainGauge;
constexpr bool kShortFormToo = true;
constexpr bool kLaterIssue = true;

// Page numbers are the manual's ("Page N of 138"). The rule of the errata (docs/protocol/errata.md): the detailed
// section beats the summary tables and the examples; where the detailed section is garbled,
// the byte layout its own field list and stated packet length imply wins.
constexpr MessageInfo kTable[] = {
    // ---- Generic System Control Messages (pages 15-26) ----
    {RIGSIM_APT_MSG(MGMSG_MOD_IDENTIFY), H, G},   // p.16
    {RIGSIM_APT_MSG(MGMSG_MOD_SET_CHANENABLESTATE), H, G},   // p.17
    {RIGSIM_APT_MSG(MGMSG_MOD_REQ_CHANENABLESTATE), H, G},
    {RIGSIM_APT_MSG(MGMSG_MOD_GET_CHANENABLESTATE), H, G},
    // p.19: "0x002H" means 0x0002 (ERRATA).
    {RIGSIM_APT_MSG(MGMSG_HW_DISCONNECT), H, G},
    {RIGSIM_APT_MSG(MGMSG_HW_RESPONSE), H, G},   // p.19
    // Named on p.13 and p.82 only, without a section. Layout from later protocol issues:
    // MsgIdent word, Code word, Notes char[64] = 68 bytes of data.
    {RIGSIM_APT_MSG(MGMSG_HW_RICHRESPONSE), 68, G},
    // p.20. The summary (p.13) gives STOP_UPDATEMSGS as 0x0011; the section's 0x0012 wins.
    {RIGSIM_APT_MSG(MGMSG_HW_START_UPDATEMSGS), H, G},
    {RIGSIM_APT_MSG(MGMSG_HW_STOP_UPDATEMSGS), H, G},
    // p.21: "0x05H"/"0x06H" mean 0x0005/0x0006 (ERRATA). GET_INFO: 84-byte (0x54) packet.
    {RIGSIM_APT_MSG(MGMSG_HW_REQ_INFO), H, G},
    {RIGSIM_APT_MSG(MGMSG_HW_GET_INFO), 84, G},
    // p.23: the examples begin "06, 00"; the IDs are 0x0060/0x0061 (ERRATA).
    {RIGSIM_APT_MSG(MGMSG_RACK_REQ_BAYUSED), H, G},
    {RIGSIM_APT_MSG(MGMSG_RACK_GET_BAYUSED), H, G},
    {RIGSIM_APT_MSG(MGMSG_HUB_REQ_BAYUSED), H, G},   // p.24
    {RIGSIM_APT_MSG(MGMSG_HUB_GET_BAYUSED), H, G},
    // p.25: the REQ table prints "28 02" (ERRATA: 0x0226). GET: 4-byte packet; its table and
    // example print the destination without the 0x80 data flag ("27, 02, 04, 00, 01, 22"),
    // which section 4 requires of every message with a data packet: the flag is required.
    {RIGSIM_APT_MSG(MGMSG_RACK_REQ_STATUSBITS), H, G},
    {RIGSIM_APT_MSG(MGMSG_RACK_GET_STATUSBITS), 4, G},
    // p.26: all three header-only (SET carries the outputs in param1). GET_DIGOUTPUTS is
    // 0x0230 in the section, its table ("30 02") and every cross-reference, not 0x022A.
    {RIGSIM_APT_MSG(MGMSG_RACK_SET_DIGOUTPUTS), H, G},
    {RIGSIM_APT_MSG(MGMSG_RACK_REQ_DIGOUTPUTS), H, G},
    {RIGSIM_APT_MSG(MGMSG_RACK_GET_DIGOUTPUTS), H, G},
    // Later protocol issues: clients send these at start-up (NO_FLASH_PROGRAMMING "to notify
    // the controller of the source and destination addresses"); units accept them silently.
    {RIGSIM_APT_MSG(MGMSG_HW_YES_FLASH_PROGRAMMING), H, G, false, kLaterIssue},
    {RIGSIM_APT_MSG(MGMSG_HW_NO_FLASH_PROGRAMMING), H, G, false, kLaterIssue},

    // ---- Motor Control Messages (pages 27-83) ----
    // p.28: chan word + position long. The REQ table prints "11 04", which is right here.
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_POSCOUNTER), 6, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_POSCOUNTER), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_POSCOUNTER), 6, M},
    // p.29: the REQ table prints "11 04"; the ID is 0x040A (ERRATA).
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_ENCCOUNTER), 6, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_ENCCOUNTER), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_ENCCOUNTER), 6, M},
    // p.30: 0x0413/0x0414/0x0415 as in the section; the summary (p.13) says SET is 0x0414.
    // 14 bytes: chan word, min velocity, acceleration, max velocity (longs).
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_VELPARAMS), 14, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_VELPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_VELPARAMS), 14, M},
    // p.32: 22 bytes (0x16); the example's "16H (28) byte" is the whole message.
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_JOGPARAMS), 22, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_JOGPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_JOGPARAMS), 22, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_GENMOVEPARAMS), 6, M},   // p.34
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_GENMOVEPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_GENMOVEPARAMS), 6, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_MOVERELPARAMS), 6, M},   // p.35
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_MOVERELPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_MOVERELPARAMS), 6, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_MOVEABSPARAMS), 6, M},   // p.36
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_MOVEABSPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_MOVEABSPARAMS), 6, M},
    // p.37: 0x0440/0x0441/0x0442 as in the section; the summary (p.13) says SET is 0x0442.
    // 14 bytes: chan, direction, limit switch (words), velocity, offset (longs).
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_HOMEPARAMS), 14, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_HOMEPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_HOMEPARAMS), 14, M},
    // p.39: 16 bytes (0x10) as the headers and field list say; GET's "20 bytes" is wrong
    // (ERRATA: 22).
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_LIMSWITCHPARAMS), 16, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_LIMSWITCHPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_LIMSWITCHPARAMS), 16, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_MOVE_HOME), H, M},    // p.41
    {RIGSIM_APT_MSG(MGMSG_MOT_MOVE_HOMED), H, M},
    // p.42: a short header-only form and a long form with the MOVERELPARAMS packet. The
    // long example's explanation names header "45, 04"; the message is 0x0448 (ERRATA).
    {RIGSIM_APT_MSG(MGMSG_MOT_MOVE_RELATIVE), 6, M, kShortFormToo},
    // p.44 / p.50: both print a header-only table but say 20 bytes "followed by a 14-byte
    // data packet" (the status structure of GET_STATUSUPDATE / GET_DCSTATUSUPDATE): always
    // sent with the data flag and length 14 (ERRATA).
    {RIGSIM_APT_MSG(MGMSG_MOT_MOVE_COMPLETED), 14, M},
    // p.45: short and long forms as MOVE_RELATIVE; the explanation's "45, 04" is 0x0453.
    {RIGSIM_APT_MSG(MGMSG_MOT_MOVE_ABSOLUTE), 6, M, kShortFormToo},
    // p.47 / p.48: header-only; the "Data Structure" tables describe param1 (chan) and
    // param2 (direction) although they say "word".
    {RIGSIM_APT_MSG(MGMSG_MOT_MOVE_JOG), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_MOVE_VELOCITY), H, M},
    // p.49: header-only, param2 = stop mode. The TDC001 cross-reference (p.136) lists 0x0465
    // as "MOVE STOPPED": 0x0465 is MOVE_STOP, 0x0466 MOVE_STOPPED (ERRATA).
    {RIGSIM_APT_MSG(MGMSG_MOT_MOVE_STOP), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_MOVE_STOPPED), 14, M},   // p.50, see MOVE_COMPLETED
    // p.51: 20 bytes (0x14): chan word, P, I, D, integral limit (longs), filter control word.
    // The example encodes P/I/D in 2 bytes each and is 6 bytes short of its own header's
    // length; the field list and the stated 26-byte message win (ERRATA). The REQ/GET
    // tables print "A0 04"; the IDs are 0x04A1/0x04A2 (ERRATA).
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_DCPIDPARAMS), 20, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_DCPIDPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_DCPIDPARAMS), 20, M},
    // p.53: 4 bytes. The REQ table prints "11 04"; the ID is 0x04B4 (ERRATA).
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_AVMODES), 4, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_AVMODES), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_AVMODES), 4, M},
    // p.55-57: 26 bytes (0x1A): chan, ZeroWnd (words), then Vel1..Vel4 (longs) interleaved
    // with Wnd1..Wnd3 (words) = 2+2+4+2+4+2+4+2+4. GET says "28 bytes ... 22 byte data
    // packet" but prints length "1A" and the same 32-byte layout: 26 wins. The
    // SET example is a copy of the JOGPARAMS bytes (22 data bytes under a 0x1A header) and is
    // ignored. The REQ table prints "17 04"; the ID is 0x04B1.
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_POTPARAMS), 26, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_POTPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_POTPARAMS), 26, M},
    // p.58: 16 bytes: chan, mode (words), Position1, Position2 (longs), TimeOut, not used
    // (words). The SET table prints length "0E" (ERRATA: 0x10, as the example header); the
    // example's data is 14 bytes and is ignored. REQ prints "DB 04", GET "B6 04 0E 00";
    // the IDs are 0x04B7/0x04B8 (ERRATA).
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_BUTTONPARAMS), 16, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_BUTTONPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_BUTTONPARAMS), 16, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_EEPROMPARAMS), 4, M},   // p.60: chan word + MsgID word
    // p.61: 28 bytes (0x1C): chan, Kp, Ki (words), ILim (dword), Kd, KdTime, Kout, Kvff,
    // Kaff (words), PosErrLim (dword), two unused words. The example carries 26 data bytes
    // (one unused word missing) under its 0x1C header: 28 win.
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS), 28, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_PMDPOSITIONLOOPPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_PMDPOSITIONLOOPPARAMS), 28, M},
    // p.64: 14 bytes (seven words).
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS), 14, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_PMDMOTOROUTPUTPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_PMDMOTOROUTPUTPARAMS), 14, M},
    // p.66: 12 bytes (six words). The contents (p.2) list GET as 0x04E1; the section's 0x04E2
    // wins. The example carries 14 data bytes under its 0x0C header: 12 win (the framer
    // drops the two extra bytes).
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_PMDTRACKSETTLEPARAMS), 12, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_PMDTRACKSETTLEPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_PMDTRACKSETTLEPARAMS), 12, M},
    // p.69: 12 bytes: chan, mode (words), jerk (dword), two unused words.
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_PMDPROFILEMODEPARAMS), 12, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_PMDPROFILEMODEPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_PMDPROFILEMODEPARAMS), 12, M},
    // p.71: 18 bytes (nine words). The REQ table prints "D8 04"; the ID is 0x04D5.
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS), 18, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_PMDCURRENTLOOPPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_PMDCURRENTLOOPPARAMS), 18, M},
    // p.73: 18 bytes (nine words). The REQ table prints "D8 04"; the ID is 0x04EA. The
    // example's explanation names header "D4, 04"; its bytes (E9 04) are right.
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS), 18, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_PMDSETTLEDCURRENTLOOPPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_PMDSETTLEDCURRENTLOOPPARAMS), 18, M},
    // p.75: 74 bytes (0x4A), as "80 bytes" and the example header "F2, 04, 4A, 00" say; the
    // GET table prints length "12 00".
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_PMDSTAGEAXISPARAMS), 74, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_PMDSTAGEAXISPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_PMDSTAGEAXISPARAMS), 74, M},
    // p.77: 14 bytes: chan word, position, encoder count (longs), status bits (dword).
    // p.78: the REQ table prints "90 04"; the ID is 0x0480 (ERRATA).
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_STATUSUPDATE), 14, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_STATUSUPDATE), H, M},
    // p.79: 14 bytes: chan word, position long, velocity, reserved (words), status dword.
    // p.80: ACK's table prints "62 06" (PZ_ACK_PZSTATUSUPDATE); the example "92 04" is right.
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_DCSTATUSUPDATE), 14, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_DCSTATUSUPDATE), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_ACK_DCSTATUSUPDATE), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_STATUSBITS), H, M},   // p.81
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_STATUSBITS), 6, M},   // chan word + status dword
    {RIGSIM_APT_MSG(MGMSG_MOT_SUSPEND_ENDOFMOVEMSGS), H, M},   // p.82
    {RIGSIM_APT_MSG(MGMSG_MOT_RESUME_ENDOFMOVEMSGS), H, M},    // p.83

    // ---- Solenoid Control Messages (pages 84-92): MOT_ messages of the TSC001 ----
    // p.85: header-only; the "Data Structure" (char, char) describes param1/param2.
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_SOL_OPERATINGMODE), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_SOL_OPERATINGMODE), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_SOL_OPERATINGMODE), H, M},
    // p.87: 14 bytes: chan word, OnTime, OffTime, NumCycles (longs). The example's
    // "D0H (14)" is 0x0E.
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_SOL_CYCLEPARAMS), 14, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_SOL_CYCLEPARAMS), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_SOL_CYCLEPARAMS), 14, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_SOL_INTERLOCKMODE), H, M},   // p.89
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_SOL_INTERLOCKMODE), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_SOL_INTERLOCKMODE), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_SOL_STATE), H, M},   // p.91
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_SOL_STATE), H, M},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_SOL_STATE), H, M},

    // ---- Piezo Control Messages (pages 93-129) ----
    // p.94: header-only, param1 = channel, param2 = mode.
    {RIGSIM_APT_MSG(MGMSG_PZ_SET_POSCONTROLMODE), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_POSCONTROLMODE), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_POSCONTROLMODE), H, P},
    // p.96: 4 bytes: chan word, voltage short.
    {RIGSIM_APT_MSG(MGMSG_PZ_SET_OUTPUTVOLTS), 4, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_OUTPUTVOLTS), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_OUTPUTVOLTS), 4, P},
    // p.97: 4 bytes: chan word, PositionSW word. The example's explanation names header
    // "43, 06" (the bytes' "46, 06" is right) and value "33, 13" against the bytes' "66, 26"
    // (ERRATA): on the 0..32767 scale 15 um of 100 um is 4915 = "33, 13" (9830 = "66, 26" is
    // 30 %); the explanation's value is right. Neither changes the length.
    {RIGSIM_APT_MSG(MGMSG_PZ_SET_OUTPUTPOS), 4, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_OUTPUTPOS), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_OUTPUTPOS), 4, P},
    // p.98: 4 bytes: chan word, VoltSrc word (the SET table labels it PositionSW, ERRATA).
    {RIGSIM_APT_MSG(MGMSG_PZ_SET_INPUTVOLTSSRC), 4, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_INPUTVOLTSSRC), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_INPUTVOLTSSRC), 4, P},
    // p.100: 6 bytes: chan, PropConst, IntConst (words). The explanation's header
    // "55, 06, 05, 00" contradicts its own bytes "55, 06, 06, 00": 6 wins.
    {RIGSIM_APT_MSG(MGMSG_PZ_SET_PICONSTS), 6, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_PICONSTS), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_PICONSTS), 6, P},
    // p.101: GET 6 bytes: chan word, status dword.
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_PZSTATUSBITS), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_PZSTATUSBITS), 6, P},
    // p.103: the byte table prints "91 04 0E 00" (MOT_GET_DCSTATUSUPDATE's) under a
    // "16 bytes ... 10 byte data packet" heading; the field list (chan word, OPVoltage
    // short, Position short, status dword) makes 10 bytes: 0x0661, length 10 (ERRATA).
    // The contents print the ID "0x00661". The manual has no REQ for it.
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_PZSTATUSUPDATE), 10, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_ACK_PZSTATUSUPDATE), H, P},   // p.105: params 0
    // p.106: 6 bytes: chan, Index (words), Output short. The REQ table prints "1 07"
    // (0x0701).
    {RIGSIM_APT_MSG(MGMSG_PZ_SET_OUTPUTLUT), 6, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_OUTPUTLUT), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_OUTPUTLUT), 6, P},
    // p.108: 30 bytes (0x1E): chan, Mode, CycleLength (words), NumCycles, DelayTime,
    // PreCycleRest, PostCycleRest (longs), OPTrigStart word, OPTrigWidth long,
    // TrigRepeatCycle word. The example (p.111) prints header length "06" and its values
    // most-significant byte first (ERRATA): 30 wins. The GET table prints "03 07"; the ID
    // is 0x0705.
    {RIGSIM_APT_MSG(MGMSG_PZ_SET_OUTPUTLUTPARAMS), 30, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_OUTPUTLUTPARAMS), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_OUTPUTLUTPARAMS), 30, P},
    // p.112: header-only, param1 = channel. The headings give no IDs; the contents and
    // the cross-references (p.131) give 0x0706/0x0707, as do the tables' "06 07"/"07 07".
    {RIGSIM_APT_MSG(MGMSG_PZ_START_LUTOUTPUT), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_STOP_LUTOUTPUT), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_SET_EEPROMPARAMS), 4, P},   // p.113: chan word + MsgID word
    // p.114: 2 bytes: DispIntensity word (no channel). REQ is header-only (param1 1).
    {RIGSIM_APT_MSG(MGMSG_PZ_SET_TPZ_DISPSETTINGS), 2, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_TPZ_DISPSETTINGS), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_TPZ_DISPSETTINGS), 2, P},
    // p.115: the heading gives no IDs: 0x07D4/0x07D5/0x07D6 from the contents and the
    // REQ table "D5 07"; the GET table prints "D4 07" (0x07D6 wins). Both tables print
    // length "0E" under "16 bytes ... 10 byte data packet"; the field list (chan,
    // VoltageLimit, HubAnalogInput, two future-use words) makes 10: 10 wins.
    {RIGSIM_APT_MSG(MGMSG_PZ_SET_TPZ_IOSETTINGS), 10, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_TPZ_IOSETTINGS), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_TPZ_IOSETTINGS), 10, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_SET_ZERO), H, P},   // p.117: header-only, param1 = channel
    // p.118: GET 4 bytes: chan word, Travel word (100 nm steps).
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_MAXTRAVEL), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_MAXTRAVEL), 4, P},
    // p.119: tables print length "0E" under "16 bytes ... 10 byte data packet"; the field
    // list (chan, AmpCurrentLim, AmpLPFilter, FeedbackSig, BNCTrigORLVOut words) makes
    // 10: 10 wins.
    {RIGSIM_APT_MSG(MGMSG_PZ_SET_IOSETTINGS), 10, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_IOSETTINGS), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_IOSETTINGS), 10, P},
    // p.121: 6 bytes: chan, Voltage, Flags (words). The SET table prints length "0C"; the
    // "12 bytes ... 6 byte data packet" heading, the field list, the GET table and both
    // examples ("80, 06, 06, 00") make 6: 6 wins.
    {RIGSIM_APT_MSG(MGMSG_PZ_SET_OUTPUTMAXVOLTS), 6, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_OUTPUTMAXVOLTS), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_OUTPUTMAXVOLTS), 6, P},
    // p.123: 6 bytes: chan, SlewOpen, SlewClosed (words). The BPC30x cross-reference
    // (p.132) spells them PZ_SET/REQ/GET_SLEWRATES; the section's TPZ_ names are kept.
    {RIGSIM_APT_MSG(MGMSG_PZ_SET_TPZ_SLEWRATES), 6, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_TPZ_SLEWRATES), H, P},
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_TPZ_SLEWRATES), 6, P},
    // p.125 (piezo chapter): header-only. The table prints "58 06" (PZ_SET_ZERO); the
    // heading and the BPC30x cross-reference (p.132) give 0x0686.
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_PZSTAGEPARAMDEFAULTS), H, M},
    // p.126: header-only, param1 = LUTType; its "Data Structure" (char) describes param1.
    {RIGSIM_APT_MSG(MGMSG_PZ_SET_LUTVALUETYPE), H, P},

    // ---- Strain gauge reader (TSG001; pages 127-129, in the piezo chapter) ----
    // p.127: SET says "20 bytes ... 14 byte data packet", both tables print length "0E"
    // and byte positions up to 19; GET's "16 bytes ... 10 byte data packet" is wrong: 14
    // wins. The field list (chan, HubAnalogueOutput, DisplayMode, ForceCalib words) names
    // 8 bytes; the rest is future use. The SET example carries 13 data bytes and is ignored.
    {RIGSIM_APT_MSG(MGMSG_PZ_SET_TSG_IOSETTINGS), 14, S},
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_TSG_IOSETTINGS), H, S},
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_TSG_IOSETTINGS), 14, S},
    // p.129: GET 6 bytes: chan word, Reading short, Smoothed word (the table labels the
    // last 4 bytes StatusBits; the field list and the example win).
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_TSG_READING), H, S},
    {RIGSIM_APT_MSG(MGMSG_PZ_GET_TSG_READING), 6, S},

    // ---- Later protocol issues: motor messages the 2012 manual lacks (issue 14) ----
    // After the manual's chapters, so the manual's table keeps its positions. A unit of the
    // manual's generation ("issue-3") ignores and logs them; the "issue-44.1" generation acts on
    // them (kcube_params.cpp, docs/protocol/apt.md "Firmware generations").
    // Issue 16 (29 Sept 2015, p. 44; doc/APT_Communications_Protocol_Rev_16.pdf of
    // UniNE-CHYN/thorpy): 6 bytes: chan, RestFactor, MoveFactor (words). Its example
    // "26, 04, 06, 00, A2, 01, 01, 00, 0A, 00, 64, 00"; yaq's thorlabs_apt_protocol "<3H".
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_POWERPARAMS), 6, M, false, kLaterIssue},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_POWERPARAMS), H, M, false, kLaterIssue},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_POWERPARAMS), 6, M, false, kLaterIssue},
    // Issue 16 p. 94: header-only, param1 = actuator ident ("FE, 04, 31, 00, 50, 01").
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_TSTACTUATORTYPE), H, M, false, kLaterIssue},
    // Issue 16 p. 102-103: header-only, param1 = chan, param2 = mode bits
    // ("00, 05, 01, 53, 50, 01"; REQ "01, 05, 01, 00, 50, 01"; GET "02 05 Chan Mode").
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_TRIGGER), H, M, false, kLaterIssue},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_TRIGGER), H, M, false, kLaterIssue},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_TRIGGER), H, M, false, kLaterIssue},
    // 36 bytes: chan, JSMode (words), JSMaxVel, JSAccn (longs), DirSense (word), PresetPos1,
    // PresetPos2 (longs), DispBrightness, DispTimeout, DispDimLevel (words), PresetPos3 (long),
    // JSSensitivity, reserved (words): quantumion/thorlabs_cube kdc.py ("<HHllHllHHHlHH", after
    // protocol issue 38) and MSLNZ/msl-equipment thorlabs/ksc.py ("<H20x3H8x"). yaq's "<HHllHll3H"
    // (28) stops at DispDimLevel: 36 wins (two sources, the later fields named by issue 37 clients).
    // A KSC101 reads the display words only (28 bytes, msl-equipment); the motor K-Cubes read
    // up to JSSensitivity (34: KCubeParams::fields_read), so yaq's 28 bytes are short for them.
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_KCUBEMMIPARAMS), 36, M, false, kLaterIssue, 28},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_KCUBEMMIPARAMS), H, M, false, kLaterIssue},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_KCUBEMMIPARAMS), 36, M, false, kLaterIssue},
    // 22 bytes: chan, Trig1Mode, Trig1Polarity, Trig2Mode, Trig2Polarity (words), 12 reserved
    // bytes: Thorlabs' own example ("23 05 16 00 D0 01 ...", Thorlabs/Motion_Control_Examples KBD101
    // Python example) and msl-equipment ksc.py ("<5H12x"). Clients disagree on the reserved tail
    // (pyLabLib 10, yaq 12, quantumion 20 bytes): Thorlabs' example wins, and a SET of the 10
    // bytes before the reserved tail is acted on.
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_KCUBETRIGIOCONFIG), 22, M, false, kLaterIssue, 10},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_KCUBETRIGIOCONFIG), H, M, false, kLaterIssue},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_KCUBETRIGIOCONFIG), 22, M, false, kLaterIssue},
    // 46 bytes: chan word, StartPosFwd, IntervalFwd, NumPulsesFwd, StartPosRev, IntervalRev,
    // NumPulsesRev, PulseWidth, NumCycles (longs), 12 reserved bytes: Thorlabs' example
    // ("26 05 2E 00 D0 01 ..."). pyLabLib, yaq and quantumion send the 34 bytes before the
    // reserved tail: Thorlabs' example wins, as for TRIGIOCONFIG, and their 34 bytes are acted on.
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_KCUBEPOSTRIGPARAMS), 46, M, false, kLaterIssue, 34},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_KCUBEPOSTRIGPARAMS), H, M, false, kLaterIssue},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_KCUBEPOSTRIGPARAMS), 46, M, false, kLaterIssue},
    // 28 bytes: chan, LoopMode (words), Prop, Int, Diff, PIDClip, PIDTol (longs), EncoderConst
    // (dword): yaq's thorlabs_apt_protocol ("<HH5lL"), the only public layout found.
    {RIGSIM_APT_MSG(MGMSG_MOT_SET_KCUBEKSTLOOPPARAMS), 28, M, false, kLaterIssue},
    {RIGSIM_APT_MSG(MGMSG_MOT_REQ_KCUBEKSTLOOPPARAMS), H, M, false, kLaterIssue},
    {RIGSIM_APT_MSG(MGMSG_MOT_GET_KCUBEKSTLOOPPARAMS), 28, M, false, kLaterIssue},

    // ---- Later protocol issues: the K-Cube piezo driver and strain gauge reader ----
    // Not in the 2012 manual; a unit of the manual's generation ignores and logs them (catalogue.cpp:
    // only a KPZ101/KSG101 of the later generation takes them). Issue 44.1 is the one K-Cube drivers
    // cite (docs/protocol/apt.md "K-Cube units" gives each source).
    // PZ_REQ_PZSTATUSUPDATE: header-only, param1 = channel; answered by PZ_GET_PZSTATUSUPDATE
    // (yaq-project/thorlabs-apt-protocol functions.py pz_req_pzstatusupdate; AlexShkarin/pyLabLib
    // kinesis.py reads a KPZ's status with it).
    {RIGSIM_APT_MSG(MGMSG_PZ_REQ_PZSTATUSUPDATE), H, P, false, kLaterIssue},
    // KPZ101 MMI block: 34 bytes: chan, JSMode, JSVoltGearbox (words), JSVoltStep (long),
    // DirSense (word), PresetVolt1, PresetVolt2 (longs), DispBrightness, DispTimeout,
    // DispDimLevel (words), four reserved words (kptrofatter/kcube kcube_message.c writes length
    // 0x22; quantumion/thorlabs_cube driver/kcube/kpz.py packs the same 34 bytes, citing protocol
    // issue 38). REQ: header-only, param1 = channel. The unit reads the 26 bytes before the
    // reserved words (yaq's kpz_set_kcubemmiparams, "<HHHLHLLHHH", sends just those).
    {RIGSIM_APT_MSG(MGMSG_KPZ_SET_KCUBEMMIPARAMS), 34, P, false, kLaterIssue, 26},
    {RIGSIM_APT_MSG(MGMSG_KPZ_REQ_KCUBEMMIPARAMS), H, P, false, kLaterIssue},
    {RIGSIM_APT_MSG(MGMSG_KPZ_GET_KCUBEMMIPARAMS), 34, P, false, kLaterIssue},
    // KPZ101 trigger ports: 22 bytes: chan, Trig1Mode, Trig1Polarity, Trig2Mode, Trig2Polarity,
    // six reserved words (kcube_message.c length 0x16; thorlabs_cube kpz.py 11 words). yaq's
    // 6-word form (12 bytes) is short of both: 22 wins; the unit reads the first 10 bytes, so
    // yaq's SET is acted on.
    {RIGSIM_APT_MSG(MGMSG_KPZ_SET_KCUBETRIGIOCONFIG), 22, P, false, kLaterIssue, 10},
    {RIGSIM_APT_MSG(MGMSG_KPZ_REQ_KCUBETRIGIOCONFIG), H, P, false, kLaterIssue},
    {RIGSIM_APT_MSG(MGMSG_KPZ_GET_KCUBETRIGIOCONFIG), 22, P, false, kLaterIssue},
    // KSG101 MMI block: 8 bytes: chan, DispIntensity, DispTimeout, DispDimLevel (words)
    // (kcube_message.c length 0x08; yaq "<HHHH"). Kinesis' KSG_MMIParams struct has four more
    // reserved words, but it is the DLL's, not the wire's: the two wire-level sources win.
    {RIGSIM_APT_MSG(MGMSG_KSG_SET_KCUBEMMIPARAMS), 8, S, false, kLaterIssue},
    {RIGSIM_APT_MSG(MGMSG_KSG_REQ_KCUBEMMIPARAMS), H, S, false, kLaterIssue},
    {RIGSIM_APT_MSG(MGMSG_KSG_GET_KCUBEMMIPARAMS), 8, S, false, kLaterIssue},
    // KSG101 trigger ports: 22 bytes: chan, Trig1Mode, Trig1Polarity, Trig2Mode, Trig2Polarity
    // (words), LowerLim, UpperLim (longs), SmoothingSamples, one reserved word (kcube_message.c
    // length 0x16; yaq "<HHHHHllHH"); the unit reads the 20 bytes before the reserved word.
    {RIGSIM_APT_MSG(MGMSG_KSG_SET_KCUBETRIGIOCONFIG), 22, S, false, kLaterIssue, 20},
    {RIGSIM_APT_MSG(MGMSG_KSG_REQ_KCUBETRIGIOCONFIG), H, S, false, kLaterIssue},
    {RIGSIM_APT_MSG(MGMSG_KSG_GET_KCUBETRIGIOCONFIG), 22, S, false, kLaterIssue},
};

#undef RIGSIM_APT_MSG

constexpr std::size_t kTableSize = sizeof(kTable) / sizeof(kTable[0]);
static_assert(kTableSize < std::numeric_limits<std::uint8_t>::max(),
              "the ID index stores table positions + 1 in a byte");

/// One byte per possible ID: 0 = unknown, else table position + 1. The framer looks up
/// every byte offset while it resyncs, so the lookup is one load.
using IdIndex = std::array<std::uint8_t, 0x10000>;

IdIndex build_index()
{
    IdIndex index{};
    for (std::size_t i = 0; i < kTableSize; ++i)
        index[kTable[i].id] = static_cast<std::uint8_t>(i + 1);
    return index;
}

} // namespace

const MessageInfo* find_message(std::uint16_t id)
{
    static const IdIndex index = build_index();
    const auto slot = index[id];
    return slot == 0 ? nullptr : &kTable[slot - 1];
}

MessageTable all_messages()
{
    return MessageTable{kTable, kTableSize};
}

} // namespace rigsim::apt
