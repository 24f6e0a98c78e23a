// APT message table: the ERRATA corrections, a round trip of every message through
// encode -> framer, and the byte examples of the manual.
#include "emulator/apt/frame_framer.hpp"
#include "emulator/apt/messages.hpp"
#include "emulator/apt/wire.hpp"
#include "tests/support/hex.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace test_messages {

using namespace rigsim::apt;
using rigsim::test::hex;
const auto unhex = rigsim::test::bytes;

namespace {

const std::vector<std::uint8_t> kAddresses{0x01, 0x11, 0x21, 0x22, 0x23, 0x24, 0x25,
                                           0x26, 0x27, 0x28, 0x29, 0x2A, 0x50};


struct Parsed {
    std::vector<Frame> frames;
    std::vector<std::string> data;   // copies: a frame's view dies with the next parse()
    std::size_t dropped = 0;
    std::size_t buffered = 0;
};

/// Feed `input` in pieces of `chunk` bytes to a fresh framer.
Parsed parse_all(std::string_view input, std::size_t chunk)
{
    FrameFramer f;
    Parsed p;
    for (std::size_t pos = 0; pos < input.size(); pos += chunk) {
        std::string_view piece = input.substr(pos, chunk);
        while (!piece.empty()) {
            const auto r = f.parse(piece);
            REQUIRE(r.consumed > 0);
            piece.remove_prefix(r.consumed);
            p.dropped += r.dropped;
            if (r.status == FrameFramer::Status::Frame) {
                p.frames.push_back(r.frame);
                p.data.emplace_back(r.frame.data);
            }
        }
    }
    p.buffered = f.buffered();
    return p;
}

std::size_t count(Group g)
{
    std::size_t n = 0;
    for (const auto& m : all_messages())
        n += m.group == g ? 1 : 0;
    return n;
}

const std::string kSentinel = encode_header_only(MGMSG_HW_REQ_INFO, 0, 0, kGenericUsb, kHost);

/// `bad` is no frame: the framer drops every byte of it and finds the frame after it.
void check_rejected(const std::string& bad)
{
    INFO("rejected: " << hex(bad));
    for (std::size_t chunk : {1u, 1000u}) {
        const auto p = parse_all(bad + kSentinel, chunk);
        REQUIRE(p.frames.size() == 1);
        CHECK(p.frames[0].id == MGMSG_HW_REQ_INFO);
        CHECK(p.dropped == bad.size());
    }
}

} // namespace

TEST_CASE("apt message table is consistent", "[unit][apt][messages]")
{
    std::set<std::uint16_t> ids;
    std::set<std::string_view> names;
    for (const auto& m : all_messages()) {
        INFO(m.name);
        CHECK(ids.insert(m.id).second);
        CHECK(names.insert(m.name).second);
        CHECK(find_message(m.id) == &m);
        CHECK(m.name.substr(0, 6) == "MGMSG_");
        if (m.group == Group::Motor) {
            // The motor messages, and the piezo motor controllers' PZMOT_ ones of later issues.
            CHECK((m.name.substr(0, 10) == "MGMSG_MOT_" || (m.later_issue && m.name.substr(0, 12) == "MGMSG_PZMOT_")));
        } else if (m.group == Group::Piezo) {
            // The piezo chapter's PZ_ messages, and the KPZ101's own KPZ_ ones of later issues.
            CHECK((m.name.substr(0, 9) == "MGMSG_PZ_" || (m.later_issue && m.name.substr(0, 10) == "MGMSG_KPZ_")));
            CHECK(m.name.find("_TSG_") == std::string_view::npos);
        } else if (m.group == Group::StrainGauge) {
            // The TSG001's PZ_*TSG_* messages, and the KSG101's own KSG_ ones of later issues.
            if (m.later_issue) {
                CHECK(m.name.substr(0, 10) == "MGMSG_KSG_");
            } else {
                CHECK(m.name.substr(0, 9) == "MGMSG_PZ_");
                CHECK(m.name.find("_TSG_") != std::string_view::npos);
            }
        } else {
            const auto kind = m.name.substr(6, m.name.find('_', 6) - 6);
            CHECK((kind == "MOD" || kind == "HW" || kind == "RACK" || kind == "HUB"));
        }
        CHECK(m.data_length >= -1);
        CHECK(m.data_length <= static_cast<int>(kMaxDataLength));
        CHECK(m.header_only() == (m.data_length == -1));
        if (m.header_only_allowed)
            CHECK_FALSE(m.header_only());
    }
    CHECK(count(Group::Generic) == 22);
    // The manual's, then the later issues' (test_codec_kcube.cpp), the flip mount's MFF_OPERPARAMS and the
    // polarisation controller's POL_PARAMS, the piezo motor controllers' PZMOT family.
    CHECK(count(Group::Motor) == 92 + 19 + 3 + 3 + 9);
    // The piezo and strain gauge chapters' 47 and 5, and the K-Cube units' 7 and 6 of later issues.
    CHECK(count(Group::Piezo) == 47 + 7);
    CHECK(count(Group::StrainGauge) == 5 + 6);
    CHECK(all_messages().size() == 166 + 19 + 13 + 3 + 3 + 9);
    CHECK(find_message(0x0000) == nullptr);
    CHECK(find_message(0xFFFF) == nullptr);
    CHECK(find_message(0x0663) == nullptr);     // docs/protocol/apt.md's unknown ID beside 0x0000, 0xFFFF
    REQUIRE(find_message(0x0660) != nullptr);   // a REQ for PZ_GET_PZSTATUSUPDATE: not in the manual,
    CHECK(find_message(0x0660)->later_issue);   // later issues add it
    CHECK(find_message(0x0640) == &all_messages()[113]);   // the piezo chapter follows the 22 + 79 + 12
}

