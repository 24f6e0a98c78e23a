// APT codec, the K-Cube piezo driver's and strain gauge reader's own messages (later protocol
// issues; emulator/apt/codec_kcube_units.hpp): each encodes to the layout the public sources
// give (docs/protocol/apt.md "K-Cube units"), with the values of the KPZ101/KSG101 session of
// kptrofatter/kcube (its kcube_message.c writes the lengths used here), and decodes back.
#include "emulator/apt/codec.hpp"
#include "tests/support/apt_round_trip.hpp"
#include "tests/support/hex.hpp"

#include <catch2/catch.hpp>

#include <string>

namespace test_codec_kcube_units {

using namespace rigsim::apt;
using namespace rigsim::apt::msg;
using rigsim::test::hex;
using rigsim::test::round_trip;
const auto unhex = rigsim::test::bytes;

TEST_CASE("MGMSG_KPZ_SET/REQ/GET_KCUBEMMIPARAMS round-trip in their 34-byte layout", "[unit][apt][codec][kcube]")
{
    // channel 1, JSMode 1, JSVoltGearbox 1, JSVoltStep 256, DirSense 0, PresetVolt1 0,
    // PresetVolt2 32767, DispBrightness 40, DispTimeout 1, DispDimLevel 10, 4 reserved words.
    const KpzMmiParams p{1, 1, 1, 256, 0, 0, 32767, 40, 1, 10};
    const std::string data = "01 00 01 00 01 00 00 01 00 00 00 00 00 00 00 00 FF 7F 00 00 28 00 01 00 0A 00 "
                             "00 00 00 00 00 00 00 00";
    round_trip(SetKpzMmiParams{p}, "F0 07 22 00 D0 01 " + data);
    round_trip(ReqKpzMmiParams{1}, "F1 07 01 00 50 01");
    round_trip(GetKpzMmiParams{p}, "F2 07 22 00 81 50 " + data, 0x01, 0x50);
    // The reserved words are kept as they came.
    KpzMmiParams q = p;
    q.reserved4 = 0xBEEF;
    round_trip(SetKpzMmiParams{q}, "F0 07 22 00 D0 01 " + data.substr(0, data.size() - 5) + "EF BE");
}

TEST_CASE("MGMSG_KPZ_SET/REQ/GET_KCUBETRIGIOCONFIG round-trip in their 22-byte layout", "[unit][apt][codec][kcube]")
{
    const KpzTrigIoConfig p{1, 0x00, 0x01, 0x0A, 0x02};
    const std::string data = "01 00 00 00 01 00 0A 00 02 00 00 00 00 00 00 00 00 00 00 00 00 00";
    round_trip(SetKpzTrigIoConfig{p}, "F3 07 16 00 D0 01 " + data);
    round_trip(ReqKpzTrigIoConfig{1}, "F4 07 01 00 50 01");
    round_trip(GetKpzTrigIoConfig{p}, "F5 07 16 00 81 50 " + data, 0x01, 0x50);
}

TEST_CASE("MGMSG_KSG_SET/REQ/GET_KCUBEMMIPARAMS round-trip in their 8-byte layout", "[unit][apt][codec][kcube]")
{
    const KsgMmiParams p{1, 20, 5, 10};   // intensity 20 %, timeout 5 min, dim level 10
    round_trip(SetKsgMmiParams{p}, "F6 07 08 00 D0 01 01 00 14 00 05 00 0A 00");
    round_trip(ReqKsgMmiParams{1}, "F7 07 01 00 50 01");
    round_trip(GetKsgMmiParams{p}, "F8 07 08 00 81 50 01 00 14 00 05 00 0A 00", 0x01, 0x50);
}

TEST_CASE("MGMSG_KSG_SET/REQ/GET_KCUBETRIGIOCONFIG round-trip in their 22-byte layout", "[unit][apt][codec][kcube]")
{
    // Limits are signed longs: -1000 and 100; SmoothingSamples 100; one reserved word.
    const KsgTrigIoConfig p{1, 0x00, 0x01, 0x0F, 0x02, -1000, 100, 100, 0};
    const std::string data = "01 00 00 00 01 00 0F 00 02 00 18 FC FF FF 64 00 00 00 64 00 00 00";
    round_trip(SetKsgTrigIoConfig{p}, "F9 07 16 00 D0 01 " + data);
    round_trip(ReqKsgTrigIoConfig{1}, "FA 07 01 00 50 01");
    round_trip(GetKsgTrigIoConfig{p}, "FB 07 16 00 81 50 " + data, 0x01, 0x50);
}

TEST_CASE("MGMSG_PZ_REQ_PZSTATUSUPDATE round-trips as a header-only request", "[unit][apt][codec][kcube]")
{
    round_trip(PzReqPzStatusUpdate{1}, "60 06 01 00 50 01");
}

TEST_CASE("the K-Cube units' messages are later-issue entries of the table with their lengths",
          "[unit][apt][codec][kcube]")
{
    struct Row {
        std::uint16_t id;
        std::int16_t length;
        Group group;
    };
    const Row rows[] = {
        {MGMSG_PZ_REQ_PZSTATUSUPDATE, -1, Group::Piezo},
        {MGMSG_KPZ_SET_KCUBEMMIPARAMS, 34, Group::Piezo},    {MGMSG_KPZ_REQ_KCUBEMMIPARAMS, -1, Group::Piezo},
        {MGMSG_KPZ_GET_KCUBEMMIPARAMS, 34, Group::Piezo},    {MGMSG_KPZ_SET_KCUBETRIGIOCONFIG, 22, Group::Piezo},
        {MGMSG_KPZ_REQ_KCUBETRIGIOCONFIG, -1, Group::Piezo}, {MGMSG_KPZ_GET_KCUBETRIGIOCONFIG, 22, Group::Piezo},
        {MGMSG_KSG_SET_KCUBEMMIPARAMS, 8, Group::StrainGauge},
        {MGMSG_KSG_REQ_KCUBEMMIPARAMS, -1, Group::StrainGauge},
        {MGMSG_KSG_GET_KCUBEMMIPARAMS, 8, Group::StrainGauge},
        {MGMSG_KSG_SET_KCUBETRIGIOCONFIG, 22, Group::StrainGauge},
        {MGMSG_KSG_REQ_KCUBETRIGIOCONFIG, -1, Group::StrainGauge},
        {MGMSG_KSG_GET_KCUBETRIGIOCONFIG, 22, Group::StrainGauge},
    };
    for (const auto& row : rows) {
        const auto* m = find_message(row.id);
        REQUIRE(m != nullptr);
        INFO(m->name);
        CHECK(m->data_length == row.length);
        CHECK(m->group == row.group);
        CHECK(m->later_issue);
        // The codec types it in the table's form: its struct's data packet is the table's length.
        const std::string data(row.length >= 0 ? static_cast<std::size_t>(row.length) : 0, '\0');
        const auto decoded = decode(Frame{row.id, 1, 0, 0x50, 0x01, row.length >= 0, data, m, {}});
        CHECK_FALSE(holds<Untyped>(decoded));
        CHECK(encode(decoded, 0x50, 0x01).size() == 6 + data.size());
    }
}

TEST_CASE("MGMSG_MOT_SET/REQ/GET_MFF_OPERPARAMS round-trip issue 37's example in their 34-byte layout",
          "[unit][apt][codec][kcube]")
{
    // Issue 37 p. 183: "10 05 22 00 D0 01 | 01 00 F4 01 00 00 FC 01 00 00 01 00 01 00 C8 00 00 00 01 00
    // 01 00 C8 00 00 00" and 8 unused bytes: 500 ms (ADC 508), toggle on a button, 200 ms, twice.
    const MffOperParams p{1, 500, 508, 1, 1, 200, 1, 1, 200, 0, 0};
    const std::string data = "01 00 F4 01 00 00 FC 01 00 00 01 00 01 00 C8 00 00 00 01 00 01 00 C8 00 00 00 "
                             "00 00 00 00 00 00 00 00";
    round_trip(SetMffOperParams{p}, "10 05 22 00 D0 01 " + data);
    round_trip(ReqMffOperParams{1}, "11 05 01 00 50 01");
    round_trip(GetMffOperParams{p}, "12 05 22 00 81 50 " + data, 0x01, 0x50);
    STATIC_REQUIRE(SetMffOperParams::family == Family::Flipper);
}

TEST_CASE("MGMSG_MOT_SET/REQ/GET_POLPARAMS round-trip issue 37's example in their 12-byte layout",
          "[unit][apt][codec][kcube]")
{
    // Issue 37 p. 408: "30 05 0C 00 D0 01 00 00 32 00 00 00 19 00 19 00 19 00": 50 %, home 0, jog 25 x 3.
    const PolParams p{0, 50, 0, 25, 25, 25};
    round_trip(SetPolParams{p}, "30 05 0C 00 D0 01 00 00 32 00 00 00 19 00 19 00 19 00");
    round_trip(ReqPolParams{0}, "31 05 00 00 50 01");
    round_trip(GetPolParams{p}, "32 05 0C 00 81 50 00 00 32 00 00 00 19 00 19 00 19 00", 0x01, 0x50);
    STATIC_REQUIRE(SetPolParams::family == Family::Polariser);
}

} // namespace test_codec_kcube_units
