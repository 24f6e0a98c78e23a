#pragma once
// The APT message table (Thorlabs APT protocol, issue 3, 2012): every message of its
// "Generic System Control Messages", "Motor Control Messages" (including the solenoid
// messages, which the manual files under the motor controllers) and "Piezo Control
// Messages" (including the TSG001 strain gauge reader's, which the manual files under the
// piezo controllers); then the motor messages of later protocol issues that later clients
// send (`later_issue`: POWERPARAMS, TRIGGER, the K-Cube blocks, TSTACTUATORTYPE).
// The frame framer checks every header against it, as MAVLink's framer checks its
// message-entry table: an ID the table does not know, or a header-only message with the data
// flag (a data message without it), or a data packet over 255 bytes, is not a frame. A packet
// of another length than the table's layout is one (frame_framer.hpp): a SET as long as the
// fields a unit reads (`fields_length`) is acted on, a missing reserved tail read as zeros and
// bytes past the layout ignored (and noted in the wire log); a shorter one is ignored and logged.
//
// IDs and lengths follow the detailed section of each message, corrected by the errata
// (docs/protocol/errata.md) where that section is itself wrong; every choice made where
// the manual is ambiguous is a comment at the message's entry in messages.cpp.

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace rigsim::apt {

/// The chapter a message belongs to.
enum class Group : std::uint8_t {
    Generic,       ///< MOD_*, HW_*, RACK_*, HUB_* ("Generic System Control Messages")
    Motor,         ///< MOT_* ("Motor Control Messages", "Solenoid Control Messages")
    Piezo,         ///< PZ_* ("Piezo Control Messages") except the strain gauge reader's
    StrainGauge,   ///< PZ_*TSG_* (the TSG001's messages, in "Piezo Control Messages")
};

/// One message of the table.
struct MessageInfo {
    std::uint16_t id;
    std::string_view name;            ///< manual spelling, e.g. "MGMSG_MOT_MOVE_ABSOLUTE"
    std::int16_t data_length;         ///< -1: header-only; else the data packet's length in its layout
    Group group;
    bool header_only_allowed = false; ///< a short header-only form exists beside the data form
    bool later_issue = false;         ///< not in the 2012 manual but in later issues: framed always; acted on
                                      ///< only by units of a later firmware generation (HW_YES/NO_FLASH_PROGRAMMING: all)
    /// The fewest data bytes any unit reads of it: the fields before a reserved tail that
    /// clients leave out (0: all data_length bytes). A unit may read more (Module::fields_read).
    std::int16_t fields_length = 0;

    /// True when the message is a 6-byte header without a data packet (in its only form).
    constexpr bool header_only() const { return data_length < 0; }
    /// The data bytes the codec needs to type the message (fields_length, else data_length).
    constexpr std::size_t min_data_length() const
    {
        return static_cast<std::size_t>(fields_length > 0 ? fields_length : (data_length < 0 ? 0 : data_length));
    }
};

/// The message with this ID, or nullptr when the table does not know it.
const MessageInfo* find_message(std::uint16_t id);

/// The whole table, in the manual's order (generic messages first), then the later issues' motor messages.
struct MessageTable {
    const MessageInfo* first;
    std::size_t count;

    const MessageInfo* begin() const { return first; }
    const MessageInfo* end() const { return first + count; }
    std::size_t size() const { return count; }
    const MessageInfo& operator[](std::size_t i) const { return first[i]; }
};

/// Every message rigsim's APT framer accepts.
MessageTable all_messages();

// ---- Generic System Control Messages ----
constexpr std::uint16_t MGMSG_MOD_IDENTIFY = 0x0223;
constexpr std::uint16_t MGMSG_MOD_SET_CHANENABLESTATE = 0x0210;
constexpr std::uint16_t MGMSG_MOD_REQ_CHANENABLESTATE = 0x0211;
constexpr std::uint16_t MGMSG_MOD_GET_CHANENABLESTATE = 0x0212;
constexpr std::uint16_t MGMSG_HW_DISCONNECT = 0x0002;
constexpr std::uint16_t MGMSG_HW_RESPONSE = 0x0080;
constexpr std::uint16_t MGMSG_HW_RICHRESPONSE = 0x0081;
constexpr std::uint16_t MGMSG_HW_START_UPDATEMSGS = 0x0011;
constexpr std::uint16_t MGMSG_HW_STOP_UPDATEMSGS = 0x0012;
constexpr std::uint16_t MGMSG_HW_REQ_INFO = 0x0005;
constexpr std::uint16_t MGMSG_HW_GET_INFO = 0x0006;
constexpr std::uint16_t MGMSG_RACK_REQ_BAYUSED = 0x0060;
constexpr std::uint16_t MGMSG_RACK_GET_BAYUSED = 0x0061;
constexpr std::uint16_t MGMSG_HUB_REQ_BAYUSED = 0x0065;
constexpr std::uint16_t MGMSG_HUB_GET_BAYUSED = 0x0066;
constexpr std::uint16_t MGMSG_RACK_REQ_STATUSBITS = 0x0226;
constexpr std::uint16_t MGMSG_RACK_GET_STATUSBITS = 0x0227;
constexpr std::uint16_t MGMSG_RACK_SET_DIGOUTPUTS = 0x0228;
constexpr std::uint16_t MGMSG_RACK_REQ_DIGOUTPUTS = 0x0229;
constexpr std::uint16_t MGMSG_RACK_GET_DIGOUTPUTS = 0x0230;
// Later protocol issues (not in the 2012 manual).
constexpr std::uint16_t MGMSG_HW_YES_FLASH_PROGRAMMING = 0x0017;
constexpr std::uint16_t MGMSG_HW_NO_FLASH_PROGRAMMING = 0x0018;

// ---- Motor Control Messages ----
constexpr std::uint16_t MGMSG_MOT_SET_POSCOUNTER = 0x0410;
constexpr std::uint16_t MGMSG_MOT_REQ_POSCOUNTER = 0x0411;
constexpr std::uint16_t MGMSG_MOT_GET_POSCOUNTER = 0x0412;
constexpr std::uint16_t MGMSG_MOT_SET_ENCCOUNTER = 0x0409;
constexpr std::uint16_t MGMSG_MOT_REQ_ENCCOUNTER = 0x040A;
constexpr std::uint16_t MGMSG_MOT_GET_ENCCOUNTER = 0x040B;
constexpr std::uint16_t MGMSG_MOT_SET_VELPARAMS = 0x0413;
constexpr std::uint16_t MGMSG_MOT_REQ_VELPARAMS = 0x0414;
constexpr std::uint16_t MGMSG_MOT_GET_VELPARAMS = 0x0415;
constexpr std::uint16_t MGMSG_MOT_SET_JOGPARAMS = 0x0416;
constexpr std::uint16_t MGMSG_MOT_REQ_JOGPARAMS = 0x0417;
constexpr std::uint16_t MGMSG_MOT_GET_JOGPARAMS = 0x0418;
constexpr std::uint16_t MGMSG_MOT_SET_GENMOVEPARAMS = 0x043A;
constexpr std::uint16_t MGMSG_MOT_REQ_GENMOVEPARAMS = 0x043B;
constexpr std::uint16_t MGMSG_MOT_GET_GENMOVEPARAMS = 0x043C;
constexpr std::uint16_t MGMSG_MOT_SET_MOVERELPARAMS = 0x0445;
constexpr std::uint16_t MGMSG_MOT_REQ_MOVERELPARAMS = 0x0446;
constexpr std::uint16_t MGMSG_MOT_GET_MOVERELPARAMS = 0x0447;
constexpr std::uint16_t MGMSG_MOT_SET_MOVEABSPARAMS = 0x0450;
constexpr std::uint16_t MGMSG_MOT_REQ_MOVEABSPARAMS = 0x0451;
constexpr std::uint16_t MGMSG_MOT_GET_MOVEABSPARAMS = 0x0452;
constexpr std::uint16_t MGMSG_MOT_SET_HOMEPARAMS = 0x0440;
constexpr std::uint16_t MGMSG_MOT_REQ_HOMEPARAMS = 0x0441;
constexpr std::uint16_t MGMSG_MOT_GET_HOMEPARAMS = 0x0442;
constexpr std::uint16_t MGMSG_MOT_SET_LIMSWITCHPARAMS = 0x0423;
constexpr std::uint16_t MGMSG_MOT_REQ_LIMSWITCHPARAMS = 0x0424;
constexpr std::uint16_t MGMSG_MOT_GET_LIMSWITCHPARAMS = 0x0425;
constexpr std::uint16_t MGMSG_MOT_MOVE_HOME = 0x0443;
constexpr std::uint16_t MGMSG_MOT_MOVE_HOMED = 0x0444;
constexpr std::uint16_t MGMSG_MOT_MOVE_RELATIVE = 0x0448;
constexpr std::uint16_t MGMSG_MOT_MOVE_COMPLETED = 0x0464;
constexpr std::uint16_t MGMSG_MOT_MOVE_ABSOLUTE = 0x0453;
constexpr std::uint16_t MGMSG_MOT_MOVE_JOG = 0x046A;
constexpr std::uint16_t MGMSG_MOT_MOVE_VELOCITY = 0x0457;
constexpr std::uint16_t MGMSG_MOT_MOVE_STOP = 0x0465;
constexpr std::uint16_t MGMSG_MOT_MOVE_STOPPED = 0x0466;
constexpr std::uint16_t MGMSG_MOT_SET_DCPIDPARAMS = 0x04A0;
constexpr std::uint16_t MGMSG_MOT_REQ_DCPIDPARAMS = 0x04A1;
constexpr std::uint16_t MGMSG_MOT_GET_DCPIDPARAMS = 0x04A2;
constexpr std::uint16_t MGMSG_MOT_SET_AVMODES = 0x04B3;
constexpr std::uint16_t MGMSG_MOT_REQ_AVMODES = 0x04B4;
constexpr std::uint16_t MGMSG_MOT_GET_AVMODES = 0x04B5;
constexpr std::uint16_t MGMSG_MOT_SET_POTPARAMS = 0x04B0;
constexpr std::uint16_t MGMSG_MOT_REQ_POTPARAMS = 0x04B1;
constexpr std::uint16_t MGMSG_MOT_GET_POTPARAMS = 0x04B2;
constexpr std::uint16_t MGMSG_MOT_SET_BUTTONPARAMS = 0x04B6;
constexpr std::uint16_t MGMSG_MOT_REQ_BUTTONPARAMS = 0x04B7;
constexpr std::uint16_t MGMSG_MOT_GET_BUTTONPARAMS = 0x04B8;
constexpr std::uint16_t MGMSG_MOT_SET_EEPROMPARAMS = 0x04B9;
constexpr std::uint16_t MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS = 0x04D7;
constexpr std::uint16_t MGMSG_MOT_REQ_PMDPOSITIONLOOPPARAMS = 0x04D8;
constexpr std::uint16_t MGMSG_MOT_GET_PMDPOSITIONLOOPPARAMS = 0x04D9;
constexpr std::uint16_t MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS = 0x04DA;
constexpr std::uint16_t MGMSG_MOT_REQ_PMDMOTOROUTPUTPARAMS = 0x04DB;
constexpr std::uint16_t MGMSG_MOT_GET_PMDMOTOROUTPUTPARAMS = 0x04DC;
constexpr std::uint16_t MGMSG_MOT_SET_PMDTRACKSETTLEPARAMS = 0x04E0;
constexpr std::uint16_t MGMSG_MOT_REQ_PMDTRACKSETTLEPARAMS = 0x04E1;
constexpr std::uint16_t MGMSG_MOT_GET_PMDTRACKSETTLEPARAMS = 0x04E2;
constexpr std::uint16_t MGMSG_MOT_SET_PMDPROFILEMODEPARAMS = 0x04E3;
constexpr std::uint16_t MGMSG_MOT_REQ_PMDPROFILEMODEPARAMS = 0x04E4;
constexpr std::uint16_t MGMSG_MOT_GET_PMDPROFILEMODEPARAMS = 0x04E5;
constexpr std::uint16_t MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS = 0x04D4;
constexpr std::uint16_t MGMSG_MOT_REQ_PMDCURRENTLOOPPARAMS = 0x04D5;
constexpr std::uint16_t MGMSG_MOT_GET_PMDCURRENTLOOPPARAMS = 0x04D6;
constexpr std::uint16_t MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS = 0x04E9;
constexpr std::uint16_t MGMSG_MOT_REQ_PMDSETTLEDCURRENTLOOPPARAMS = 0x04EA;
constexpr std::uint16_t MGMSG_MOT_GET_PMDSETTLEDCURRENTLOOPPARAMS = 0x04EB;
constexpr std::uint16_t MGMSG_MOT_SET_PMDSTAGEAXISPARAMS = 0x04F0;
constexpr std::uint16_t MGMSG_MOT_REQ_PMDSTAGEAXISPARAMS = 0x04F1;
constexpr std::uint16_t MGMSG_MOT_GET_PMDSTAGEAXISPARAMS = 0x04F2;
constexpr std::uint16_t MGMSG_MOT_GET_STATUSUPDATE = 0x0481;
constexpr std::uint16_t MGMSG_MOT_REQ_STATUSUPDATE = 0x0480;
constexpr std::uint16_t MGMSG_MOT_GET_DCSTATUSUPDATE = 0x0491;
constexpr std::uint16_t MGMSG_MOT_REQ_DCSTATUSUPDATE = 0x0490;
constexpr std::uint16_t MGMSG_MOT_ACK_DCSTATUSUPDATE = 0x0492;
constexpr std::uint16_t MGMSG_MOT_REQ_STATUSBITS = 0x0429;
constexpr std::uint16_t MGMSG_MOT_GET_STATUSBITS = 0x042A;
constexpr std::uint16_t MGMSG_MOT_SUSPEND_ENDOFMOVEMSGS = 0x046B;
constexpr std::uint16_t MGMSG_MOT_RESUME_ENDOFMOVEMSGS = 0x046C;
// Solenoid Control Messages (TSC001; the manual treats it as a motor controller).
constexpr std::uint16_t MGMSG_MOT_SET_SOL_OPERATINGMODE = 0x04C0;
constexpr std::uint16_t MGMSG_MOT_REQ_SOL_OPERATINGMODE = 0x04C1;
constexpr std::uint16_t MGMSG_MOT_GET_SOL_OPERATINGMODE = 0x04C2;
constexpr std::uint16_t MGMSG_MOT_SET_SOL_CYCLEPARAMS = 0x04C3;
constexpr std::uint16_t MGMSG_MOT_REQ_SOL_CYCLEPARAMS = 0x04C4;
constexpr std::uint16_t MGMSG_MOT_GET_SOL_CYCLEPARAMS = 0x04C5;
constexpr std::uint16_t MGMSG_MOT_SET_SOL_INTERLOCKMODE = 0x04C6;
constexpr std::uint16_t MGMSG_MOT_REQ_SOL_INTERLOCKMODE = 0x04C7;
constexpr std::uint16_t MGMSG_MOT_GET_SOL_INTERLOCKMODE = 0x04C8;
constexpr std::uint16_t MGMSG_MOT_SET_SOL_STATE = 0x04CB;
constexpr std::uint16_t MGMSG_MOT_REQ_SOL_STATE = 0x04CC;
constexpr std::uint16_t MGMSG_MOT_GET_SOL_STATE = 0x04CD;
// Later protocol issues (not in the 2012 manual): the stepper power, trigger and K-Cube
// parameter blocks (messages.cpp names the public source of each).
constexpr std::uint16_t MGMSG_MOT_SET_POWERPARAMS = 0x0426;
constexpr std::uint16_t MGMSG_MOT_REQ_POWERPARAMS = 0x0427;
constexpr std::uint16_t MGMSG_MOT_GET_POWERPARAMS = 0x0428;
constexpr std::uint16_t MGMSG_MOT_SET_TSTACTUATORTYPE = 0x04FE;
constexpr std::uint16_t MGMSG_MOT_SET_TRIGGER = 0x0500;
constexpr std::uint16_t MGMSG_MOT_REQ_TRIGGER = 0x0501;
constexpr std::uint16_t MGMSG_MOT_GET_TRIGGER = 0x0502;
constexpr std::uint16_t MGMSG_MOT_SET_KCUBEMMIPARAMS = 0x0520;
constexpr std::uint16_t MGMSG_MOT_REQ_KCUBEMMIPARAMS = 0x0521;
constexpr std::uint16_t MGMSG_MOT_GET_KCUBEMMIPARAMS = 0x0522;
constexpr std::uint16_t MGMSG_MOT_SET_KCUBETRIGIOCONFIG = 0x0523;
constexpr std::uint16_t MGMSG_MOT_REQ_KCUBETRIGIOCONFIG = 0x0524;
constexpr std::uint16_t MGMSG_MOT_GET_KCUBETRIGIOCONFIG = 0x0525;
constexpr std::uint16_t MGMSG_MOT_SET_KCUBEPOSTRIGPARAMS = 0x0526;
constexpr std::uint16_t MGMSG_MOT_REQ_KCUBEPOSTRIGPARAMS = 0x0527;
constexpr std::uint16_t MGMSG_MOT_GET_KCUBEPOSTRIGPARAMS = 0x0528;
constexpr std::uint16_t MGMSG_MOT_SET_KCUBEKSTLOOPPARAMS = 0x0529;
constexpr std::uint16_t MGMSG_MOT_REQ_KCUBEKSTLOOPPARAMS = 0x052A;
constexpr std::uint16_t MGMSG_MOT_GET_KCUBEKSTLOOPPARAMS = 0x052B;
// A MOT_ message printed in the piezo chapter (TX structure, page 125).
constexpr std::uint16_t MGMSG_MOT_SET_PZSTAGEPARAMDEFAULTS = 0x0686;

// ---- Piezo Control Messages ----
constexpr std::uint16_t MGMSG_PZ_SET_POSCONTROLMODE = 0x0640;
constexpr std::uint16_t MGMSG_PZ_REQ_POSCONTROLMODE = 0x0641;
constexpr std::uint16_t MGMSG_PZ_GET_POSCONTROLMODE = 0x0642;
constexpr std::uint16_t MGMSG_PZ_SET_OUTPUTVOLTS = 0x0643;
constexpr std::uint16_t MGMSG_PZ_REQ_OUTPUTVOLTS = 0x0644;
constexpr std::uint16_t MGMSG_PZ_GET_OUTPUTVOLTS = 0x0645;
constexpr std::uint16_t MGMSG_PZ_SET_OUTPUTPOS = 0x0646;
constexpr std::uint16_t MGMSG_PZ_REQ_OUTPUTPOS = 0x0647;
constexpr std::uint16_t MGMSG_PZ_GET_OUTPUTPOS = 0x0648;
constexpr std::uint16_t MGMSG_PZ_SET_INPUTVOLTSSRC = 0x0652;
constexpr std::uint16_t MGMSG_PZ_REQ_INPUTVOLTSSRC = 0x0653;
constexpr std::uint16_t MGMSG_PZ_GET_INPUTVOLTSSRC = 0x0654;
constexpr std::uint16_t MGMSG_PZ_SET_PICONSTS = 0x0655;
constexpr std::uint16_t MGMSG_PZ_REQ_PICONSTS = 0x0656;
constexpr std::uint16_t MGMSG_PZ_GET_PICONSTS = 0x0657;
constexpr std::uint16_t MGMSG_PZ_REQ_PZSTATUSBITS = 0x065B;
constexpr std::uint16_t MGMSG_PZ_GET_PZSTATUSBITS = 0x065C;
constexpr std::uint16_t MGMSG_PZ_GET_PZSTATUSUPDATE = 0x0661;
constexpr std::uint16_t MGMSG_PZ_ACK_PZSTATUSUPDATE = 0x0662;
constexpr std::uint16_t MGMSG_PZ_SET_OUTPUTLUT = 0x0700;
constexpr std::uint16_t MGMSG_PZ_REQ_OUTPUTLUT = 0x0701;
constexpr std::uint16_t MGMSG_PZ_GET_OUTPUTLUT = 0x0702;
constexpr std::uint16_t MGMSG_PZ_SET_OUTPUTLUTPARAMS = 0x0703;
constexpr std::uint16_t MGMSG_PZ_REQ_OUTPUTLUTPARAMS = 0x0704;
constexpr std::uint16_t MGMSG_PZ_GET_OUTPUTLUTPARAMS = 0x0705;
constexpr std::uint16_t MGMSG_PZ_START_LUTOUTPUT = 0x0706;
constexpr std::uint16_t MGMSG_PZ_STOP_LUTOUTPUT = 0x0707;
constexpr std::uint16_t MGMSG_PZ_SET_EEPROMPARAMS = 0x07D0;
constexpr std::uint16_t MGMSG_PZ_SET_TPZ_DISPSETTINGS = 0x07D1;
constexpr std::uint16_t MGMSG_PZ_REQ_TPZ_DISPSETTINGS = 0x07D2;
constexpr std::uint16_t MGMSG_PZ_GET_TPZ_DISPSETTINGS = 0x07D3;
constexpr std::uint16_t MGMSG_PZ_SET_TPZ_IOSETTINGS = 0x07D4;
constexpr std::uint16_t MGMSG_PZ_REQ_TPZ_IOSETTINGS = 0x07D5;
constexpr std::uint16_t MGMSG_PZ_GET_TPZ_IOSETTINGS = 0x07D6;
constexpr std::uint16_t MGMSG_PZ_SET_ZERO = 0x0658;
constexpr std::uint16_t MGMSG_PZ_REQ_MAXTRAVEL = 0x0650;
constexpr std::uint16_t MGMSG_PZ_GET_MAXTRAVEL = 0x0651;
constexpr std::uint16_t MGMSG_PZ_SET_IOSETTINGS = 0x0670;
constexpr std::uint16_t MGMSG_PZ_REQ_IOSETTINGS = 0x0671;
constexpr std::uint16_t MGMSG_PZ_GET_IOSETTINGS = 0x0672;
constexpr std::uint16_t MGMSG_PZ_SET_OUTPUTMAXVOLTS = 0x0680;
constexpr std::uint16_t MGMSG_PZ_REQ_OUTPUTMAXVOLTS = 0x0681;
constexpr std::uint16_t MGMSG_PZ_GET_OUTPUTMAXVOLTS = 0x0682;
constexpr std::uint16_t MGMSG_PZ_SET_TPZ_SLEWRATES = 0x0683;
constexpr std::uint16_t MGMSG_PZ_REQ_TPZ_SLEWRATES = 0x0684;
constexpr std::uint16_t MGMSG_PZ_GET_TPZ_SLEWRATES = 0x0685;
constexpr std::uint16_t MGMSG_PZ_SET_LUTVALUETYPE = 0x0708;
// The TSG001 strain gauge reader (filed under the piezo controllers, p. 93).
constexpr std::uint16_t MGMSG_PZ_SET_TSG_IOSETTINGS = 0x07DA;
constexpr std::uint16_t MGMSG_PZ_REQ_TSG_IOSETTINGS = 0x07DB;
constexpr std::uint16_t MGMSG_PZ_GET_TSG_IOSETTINGS = 0x07DC;
constexpr std::uint16_t MGMSG_PZ_REQ_TSG_READING = 0x07DD;
constexpr std::uint16_t MGMSG_PZ_GET_TSG_READING = 0x07DE;
// Later protocol issues (not in the 2012 manual): the K-Cube piezo driver's and strain gauge
// reader's own blocks, and the piezo status-update request (messages.cpp: sources).
constexpr std::uint16_t MGMSG_PZ_REQ_PZSTATUSUPDATE = 0x0660;
constexpr std::uint16_t MGMSG_KPZ_SET_KCUBEMMIPARAMS = 0x07F0;
constexpr std::uint16_t MGMSG_KPZ_REQ_KCUBEMMIPARAMS = 0x07F1;
constexpr std::uint16_t MGMSG_KPZ_GET_KCUBEMMIPARAMS = 0x07F2;
constexpr std::uint16_t MGMSG_KPZ_SET_KCUBETRIGIOCONFIG = 0x07F3;
constexpr std::uint16_t MGMSG_KPZ_REQ_KCUBETRIGIOCONFIG = 0x07F4;
constexpr std::uint16_t MGMSG_KPZ_GET_KCUBETRIGIOCONFIG = 0x07F5;
constexpr std::uint16_t MGMSG_KSG_SET_KCUBEMMIPARAMS = 0x07F6;
constexpr std::uint16_t MGMSG_KSG_REQ_KCUBEMMIPARAMS = 0x07F7;
constexpr std::uint16_t MGMSG_KSG_GET_KCUBEMMIPARAMS = 0x07F8;
constexpr std::uint16_t MGMSG_KSG_SET_KCUBETRIGIOCONFIG = 0x07F9;
constexpr std::uint16_t MGMSG_KSG_REQ_KCUBETRIGIOCONFIG = 0x07FA;
constexpr std::uint16_t MGMSG_KSG_GET_KCUBETRIGIOCONFIG = 0x07FB;

} // namespace rigsim::apt