TEST_CASE("apt message table applies the ERRATA to the piezo and strain gauge messages", "[unit][apt][messages]")
{
    struct Expect {
        std::uint16_t id;
        std::string_view name;
        int data_length;
        Group group;
    };
    const std::vector<Expect> expected{
        // p.103: table "91 04 0E 00"; ERRATA: 0x0661, 10 bytes.
        {0x0661, "MGMSG_PZ_GET_PZSTATUSUPDATE", 10, Group::Piezo},
        {0x0662, "MGMSG_PZ_ACK_PZSTATUSUPDATE", -1, Group::Piezo},
        // p.108: example header length "06"; ERRATA: 30 (0x1E).
        {0x0703, "MGMSG_PZ_SET_OUTPUTLUTPARAMS", 30, Group::Piezo},
        {0x0705, "MGMSG_PZ_GET_OUTPUTLUTPARAMS", 30, Group::Piezo},
        // The choices at the entries of messages.cpp.
        {0x0643, "MGMSG_PZ_SET_OUTPUTVOLTS", 4, Group::Piezo},
        {0x0644, "MGMSG_PZ_REQ_OUTPUTVOLTS", -1, Group::Piezo},
        {0x0646, "MGMSG_PZ_SET_OUTPUTPOS", 4, Group::Piezo},
        {0x0652, "MGMSG_PZ_SET_INPUTVOLTSSRC", 4, Group::Piezo},
        {0x0655, "MGMSG_PZ_SET_PICONSTS", 6, Group::Piezo},
        {0x065C, "MGMSG_PZ_GET_PZSTATUSBITS", 6, Group::Piezo},
        {0x0701, "MGMSG_PZ_REQ_OUTPUTLUT", -1, Group::Piezo},
        {0x0706, "MGMSG_PZ_START_LUTOUTPUT", -1, Group::Piezo},
        {0x0707, "MGMSG_PZ_STOP_LUTOUTPUT", -1, Group::Piezo},
        {0x07D0, "MGMSG_PZ_SET_EEPROMPARAMS", 4, Group::Piezo},
        {0x07D1, "MGMSG_PZ_SET_TPZ_DISPSETTINGS", 2, Group::Piezo},
        {0x07D4, "MGMSG_PZ_SET_TPZ_IOSETTINGS", 10, Group::Piezo},
        {0x07D6, "MGMSG_PZ_GET_TPZ_IOSETTINGS", 10, Group::Piezo},
        {0x0658, "MGMSG_PZ_SET_ZERO", -1, Group::Piezo},
        {0x0651, "MGMSG_PZ_GET_MAXTRAVEL", 4, Group::Piezo},
        {0x0670, "MGMSG_PZ_SET_IOSETTINGS", 10, Group::Piezo},
        {0x0680, "MGMSG_PZ_SET_OUTPUTMAXVOLTS", 6, Group::Piezo},
        {0x0683, "MGMSG_PZ_SET_TPZ_SLEWRATES", 6, Group::Piezo},
        {0x0708, "MGMSG_PZ_SET_LUTVALUETYPE", -1, Group::Piezo},
        {0x0686, "MGMSG_MOT_SET_PZSTAGEPARAMDEFAULTS", -1, Group::Motor},
        {0x07DA, "MGMSG_PZ_SET_TSG_IOSETTINGS", 14, Group::StrainGauge},
        {0x07DC, "MGMSG_PZ_GET_TSG_IOSETTINGS", 14, Group::StrainGauge},
        {0x07DD, "MGMSG_PZ_REQ_TSG_READING", -1, Group::StrainGauge},
        {0x07DE, "MGMSG_PZ_GET_TSG_READING", 6, Group::StrainGauge},
    };
    for (const auto& e : expected) {
        INFO(e.name);
        const auto* m = find_message(e.id);
        REQUIRE(m != nullptr);
        CHECK(m->name == e.name);
        CHECK(m->data_length == e.data_length);
        CHECK(m->group == e.group);
        CHECK_FALSE(m->later_issue);
        CHECK_FALSE(m->header_only_allowed);
    }
    // The ERRATA's PZSTATUSUPDATE header, and the manual's misprinted one (a DC status header).
    const auto p = parse_all(unhex("61 06 0A 00 81 50 01 00 77 77 33 13 01 04 00 00"), 1);
    REQUIRE(p.frames.size() == 1);
    CHECK(p.frames[0].id == MGMSG_PZ_GET_PZSTATUSUPDATE);
    CHECK(get_i16(p.data[0], 2) == 0x7777);   // OPVoltage
    CHECK(get_i16(p.data[0], 4) == 0x1333);   // Position
    CHECK(get_u32(p.data[0], 6) == 0x00000401);
    // The misprinted length "0E" is a frame of 14 data bytes (the header's length): a reader
    // takes the 10 of the layout and ignores the other 4.
    const auto misprinted = parse_all(unhex("61 06 0E 00 81 50 01 00 77 77 33 13 01 04 00 00 00 00 00 00") + kSentinel, 1);
    REQUIRE(misprinted.frames.size() == 2);
    CHECK(misprinted.data[0].size() == 14);
    CHECK(misprinted.dropped == 0);
    // The OUTPUTLUTPARAMS example's header ("03, 07, 06, 00") over its 30 bytes: a frame of 6 data
    // bytes (the header's length; a unit ignores it as short of the 30 it reads), the other 24 dropped.
    const auto lut = parse_all(unhex("03 07 06 00 D0 01") + std::string(30, '\0') + kSentinel, 1);
    REQUIRE(lut.frames.size() == 2);
    CHECK(lut.frames[0].id == MGMSG_PZ_SET_OUTPUTLUTPARAMS);
    CHECK(lut.data[0].size() == 6);
    CHECK(lut.dropped == 24);
    // Examples printed with an impossible address (p.129: source 0x00; p.118: d and s swapped).
    check_rejected(unhex("DE 07 06 00 D0 00 01 00 52 00 50 00"));
    check_rejected(unhex("51 06 04 00 01 A2 01 00 C8 00"));
}

