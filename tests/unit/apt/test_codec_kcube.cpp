// The motor messages of later protocol issues (codec_kcube.hpp): each encodes to the bytes the
// public sources print (examples quoted at each case) and decodes back through the framer; the
// table knows their IDs and lengths and flags them later_issue.
#include "emulator/apt/codec.hpp"
#include "tests/support/apt_round_trip.hpp"
#include "tests/support/hex.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace test_codec_kcube {

using namespace rigsim::apt;
using namespace rigsim::apt::msg;
using rigsim::test::hex;
using rigsim::test::round_trip;
const auto unhex = rigsim::test::bytes;

namespace {

const std::string kTwelveZeros = " 00 00 00 00 00 00 00 00 00 00 00 00";

} // namespace

TEST_CASE("MOT_SET/REQ/GET_POWERPARAMS round-trip the issue 16 example and an APT trace", "[unit][apt][codec][kcube]")
{
    // Issue 16 p. 44: "TX 26, 04, 06, 00, A2, 01, 01, 00, 0A, 00, 64, 00" (rest 10 %, move 100 %).
    round_trip(SetPowerParams{{1, 10, 100}}, "26 04 06 00 A2 01 01 00 0A 00 64 00", 0x22);
    // The APT ActiveX start-up of a BSC203 bay quoted by a public driver: rest 15 %, move 30 %.
    round_trip(SetPowerParams{{1, 15, 30}}, "26 04 06 00 A1 01 01 00 0F 00 1E 00", 0x21);
    round_trip(ReqPowerParams{1}, "27 04 01 00 50 01");
    round_trip(GetPowerParams{{1, 5, 30}}, "28 04 06 00 81 50 01 00 05 00 1E 00", 0x01, 0x50);
    STATIC_REQUIRE(SetPowerParams::family == Family::KCubeMotor);
    STATIC_REQUIRE(GetPowerParams::family == Family::UnitToHost);
}

TEST_CASE("MOT_SET_TSTACTUATORTYPE carries the actuator in param1", "[unit][apt][codec][kcube]")
{
    // Issue 16 p. 94: "Header: FE, 04, 31, 00, 50, 01"; a public KST driver sends ZFS13 (0x41).
    MotSetTstActuatorType zst13;
    zst13.params.actuator_ident = 0x31;
    round_trip(zst13, "FE 04 31 00 50 01");
    MotSetTstActuatorType zfs13;
    zfs13.params.actuator_ident = 0x41;
    round_trip(zfs13, "FE 04 41 00 50 01");
    STATIC_REQUIRE(MotSetTstActuatorType::header_only);
}

TEST_CASE("MOT_SET/REQ/GET_TRIGGER round-trip the issue 16 example", "[unit][apt][codec][kcube]")
{
    // Issue 16 p. 103: "TX 00, 05, 01, 53, 50, 01" and "TX 01, 05, 01, 00, 50, 01".
    round_trip(MotSetTrigger{1, 0x53}, "00 05 01 53 50 01");
    round_trip(MotReqTrigger{1}, "01 05 01 00 50 01");
    round_trip(MotGetTrigger{1, 0x53}, "02 05 01 53 01 50", 0x01, 0x50);
}

TEST_CASE("MOT_SET/REQ/GET_KCUBEMMIPARAMS round-trip their 36-byte layout", "[unit][apt][codec][kcube]")
{
    // chan 1, jog mode (2), max vel 0x00010000, accn 0x00000800, dir sense 1, presets 1000 and -1000,
    // brightness 60, timeout 10 min, dim level 2, preset 3 0x7FFFFFFF, sensitivity 3, reserved 0.
    const KCubeMmiParams p{1, 2, 0x00010000, 0x00000800, 1, 1000, -1000, 60, 10, 2, 0x7FFFFFFF, 3, 0};
    round_trip(SetKCubeMmiParams{p}, "20 05 24 00 D0 01 01 00 02 00 00 00 01 00 00 08 00 00 01 00 E8 03 00 00 "
                                     "18 FC FF FF 3C 00 0A 00 02 00 FF FF FF 7F 03 00 00 00");
    round_trip(ReqKCubeMmiParams{1}, "21 05 01 00 50 01");
    CHECK(encode(GetKCubeMmiParams{p}, 0x01, 0x50).substr(0, 6) == unhex("22 05 24 00 81 50"));
}

