// APT codec: every typed message encodes to the bytes of the manual's layout (written out by
// hand below, little-endian as the ERRATA says), and those bytes, through the framer, decode
// back to the same struct.
#include "emulator/apt/codec.hpp"
#include "tests/support/apt_round_trip.hpp"
#include "tests/support/hex.hpp"

#include <catch2/catch.hpp>

#include <string>

namespace test_apt_codec {

using namespace rigsim::apt;
using namespace rigsim::apt::msg;
using rigsim::test::hex;
using rigsim::test::round_trip;
const auto unhex = rigsim::test::bytes;

namespace {

template <std::size_t N> std::array<char, N> chars(const std::string& s)
{
    std::array<char, N> a{};
    s.copy(a.data(), N);
    return a;
}

} // namespace

// ---- Generic System Control Messages ----

TEST_CASE("MGMSG_MOD_IDENTIFY round-trips through the codec", "[apt][codec]")
{
    round_trip(ModIdentify{0}, "23 02 00 00 50 01");
}

TEST_CASE("MGMSG_MOD_SET_CHANENABLESTATE, MGMSG_MOD_REQ_CHANENABLESTATE and MGMSG_MOD_GET_CHANENABLESTATE round-trip",
          "[apt][codec]")
{
    round_trip(ModSetChanEnableState{1, 2}, "10 02 01 02 50 01");
    round_trip(ModReqChanEnableState{1}, "11 02 01 00 50 01");
    round_trip(ModGetChanEnableState{1, 1}, "12 02 01 01 01 50", 0x01, 0x50);
}

TEST_CASE("MGMSG_HW_DISCONNECT and MGMSG_HW_RESPONSE round-trip", "[apt][codec]")
{
    round_trip(HwDisconnect{}, "02 00 00 00 50 01");
    round_trip(HwResponse{}, "80 00 00 00 01 11", 0x01, 0x11);   // p. 19 example
}

TEST_CASE("MGMSG_HW_RICHRESPONSE round-trips", "[apt][codec]")
{
    HwRichResponse m{MGMSG_MOT_MOVE_ABSOLUTE, 1, chars<64>("Stall")};
    std::string notes = "53 74 61 6C 6C";
    for (int i = 5; i < 64; ++i)
        notes += " 00";
    round_trip(m, "81 00 44 00 81 50 53 04 01 00 " + notes, 0x01, 0x50);
}

TEST_CASE("MGMSG_HW_START_UPDATEMSGS and MGMSG_HW_STOP_UPDATEMSGS round-trip", "[apt][codec]")
{
    round_trip(HwStartUpdateMsgs{10}, "11 00 0A 00 50 01");
    round_trip(HwStopUpdateMsgs{}, "12 00 00 00 50 01");
}

TEST_CASE("MGMSG_HW_REQ_INFO and MGMSG_HW_GET_INFO round-trip", "[apt][codec]")
{
    round_trip(HwReqInfo{}, "05 00 00 00 50 01");
    HwGetInfo info{83000001, chars<8>("TDC001"), 31, chars<4>(std::string("\x03\x00\x01\x00", 4)),
                   chars<64>("APT DC Motor Controller"), 1};
    std::string notes = "41 50 54 20 44 43 20 4D 6F 74 6F 72 20 43 6F 6E 74 72 6F 6C 6C 65 72";   // 23 chars
    for (int i = 23; i < 64; ++i)
        notes += " 00";
    round_trip(info,
               "06 00 54 00 81 50 C1 7A F2 04 54 44 43 30 30 31 00 00 1F 00 03 00 01 00 " + notes + " 01 00",
               0x01, 0x50);
}

TEST_CASE("MGMSG_RACK_REQ_BAYUSED and MGMSG_RACK_GET_BAYUSED round-trip", "[apt][codec]")
{
    round_trip(RackReqBayUsed{0}, "60 00 00 00 11 01", 0x11);
    round_trip(RackGetBayUsed{2, 1}, "61 00 02 01 01 11", 0x01, 0x11);
}

TEST_CASE("MGMSG_HUB_REQ_BAYUSED and MGMSG_HUB_GET_BAYUSED round-trip", "[apt][codec]")
{
    round_trip(HubReqBayUsed{}, "65 00 00 00 50 01");
    round_trip(HubGetBayUsed{0xFF}, "66 00 FF 00 01 50", 0x01, 0x50);
}

TEST_CASE("MGMSG_RACK_REQ_STATUSBITS and MGMSG_RACK_GET_STATUSBITS round-trip", "[apt][codec]")
{
    round_trip(RackReqStatusBits{}, "26 02 00 00 11 01", 0x11);
    round_trip(RackGetStatusBits{0x0000000A}, "27 02 04 00 81 11 0A 00 00 00", 0x01, 0x11);
}

TEST_CASE("MGMSG_RACK_SET_DIGOUTPUTS, MGMSG_RACK_REQ_DIGOUTPUTS and MGMSG_RACK_GET_DIGOUTPUTS round-trip",
          "[apt][codec]")
{
    round_trip(RackSetDigOutputs{0x01, 0x22}, "28 02 01 22 11 01", 0x11);   // p. 26 example
    round_trip(RackReqDigOutputs{0, 0x22}, "29 02 00 22 11 01", 0x11);
    round_trip(RackGetDigOutputs{0x05, 0x22}, "30 02 05 22 01 11", 0x01, 0x11);
}

TEST_CASE("MGMSG_HW_YES_FLASH_PROGRAMMING and MGMSG_HW_NO_FLASH_PROGRAMMING round-trip", "[apt][codec]")
{
    round_trip(HwYesFlashProgramming{}, "17 00 00 00 50 01");
    round_trip(HwNoFlashProgramming{}, "18 00 00 00 50 01");
}

// ---- Motor parameter trios ----

TEST_CASE("MGMSG_MOT_SET_POSCOUNTER, MGMSG_MOT_REQ_POSCOUNTER and MGMSG_MOT_GET_POSCOUNTER round-trip",
          "[apt][codec]")
{
    round_trip(SetPosCounter{{1, 200000}}, "10 04 06 00 A2 01 01 00 40 0D 03 00", 0x22);   // p. 28 (10 mm)
    round_trip(ReqPosCounter{1}, "11 04 01 00 50 01");
    round_trip(GetPosCounter{{1, -2}}, "12 04 06 00 81 50 01 00 FE FF FF FF", 0x01, 0x50);
}

TEST_CASE("MGMSG_MOT_SET_ENCCOUNTER, MGMSG_MOT_REQ_ENCCOUNTER and MGMSG_MOT_GET_ENCCOUNTER round-trip",
          "[apt][codec]")
{
    round_trip(SetEncCounter{{1, 200000}}, "09 04 06 00 A2 01 01 00 40 0D 03 00", 0x22);
    round_trip(ReqEncCounter{1}, "0A 04 01 00 50 01");
    round_trip(GetEncCounter{{1, 0x01020304}}, "0B 04 06 00 81 50 01 00 04 03 02 01", 0x01, 0x50);
}

TEST_CASE("MGMSG_MOT_SET_VELPARAMS, MGMSG_MOT_REQ_VELPARAMS and MGMSG_MOT_GET_VELPARAMS round-trip",
          "[apt][codec]")
{
    // p. 30 example bytes: min 0, acceleration 0x35B0, maximum 0xCCCCCD.
    round_trip(SetVelParams{{1, 0, 0x35B0, 0xCCCCCD}}, "13 04 0E 00 A2 01 01 00 00 00 00 00 B0 35 00 00 CD CC CC 00",
               0x22);
    round_trip(ReqVelParams{1}, "14 04 01 00 50 01");
    round_trip(GetVelParams{{1, 5, 393, 1841682}}, "15 04 0E 00 81 50 01 00 05 00 00 00 89 01 00 00 12 1A 1C 00",
               0x01, 0x50);
}

TEST_CASE("MGMSG_MOT_SET_JOGPARAMS, MGMSG_MOT_REQ_JOGPARAMS and MGMSG_MOT_GET_JOGPARAMS round-trip",
          "[apt][codec]")
{
    // p. 32 example: continuous, step 1000, min 0, acceleration 0x35B0, max 0xCCCCCD, profiled stop.
    const JogParams p{1, 1, 1000, 0, 0x35B0, 0xCCCCCD, 2};
    round_trip(SetJogParams{p}, "16 04 16 00 A2 01 01 00 01 00 E8 03 00 00 00 00 00 00 B0 35 00 00 CD CC CC 00 02 00",
               0x22);
    round_trip(ReqJogParams{1}, "17 04 01 00 50 01");
    round_trip(GetJogParams{p}, "18 04 16 00 81 50 01 00 01 00 E8 03 00 00 00 00 00 00 B0 35 00 00 CD CC CC 00 02 00",
               0x01, 0x50);
}

TEST_CASE("MGMSG_MOT_SET_GENMOVEPARAMS, MGMSG_MOT_REQ_GENMOVEPARAMS and MGMSG_MOT_GET_GENMOVEPARAMS round-trip",
          "[apt][codec]")
{
    round_trip(SetGenMoveParams{{1, 20000}}, "3A 04 06 00 A2 01 01 00 20 4E 00 00", 0x22);   // p. 34 example
    round_trip(ReqGenMoveParams{1}, "3B 04 01 00 50 01");
    round_trip(GetGenMoveParams{{1, 20000}}, "3C 04 06 00 81 50 01 00 20 4E 00 00", 0x01, 0x50);
}

TEST_CASE("MGMSG_MOT_SET_MOVERELPARAMS, MGMSG_MOT_REQ_MOVERELPARAMS and MGMSG_MOT_GET_MOVERELPARAMS round-trip",
          "[apt][codec]")
{
    round_trip(SetMoveRelParams{{1, 200000}}, "45 04 06 00 D0 01 01 00 40 0D 03 00");
    round_trip(ReqMoveRelParams{1}, "46 04 01 00 50 01");
    round_trip(GetMoveRelParams{{1, -200000}}, "47 04 06 00 81 50 01 00 C0 F2 FC FF", 0x01, 0x50);
}

TEST_CASE("MGMSG_MOT_SET_MOVEABSPARAMS, MGMSG_MOT_REQ_MOVEABSPARAMS and MGMSG_MOT_GET_MOVEABSPARAMS round-trip",
          "[apt][codec]")
{
    round_trip(SetMoveAbsParams{{1, 200000}}, "50 04 06 00 D0 01 01 00 40 0D 03 00");
    round_trip(ReqMoveAbsParams{1}, "51 04 01 00 50 01");
    round_trip(GetMoveAbsParams{{1, 7}}, "52 04 06 00 81 50 01 00 07 00 00 00", 0x01, 0x50);
}

TEST_CASE("MGMSG_MOT_SET_HOMEPARAMS, MGMSG_MOT_REQ_HOMEPARAMS and MGMSG_MOT_GET_HOMEPARAMS round-trip",
          "[apt][codec]")
{
    const HomeParams p{1, 2, 1, 767367, 10291};
    round_trip(SetHomeParams{p}, "40 04 0E 00 D0 01 01 00 02 00 01 00 87 B5 0B 00 33 28 00 00");
    round_trip(ReqHomeParams{1}, "41 04 01 00 50 01");
    round_trip(GetHomeParams{p}, "42 04 0E 00 81 50 01 00 02 00 01 00 87 B5 0B 00 33 28 00 00", 0x01, 0x50);
}

TEST_CASE("MGMSG_MOT_SET_LIMSWITCHPARAMS, MGMSG_MOT_REQ_LIMSWITCHPARAMS and MGMSG_MOT_GET_LIMSWITCHPARAMS round-trip",
          "[apt][codec]")
{
    const LimSwitchParams p{1, 0x82, 3, 100000, -5, 3};
    round_trip(SetLimSwitchParams{p}, "23 04 10 00 D0 01 01 00 82 00 03 00 A0 86 01 00 FB FF FF FF 03 00");
    round_trip(ReqLimSwitchParams{1}, "24 04 01 00 50 01");
    round_trip(GetLimSwitchParams{p}, "25 04 10 00 81 50 01 00 82 00 03 00 A0 86 01 00 FB FF FF FF 03 00", 0x01,
               0x50);
}

TEST_CASE("MGMSG_MOT_SET_DCPIDPARAMS, MGMSG_MOT_REQ_DCPIDPARAMS and MGMSG_MOT_GET_DCPIDPARAMS round-trip",
          "[apt][codec]")
{
    const DcPidParams p{1, 396, 270, 4000, 4860, 15};
    round_trip(SetDcPidParams{p}, "A0 04 14 00 D0 01 01 00 8C 01 00 00 0E 01 00 00 A0 0F 00 00 FC 12 00 00 0F 00");
    round_trip(ReqDcPidParams{1}, "A1 04 01 00 50 01");
    round_trip(GetDcPidParams{p}, "A2 04 14 00 81 50 01 00 8C 01 00 00 0E 01 00 00 A0 0F 00 00 FC 12 00 00 0F 00",
               0x01, 0x50);
}

TEST_CASE("MGMSG_MOT_SET_AVMODES, MGMSG_MOT_REQ_AVMODES and MGMSG_MOT_GET_AVMODES round-trip", "[apt][codec]")
{
    round_trip(SetAvModes{{1, 0x000B}}, "B3 04 04 00 D0 01 01 00 0B 00");
    round_trip(ReqAvModes{1}, "B4 04 01 00 50 01");
    round_trip(GetAvModes{{1, 0x0008}}, "B5 04 04 00 81 50 01 00 08 00", 0x01, 0x50);
}

TEST_CASE("MGMSG_MOT_SET_POTPARAMS, MGMSG_MOT_REQ_POTPARAMS and MGMSG_MOT_GET_POTPARAMS round-trip", "[apt][codec]")
{
    const PotParams p{1, 20, 1000, 50, 2000, 80, 3000, 100, 4000};
    const std::string data = "01 00 14 00 E8 03 00 00 32 00 D0 07 00 00 50 00 B8 0B 00 00 64 00 A0 0F 00 00";
    round_trip(SetPotParams{p}, "B0 04 1A 00 D0 01 " + data);
    round_trip(ReqPotParams{1}, "B1 04 01 00 50 01");
    round_trip(GetPotParams{p}, "B2 04 1A 00 81 50 " + data, 0x01, 0x50);
}

TEST_CASE("MGMSG_MOT_SET_BUTTONPARAMS, MGMSG_MOT_REQ_BUTTONPARAMS and MGMSG_MOT_GET_BUTTONPARAMS round-trip",
          "[apt][codec]")
{
    const ButtonParams p{1, 2, 1000, 2000, 500, 0};
    const std::string data = "01 00 02 00 E8 03 00 00 D0 07 00 00 F4 01 00 00";
    round_trip(SetButtonParams{p}, "B6 04 10 00 D0 01 " + data);
    round_trip(ReqButtonParams{1}, "B7 04 01 00 50 01");
    round_trip(GetButtonParams{p}, "B8 04 10 00 81 50 " + data, 0x01, 0x50);
}

// ---- Brushless (PMD) parameter trios ----

TEST_CASE("MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, MGMSG_MOT_REQ_PMDPOSITIONLOOPPARAMS and "
          "MGMSG_MOT_GET_PMDPOSITIONLOOPPARAMS round-trip",
          "[apt][codec]")
{
    const PmdPositionLoopParams p{1, 0x0203, 0x0405, 0x06070809, 0x0A0B, 0x0C0D, 0x0E0F, 0x1011, 0x1213, 0x14151617, 0, 0};
    const std::string data = "01 00 03 02 05 04 09 08 07 06 0B 0A 0D 0C 0F 0E 11 10 13 12 17 16 15 14 00 00 00 00";
    round_trip(SetPmdPositionLoopParams{p}, "D7 04 1C 00 A1 01 " + data, 0x21);
    round_trip(ReqPmdPositionLoopParams{1}, "D8 04 01 00 21 01", 0x21);
    round_trip(GetPmdPositionLoopParams{p}, "D9 04 1C 00 81 21 " + data, 0x01, 0x21);
}

TEST_CASE("MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS, MGMSG_MOT_REQ_PMDMOTOROUTPUTPARAMS and "
          "MGMSG_MOT_GET_PMDMOTOROUTPUTPARAMS round-trip",
          "[apt][codec]")
{
    const PmdMotorOutputParams p{1, 1000, 2000, 3000, -2, 0, 0};
    const std::string data = "01 00 E8 03 D0 07 B8 0B FE FF 00 00 00 00";
    round_trip(SetPmdMotorOutputParams{p}, "DA 04 0E 00 A1 01 " + data, 0x21);
    round_trip(ReqPmdMotorOutputParams{1}, "DB 04 01 00 21 01", 0x21);
    round_trip(GetPmdMotorOutputParams{p}, "DC 04 0E 00 81 21 " + data, 0x01, 0x21);
}

TEST_CASE("MGMSG_MOT_SET_PMDTRACKSETTLEPARAMS, MGMSG_MOT_REQ_PMDTRACKSETTLEPARAMS and "
          "MGMSG_MOT_GET_PMDTRACKSETTLEPARAMS round-trip",
          "[apt][codec]")
{
    const PmdTrackSettleParams p{1, 100, 20, 40, 0, 0};
    const std::string data = "01 00 64 00 14 00 28 00 00 00 00 00";
    round_trip(SetPmdTrackSettleParams{p}, "E0 04 0C 00 A1 01 " + data, 0x21);
    round_trip(ReqPmdTrackSettleParams{1}, "E1 04 01 00 21 01", 0x21);
    round_trip(GetPmdTrackSettleParams{p}, "E2 04 0C 00 81 21 " + data, 0x01, 0x21);
}

TEST_CASE("MGMSG_MOT_SET_PMDPROFILEMODEPARAMS, MGMSG_MOT_REQ_PMDPROFILEMODEPARAMS and "
          "MGMSG_MOT_GET_PMDPROFILEMODEPARAMS round-trip",
          "[apt][codec]")
{
    const PmdProfileModeParams p{1, 2, 10000, 0, 0};
    const std::string data = "01 00 02 00 10 27 00 00 00 00 00 00";
    round_trip(SetPmdProfileModeParams{p}, "E3 04 0C 00 A1 01 " + data, 0x21);
    round_trip(ReqPmdProfileModeParams{1}, "E4 04 01 00 21 01", 0x21);
    round_trip(GetPmdProfileModeParams{p}, "E5 04 0C 00 81 21 " + data, 0x01, 0x21);
}

TEST_CASE("MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS, MGMSG_MOT_REQ_PMDCURRENTLOOPPARAMS and "
          "MGMSG_MOT_GET_PMDCURRENTLOOPPARAMS round-trip",
          "[apt][codec]")
{
    const PmdCurrentLoopParams p{1, 2, 35, 80, 32767, 50, 1500, 0, 0};
    const std::string data = "01 00 02 00 23 00 50 00 FF 7F 32 00 DC 05 00 00 00 00";
    round_trip(SetPmdCurrentLoopParams{p}, "D4 04 12 00 A1 01 " + data, 0x21);
    round_trip(ReqPmdCurrentLoopParams{1}, "D5 04 01 00 21 01", 0x21);
    round_trip(GetPmdCurrentLoopParams{p}, "D6 04 12 00 81 21 " + data, 0x01, 0x21);
}

TEST_CASE("MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS, MGMSG_MOT_REQ_PMDSETTLEDCURRENTLOOPPARAMS and "
          "MGMSG_MOT_GET_PMDSETTLEDCURRENTLOOPPARAMS round-trip",
          "[apt][codec]")
{
    const PmdSettledCurrentLoopParams p{1, 2, 35, 80, 32767, 50, 1500, 0, 0};
    const std::string data = "01 00 02 00 23 00 50 00 FF 7F 32 00 DC 05 00 00 00 00";
    round_trip(SetPmdSettledCurrentLoopParams{p}, "E9 04 12 00 A1 01 " + data, 0x21);
    round_trip(ReqPmdSettledCurrentLoopParams{1}, "EA 04 01 00 21 01", 0x21);
    round_trip(GetPmdSettledCurrentLoopParams{p}, "EB 04 12 00 81 21 " + data, 0x01, 0x21);
}

TEST_CASE("MGMSG_MOT_SET_PMDSTAGEAXISPARAMS, MGMSG_MOT_REQ_PMDSTAGEAXISPARAMS and "
          "MGMSG_MOT_GET_PMDSTAGEAXISPARAMS round-trip",
          "[apt][codec]")
{
    PmdStageAxisParams p{1, 0x10, 0, chars<16>("MLS203 X"), 0x01020304, 20000, 0, 2200000, 5, 5, 134218, {}};
    p.reserved[23] = 0x7F;
    const std::string data = "01 00 10 00 00 00 4D 4C 53 32 30 33 20 58 00 00 00 00 00 00 00 00 04 03 02 01 20 4E 00 00 "
                             "00 00 00 00 C0 91 21 00 05 00 00 00 05 00 00 00 4A 0C 02 00 "
                             "00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 7F";
    round_trip(SetPmdStageAxisParams{p}, "F0 04 4A 00 A1 01 " + data, 0x21);
    round_trip(ReqPmdStageAxisParams{1}, "F1 04 01 00 21 01", 0x21);
    round_trip(GetPmdStageAxisParams{p}, "F2 04 4A 00 81 21 " + data, 0x01, 0x21);
}

// ---- Moves ----

TEST_CASE("MGMSG_MOT_MOVE_HOME and MGMSG_MOT_MOVE_HOMED round-trip", "[apt][codec]")
{
    round_trip(MoveHome{1}, "43 04 01 00 50 01");
    round_trip(MoveHomed{1}, "44 04 01 00 01 50", 0x01, 0x50);
}

TEST_CASE("MGMSG_MOT_MOVE_RELATIVE round-trips in its short and long forms", "[apt][codec]")
{
    round_trip(MoveRelative{1, std::nullopt}, "48 04 01 00 50 01");
    round_trip(MoveRelative{1, 100000}, "48 04 06 00 A2 01 01 00 A0 86 01 00", 0x22);   // p. 42 (5 mm)
}

TEST_CASE("MGMSG_MOT_MOVE_ABSOLUTE round-trips in its short and long forms", "[apt][codec]")
{
    round_trip(MoveAbsolute{1, std::nullopt}, "53 04 01 00 50 01");
    round_trip(MoveAbsolute{1, 200000}, "53 04 06 00 A2 01 01 00 40 0D 03 00", 0x22);   // p. 45 (10 mm)
}

TEST_CASE("MGMSG_MOT_MOVE_JOG, MGMSG_MOT_MOVE_VELOCITY and MGMSG_MOT_MOVE_STOP round-trip", "[apt][codec]")
{
    round_trip(MoveJog{1, 2}, "6A 04 01 02 50 01");
    round_trip(MoveVelocity{1, 1}, "57 04 01 01 50 01");
    round_trip(MoveStop{1, 2}, "65 04 01 02 50 01");
}

TEST_CASE("MGMSG_MOT_MOVE_COMPLETED and MGMSG_MOT_MOVE_STOPPED round-trip with the DC status", "[apt][codec]")
{
    const DcStatus s{1, 0x01020304, -1, 0, 0x80002400};
    const std::string data = "01 00 04 03 02 01 FF FF 00 00 00 24 00 80";
    round_trip(MoveCompleted{s}, "64 04 0E 00 81 50 " + data, 0x01, 0x50);
    round_trip(MoveStopped{s}, "66 04 0E 00 81 50 " + data, 0x01, 0x50);
}

TEST_CASE("MGMSG_MOT_MOVE_COMPLETED of a stepper carries the stepper status", "[apt][codec]")
{
    const MoveCompleted m{MotStatus{1, 100, 200, 0x80000400}};
    CHECK(hex(encode(m, 0x01, 0x50)) == "64 04 0E 00 81 50 01 00 64 00 00 00 C8 00 00 00 00 04 00 80");
}

TEST_CASE("MGMSG_MOT_SET_EEPROMPARAMS round-trips", "[apt][codec]")
{
    round_trip(SetEepromParams{1, MGMSG_MOT_SET_VELPARAMS}, "B9 04 04 00 D0 01 01 00 13 04");
}

// ---- Status ----

TEST_CASE("MGMSG_MOT_REQ_STATUSUPDATE and MGMSG_MOT_GET_STATUSUPDATE round-trip", "[apt][codec]")
{
    round_trip(ReqStatusUpdate{1}, "80 04 01 00 50 01");
    round_trip(GetStatusUpdate{{1, -1, 2, 0x80000100}}, "81 04 0E 00 81 50 01 00 FF FF FF FF 02 00 00 00 00 01 00 80",
               0x01, 0x50);
}

TEST_CASE("MGMSG_MOT_REQ_DCSTATUSUPDATE, MGMSG_MOT_GET_DCSTATUSUPDATE and MGMSG_MOT_ACK_DCSTATUSUPDATE round-trip",
          "[apt][codec]")
{
    round_trip(ReqDcStatusUpdate{1}, "90 04 01 00 50 01");
    round_trip(GetDcStatusUpdate{{1, 1000, 300, 0, 0x80000110}},
               "91 04 0E 00 81 50 01 00 E8 03 00 00 2C 01 00 00 10 01 00 80", 0x01, 0x50);
    round_trip(AckDcStatusUpdate{}, "92 04 00 00 50 01");
}

TEST_CASE("MGMSG_MOT_REQ_STATUSBITS and MGMSG_MOT_GET_STATUSBITS round-trip", "[apt][codec]")
{
    round_trip(ReqStatusBits{1}, "29 04 01 00 50 01");
    round_trip(GetStatusBits{1, 0x80000400}, "2A 04 06 00 81 50 01 00 00 04 00 80", 0x01, 0x50);
}

TEST_CASE("MGMSG_MOT_SUSPEND_ENDOFMOVEMSGS and MGMSG_MOT_RESUME_ENDOFMOVEMSGS round-trip", "[apt][codec]")
{
    round_trip(SuspendEndOfMoveMsgs{}, "6B 04 00 00 50 01");
    round_trip(ResumeEndOfMoveMsgs{}, "6C 04 00 00 50 01");
}

// ---- Solenoid Control Messages (p. 84-92) ----

TEST_CASE("MGMSG_MOT_SET_SOL_OPERATINGMODE, MGMSG_MOT_REQ_SOL_OPERATINGMODE and MGMSG_MOT_GET_SOL_OPERATINGMODE "
          "round-trip",
          "[apt][codec]")
{
    round_trip(SolSetOperatingMode{1, 2}, "C0 04 01 02 50 01");            // p. 85 example: 'Single'
    round_trip(SolReqOperatingMode{1}, "C1 04 01 00 50 01");               // p. 85 example
    round_trip(SolGetOperatingMode{1, 1}, "C2 04 01 01 01 50", 0x01, 0x50);   // p. 85 example
    STATIC_REQUIRE(SolSetOperatingMode::family == Family::Solenoid);
    STATIC_REQUIRE(SolGetOperatingMode::family == Family::UnitToHost);
}

TEST_CASE("MGMSG_MOT_SET_SOL_CYCLEPARAMS, MGMSG_MOT_REQ_SOL_CYCLEPARAMS and MGMSG_MOT_GET_SOL_CYCLEPARAMS round-trip",
          "[apt][codec]")
{
    // p. 87 example: OnTime and OffTime 1000 ms (4000 x 250 us), 20 cycles.
    const std::string data = "01 00 A0 0F 00 00 A0 0F 00 00 14 00 00 00";
    round_trip(SetSolCycleParams{{1, 4000, 4000, 20}}, "C3 04 0E 00 D0 01 " + data);
    round_trip(ReqSolCycleParams{1}, "C4 04 01 00 50 01");
    round_trip(GetSolCycleParams{{1, 4000, 4000, 20}}, "C5 04 0E 00 81 50 " + data, 0x01, 0x50);
    STATIC_REQUIRE(SetSolCycleParams::family == Family::Solenoid);
    STATIC_REQUIRE(ReqSolCycleParams::family == Family::Solenoid);
}

TEST_CASE("MGMSG_MOT_SET_SOL_INTERLOCKMODE, MGMSG_MOT_REQ_SOL_INTERLOCKMODE and MGMSG_MOT_GET_SOL_INTERLOCKMODE "
          "round-trip",
          "[apt][codec]")
{
    round_trip(SolSetInterlockMode{1, 1}, "C6 04 01 01 50 01");            // p. 89 example: 'Enabled'
    round_trip(SolReqInterlockMode{1}, "C7 04 01 00 50 01");               // p. 90 example
    round_trip(SolGetInterlockMode{1, 1}, "C8 04 01 01 01 50", 0x01, 0x50);   // p. 90 example
    round_trip(SolSetInterlockMode{1, 2}, "C6 04 01 02 50 01");
}

TEST_CASE("MGMSG_MOT_SET_SOL_STATE, MGMSG_MOT_REQ_SOL_STATE and MGMSG_MOT_GET_SOL_STATE round-trip", "[apt][codec]")
{
    round_trip(SolSetState{1, 1}, "CB 04 01 01 50 01");            // p. 91 example: 'ON'
    round_trip(SolReqState{1}, "CC 04 01 00 50 01");               // p. 92 example
    round_trip(SolGetState{1, 1}, "CD 04 01 01 01 50", 0x01, 0x50);   // p. 92 example
    round_trip(SolSetState{1, 2}, "CB 04 01 02 50 01");
}

// ---- What the codec does not type ----

TEST_CASE("apt codec keeps a message it does not type whole, as Untyped", "[apt][codec]")
{
    // Every ID of the message table is typed; a frame of another ID (the framer drops those,
    // decode() may still be handed one) is kept whole, header-only or with its data packet.
    Frame f;
    f.id = 0x0001;
    f.param1 = 7;
    f.param2 = 9;
    auto m = decode(f);
    REQUIRE(holds<Untyped>(m));
    CHECK((*get_if<Untyped>(m) == Untyped{0x0001, 7, 9, false, ""}));
    CHECK(message_id(m) == 0x0001);
    CHECK(hex(encode(m, 0x50, 0x01)) == "01 00 07 09 50 01");

    const std::string data = unhex("01 00 E8 03");
    f.has_data = true;
    f.param1 = f.param2 = 0;
    f.data = data;
    m = decode(f);
    REQUIRE(holds<Untyped>(m));
    CHECK(get_if<Untyped>(m)->data == data);
    CHECK(hex(encode(m, 0x50, 0x01)) == "01 00 04 00 D0 01 01 00 E8 03");

    // IDs the table does not know: between its entries (0x07DF), above its highest (0x07FB), up to the
    // largest a header can carry.
    f.has_data = false;
    for (std::uint16_t id : {0x07DF, 0x0800, 0x0801, 0xFFFF}) {
        f.id = id;
        m = decode(f);
        REQUIRE(holds<Untyped>(m));
        CHECK(message_id(m) == id);
    }
}

TEST_CASE("apt codec decodes a typed message in a form its struct does not have as Untyped", "[apt][codec]")
{
    Frame f;
    f.id = MGMSG_MOT_SET_VELPARAMS;
    f.has_data = true;
    const std::string short_data = unhex("01 00 02 00");
    f.data = short_data;
    const auto m = decode(f);
    REQUIRE(holds<Untyped>(m));
    CHECK(get_if<Untyped>(m)->data == short_data);
    f.id = MGMSG_MOT_REQ_VELPARAMS;   // a REQ with a data packet
    CHECK(holds<Untyped>(decode(f)));
}

// ---- Piezo Control Messages (p. 93-126) and the TSG001 strain gauge reader (p. 127-129) ----

TEST_CASE("MGMSG_PZ_SET_POSCONTROLMODE, MGMSG_PZ_REQ_POSCONTROLMODE and MGMSG_PZ_GET_POSCONTROLMODE round-trip",
          "[apt][codec]")
{
    round_trip(PzSetPosControlMode{1, 2}, "40 06 01 02 50 01");
    round_trip(PzReqPosControlMode{1}, "41 06 01 00 50 01");
    round_trip(PzGetPosControlMode{1, 2}, "42 06 01 02 01 50", 0x01, 0x50);
}

TEST_CASE("MGMSG_PZ_SET_OUTPUTVOLTS, MGMSG_PZ_REQ_OUTPUTVOLTS and MGMSG_PZ_GET_OUTPUTVOLTS round-trip", "[apt][codec]")
{
    round_trip(SetPzOutputVolts{{1, 32767}}, "43 06 04 00 D0 01 01 00 FF 7F");
    round_trip(ReqPzOutputVolts{1}, "44 06 01 00 50 01");
    round_trip(GetPzOutputVolts{{1, -32767}}, "45 06 04 00 81 50 01 00 01 80", 0x01, 0x50);
}

TEST_CASE("MGMSG_PZ_SET_OUTPUTPOS, MGMSG_PZ_REQ_OUTPUTPOS and MGMSG_PZ_GET_OUTPUTPOS round-trip", "[apt][codec]")
{
    round_trip(SetPzOutputPos{{1, 0x2666}}, "46 06 04 00 D0 01 01 00 66 26");   // p. 97 example bytes
    round_trip(ReqPzOutputPos{1}, "47 06 01 00 50 01");
    round_trip(GetPzOutputPos{{1, 0x2666}}, "48 06 04 00 81 50 01 00 66 26", 0x01, 0x50);
}

TEST_CASE("MGMSG_PZ_SET_INPUTVOLTSSRC, MGMSG_PZ_REQ_INPUTVOLTSSRC and MGMSG_PZ_GET_INPUTVOLTSSRC round-trip",
          "[apt][codec]")
{
    round_trip(SetPzInputVoltsSrc{{1, 2}}, "52 06 04 00 D0 01 01 00 02 00");
    round_trip(ReqPzInputVoltsSrc{1}, "53 06 01 00 50 01");
    round_trip(GetPzInputVoltsSrc{{1, 3}}, "54 06 04 00 81 50 01 00 03 00", 0x01, 0x50);
}

TEST_CASE("MGMSG_PZ_SET_PICONSTS, MGMSG_PZ_REQ_PICONSTS and MGMSG_PZ_GET_PICONSTS round-trip", "[apt][codec]")
{
    round_trip(SetPzPiConsts{{1, 100, 15}}, "55 06 06 00 D0 01 01 00 64 00 0F 00");
    round_trip(ReqPzPiConsts{1}, "56 06 01 00 50 01");
    round_trip(GetPzPiConsts{{1, 100, 15}}, "57 06 06 00 81 50 01 00 64 00 0F 00", 0x01, 0x50);
}

TEST_CASE("MGMSG_PZ_REQ_PZSTATUSBITS and MGMSG_PZ_GET_PZSTATUSBITS round-trip", "[apt][codec]")
{
    round_trip(PzReqPzStatusBits{1}, "5B 06 01 00 50 01");
    round_trip(PzGetPzStatusBits{1, 0x80000401}, "5C 06 06 00 81 50 01 00 01 04 00 80", 0x01, 0x50);
}

TEST_CASE("MGMSG_PZ_GET_PZSTATUSUPDATE and MGMSG_PZ_ACK_PZSTATUSUPDATE round-trip", "[apt][codec]")
{
    // 10-byte data packet (ERRATA: the byte table prints MOT_GET_DCSTATUSUPDATE's header).
    round_trip(PzGetPzStatusUpdate{1, 1000, -1000, 0x00000401}, "61 06 0A 00 81 50 01 00 E8 03 18 FC 01 04 00 00",
               0x01, 0x50);
    round_trip(PzAckPzStatusUpdate{}, "62 06 00 00 50 01");
}

TEST_CASE("MGMSG_PZ_SET_OUTPUTLUT, MGMSG_PZ_REQ_OUTPUTLUT and MGMSG_PZ_GET_OUTPUTLUT round-trip", "[apt][codec]")
{
    round_trip(SetPzOutputLut{{1, 511, -2}}, "00 07 06 00 D0 01 01 00 FF 01 FE FF");
    round_trip(ReqPzOutputLut{1}, "01 07 01 00 50 01");
    round_trip(GetPzOutputLut{{1, 7, 300}}, "02 07 06 00 81 50 01 00 07 00 2C 01", 0x01, 0x50);
}

TEST_CASE("MGMSG_PZ_SET_OUTPUTLUTPARAMS, MGMSG_PZ_REQ_OUTPUTLUTPARAMS and MGMSG_PZ_GET_OUTPUTLUTPARAMS round-trip",
          "[apt][codec]")
{
    // 30-byte packet (ERRATA: the example's header says 6), least-significant byte first.
    const PzOutputLutParams p{1, 1, 20, 1, 10, 30, 40, 1, 50, 2};
    const std::string data =
        "01 00 01 00 14 00 01 00 00 00 0A 00 00 00 1E 00 00 00 28 00 00 00 01 00 32 00 00 00 02 00";
    round_trip(SetPzOutputLutParams{p}, "03 07 1E 00 D0 01 " + data);
    round_trip(ReqPzOutputLutParams{1}, "04 07 01 00 50 01");
    round_trip(GetPzOutputLutParams{p}, "05 07 1E 00 81 50 " + data, 0x01, 0x50);
}

TEST_CASE("MGMSG_PZ_START_LUTOUTPUT and MGMSG_PZ_STOP_LUTOUTPUT round-trip", "[apt][codec]")
{
    round_trip(PzStartLutOutput{1}, "06 07 01 00 50 01");
    round_trip(PzStopLutOutput{1}, "07 07 01 00 50 01");
}

TEST_CASE("MGMSG_PZ_SET_EEPROMPARAMS round-trips", "[apt][codec]")
{
    round_trip(PzSetEepromParams{1, MGMSG_PZ_SET_OUTPUTMAXVOLTS}, "D0 07 04 00 D0 01 01 00 80 06");
}

TEST_CASE("MGMSG_PZ_SET_TPZ_DISPSETTINGS, MGMSG_PZ_REQ_TPZ_DISPSETTINGS and MGMSG_PZ_GET_TPZ_DISPSETTINGS round-trip",
          "[apt][codec]")
{
    round_trip(SetTpzDispSettings{{255}}, "D1 07 02 00 D0 01 FF 00");   // no channel word (p. 114)
    round_trip(ReqTpzDispSettings{1}, "D2 07 01 00 50 01");
    round_trip(GetTpzDispSettings{{100}}, "D3 07 02 00 81 50 64 00", 0x01, 0x50);
}

TEST_CASE("MGMSG_PZ_SET_TPZ_IOSETTINGS, MGMSG_PZ_REQ_TPZ_IOSETTINGS and MGMSG_PZ_GET_TPZ_IOSETTINGS round-trip",
          "[apt][codec]")
{
    round_trip(SetTpzIoSettings{{1, 3, 2, 0, 0}}, "D4 07 0A 00 D0 01 01 00 03 00 02 00 00 00 00 00");
    round_trip(ReqTpzIoSettings{1}, "D5 07 01 00 50 01");
    round_trip(GetTpzIoSettings{{1, 1, 1, 0, 0}}, "D6 07 0A 00 81 50 01 00 01 00 01 00 00 00 00 00", 0x01, 0x50);
}

TEST_CASE("MGMSG_PZ_SET_ZERO round-trips", "[apt][codec]")
{
    round_trip(PzSetZero{1}, "58 06 01 00 50 01");
}

TEST_CASE("MGMSG_PZ_REQ_MAXTRAVEL and MGMSG_PZ_GET_MAXTRAVEL round-trip", "[apt][codec]")
{
    round_trip(PzReqMaxTravel{1}, "50 06 01 00 50 01");
    round_trip(PzGetMaxTravel{1, 200}, "51 06 04 00 81 50 01 00 C8 00", 0x01, 0x50);   // 20 um
}

TEST_CASE("MGMSG_PZ_SET_IOSETTINGS, MGMSG_PZ_REQ_IOSETTINGS and MGMSG_PZ_GET_IOSETTINGS round-trip", "[apt][codec]")
{
    round_trip(SetPzIoSettings{{1, 2, 3, 1, 2}}, "70 06 0A 00 D0 01 01 00 02 00 03 00 01 00 02 00");
    round_trip(ReqPzIoSettings{1}, "71 06 01 00 50 01");
    round_trip(GetPzIoSettings{{1, 2, 3, 1, 2}}, "72 06 0A 00 81 50 01 00 02 00 03 00 01 00 02 00", 0x01, 0x50);
}

TEST_CASE("MGMSG_PZ_SET_OUTPUTMAXVOLTS, MGMSG_PZ_REQ_OUTPUTMAXVOLTS and MGMSG_PZ_GET_OUTPUTMAXVOLTS round-trip",
          "[apt][codec]")
{
    round_trip(SetPzOutputMaxVolts{{1, 750, 0}}, "80 06 06 00 D0 01 01 00 EE 02 00 00");   // 75 V
    round_trip(ReqPzOutputMaxVolts{1}, "81 06 01 00 50 01");
    round_trip(GetPzOutputMaxVolts{{1, 1500, 2}}, "82 06 06 00 81 50 01 00 DC 05 02 00", 0x01, 0x50);
}

TEST_CASE("MGMSG_PZ_SET_TPZ_SLEWRATES, MGMSG_PZ_REQ_TPZ_SLEWRATES and MGMSG_PZ_GET_TPZ_SLEWRATES round-trip",
          "[apt][codec]")
{
    round_trip(SetTpzSlewRates{{1, 100, 200}}, "83 06 06 00 D0 01 01 00 64 00 C8 00");
    round_trip(ReqTpzSlewRates{1}, "84 06 01 00 50 01");
    round_trip(GetTpzSlewRates{{1, 100, 200}}, "85 06 06 00 81 50 01 00 64 00 C8 00", 0x01, 0x50);
}

TEST_CASE("MGMSG_MOT_SET_PZSTAGEPARAMDEFAULTS and MGMSG_PZ_SET_LUTVALUETYPE round-trip", "[apt][codec]")
{
    round_trip(MotSetPzStageParamDefaults{1}, "86 06 01 00 50 01");
    round_trip(PzSetLutValueType{2}, "08 07 02 00 50 01");
}

TEST_CASE("MGMSG_PZ_SET_TSG_IOSETTINGS, MGMSG_PZ_REQ_TSG_IOSETTINGS and MGMSG_PZ_GET_TSG_IOSETTINGS round-trip",
          "[apt][codec]")
{
    // p. 127: the example's values (hub output 1, force display 2... 3, calibration 30,000);
    // 14 bytes of data, its last 6 for future use.
    const TsgIoSettings p{1, 1, 3, 30000, 0, 0, 0};
    const std::string data = "01 00 01 00 03 00 30 75 00 00 00 00 00 00";
    round_trip(SetTsgIoSettings{p}, "DA 07 0E 00 D0 01 " + data);
    round_trip(ReqTsgIoSettings{1}, "DB 07 01 00 50 01");
    round_trip(GetTsgIoSettings{p}, "DC 07 0E 00 81 50 " + data, 0x01, 0x50);
}

TEST_CASE("MGMSG_PZ_REQ_TSG_READING and MGMSG_PZ_GET_TSG_READING round-trip", "[apt][codec]")
{
    round_trip(TsgReqReading{1}, "DD 07 01 00 50 01");
    round_trip(TsgGetReading{1, 0x0052, 0x0050}, "DE 07 06 00 81 50 01 00 52 00 50 00", 0x01, 0x50);   // p. 129
}

} // namespace test_apt_codec