TEST_CASE("apt message table applies the ERRATA", "[unit][apt][messages]")
{
    struct Expect {
        std::uint16_t id;
        std::string_view name;
        int data_length;
    };
    const std::vector<Expect> expected{
        {0x0002, "MGMSG_HW_DISCONNECT", -1},
        {0x0005, "MGMSG_HW_REQ_INFO", -1},
        {0x0006, "MGMSG_HW_GET_INFO", 84},
        {0x0011, "MGMSG_HW_START_UPDATEMSGS", -1},
        {0x0012, "MGMSG_HW_STOP_UPDATEMSGS", -1},
        {0x0060, "MGMSG_RACK_REQ_BAYUSED", -1},
        {0x0061, "MGMSG_RACK_GET_BAYUSED", -1},
        {0x0226, "MGMSG_RACK_REQ_STATUSBITS", -1},
        {0x0227, "MGMSG_RACK_GET_STATUSBITS", 4},
        {0x0230, "MGMSG_RACK_GET_DIGOUTPUTS", -1},
        {0x0411, "MGMSG_MOT_REQ_POSCOUNTER", -1},
        {0x040A, "MGMSG_MOT_REQ_ENCCOUNTER", -1},
        {0x0413, "MGMSG_MOT_SET_VELPARAMS", 14},
        {0x0414, "MGMSG_MOT_REQ_VELPARAMS", -1},
        {0x0415, "MGMSG_MOT_GET_VELPARAMS", 14},
        {0x0440, "MGMSG_MOT_SET_HOMEPARAMS", 14},
        {0x0441, "MGMSG_MOT_REQ_HOMEPARAMS", -1},
        {0x0442, "MGMSG_MOT_GET_HOMEPARAMS", 14},
        {0x0423, "MGMSG_MOT_SET_LIMSWITCHPARAMS", 16},
        {0x0425, "MGMSG_MOT_GET_LIMSWITCHPARAMS", 16},
        {0x0448, "MGMSG_MOT_MOVE_RELATIVE", 6},
        {0x0453, "MGMSG_MOT_MOVE_ABSOLUTE", 6},
        {0x0464, "MGMSG_MOT_MOVE_COMPLETED", 14},
        {0x0465, "MGMSG_MOT_MOVE_STOP", -1},
        {0x0466, "MGMSG_MOT_MOVE_STOPPED", 14},
        {0x04A0, "MGMSG_MOT_SET_DCPIDPARAMS", 20},
        {0x04A1, "MGMSG_MOT_REQ_DCPIDPARAMS", -1},
        {0x04A2, "MGMSG_MOT_GET_DCPIDPARAMS", 20},
        {0x04B4, "MGMSG_MOT_REQ_AVMODES", -1},
        {0x04B1, "MGMSG_MOT_REQ_POTPARAMS", -1},
        {0x04B2, "MGMSG_MOT_GET_POTPARAMS", 26},
        {0x04B6, "MGMSG_MOT_SET_BUTTONPARAMS", 16},
        {0x04B7, "MGMSG_MOT_REQ_BUTTONPARAMS", -1},
        {0x04B8, "MGMSG_MOT_GET_BUTTONPARAMS", 16},
        {0x04E2, "MGMSG_MOT_GET_PMDTRACKSETTLEPARAMS", 12},
        {0x04D5, "MGMSG_MOT_REQ_PMDCURRENTLOOPPARAMS", -1},
        {0x04EA, "MGMSG_MOT_REQ_PMDSETTLEDCURRENTLOOPPARAMS", -1},
        {0x04F2, "MGMSG_MOT_GET_PMDSTAGEAXISPARAMS", 74},
        {0x0480, "MGMSG_MOT_REQ_STATUSUPDATE", -1},
        {0x0481, "MGMSG_MOT_GET_STATUSUPDATE", 14},
        {0x0491, "MGMSG_MOT_GET_DCSTATUSUPDATE", 14},
        {0x0492, "MGMSG_MOT_ACK_DCSTATUSUPDATE", -1},
        {0x0686, "MGMSG_MOT_SET_PZSTAGEPARAMDEFAULTS", -1},
    };
    for (const auto& e : expected) {
        INFO(e.name);
        const auto* m = find_message(e.id);
        REQUIRE(m != nullptr);
        CHECK(m->name == e.name);
        CHECK(m->data_length == e.data_length);
    }
    CHECK(MGMSG_HW_STOP_UPDATEMSGS == 0x0012);
    CHECK(MGMSG_MOT_SET_VELPARAMS == 0x0413);
    CHECK(MGMSG_MOT_SET_HOMEPARAMS == 0x0440);
}

