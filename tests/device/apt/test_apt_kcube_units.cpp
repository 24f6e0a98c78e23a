// The K-Cube piezo, solenoid and strain gauge units (KPZ101, KSC101, KSG101) of the later firmware
// generation ("issue-44.1"): their own messages of the later protocol issues, SET then REQ -> GET
// bytes, SETs out of the documented ranges ignored, the manual's generation ("issue-3", the
// default) ignoring them as a 2012 unit would, EEPROM saves, and the KSC101's state encoding on
// the wire (docs/protocol/apt.md "K-Cube units").
#include "apt_harness.hpp"

namespace test_apt_kcube_units {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;

namespace {

/// A single unit `model` ("unit") following firmware generation `firmware`.
DeviceConfig unit(const std::string& model, Firmware firmware)
{
    DeviceConfig c;
    c.name = "unit";
    c.protocol = "apt";
    c.model = model;
    c.firmware = std::string(firmware_name(firmware));
    config_of(c).firmware = firmware;
    config_of(c).solenoid.interlock_fitted = true;
    return c;
}

constexpr Firmware kLater = Firmware::Issue44_1;
constexpr Firmware kManual = Firmware::Issue3;

// Host 0x01, unit 0x50.
// KPZ_SET_KCUBEMMIPARAMS: JSMode 2, JSVoltGearbox 3, JSVoltStep 256, DirSense 2, PresetVolt1 1000,
// PresetVolt2 32767, display 40 %, 1 min, dim level 10.
const std::string kKpzMmi = "01 00 02 00 03 00 00 01 00 00 02 00 E8 03 00 00 FF 7F 00 00 28 00 01 00 0A 00 "
                            "00 00 00 00 00 00 00 00";
const std::string kSetKpzMmi = "F0 07 22 00 D0 01 " + kKpzMmi;
const std::string kReqKpzMmi = "F1 07 01 00 50 01";
/// The power-up block: JSMode 1, gearbox 1, step 1, DirSense 1, presets 0, display 50 %, 2 min, 5.
const std::string kKpzMmiPowerUp = "F2 07 22 00 81 50 01 00 01 00 01 00 01 00 00 00 01 00 00 00 00 00 00 00 00 00 "
                                   "32 00 02 00 05 00 00 00 00 00 00 00 00 00";
// KPZ_SET_KCUBETRIGIOCONFIG: TRIG1 voltage step up (2), active low; TRIG2 output (0x0A), active high.
const std::string kKpzTrig = "01 00 02 00 02 00 0A 00 01 00 00 00 00 00 00 00 00 00 00 00 00 00";
const std::string kSetKpzTrig = "F3 07 16 00 D0 01 " + kKpzTrig;
const std::string kReqKpzTrig = "F4 07 01 00 50 01";
// KSG_SET_KCUBEMMIPARAMS: 20 %, 5 min, dim level 10.
const std::string kSetKsgMmi = "F6 07 08 00 D0 01 01 00 14 00 05 00 0A 00";
const std::string kReqKsgMmi = "F7 07 01 00 50 01";
// KSG_SET_KCUBETRIGIOCONFIG: TRIG1 above the upper limit (0x0E), high; TRIG2 between them (0x0F),
// low; limits -1000 and 1000; 100 samples.
const std::string kKsgTrig = "01 00 0E 00 01 00 0F 00 02 00 18 FC FF FF E8 03 00 00 64 00 00 00";
const std::string kSetKsgTrig = "F9 07 16 00 D0 01 " + kKsgTrig;
const std::string kReqKsgTrig = "FA 07 01 00 50 01";
const std::string kReqPzStatusUpdate = "60 06 01 00 50 01";

/// `data_hex` with the 2-byte little-endian word at byte `offset` replaced by `word_hex` ("04 00").
std::string with_word(const std::string& data_hex, std::size_t offset, const std::string& word_hex)
{
    std::string out = data_hex;
    out.replace(offset * 3, 5, word_hex);
    return out;
}

} // namespace

// ---- KPZ101 ----

TEST_CASE("apt KPZ101 issue-44.1: KPZ_SET/REQ/GET_KCUBEMMIPARAMS keep and answer the block",
          "[device][apt][kcube]")
{
    AptHarness h(unit("KPZ101", kLater));
    CHECK(h.send(kReqKpzMmi) == kKpzMmiPowerUp);
    CHECK(h.send(kSetKpzMmi).empty());
    CHECK(h.send(kReqKpzMmi) == "F2 07 22 00 81 50 " + kKpzMmi);
    // Channel 0 is the cube's one channel too; the answer says channel 1.
    CHECK(h.send("F0 07 22 00 D0 01 " + with_word(kKpzMmi, 2, "01 00")).empty());
    CHECK(h.send(kReqKpzMmi) == "F2 07 22 00 81 50 " + with_word(kKpzMmi, 2, "01 00"));
}

TEST_CASE("apt KPZ101 issue-44.1: a KCUBEMMIPARAMS SET out of the documented ranges is ignored",
          "[device][apt][kcube]")
{
    AptHarness h(unit("KPZ101", kLater));
    CHECK(h.send(kSetKpzMmi).empty());
    const std::string kept = h.send(kReqKpzMmi);
    // JSMode 4, JSVoltGearbox 0, DirSense 3, brightness 101, timeout 481, dim level 11.
    for (const auto& [offset, word] : std::vector<std::pair<std::size_t, std::string>>{
             {2, "04 00"}, {4, "00 00"}, {10, "03 00"}, {20, "65 00"}, {22, "E1 01"}, {24, "0B 00"}}) {
        INFO("word at " << offset);
        CHECK(h.send("F0 07 22 00 D0 01 " + with_word(kKpzMmi, offset, word)).empty());
        CHECK(h.send(kReqKpzMmi) == kept);
    }
    // The range's ends are taken: DirSense 0 (sent by public clients), timeout 480, dim level 0.
    const auto ends = with_word(with_word(with_word(kKpzMmi, 10, "00 00"), 22, "E0 01"), 24, "00 00");
    CHECK(h.send("F0 07 22 00 D0 01 " + ends).empty());
    CHECK(h.send(kReqKpzMmi) == "F2 07 22 00 81 50 " + ends);
}

TEST_CASE("apt KPZ101 issue-44.1: KPZ_SET/REQ/GET_KCUBETRIGIOCONFIG keep the trigger ports, refuse unknown modes",
          "[device][apt][kcube]")
{
    AptHarness h(unit("KPZ101", kLater));
    CHECK(h.send(kReqKpzTrig) == "F5 07 16 00 81 50 01 00 00 00 01 00 00 00 01 00 00 00 00 00 00 00 00 00 00 00 "
                                 "00 00");
    CHECK(h.send(kSetKpzTrig).empty());
    CHECK(h.send(kReqKpzTrig) == "F5 07 16 00 81 50 " + kKpzTrig);
    CHECK(h.send("F3 07 16 00 D0 01 " + with_word(kKpzTrig, 2, "04 00")).empty());   // mode 4: none
    CHECK(h.send("F3 07 16 00 D0 01 " + with_word(kKpzTrig, 8, "03 00")).empty());   // polarity 3
    CHECK(h.send(kReqKpzTrig) == "F5 07 16 00 81 50 " + kKpzTrig);
}

TEST_CASE("apt KPZ101 issue-44.1: PZ_REQ_PZSTATUSUPDATE answers the status update of that tick",
          "[device][apt][kcube]")
{
    AptHarness h(unit("KPZ101", kLater));
    CHECK(h.send("43 06 04 00 D0 01 01 00 FF 3F").empty());   // PZ_SET_OUTPUTVOLTS 50 %
    h.advance_ms(50);
    const auto answer = h.send(kReqPzStatusUpdate);
    REQUIRE(frames(answer).size() == 1);
    CHECK(answer.substr(0, 17) == "61 06 0A 00 81 50");
    // The same bytes as the update the unit sends unprompted at that tick.
    CHECK(h.send("11 00 00 00 50 01").empty());
    h.advance_ms(100);
    const auto updates = frames(h.take());
    REQUIRE(!updates.empty());
    CHECK(updates.front() == answer);
}

TEST_CASE("apt KPZ101 issue-3 and TPZ001 issue-44.1 ignore the KPZ101's later messages", "[device][apt][kcube]")
{
    for (const auto& [model, firmware] :
         std::vector<std::pair<std::string, Firmware>>{{"KPZ101", kManual}, {"TPZ001", kLater}, {"TPZ001", kManual}}) {
        INFO(model << " " << firmware_name(firmware));
        AptHarness h(unit(model, firmware));
        CHECK(h.send(kSetKpzMmi).empty());
        CHECK(h.send(kReqKpzMmi).empty());
        CHECK(h.send(kSetKpzTrig).empty());
        CHECK(h.send(kReqKpzTrig).empty());
        // PZ_REQ_PZSTATUSUPDATE: the later generation's TPZ001 answers it (next test case).
        CHECK(h.send(kReqPzStatusUpdate).empty() == (firmware == kManual));
        // The unit still answers the manual's messages (PZ_REQ_POSCONTROLMODE).
        CHECK(h.send("41 06 01 00 50 01") == "42 06 01 01 01 50");
    }
}

TEST_CASE("apt TPZ001 and TSG001 issue-44.1 answer PZ_REQ_PZSTATUSUPDATE as pyLabLib queries a T-Cube, issue-3 ignore it",
          "[device][apt][kcube]")
{
    // pyLabLib kinesis.py KinesisPiezoController ("TPZ/KPZ series") _pzctl_get_status_n:
    // query(0x0660, channel), the reply 0x0661, the status dword at data 6..9.
    AptHarness h(unit("TPZ001", kLater));
    CHECK(h.send("43 06 04 00 D0 01 01 00 FF 3F").empty());   // PZ_SET_OUTPUTVOLTS 50 %
    h.advance_ms(50);
    const auto answer = h.send(kReqPzStatusUpdate);
    REQUIRE(frames(answer).size() == 1);
    CHECK(answer.substr(0, 17) == "61 06 0A 00 81 50");
    // The same bytes as the update the unit sends unprompted at that tick, its bits the TPZ001's
    // table (p. 103): the actuator connected, nothing more (the channel-enabled bit is the BPC's).
    CHECK(h.send("11 00 00 00 50 01").empty());
    h.advance_ms(100);
    const auto updates = frames(h.take());
    REQUIRE(!updates.empty());
    CHECK(updates.front() == answer);
    CHECK(get_u32(bytes(answer), 12) == 0x00000001u);
    // A TSG001 with no gauge fitted: OPVoltage 0, Position 0, no status bit (as the KSG101's).
    AptHarness g(unit("TSG001", kLater));
    CHECK(g.send(kReqPzStatusUpdate) == "61 06 0A 00 81 50 01 00 00 00 00 00 00 00 00 00");
    for (const auto* model : {"TPZ001", "TSG001"}) {
        INFO(model);
        AptHarness old(unit(model, kManual));
        CHECK(old.send(kReqPzStatusUpdate).empty());
    }
}

TEST_CASE("apt KPZ101 issue-44.1: PZ_SET_EEPROMPARAMS saves its K-Cube blocks across a power cycle",
          "[device][apt][kcube][eeprom]")
{
    StateStore store;
    AptHarness h(unit("KPZ101", kLater), &store);
    CHECK(h.send(kSetKpzMmi).empty());
    CHECK(h.send(kSetKpzTrig).empty());
    CHECK(h.send("D0 07 04 00 D0 01 01 00 F0 07").empty());   // saves KCUBEMMIPARAMS only
    h.device().power_cycle(PowerCycle{true, false});
    CHECK(h.send(kReqKpzMmi) == "F2 07 22 00 81 50 " + kKpzMmi);
    CHECK(h.send(kReqKpzTrig) == "F5 07 16 00 81 50 01 00 00 00 01 00 00 00 01 00 00 00 00 00 00 00 00 00 00 00 "
                                 "00 00");
}

TEST_CASE("apt KPZ101 issue-3: PZ_SET_EEPROMPARAMS of a K-Cube block saves nothing", "[device][apt][kcube][eeprom]")
{
    StateStore store;
    AptHarness h(unit("KPZ101", kManual), &store);
    CHECK(h.send(kSetKpzMmi).empty());
    CHECK(h.send("D0 07 04 00 D0 01 01 00 F0 07").empty());
    CHECK(store.device_state("unit").empty());
}

// ---- KSG101 ----

TEST_CASE("apt KSG101 issue-44.1: KSG_SET/REQ/GET_KCUBEMMIPARAMS keep the display block, refuse out of range",
          "[device][apt][kcube]")
{
    AptHarness h(unit("KSG101", kLater));
    CHECK(h.send(kReqKsgMmi) == "F8 07 08 00 81 50 01 00 32 00 02 00 05 00");
    CHECK(h.send(kSetKsgMmi).empty());
    CHECK(h.send(kReqKsgMmi) == "F8 07 08 00 81 50 01 00 14 00 05 00 0A 00");
    CHECK(h.send("F6 07 08 00 D0 01 01 00 65 00 05 00 0A 00").empty());   // intensity 101
    CHECK(h.send("F6 07 08 00 D0 01 01 00 14 00 E1 01 0A 00").empty());   // timeout 481 min
    CHECK(h.send("F6 07 08 00 D0 01 01 00 14 00 05 00 0B 00").empty());   // dim level 11
    CHECK(h.send(kReqKsgMmi) == "F8 07 08 00 81 50 01 00 14 00 05 00 0A 00");
}

TEST_CASE("apt KSG101 issue-44.1: KSG_SET/REQ/GET_KCUBETRIGIOCONFIG keep the ports and limits, refuse unknown modes",
          "[device][apt][kcube]")
{
    AptHarness h(unit("KSG101", kLater));
    CHECK(h.send(kReqKsgTrig) == "FB 07 16 00 81 50 01 00 00 00 01 00 00 00 01 00 00 00 00 00 00 00 00 00 01 00 "
                                 "00 00");
    CHECK(h.send(kSetKsgTrig).empty());
    CHECK(h.send(kReqKsgTrig) == "FB 07 16 00 81 50 " + kKsgTrig);
    CHECK(h.send("F9 07 16 00 D0 01 " + with_word(kKsgTrig, 2, "11 00")).empty());   // mode 0x11: none
    CHECK(h.send("F9 07 16 00 D0 01 " + with_word(kKsgTrig, 6, "02 00")).empty());   // mode 2: a KPZ's only
    CHECK(h.send("F9 07 16 00 D0 01 " + with_word(kKsgTrig, 4, "00 00")).empty());   // polarity 0
    CHECK(h.send(kReqKsgTrig) == "FB 07 16 00 81 50 " + kKsgTrig);
}

TEST_CASE("apt KSG101 issue-44.1: PZ_REQ_PZSTATUSUPDATE and EEPROM saves of its blocks", "[device][apt][kcube]")
{
    StateStore store;
    AptHarness h(unit("KSG101", kLater), &store);
    // No gauge fitted: OPVoltage 0, Position 0, no status bit (docs/protocol/apt.md).
    CHECK(h.send(kReqPzStatusUpdate) == "61 06 0A 00 81 50 01 00 00 00 00 00 00 00 00 00");
    CHECK(h.send(kSetKsgMmi).empty());
    CHECK(h.send(kSetKsgTrig).empty());
    CHECK(h.send("D0 07 04 00 D0 01 01 00 F6 07").empty());
    CHECK(h.send("D0 07 04 00 D0 01 01 00 F9 07").empty());
    h.device().power_cycle(PowerCycle{true, false});
    CHECK(h.send(kReqKsgMmi) == "F8 07 08 00 81 50 01 00 14 00 05 00 0A 00");
    CHECK(h.send(kReqKsgTrig) == "FB 07 16 00 81 50 " + kKsgTrig);
}

TEST_CASE("apt KSG101 issue-3 and TSG001 issue-44.1 ignore the KSG101's later messages", "[device][apt][kcube]")
{
    for (const auto& [model, firmware] :
         std::vector<std::pair<std::string, Firmware>>{{"KSG101", kManual}, {"TSG001", kLater}}) {
        INFO(model << " " << firmware_name(firmware));
        AptHarness h(unit(model, firmware));
        CHECK(h.send(kSetKsgMmi).empty());
        CHECK(h.send(kReqKsgMmi).empty());
        CHECK(h.send(kSetKsgTrig).empty());
        CHECK(h.send(kReqKsgTrig).empty());
        CHECK(h.send(kReqPzStatusUpdate).empty() == (firmware == kManual));   // a later TSG001 answers it
        CHECK(h.send("DB 07 01 00 50 01").substr(0, 17) == "DC 07 0E 00 81 50");   // the manual's TSG_IOSETTINGS
    }
    // A KPZ101's block sent to a KSG101 of the later generation is not its own.
    AptHarness h(unit("KSG101", kLater));
    CHECK(h.send(kSetKpzMmi).empty());
    CHECK(h.send(kReqKpzMmi).empty());
}

// ---- KSC101 ----

TEST_CASE("apt KSC101 issue-44.1: MOT_GET_SOL_STATE reports the output off as 0, on as 1", "[device][apt][kcube]")
{
    AptHarness h(unit("KSC101", kLater));
    CHECK(h.send("CC 04 01 00 50 01") == "CD 04 01 00 01 50");
    CHECK(h.send("CB 04 01 01 50 01").empty());   // ON (manual mode)
    CHECK(h.send("CC 04 01 00 50 01") == "CD 04 01 01 01 50");
    CHECK(h.send("CB 04 01 02 50 01").empty());   // OFF: the host still sends 2
    CHECK(h.send("CC 04 01 00 50 01") == "CD 04 01 00 01 50");
    // The manual's generation, and the T-Cube of either, report 2 (p. 91).
    for (const auto& [model, firmware] : std::vector<std::pair<std::string, Firmware>>{
             {"KSC101", kManual}, {"TSC001", kLater}, {"TSC001", kManual}}) {
        INFO(model << " " << firmware_name(firmware));
        AptHarness t(unit(model, firmware));
        CHECK(t.send("CC 04 01 00 50 01") == "CD 04 01 02 01 50");
    }
}

TEST_CASE("apt KSC101 issue-44.1 passes amsikking/thorlabs_KSC101's start-up checks: firmware 1.0.6, state 0 or 1",
          "[device][apt][kcube]")
{
    // thorlabs_KSC101.py Controller.__init__ and its calls, byte for byte (channel 0 throughout).
    AptHarness h(unit("KSC101", kLater));
    const auto info = bytes(h.send("05 00 00 00 50 01"));                 // _get_info: 90 bytes
    REQUIRE(info.size() == 90);
    CHECK(info.substr(10, 8) == std::string("KSC101\0\0", 8));          // assert model_number
    CHECK(get_u32(info, 20) == 65542u);                                   // assert firmware_v == 65542
    CHECK(h.send("10 02 00 01 50 01").empty());                           // _set_enable(True)
    CHECK(h.send("11 02 00 00 50 01") == "12 02 01 01 01 50");            // _get_enable: response[3] 1
    CHECK(h.send("CB 04 00 02 50 01").empty());                           // set_state('closed')
    CHECK(h.send("CC 04 00 00 50 01") == "CD 04 01 00 01 50");            // get_state: 0 "closed"
    CHECK(h.send("C0 04 00 01 50 01").empty());                           // set_mode('manual')
    CHECK(h.send("C1 04 00 00 50 01") == "C2 04 01 01 01 50");            // get_mode: 1
    CHECK(h.send("CB 04 00 01 50 01").empty());                           // set_state('open')
    CHECK(h.send("CC 04 00 00 50 01") == "CD 04 01 01 01 50");            // get_state: 1 "open"
    // The manual's generation and the TSC001 keep 1.0.3 (bytes 03 00 01 00).
    for (const auto& [model, firmware] :
         std::vector<std::pair<std::string, Firmware>>{{"KSC101", kManual}, {"TSC001", kLater}, {"KPZ101", kLater}}) {
        INFO(model << " " << firmware_name(firmware));
        AptHarness t(unit(model, firmware));
        CHECK(get_u32(bytes(t.send("05 00 00 00 50 01")), 20) == 0x00010003u);
    }
}

TEST_CASE("apt KSC101 issue-44.1: MOT_REQ_STATUSBITS and MOT_REQ_STATUSUPDATE give the shutter and key bits",
          "[device][apt][kcube]")
{
    AptHarness h(unit("KSC101", kLater));
    // Interlock enabled (0x1000) and the key unlocked (0x2000); the output off.
    CHECK(h.send("29 04 01 00 50 01") == "2A 04 06 00 81 50 01 00 00 30 00 00");
    CHECK(h.send("CB 04 01 01 50 01").empty());
    CHECK(h.send("29 04 01 00 50 01") == "2A 04 06 00 81 50 01 00 01 30 00 00");
    CHECK(h.send("80 04 01 00 50 01") == "81 04 0E 00 81 50 01 00 00 00 00 00 00 00 00 00 01 30 00 00");
    // The unprompted update carries the same bits.
    CHECK(h.send("11 00 00 00 50 01").empty());
    h.advance_ms(100);
    const auto updates = frames(h.take());
    REQUIRE(!updates.empty());
    CHECK(updates.front() == "81 04 0E 00 81 50 01 00 00 00 00 00 00 00 00 00 01 30 00 00");
}

TEST_CASE("apt KSC101 issue-3 and TSC001 issue-44.1 ignore MOT_REQ_STATUSBITS and MOT_REQ_STATUSUPDATE",
          "[device][apt][kcube]")
{
    for (const auto& [model, firmware] :
         std::vector<std::pair<std::string, Firmware>>{{"KSC101", kManual}, {"TSC001", kLater}}) {
        INFO(model << " " << firmware_name(firmware));
        AptHarness h(unit(model, firmware));
        CHECK(h.send("29 04 01 00 50 01").empty());
        CHECK(h.send("80 04 01 00 50 01").empty());
        // Their status update keeps the manual's bits: no key bit.
        CHECK(h.send("11 00 00 00 50 01").empty());
        h.advance_ms(100);
        const auto updates = frames(h.take());
        REQUIRE(!updates.empty());
        CHECK(status_of(updates.front()) == 0x1000);
    }
}

TEST_CASE("apt KSC101 issue-44.1: MOT_SET/REQ/GET_KCUBEMMIPARAMS and KCUBETRIGIOCONFIG keep its display and ports",
          "[device][apt][kcube]")
{
    AptHarness h(unit("KSC101", kLater));
    const std::string zeros20 = "00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00";
    const std::string zeros8 = "00 00 00 00 00 00 00 00";
    // Power-up (KCubeParams): JSMode 1, the rest 0.
    CHECK(h.send("21 05 01 00 50 01") == "22 05 24 00 81 50 01 00 01 00 " + zeros20 + " 00 00 00 00 " + zeros8);
    // msl-equipment ksc.py set_display_parameters ("<H20x3H8x"): the display words, JSMode 0 and
    // the other wheel words 0. A KSC101 has no wheel (Kinesis' KSC_MMIParams: "unused") and takes
    // it (set_ranges.cpp checks its display words only).
    const std::string mmi = "01 00 " + zeros20 + " 32 00 05 00 02 00 " + zeros8;
    CHECK(h.send("20 05 24 00 D0 01 " + mmi).empty());
    CHECK(h.send("21 05 01 00 50 01") == "22 05 24 00 81 50 " + mmi);
    // Brightness 101: out of range (set_ranges.cpp), ignored.
    CHECK(h.send("20 05 24 00 D0 01 01 00 " + zeros20 + " 65 00 05 00 02 00 " + zeros8).empty());
    CHECK(h.send("21 05 01 00 50 01") == "22 05 24 00 81 50 " + mmi);
    // yaq's 28 bytes (no reserved tail) hold the display words a KSC101 reads: taken.
    CHECK(h.send("20 05 1C 00 D0 01 01 00 " + zeros20 + " 14 00 0A 00 03 00").empty());
    CHECK(h.send("21 05 01 00 50 01") == "22 05 24 00 81 50 01 00 " + zeros20 + " 14 00 0A 00 03 00 " + zeros8);
    CHECK(h.send("20 05 24 00 D0 01 " + mmi).empty());
    // ksc.py set_trigger_parameters' defaults ("<5H12x"): TRIG1 input, TRIG2 output, both high.
    const std::string trig = "01 00 01 00 01 00 0A 00 01 00 00 00 00 00 00 00 00 00 00 00 00 00";
    CHECK(h.send("23 05 16 00 D0 01 " + trig).empty());
    CHECK(h.send("24 05 01 00 50 01") == "25 05 16 00 81 50 " + trig);
    // A motor cube's mode (2: relative move on input) is not a solenoid cube's: ignored.
    CHECK(h.send("23 05 16 00 D0 01 01 00 02 00 01 00 0A 00 01 00 00 00 00 00 00 00 00 00 00 00 00 00").empty());
    CHECK(h.send("24 05 01 00 50 01") == "25 05 16 00 81 50 " + trig);
    // The manual's generation, and the TSC001, do not know them.
    for (const auto& [model, firmware] :
         std::vector<std::pair<std::string, Firmware>>{{"KSC101", kManual}, {"TSC001", kLater}}) {
        INFO(model << " " << firmware_name(firmware));
        AptHarness t(unit(model, firmware));
        CHECK(t.send("20 05 24 00 D0 01 " + mmi).empty());
        CHECK(t.send("21 05 01 00 50 01").empty());
        CHECK(t.send("23 05 16 00 D0 01 " + trig).empty());
        CHECK(t.send("24 05 01 00 50 01").empty());
    }
}

TEST_CASE("apt KSC101 issue-44.1: MOT_SET_EEPROMPARAMS saves its trigger ports across a power cycle",
          "[device][apt][kcube][eeprom]")
{
    StateStore store;
    AptHarness h(unit("KSC101", kLater), &store);
    const std::string trig = "01 00 01 00 02 00 0A 00 02 00 00 00 00 00 00 00 00 00 00 00 00 00";
    CHECK(h.send("23 05 16 00 D0 01 " + trig).empty());
    CHECK(h.send("B9 04 04 00 D0 01 01 00 23 05").empty());
    h.device().power_cycle(PowerCycle{true, false});
    CHECK(h.send("24 05 01 00 50 01") == "25 05 16 00 81 50 " + trig);
}

} // namespace test_apt_kcube_units