TEST_CASE("MOT_SET/REQ/GET_KCUBETRIGIOCONFIG round-trip Thorlabs' example", "[unit][apt][codec][kcube]")
{
    // Thorlabs' KBD101 example: "23 05 16 00 D0 01 01 00 02 00 01 00 0B 00 01 00" and 12 reserved
    // bytes: TRIG1 relative move input, active high; TRIG2 in-motion output, active high.
    round_trip(SetKCubeTrigIoConfig{{1, 0x02, 1, 0x0B, 1, {}}},
               "23 05 16 00 D0 01 01 00 02 00 01 00 0B 00 01 00" + kTwelveZeros);
    round_trip(ReqKCubeTrigIoConfig{1}, "24 05 01 00 50 01");
    round_trip(GetKCubeTrigIoConfig{{1, 0x0D, 2, 0x00, 1, {}}},
               "25 05 16 00 81 50 01 00 0D 00 02 00 00 00 01 00" + kTwelveZeros, 0x01, 0x50);
}

TEST_CASE("MOT_SET/REQ/GET_KCUBEPOSTRIGPARAMS round-trip Thorlabs' example", "[unit][apt][codec][kcube]")
{
    // Thorlabs' KBD101 example ("Values are set as default at controller startup"): one pulse each
    // way from 0, 50 us wide, one cycle, then 12 reserved bytes.
    round_trip(SetKCubePosTrigParams{{1, 0, 0, 1, 0, 0, 1, 50, 1, {}}},
               "26 05 2E 00 D0 01 01 00 00 00 00 00 00 00 00 00 01 00 00 00 00 00 00 00 00 00 00 00 01 00 00 00 "
               "32 00 00 00 01 00 00 00" + kTwelveZeros);
    round_trip(ReqKCubePosTrigParams{1}, "27 05 01 00 50 01");
}

TEST_CASE("MOT_SET/REQ/GET_KCUBEKSTLOOPPARAMS round-trip yaq's layout", "[unit][apt][codec][kcube]")
{
    // The values a public thorpy example sends "as set by APT": open loop, Prop 200000, Int 1000,
    // Diff 100, PIDClip 100000000, PIDTol 200, EncoderConst 0.
    round_trip(SetKCubeKstLoopParams{{1, 1, 200000, 1000, 100, 100000000, 200, 0}},
               "29 05 1C 00 D0 01 01 00 01 00 40 0D 03 00 E8 03 00 00 64 00 00 00 00 E1 F5 05 C8 00 00 00 00 00 00 00");
    round_trip(ReqKCubeKstLoopParams{1}, "2A 05 01 00 50 01");
    round_trip(GetKCubeKstLoopParams{{1, 2, 1, 2, 3, 4, 5, 0xFFFFFFFF}},
               "2B 05 1C 00 81 50 01 00 02 00 01 00 00 00 02 00 00 00 03 00 00 00 04 00 00 00 05 00 00 00 FF FF FF FF",
               0x01, 0x50);
}

TEST_CASE("the later-issue motor messages are in the table with their lengths, flagged later_issue",
          "[unit][apt][codec][kcube][messages]")
{
    const std::vector<std::pair<std::uint16_t, int>> expected{
        {0x0426, 6},  {0x0427, -1}, {0x0428, 6},  {0x04FE, -1}, {0x0500, -1}, {0x0501, -1}, {0x0502, -1},
        {0x0520, 36}, {0x0521, -1}, {0x0522, 36}, {0x0523, 22}, {0x0524, -1}, {0x0525, 22}, {0x0526, 46},
        {0x0527, -1}, {0x0528, 46}, {0x0529, 28}, {0x052A, -1}, {0x052B, 28}};
    for (const auto& [id, length] : expected) {
        INFO(std::hex << id);
        const auto* info = find_message(id);
        REQUIRE(info != nullptr);
        CHECK(info->data_length == length);
        CHECK(info->later_issue);
        CHECK(info->group == Group::Motor);
        // Every data length is its struct's: a frame of the table's length is typed, not Untyped.
        std::string frame = info->header_only() ? encode_header_only(id, 1, 0, 0x50, 0x01)
                                                : encode_with_data(id, 0x50, 0x01, std::string(length, '\0'));
        CHECK_FALSE(holds<Untyped>(rigsim::test::decode_frame(frame)));
    }
}