TEST_CASE("apt message table flags the short forms and the later-issue messages", "[unit][apt][messages]")
{
    std::vector<std::string_view> short_forms;
    std::vector<std::string_view> later;
    for (const auto& m : all_messages()) {
        if (m.header_only_allowed)
            short_forms.push_back(m.name);
        if (m.later_issue)
            later.push_back(m.name);
    }
    CHECK(short_forms == std::vector<std::string_view>{"MGMSG_MOT_MOVE_RELATIVE", "MGMSG_MOT_MOVE_ABSOLUTE"});
    CHECK(later == std::vector<std::string_view>{
                       "MGMSG_HW_YES_FLASH_PROGRAMMING", "MGMSG_HW_NO_FLASH_PROGRAMMING", "MGMSG_MOT_SET_POWERPARAMS",
                       "MGMSG_MOT_REQ_POWERPARAMS", "MGMSG_MOT_GET_POWERPARAMS", "MGMSG_MOT_SET_TSTACTUATORTYPE",
                       "MGMSG_MOT_SET_TRIGGER", "MGMSG_MOT_REQ_TRIGGER", "MGMSG_MOT_GET_TRIGGER",
                       "MGMSG_MOT_SET_KCUBEMMIPARAMS", "MGMSG_MOT_REQ_KCUBEMMIPARAMS", "MGMSG_MOT_GET_KCUBEMMIPARAMS",
                       "MGMSG_MOT_SET_KCUBETRIGIOCONFIG", "MGMSG_MOT_REQ_KCUBETRIGIOCONFIG",
                       "MGMSG_MOT_GET_KCUBETRIGIOCONFIG", "MGMSG_MOT_SET_KCUBEPOSTRIGPARAMS",
                       "MGMSG_MOT_REQ_KCUBEPOSTRIGPARAMS", "MGMSG_MOT_GET_KCUBEPOSTRIGPARAMS",
                       "MGMSG_MOT_SET_KCUBEKSTLOOPPARAMS", "MGMSG_MOT_REQ_KCUBEKSTLOOPPARAMS",
                       "MGMSG_MOT_GET_KCUBEKSTLOOPPARAMS",
                       // The K-Cube piezo driver's and strain gauge reader's own (codec_kcube_units.hpp).
                       "MGMSG_PZ_REQ_PZSTATUSUPDATE", "MGMSG_KPZ_SET_KCUBEMMIPARAMS", "MGMSG_KPZ_REQ_KCUBEMMIPARAMS",
                       "MGMSG_KPZ_GET_KCUBEMMIPARAMS", "MGMSG_KPZ_SET_KCUBETRIGIOCONFIG",
                       "MGMSG_KPZ_REQ_KCUBETRIGIOCONFIG", "MGMSG_KPZ_GET_KCUBETRIGIOCONFIG",
                       "MGMSG_KSG_SET_KCUBEMMIPARAMS", "MGMSG_KSG_REQ_KCUBEMMIPARAMS", "MGMSG_KSG_GET_KCUBEMMIPARAMS",
                       "MGMSG_KSG_SET_KCUBETRIGIOCONFIG", "MGMSG_KSG_REQ_KCUBETRIGIOCONFIG",
                       "MGMSG_KSG_GET_KCUBETRIGIOCONFIG",
                       // The MFF101/MFF102 flip mount's (issue 28).
                       "MGMSG_MOT_SET_MFF_OPERPARAMS", "MGMSG_MOT_REQ_MFF_OPERPARAMS", "MGMSG_MOT_GET_MFF_OPERPARAMS",
                       // The MPC320/MPC220 polarisation controllers' (issue 28).
                       "MGMSG_MOT_SET_POLPARAMS", "MGMSG_MOT_REQ_POLPARAMS", "MGMSG_MOT_GET_POLPARAMS",
                       // The KIM101/TIM101 piezo motor controllers' (issue 28).
                       "MGMSG_PZMOT_SET_PARAMS", "MGMSG_PZMOT_REQ_PARAMS", "MGMSG_PZMOT_GET_PARAMS",
                       "MGMSG_PZMOT_MOVE_ABSOLUTE", "MGMSG_PZMOT_MOVE_COMPLETED", "MGMSG_PZMOT_MOVE_JOG",
                       "MGMSG_PZMOT_REQ_STATUSUPDATE", "MGMSG_PZMOT_GET_STATUSUPDATE",
                       "MGMSG_PZMOT_ACK_STATUSUPDATE"});
    CHECK(find_message(MGMSG_HW_NO_FLASH_PROGRAMMING)->header_only());
    CHECK(find_message(MGMSG_HW_YES_FLASH_PROGRAMMING)->header_only());
    CHECK(find_message(MGMSG_MOT_MOVE_JOG)->header_only());
    CHECK(find_message(MGMSG_MOT_MOVE_VELOCITY)->header_only());
}

TEST_CASE("every apt message round-trips through encode and the framer", "[unit][apt][messages]")
{
    for (const auto& m : all_messages()) {
        INFO(m.name);
        std::string data;
        if (!m.header_only())
            for (int k = 0; k < m.data_length; ++k)
                data.push_back(static_cast<char>(k * 37 + 11));

        // Every destination and source of section 4.
        std::string stream;
        for (auto dest : kAddresses)
            for (auto source : kAddresses)
                stream += m.header_only() ? encode_header_only(m.id, 0x01, 0x02, dest, source)
                                          : encode_with_data(m.id, dest, source, data);
        const auto p = parse_all(stream, stream.size());
        REQUIRE(p.frames.size() == kAddresses.size() * kAddresses.size());
        CHECK(p.dropped == 0);
        CHECK(p.buffered == 0);
        std::size_t n = 0;
        for (auto dest : kAddresses) {
            for (auto source : kAddresses) {
                const Frame& f = p.frames[n];
                CHECK(f.id == m.id);
                CHECK(f.info == &m);
                CHECK(f.dest == dest);
                CHECK(f.source == source);
                CHECK(f.has_data == !m.header_only());
                CHECK(f.param1 == (m.header_only() ? 0x01 : 0));
                CHECK(f.param2 == (m.header_only() ? 0x02 : 0));
                CHECK(p.data[n] == data);
                ++n;
            }
        }

        // Byte-wise too (the frame is assembled inside the framer).
        const std::string one = m.header_only() ? encode_header_only(m.id, 0x7F, 0xFF, kGenericUsb, kHost)
                                                : encode_with_data(m.id, kHost, kGenericUsb, data);
        const auto b = parse_all(one, 1);
        REQUIRE(b.frames.size() == 1);
        CHECK(b.frames[0].id == m.id);
        CHECK(b.data[0] == data);

        // The other form is no frame, except where the table lists both.
        if (m.header_only()) {
            check_rejected(encode_with_data(m.id, kGenericUsb, kHost, std::string(6, '\0')));
            check_rejected(encode_with_data(m.id, kGenericUsb, kHost, ""));
        } else {
            const std::string short_form = encode_header_only(m.id, 0x01, 0x00, kGenericUsb, kHost);
            if (m.header_only_allowed) {
                const auto s = parse_all(short_form, 1);
                REQUIRE(s.frames.size() == 1);
                CHECK_FALSE(s.frames[0].has_data);
                CHECK(s.frames[0].param1 == 0x01);
            } else {
                check_rejected(short_form);
            }
            // One byte short of the layout, one byte past it, 255 bytes: frames (the unit judges
            // their length); 256 is none.
            const auto length = static_cast<std::size_t>(m.data_length);
            for (const std::size_t n : {length - 1, length + 1, kMaxDataLength}) {
                if (n > kMaxDataLength)   // one short of an empty layout
                    continue;
                INFO(n << " data bytes");
                const auto s = parse_all(encode_with_data(m.id, kGenericUsb, kHost, std::string(n, '\0')), 1);
                REQUIRE(s.frames.size() == 1);
                CHECK(s.data[0].size() == n);
                CHECK(s.dropped == 0);
            }
            std::string too_long = encode_with_data(m.id, kGenericUsb, kHost, std::string(kMaxDataLength, '\0'));
            too_long[2] = 0x00;   // length 0x0100
            too_long[3] = 0x01;
            check_rejected(too_long + '\0');
        }
    }
}

