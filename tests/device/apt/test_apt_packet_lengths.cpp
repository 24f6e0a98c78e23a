// Data packets of another length than the table's layout (frame_framer.hpp, messages.hpp
// fields_length): the public clients' SETs of the later K-Cube blocks without their reserved
// tails are acted on, as their REQs are answered; a SET short of the fields the unit reads is
// ignored, and the wire log says so; a longer one is acted on, its tail ignored and noted
// (docs/protocol/apt.md "Framing and bad input").
#include "apt_harness.hpp"

#include <string>
#include <vector>

namespace test_apt_packet_lengths {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;

namespace {

DeviceConfig later(DeviceConfig c)
{
    c.firmware = "issue-44.1";
    config_of(c).firmware = Firmware::Issue44_1;
    return c;
}

/// A single unit `model` without a stage (solenoid, piezo) of the later generation.
DeviceConfig later_unit(const std::string& model)
{
    DeviceConfig c;
    c.name = "unit";
    c.protocol = "apt";
    c.model = model;
    config_of(c).solenoid.interlock_fitted = true;
    return later(c);
}

/// The notes of the wire log's last inbound entry.
std::vector<std::string> last_inbound_notes(AptDevice& d)
{
    const auto log = d.wire_log().to_json(d.wire_log().size());
    for (auto it = log.rbegin(); it != log.rend(); ++it)
        if ((*it)["direction"] == "in")
            return (*it)["notes"].get<std::vector<std::string>>();
    return {};
}

const std::string kTwelveZeros = " 00 00 00 00 00 00 00 00 00 00 00 00";

} // namespace

TEST_CASE("apt KDC101 issue-44.1 takes pyLabLib's 10-byte KCUBETRIGIOCONFIG and 34-byte KCUBEPOSTRIGPARAMS",
          "[device][apt][kcube][lengths]")
{
    AptHarness h(later(apt_cube("KDC101", "Z825B")));
    // pyLabLib kinesis.py _setup_kcube_trigio: "<HHHHH", TRIG1 out_gpio (0x0A) high, TRIG2
    // out_in_motion (0x0B) low.
    CHECK(h.send("23 05 0A 00 D0 01 01 00 0A 00 01 00 0B 00 02 00") == "");
    CHECK(last_inbound_notes(h.device()).empty());
    // Answered in the table's layout, the reserved tail zero: what pyLabLib reads back (data[2:10]).
    CHECK(h.send("24 05 01 00 50 01") == "25 05 16 00 81 50 01 00 0A 00 01 00 0B 00 02 00" + kTwelveZeros);
    // _setup_kcube_trigpos: "<Hiiiiiiii" (34 bytes): start 1000 fwd, 500 apart, 3 pulses; 2000
    // rev, 250 apart, 2; width 100 us, 4 cycles.
    const std::string pos = "01 00 E8 03 00 00 F4 01 00 00 03 00 00 00 D0 07 00 00 FA 00 00 00 02 00 00 00 "
                            "64 00 00 00 04 00 00 00";
    CHECK(h.send("26 05 22 00 D0 01 " + pos) == "");
    CHECK(h.send("27 05 01 00 50 01") == "28 05 2E 00 81 50 " + pos + kTwelveZeros);
    // The saved form is the table's layout: MOT_SET_EEPROMPARAMS then a power cycle restores it.
    StateStore store;
    AptHarness s(later(apt_cube("KDC101", "Z825B")), &store);
    CHECK(s.send("23 05 0A 00 D0 01 01 00 0A 00 01 00 0B 00 02 00") == "");
    CHECK(s.send("B9 04 04 00 D0 01 01 00 23 05") == "");
    s.device().power_cycle(PowerCycle{true, false});
    CHECK(s.send("24 05 01 00 50 01") == "25 05 16 00 81 50 01 00 0A 00 01 00 0B 00 02 00" + kTwelveZeros);
}

TEST_CASE("apt yaq's and quantumion's K-Cube SETs: the fields the unit reads are taken, a shorter SET is ignored and noted",
          "[device][apt][kcube][lengths]")
{
    AptHarness h(later(apt_cube("KDC101", "Z825B")));
    // yaq mot_set_kcubetrigioconfig, "<6H" (12 bytes), and quantumion kdc.py, "<HHHHHQH" (20).
    CHECK(h.send("23 05 0C 00 D0 01 01 00 01 00 01 00 0A 00 02 00 00 00") == "");
    CHECK(h.send("24 05 01 00 50 01") == "25 05 16 00 81 50 01 00 01 00 01 00 0A 00 02 00" + kTwelveZeros);
    CHECK(h.send("23 05 14 00 D0 01 01 00 0A 00 02 00 01 00 01 00 00 00 00 00 00 00 00 00 00 00") == "");
    CHECK(h.send("24 05 01 00 50 01") == "25 05 16 00 81 50 01 00 0A 00 02 00 01 00 01 00" + kTwelveZeros);
    // yaq mot_set_kcubemmiparams, "<HHllHll3H" (28 bytes), stops at DispDimLevel: a KDC101 reads
    // PresetPos3 and JSSensitivity too (34), so the SET is ignored, and the log says why.
    const std::string power_up = h.send("21 05 01 00 50 01");
    CHECK(h.send("20 05 1C 00 D0 01 01 00 02 00 00 08 00 00 00 01 00 00 01 00 00 00 00 00 00 00 00 00 "
                 "32 00 05 00 02 00") == "");
    const auto notes = last_inbound_notes(h.device());
    REQUIRE(notes.size() == 1);
    CHECK(notes[0] == "ignored by the unit: MGMSG_MOT_SET_KCUBEMMIPARAMS with 28 data byte(s), short of the 34 a "
                      "KDC101 reads: ignored");
    CHECK(h.send("21 05 01 00 50 01") == power_up);
    // A TRIGIOCONFIG without TRIG2's polarity (8 bytes) is short of the 10 every unit reads.
    CHECK(h.send("23 05 08 00 D0 01 01 00 00 00 01 00 00 00") == "");
    CHECK(last_inbound_notes(h.device()).at(0).find("with 8 data byte(s), short of the 10 a KDC101 reads")
          != std::string::npos);
    CHECK(h.send("24 05 01 00 50 01") == "25 05 16 00 81 50 01 00 0A 00 02 00 01 00 01 00" + kTwelveZeros);
}

TEST_CASE("apt KPZ101 issue-44.1 takes yaq's 12-byte KPZ_SET_KCUBETRIGIOCONFIG and 26-byte KPZ_SET_KCUBEMMIPARAMS",
          "[device][apt][kcube][lengths]")
{
    AptHarness h(later_unit("KPZ101"));
    // yaq kpz_set_kcubetrigioconfig, "<6H": TRIG1 voltage step up (2) low, TRIG2 output (0x0A) high.
    CHECK(h.send("F3 07 0C 00 D0 01 01 00 02 00 02 00 0A 00 01 00 00 00") == "");
    CHECK(h.send("F4 07 01 00 50 01") == "F5 07 16 00 81 50 01 00 02 00 02 00 0A 00 01 00" + kTwelveZeros);
    // yaq kpz_set_kcubemmiparams, "<HHHLHLLHHH" (26): JSMode 2, gearbox 3, step 256, DirSense 2,
    // presets 1000 and 32767, display 40 %, 1 min, dim level 10.
    const std::string mmi = "01 00 02 00 03 00 00 01 00 00 02 00 E8 03 00 00 FF 7F 00 00 28 00 01 00 0A 00";
    CHECK(h.send("F0 07 1A 00 D0 01 " + mmi) == "");
    CHECK(h.send("F1 07 01 00 50 01") == "F2 07 22 00 81 50 " + mmi + " 00 00 00 00 00 00 00 00");
}

TEST_CASE("apt a manual SET one byte short of its layout is ignored and noted, the next request answered",
          "[device][apt][lengths]")
{
    AptHarness h;   // TDC001
    const std::string power_up = h.send("14 04 01 00 50 01");
    // SET_VELPARAMS with 13 of its 14 bytes: a frame at the header's length, short of the fields.
    CHECK(h.send("13 04 0D 00 D0 01 01 00 00 00 00 00 0A 00 00 00 64 00 00") == "");
    CHECK(last_inbound_notes(h.device()).at(0)
          == "ignored by the unit: MGMSG_MOT_SET_VELPARAMS with 13 data byte(s), short of the 14 a TDC001 reads: "
             "ignored");
    CHECK(h.send("14 04 01 00 50 01") == power_up);
    // A long-form MOVE_ABSOLUTE of no data at all, and a SET of no data: ignored, nothing moves.
    CHECK(h.send("53 04 00 00 D0 01") == "");
    CHECK(h.send("10 04 00 00 D0 01") == "");
    CHECK(h.send("11 04 01 00 50 01") == "12 04 06 00 81 50 01 00 00 00 00 00");
    // On a KDC101 of the manual's generation a short later-issue SET is a message it does not know.
    AptHarness old(apt_cube("KDC101", "Z825B"));
    CHECK(old.send("23 05 08 00 D0 01 01 00 00 00 01 00 00 00") == "");
    CHECK(last_inbound_notes(old.device()).at(0).find("of the issue-3 generation (the 2012 manual) does not know it")
          != std::string::npos);
}

TEST_CASE("apt KSC101 issue-44.1 takes quantumion's 38-byte KCUBEMMIPARAMS at the table's offsets, its tail ignored",
          "[device][apt][kcube][lengths]")
{
    AptHarness h(later_unit("KSC101"));
    // quantumion/thorlabs_cube kcube/ksc.py set_kcubemmi_params, "<HHLLLHHLLLLH" (38 bytes, the
    // table's 36): JSMode 1, DirSense 0 as a dword, presets 0, brightness 60, timeout 10, dim
    // level 2, JSSensitivity 0x7777 as dwords and words of its own. Its DirSense dword moves
    // every later field 2 bytes on from the table's; the unit reads its own offsets: brightness
    // 0 (22), timeout 60 (24), dim level 0 (26), PresetPos3 10 (28), JSSensitivity 2 (32); the
    // last 2 bytes are past the layout.
    const std::string zeros10 = "00 00 00 00 00 00 00 00 00 00";
    CHECK(h.send("20 05 26 00 D0 01 01 00 01 00 " + zeros10 + " 00 00 00 00 00 00 00 00 00 00 "
                 "3C 00 00 00 0A 00 00 00 02 00 00 00 77 77") == "");
    const auto notes = last_inbound_notes(h.device());
    REQUIRE(notes.size() == 1);
    CHECK(notes[0] == "MGMSG_MOT_SET_KCUBEMMIPARAMS with 38 data byte(s), longer than the 36 of its layout: the unit "
                      "ignores the last 2");
    CHECK(h.send("21 05 01 00 50 01") == "22 05 24 00 81 50 01 00 01 00 " + zeros10 + " 00 00 00 00 00 00 00 00 00 00 "
                                         "3C 00 00 00 0A 00 00 00 02 00 00 00");
}

TEST_CASE("apt a manual SET two bytes past its layout is acted on and noted, a long MOVE_ABSOLUTE moves",
          "[device][apt][lengths]")
{
    AptHarness h;   // TDC001, MTS50-Z8
    // SET_VELPARAMS 0, 500, 1,000,000 and two bytes more.
    CHECK(h.send("13 04 10 00 D0 01 01 00 00 00 00 00 F4 01 00 00 40 42 0F 00 AA BB") == "");
    CHECK(last_inbound_notes(h.device())
          == std::vector<std::string>{"MGMSG_MOT_SET_VELPARAMS with 16 data byte(s), longer than the 14 of its "
                                      "layout: the unit ignores the last 2"});
    CHECK(h.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 01 00 00 00 00 00 F4 01 00 00 40 42 0F 00");
    // The long form of MOVE_ABSOLUTE with two bytes past its 6: to 1 mm (34,304 counts).
    CHECK(h.send("53 04 08 00 D0 01 01 00 00 86 00 00 EE EE") == "");
    h.advance_ms(5000);
    CHECK(frames(h.take()).back().substr(0, 5) == "64 04");   // MOVE_COMPLETED
    CHECK(h.send("11 04 01 00 50 01") == "12 04 06 00 81 50 01 00 00 86 00 00");
}

TEST_CASE("apt a garbage header of a plausible length takes the requests behind it as its data, as a unit does",
          "[device][apt][lengths]")
{
    AptHarness h;   // TDC001
    const std::string req_pos = "11 04 01 00 50 01";
    const std::string pos = "12 04 06 00 81 50 01 00 00 00 00 00";
    // Noise reading as SET_VELPARAMS with 12 data bytes: the two REQ_POSCOUNTERs after it are its
    // packet (short of the 14 the unit reads: ignored and noted), the third is answered.
    CHECK(h.send("13 04 0C 00 D0 01 " + req_pos + " " + req_pos + " " + req_pos) == pos);
    // Noise with a length past what follows holds the request after it until the 50 ms
    // inter-byte timeout drops both; the request sent again is answered.
    CHECK(h.send("13 04 FF 00 D0 01 " + req_pos) == "");
    h.advance_ms(AptDevice::kInterByteTimeout_ms + 1);
    CHECK(h.send(req_pos) == pos);
    // A header-only REQ with a data packet (quantumion/thorlabs_cube's Message packs the channel
    // word of its REQs so) is no frame: all of it is dropped, unanswered; the next one is answered.
    AptHarness k(later_unit("KSC101"));
    CHECK(k.send("21 05 02 00 D0 01 01 00") == "");
    CHECK(frames(k.send("21 05 01 00 50 01")).size() == 1);
}

TEST_CASE("apt every unit ignores every data message cut short, to every module address, then answers",
          "[device][apt][lengths]")
{
    // Short packets reach the modules' checks before anything reads their fields: an empty
    // packet, one byte (half a channel word), one byte short of the fields the table names.
    struct Unit {
        DeviceConfig config;
        std::vector<std::uint8_t> addresses;
    };
    std::vector<Unit> units{{later(apt_cube("KDC101", "Z825B")), {0x50}},
                            {later(apt_cube("KST101", "DRV014")), {0x50}},
                            {apt_rack("BBD203", {"MLS203-X"}), {0x11, 0x21, 0x22}},
                            {later_unit("KSC101"), {0x50}},
                            {later_unit("KPZ101"), {0x50}},
                            {later_unit("KSG101"), {0x50}}};
    for (auto& u : units) {
        INFO(u.config.model);
        AptHarness h(u.config);
        for (const auto& m : all_messages()) {
            if (m.header_only())
                continue;
            for (const auto dest : u.addresses) {
                for (const std::size_t n : {std::size_t{0}, std::size_t{1}, m.min_data_length() - 1}) {
                    INFO(m.name << " with " << n << " data bytes to 0x" << std::hex << int(dest));
                    CHECK(h.send(hex(encode_with_data(m.id, dest, kHost, std::string(n, '\x01')))).empty());
                }
            }
        }
        // HW_REQ_INFO answered after all of it (a rack's motherboard at 0x11).
        CHECK(frames(h.send(hex(encode_header_only(MGMSG_HW_REQ_INFO, 0, 0, u.addresses[0], kHost)))).size() == 1);
    }
}

} // namespace test_apt_packet_lengths