TEST_CASE("later-issue SETs with the reserved tails public clients leave out decode, their tail as zeros",
          "[unit][apt][codec][kcube]")
{
    // pyLabLib kinesis.py _setup_kcube_trigio: "<HHHHH" (10 bytes, no reserved tail): Trig1 0x0A
    // active high, Trig2 0x0B active high.
    auto m = rigsim::test::decode_frame(unhex("23 05 0A 00 D0 01 01 00 0A 00 01 00 0B 00 01 00"));
    REQUIRE(holds<SetKCubeTrigIoConfig>(m));
    const auto trig = get_if<SetKCubeTrigIoConfig>(m)->params;
    CHECK(trig.trig1_mode == 0x0A);
    CHECK(trig.trig2_mode == 0x0B);
    CHECK(trig.trig2_polarity == 1);
    CHECK(trig.reserved == std::array<char, 12>{});
    // Encoded again it has the table's layout: the reserved tail as zeros.
    CHECK(hex(encode(m, 0x50, 0x01)) == "23 05 16 00 D0 01 01 00 0A 00 01 00 0B 00 01 00" + kTwelveZeros);
    // pyLabLib _setup_kcube_trigpos, yaq mot_set_kcubeposttrigparams, quantumion kdc.py: "<H8l" (34).
    std::string pos = "26 05 22 00 D0 01 01 00";
    for (int v : {100, 200, 3, -100, 200, 3, 50, 1})
        pos += " " + hex(std::string{static_cast<char>(v & 0xFF), static_cast<char>((v >> 8) & 0xFF),
                                     static_cast<char>((v >> 16) & 0xFF), static_cast<char>((v >> 24) & 0xFF)});
    m = rigsim::test::decode_frame(unhex(pos));
    REQUIRE(holds<SetKCubePosTrigParams>(m));
    CHECK(get_if<SetKCubePosTrigParams>(m)->params.start_pos_rev == -100);
    CHECK(get_if<SetKCubePosTrigParams>(m)->params.num_cycles == 1);
    // yaq's KCUBEMMIPARAMS, "<HHllHll3H" (28): the display words are there, the rest zeros.
    m = rigsim::test::decode_frame(unhex("20 05 1C 00 D0 01 01 00 02 00 00 00 00 00 00 00 00 00 01 00 "
                                         "00 00 00 00 00 00 00 00 32 00 05 00 02 00"));
    REQUIRE(holds<SetKCubeMmiParams>(m));
    CHECK(get_if<SetKCubeMmiParams>(m)->params.disp_dim_level == 2);
    CHECK(get_if<SetKCubeMmiParams>(m)->params.js_sensitivity == 0);
}

TEST_CASE("a later-issue SET short of the fields any unit reads is Untyped, one longer than its layout decodes",
          "[unit][apt][codec][kcube]")
{
    // TRIGIOCONFIG without Trig2Polarity (8 bytes): no unit reads it as the block.
    const auto m = rigsim::test::decode_frame(unhex("23 05 08 00 D0 01 01 00 0A 00 01 00 0B 00"));
    REQUIRE(holds<Untyped>(m));
    CHECK(get_if<Untyped>(m)->data.size() == 8);
    // 24 bytes, two past the 22 of Thorlabs' example: a frame of the header's length, decoded
    // from its first 22 bytes, the other two ignored; encoded again it has the table's layout.
    const auto longer = rigsim::test::decode_frame(
        unhex("23 05 18 00 D0 01 01 00 02 00 01 00 0B 00 01 00" + kTwelveZeros + " 7F 7F"));
    REQUIRE(holds<SetKCubeTrigIoConfig>(longer));
    CHECK(get_if<SetKCubeTrigIoConfig>(longer)->params.trig1_mode == 0x02);
    CHECK(get_if<SetKCubeTrigIoConfig>(longer)->params.trig2_polarity == 1);
    CHECK(get_if<SetKCubeTrigIoConfig>(longer)->params.reserved == std::array<char, 12>{});
    CHECK(hex(encode(longer, 0x50, 0x01)) == "23 05 16 00 D0 01 01 00 02 00 01 00 0B 00 01 00" + kTwelveZeros);
}

} // namespace test_codec_kcube