TEST_CASE("apt wire helpers are little-endian", "[unit][apt][messages]")
{
    std::string out;
    put_u16(out, 0x3039);
    put_i32(out, 123456789);
    put_i32(out, -2);
    put_u32(out, 0x80000000u);
    put_i16(out, -32768);
    CHECK(hex(out) == "39 30 15 CD 5B 07 FE FF FF FF 00 00 00 80 00 80");   // section 6's examples
    CHECK(get_u16(out, 0) == 0x3039);
    CHECK(get_i32(out, 2) == 123456789);
    CHECK(get_i32(out, 6) == -2);
    CHECK(get_u32(out, 10) == 0x80000000u);
    CHECK(get_i16(out, 14) == -32768);
    CHECK(get_u8(out, 1) == 0x30);
    CHECK(hex(encode_header_only(MGMSG_HW_REQ_INFO, 0, 0, kGenericUsb, kHost)) == "05 00 00 00 50 01");
    CHECK(hex(encode_with_data(MGMSG_MOT_MOVE_ABSOLUTE, kBay0 + 1, kHost, unhex("01 00 40 0D 03 00")))
          == "53 04 06 00 A2 01 01 00 40 0D 03 00");
    CHECK(is_valid_address(0x2A));
    CHECK_FALSE(is_valid_address(0x2B));
    CHECK_FALSE(is_valid_address(0x00));
    CHECK_FALSE(is_valid_address(0x81));
}

TEST_CASE("apt manual examples decode as documented", "[unit][apt][messages]")
{
    struct Example {
        const char* where;
        std::string bytes;
        std::uint16_t id;
        std::uint8_t dest, source;
        std::string params_or_data;   // "p1 p2" for header-only frames, else the data packet
    };
    const std::vector<Example> examples{
        {"MOD_IDENTIFY p.16", "23 02 00 00 21 01", 0x0223, 0x21, 0x01, "00 00"},
        {"MOD_SET_CHANENABLESTATE p.17", "10 02 01 01 22 01", 0x0210, 0x22, 0x01, "01 01"},
        {"HW_RESPONSE p.19", "80 00 00 00 01 11", 0x0080, 0x01, 0x11, "00 00"},
        {"HW_REQ_INFO p.21", "05 00 00 00 11 01", 0x0005, 0x11, 0x01, "00 00"},
        {"HW_REQ_INFO to a USB unit", "05 00 00 00 50 01", 0x0005, 0x50, 0x01, "00 00"},
        {"HUB_REQ_BAYUSED p.24", "65 00 00 00 50 01", 0x0065, 0x50, 0x01, "00 00"},
        {"HUB_GET_BAYUSED p.24", "66 00 06 00 01 50", 0x0066, 0x01, 0x50, "06 00"},
        {"RACK_SET_DIGOUTPUTS p.26", "28 02 01 22 11 01", 0x0228, 0x11, 0x01, "01 22"},
        {"MOT_SET_POSCOUNTER p.28", "10 04 06 00 A2 01 01 00 04 0D 03 00", 0x0410, 0x22, 0x01,
         "01 00 04 0D 03 00"},
        {"MOT_SET_ENCCOUNTER p.29", "09 04 06 00 A2 01 01 00 04 0D 03 00", 0x0409, 0x22, 0x01,
         "01 00 04 0D 03 00"},
        {"MOT_SET_VELPARAMS p.30", "13 04 0E 00 A2 01 01 00 00 00 00 00 B0 35 00 00 CD CC CC 00", 0x0413,
         0x22, 0x01, "01 00 00 00 00 00 B0 35 00 00 CD CC CC 00"},
        {"MOT_SET_JOGPARAMS p.33",
         "16 04 16 00 A2 01 01 00 01 00 E8 03 00 00 00 00 00 00 B0 35 00 00 CD CC CC 00 02 00", 0x0416, 0x22,
         0x01, "01 00 01 00 E8 03 00 00 00 00 00 00 B0 35 00 00 CD CC CC 00 02 00"},
        {"MOT_SET_GENMOVEPARAMS p.34", "3A 04 06 00 A2 01 01 00 20 4E 00 00", 0x043A, 0x22, 0x01,
         "01 00 20 4E 00 00"},
        {"MOT_SET_MOVERELPARAMS p.35", "45 04 06 00 A2 01 01 00 40 0D 03 00", 0x0445, 0x22, 0x01,
         "01 00 40 0D 03 00"},
        {"MOT_SET_MOVEABSPARAMS p.36", "50 04 06 00 A2 01 01 00 40 0D 03 00", 0x0450, 0x22, 0x01,
         "01 00 40 0D 03 00"},
        {"MOT_SET_LIMSWITCHPARAMS p.40", "23 04 10 00 A2 01 01 00 02 00 02 00 E8 CC CC 00 00 00 00 00 03 00",
         0x0423, 0x22, 0x01, "01 00 02 00 02 00 E8 CC CC 00 00 00 00 00 03 00"},
        {"MOT_MOVE_HOME p.41", "43 04 01 00 22 01", 0x0443, 0x22, 0x01, "01 00"},
        {"MOT_MOVE_HOMED p.41", "44 04 01 00 01 22", 0x0444, 0x01, 0x22, "01 00"},
        {"MOT_MOVE_RELATIVE short p.42", "48 04 01 00 22 01", 0x0448, 0x22, 0x01, "01 00"},
        {"MOT_MOVE_RELATIVE long p.43", "48 04 06 00 A2 01 01 00 40 0D 03 00", 0x0448, 0x22, 0x01,
         "01 00 40 0D 03 00"},
        {"MOT_MOVE_ABSOLUTE short p.45", "53 04 01 00 22 01", 0x0453, 0x22, 0x01, "01 00"},
        {"MOT_MOVE_ABSOLUTE long p.46", "53 04 06 00 A2 01 01 00 40 0D 03 00", 0x0453, 0x22, 0x01,
         "01 00 40 0D 03 00"},
        {"MOT_MOVE_VELOCITY p.48", "57 04 01 01 22 01", 0x0457, 0x22, 0x01, "01 01"},
        {"MOT_SET_AVMODES p.53", "B3 04 04 00 D0 01 01 00 09 00", 0x04B3, 0x50, 0x01, "01 00 09 00"},
        {"MOT_SET_EEPROMPARAMS p.60", "B9 04 04 00 D0 01 01 00 B6 04", 0x04B9, 0x50, 0x01, "01 00 B6 04"},
        {"MOT_SET_PMDMOTOROUTPUTPARAMS p.65", "DA 04 0E 00 A2 01 01 00 99 19 C0 12 00 00 00 00 00 00 00 00",
         0x04DA, 0x22, 0x01, "01 00 99 19 C0 12 00 00 00 00 00 00 00 00"},
        {"MOT_SET_PMDPROFILEMODEPARAMS p.70", "E3 04 0C 00 A2 01 01 00 02 00 E1 12 0E 00 00 00 00 00", 0x04E3,
         0x22, 0x01, "01 00 02 00 E1 12 0E 00 00 00 00 00"},
        {"MOT_SET_PMDCURRENTLOOPPARAMS p.72",
         "D4 04 12 00 A2 01 01 00 02 00 23 00 50 00 FF 7F 32 00 00 00 00 00 00 00", 0x04D4, 0x22, 0x01,
         "01 00 02 00 23 00 50 00 FF 7F 32 00 00 00 00 00 00 00"},
        {"MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS p.74",
         "E9 04 12 00 A2 01 01 00 02 00 00 00 28 00 30 75 32 00 F4 01 00 00 00 00", 0x04E9, 0x22, 0x01,
         "01 00 02 00 00 00 28 00 30 75 32 00 F4 01 00 00 00 00"},
        {"MOT_ACK_DCSTATUSUPDATE p.80", "92 04 00 00 21 01", 0x0492, 0x21, 0x01, "00 00"},
        {"MOT_SET_SOL_OPERATINGMODE p.85", "C0 04 01 02 50 01", 0x04C0, 0x50, 0x01, "01 02"},
        {"MOT_REQ_SOL_OPERATINGMODE p.86", "C1 04 01 00 50 01", 0x04C1, 0x50, 0x01, "01 00"},
        {"MOT_GET_SOL_OPERATINGMODE p.86", "C2 04 01 01 01 50", 0x04C2, 0x01, 0x50, "01 01"},
        {"MOT_SET_SOL_CYCLEPARAMS p.87", "C3 04 0E 00 D0 01 01 00 A0 0F 00 00 A0 0F 00 00 14 00 00 00",
         0x04C3, 0x50, 0x01, "01 00 A0 0F 00 00 A0 0F 00 00 14 00 00 00"},
        {"MOT_SET_SOL_INTERLOCKMODE p.89", "C6 04 01 01 50 01", 0x04C6, 0x50, 0x01, "01 01"},
        {"MOT_REQ_SOL_INTERLOCKMODE p.90", "C7 04 01 00 50 01", 0x04C7, 0x50, 0x01, "01 00"},
        {"MOT_GET_SOL_INTERLOCKMODE p.90", "C8 04 01 01 01 50", 0x04C8, 0x01, 0x50, "01 01"},
        {"MOT_SET_SOL_STATE p.91", "CB 04 01 01 50 01", 0x04CB, 0x50, 0x01, "01 01"},
        {"MOT_REQ_SOL_STATE p.92", "CC 04 01 00 50 01", 0x04CC, 0x50, 0x01, "01 00"},
        {"MOT_GET_SOL_STATE p.92", "CD 04 01 01 01 50", 0x04CD, 0x01, 0x50, "01 01"},
        {"PZ_SET_POSCONTROLMODE p.94", "40 06 01 02 50 01", 0x0640, 0x50, 0x01, "01 02"},
        {"PZ_REQ_POSCONTROLMODE p.94", "41 06 01 00 50 01", 0x0641, 0x50, 0x01, "01 00"},
        {"PZ_GET_POSCONTROLMODE p.95", "42 06 01 02 01 50", 0x0642, 0x01, 0x50, "01 02"},
        {"PZ_SET_OUTPUTVOLTS p.96", "43 06 04 00 D0 01 01 00 77 77", 0x0643, 0x50, 0x01, "01 00 77 77"},
        {"PZ_SET_OUTPUTPOS p.97", "46 06 04 00 D0 01 01 00 66 26", 0x0646, 0x50, 0x01, "01 00 66 26"},
        {"PZ_SET_INPUTVOLTSSRC p.98", "52 06 04 00 D0 01 01 00 02 00", 0x0652, 0x50, 0x01, "01 00 02 00"},
        {"PZ_SET_PICONSTS p.100", "55 06 06 00 D0 01 01 00 64 00 0F 00", 0x0655, 0x50, 0x01,
         "01 00 64 00 0F 00"},
        {"PZ_ACK_PZSTATUSUPDATE p.105", "62 06 00 00 50 01", 0x0662, 0x50, 0x01, "00 00"},
        {"PZ_SET_OUTPUTLUT p.107", "00 07 06 00 D0 01 01 00 02 00 88 08", 0x0700, 0x50, 0x01,
         "01 00 02 00 88 08"},
        {"PZ_SET_EEPROMPARAMS p.113", "D0 07 04 00 D0 01 01 00 03 07", 0x07D0, 0x50, 0x01, "01 00 03 07"},
        {"PZ_SET_TPZ_DISPSETTINGS p.114", "D1 07 02 00 D0 01 64 00", 0x07D1, 0x50, 0x01, "64 00"},
        {"PZ_REQ_TPZ_DISPSETTINGS p.114", "D2 07 01 00 50 01", 0x07D2, 0x50, 0x01, "01 00"},
        {"PZ_REQ_MAXTRAVEL p.118", "50 06 01 00 22 01", 0x0650, 0x22, 0x01, "01 00"},
        {"PZ_GET_MAXTRAVEL p.118 (header as explained; the TX line swaps d and s)", "51 06 04 00 A2 01 01 00 C8 00", 0x0651, 0x22, 0x01, "01 00 C8 00"},
        {"PZ_SET_OUTPUTMAXVOLTS p.121", "80 06 06 00 D0 01 01 00 E8 03 08 00", 0x0680, 0x50, 0x01,
         "01 00 E8 03 08 00"},
        {"PZ_GET_OUTPUTMAXVOLTS p.122", "82 06 06 00 D0 01 01 00 E8 03 08 00", 0x0682, 0x50, 0x01,
         "01 00 E8 03 08 00"},
        {"PZ_SET_TPZ_SLEWRATES p.123", "83 06 06 00 D0 01 01 00 F2 04 F2 04", 0x0683, 0x50, 0x01,
         "01 00 F2 04 F2 04"},
        {"PZ_SET_LUTVALUETYPE p.126", "08 07 01 00 50 01", 0x0708, 0x50, 0x01, "01 00"},
        {"PZ_GET_TSG_READING p.129 (source 0x01 as its explanation says)", "DE 07 06 00 D0 01 01 00 52 00 50 00",
         0x07DE, 0x50, 0x01, "01 00 52 00 50 00"},
        {"HW_NO_FLASH_PROGRAMMING later issues", "18 00 00 00 50 01", 0x0018, 0x50, 0x01, "00 00"},
    };
    std::string all;
    for (const auto& e : examples) {
        INFO(e.where);
        const std::string in = unhex(e.bytes);
        all += in;
        for (std::size_t chunk : {1u, 100u}) {
            const auto p = parse_all(in, chunk);
            REQUIRE(p.frames.size() == 1);
            const Frame& f = p.frames[0];
            CHECK(f.id == e.id);
            CHECK(f.dest == e.dest);
            CHECK(f.source == e.source);
            CHECK(p.dropped == 0);
            if (f.has_data) {
                CHECK(hex(p.data[0]) == e.params_or_data);
            } else {
                char params[8];
                std::snprintf(params, sizeof params, "%02X %02X", f.param1, f.param2);
                CHECK(std::string(params) == e.params_or_data);
            }
        }
    }
    // All of them back to back: one frame each.
    const auto p = parse_all(all, 7);
    CHECK(p.frames.size() == examples.size());
    CHECK(p.dropped == 0);
}

TEST_CASE("apt manual example fields decode as explained", "[unit][apt][messages]")
{
    // MOVE_ABSOLUTE long form (p.46): chan 1, 10 mm = 200,000 counts.
    auto p = parse_all(unhex("53 04 06 00 A2 01 01 00 40 0D 03 00"), 5);
    REQUIRE(p.frames.size() == 1);
    CHECK(get_u16(p.data[0], 0) == 1);
    CHECK(get_i32(p.data[0], 2) == 200000);

    // SET_VELPARAMS (p.30): acceleration 13744, max velocity 13421773 (99 mm/s).
    p = parse_all(unhex("13 04 0E 00 A2 01 01 00 00 00 00 00 B0 35 00 00 CD CC CC 00"), 3);
    REQUIRE(p.frames.size() == 1);
    CHECK(get_i32(p.data[0], 2) == 0);
    CHECK(get_i32(p.data[0], 6) == 13744);
    CHECK(get_i32(p.data[0], 10) == 13421773);

    // HW_GET_INFO (p.22), the example completed with the zeros its "00..." stands for.
    std::string info = unhex("89 53 9A 05 49 4F 4E 30 30 31 20 00 2C 00 02 01 39 00");
    info += "Brushless DC Motor ION Drive";
    info.resize(76, '\0');
    info += unhex("11 00 01 00 00 00 01 00");
    REQUIRE(info.size() == 84);
    const std::string message = unhex("06 00 54 00 81 22") + info;
    for (std::size_t chunk : {1u, 13u, 90u}) {
        p = parse_all(message, chunk);
        REQUIRE(p.frames.size() == 1);
        const Frame& f = p.frames[0];
        CHECK(f.id == MGMSG_HW_GET_INFO);
        CHECK(f.dest == kHost);
        CHECK(f.source == 0x22);   // "Motor Channel 2": bay 1
        CHECK(get_u32(p.data[0], 0) == 94000009);
        CHECK(p.data[0].substr(4, 6) == "ION001");
        CHECK(get_u16(p.data[0], 12) == 44);   // brushless DC controller card
        CHECK(get_u32(p.data[0], 14) == 3735810);
        CHECK(p.data[0].substr(18, 28) == "Brushless DC Motor ION Drive");
        CHECK(get_u16(p.data[0], 82) == 1);   // one channel
    }
}

TEST_CASE("apt manual examples that the ERRATA correct", "[unit][apt][messages]")
{
    SECTION("RACK_REQ_BAYUSED printed as 06 00 (p.23) is rejected and 60 00 decodes")
    {
        check_rejected(unhex("06 00 00 00 11 01"));
        const auto p = parse_all(unhex("60 00 00 00 11 01"), 1);
        REQUIRE(p.frames.size() == 1);
        CHECK(p.frames[0].id == MGMSG_RACK_REQ_BAYUSED);
    }
    SECTION("RACK_GET_STATUSBITS without the data flag (p.25) is rejected")
    {
        check_rejected(unhex("27 02 04 00 01 22 00 00 00 00"));
        const auto p = parse_all(unhex("27 02 04 00 81 22 01 00 00 00"), 1);
        REQUIRE(p.frames.size() == 1);
        CHECK(p.frames[0].id == MGMSG_RACK_GET_STATUSBITS);
        CHECK(get_u32(p.data[0], 0) == 1);
    }
    SECTION("HW_DISCONNECT from source 0x00 (p.19) is rejected")
    {
        check_rejected(unhex("02 00 00 00 11 00"));
        const auto p = parse_all(unhex("02 00 00 00 11 01"), 1);
        REQUIRE(p.frames.size() == 1);
        CHECK(p.frames[0].id == MGMSG_HW_DISCONNECT);
    }
    SECTION("the DCPIDPARAMS example (p.52) is 6 bytes short of its 20-byte packet")
    {
        const auto p = parse_all(unhex("A0 04 14 00 D0 01 01 00 41 00 AF 00 58 02 20 4E 00 00 0F 00"), 1);
        CHECK(p.frames.empty());
        CHECK(p.buffered == 20);
        std::string full;
        put_u16(full, 1);
        for (std::int32_t v : {65, 175, 600, 20000})
            put_i32(full, v);
        put_u16(full, 15);
        const auto q = parse_all(encode_with_data(MGMSG_MOT_SET_DCPIDPARAMS, kGenericUsb, kHost, full), 1);
        REQUIRE(q.frames.size() == 1);
        CHECK(get_i32(q.data[0], 14) == 20000);
    }
    SECTION("the PMDPOSITIONLOOPPARAMS example (p.62) is 2 bytes short of its 28-byte packet")
    {
        const std::string example = unhex("D7 04 1C 00 A2 01 01 00 41 00 AF 00 80 38 01 00 58 02 05 00 "
                                          "CD 0C 00 00 E8 03 FF FF 00 00 00 00");
        auto p = parse_all(example, 1);
        CHECK(p.frames.empty());
        CHECK(p.buffered == 32);
        p = parse_all(example + unhex("00 00"), 1);
        REQUIRE(p.frames.size() == 1);
        CHECK(get_u16(p.data[0], 4) == 175);     // Ki
        CHECK(get_u32(p.data[0], 6) == 80000);   // integral limit
        CHECK(get_u32(p.data[0], 20) == 65535);  // position error limit
    }
    SECTION("the BUTTONPARAMS example (p.59) is 2 bytes short of its 16-byte packet")
    {
        const auto p = parse_all(unhex("B6 04 10 00 D0 01 01 00 02 00 C0 12 00 00 00 00 00 00 00 00"), 1);
        CHECK(p.frames.empty());
        CHECK(p.buffered == 20);
    }
    SECTION("the TRACKSETTLEPARAMS example (p.67) has 2 bytes past its 12-byte packet")
    {
        const auto p = parse_all(unhex("E0 04 0C 00 A2 01 01 00 00 00 14 00 00 00 00 00 00 00 00 00"), 1);
        REQUIRE(p.frames.size() == 1);
        CHECK(p.frames[0].id == MGMSG_MOT_SET_PMDTRACKSETTLEPARAMS);
        CHECK(get_u16(p.data[0], 4) == 20);   // settle window
        CHECK(p.dropped == 1);    // 0x0000 is no message
        CHECK(p.buffered == 1);   // a lone byte may still start a header
    }
    SECTION("MOVE_COMPLETED and MOVE_STOPPED carry the 14-byte status")
    {
        std::string status;
        put_u16(status, 1);
        put_i32(status, 200000);
        put_u16(status, 0);
        put_u16(status, 0);
        put_u32(status, 0x80000400u);
        for (auto id : {MGMSG_MOT_MOVE_COMPLETED, MGMSG_MOT_MOVE_STOPPED}) {
            const auto p = parse_all(encode_with_data(id, kHost, kGenericUsb, status), 1);
            REQUIRE(p.frames.size() == 1);
            CHECK(p.frames[0].id == id);
            CHECK(get_u32(p.data[0], 10) == 0x80000400u);
            check_rejected(encode_header_only(id, 0x01, 0x00, kHost, kGenericUsb));
        }
    }
}

TEST_CASE("messages: each takes list's IDs are the lines of messages.def that name it, in the table's order",
          "[unit][apt][messages]")
{
    auto scanned = [](TakesLists list) {
        std::vector<std::uint16_t> ids;
        for (const auto& m : messages_detail::kListed)
            if ((m.lists & list) != 0)
                ids.push_back(m.id);
        return ids;
    };
    auto derived = [](const auto& ids) { return std::vector<std::uint16_t>(ids.begin(), ids.end()); };
    CHECK(derived(kIdsOnList<kTsc>) == scanned(kTsc));
    CHECK(derived(kIdsOnList<kTpz>) == scanned(kTpz));
    CHECK(derived(kIdsOnList<kBpc>) == scanned(kBpc));
    CHECK(derived(kIdsOnList<kTsg>) == scanned(kTsg));
    CHECK(derived(kIdsOnList<kKscLater>) == scanned(kKscLater));
    CHECK(derived(kIdsOnList<kKpzLater>) == scanned(kKpzLater));
    CHECK(derived(kIdsOnList<kKsgLater>) == scanned(kKsgLater));
    CHECK(derived(kIdsOnList<kTCubeLater>) == scanned(kTCubeLater));
    CHECK(kIdsOnList<kTsc>.size() == 21);
    CHECK(kIdsOnList<kTpz>.size() == 37);
    CHECK(kIdsOnList<kBpc>.size() == 37);
    CHECK(kIdsOnList<kTsg>.size() == 14);
    CHECK(kIdsOnList<kKscLater>.size() == 9);
    CHECK(kIdsOnList<kKpzLater>.size() == 7);
    CHECK(kIdsOnList<kKsgLater>.size() == 7);
    CHECK(kIdsOnList<kTCubeLater>.size() == 1);
    // One line per message of the table, in its order; no generic message is on a list (the shell's).
    REQUIRE(std::size(messages_detail::kListed) == all_messages().size());
    for (std::size_t i = 0; i < all_messages().size(); ++i) {
        CHECK(messages_detail::kListed[i].id == all_messages()[i].id);
        if (all_messages()[i].group == Group::Generic)
            CHECK(messages_detail::kListed[i].lists == 0);
    }
}

} // namespace test_messages
