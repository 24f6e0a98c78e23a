// The units made after the 2012 manual (docs/protocol/apt.md "Units of today"): the K10CR1 cage
// rotator and the LTS150/LTS300 long-travel stages (integrated Trinamic steppers: their stage is
// built in), the KBD101 K-Cube brushless with the DDS stages. Bytes in -> bytes out on the
// stepped clock, each unit loaded from its rig JSON as a rig names it.
#include "apt_harness.hpp"

#include "emulator/core/config_reader.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

namespace test_apt_units_of_today {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;
using nlohmann::json;

namespace {

/// The device of `device` (a rig's devices[0]) as the rig loader reads it.
DeviceConfig loaded(const json& device)
{
    return loaded_apt_device(device);
}

/// The rig loader's message for `device`, or "" when it takes it.
std::string load_error(const json& device)
{
    return apt_load_error(device);
}

json unit(const char* model, json apt = json::object())
{
    return json{{"name", "unit"}, {"protocol", "apt"}, {"model", model}, {"apt", std::move(apt)}};
}

/// The 16-bit word at data offset `offset` of a HW_GET_INFO reply (hex).
std::uint16_t info_word(const std::string& reply_hex, std::size_t offset)
{
    const auto b = bytes(reply_hex);
    REQUIRE(b.size() == 90);
    return get_u16(b, 6 + offset);
}

std::uint32_t info_dword(const std::string& reply_hex, std::size_t offset)
{
    const auto b = bytes(reply_hex);
    REQUIRE(b.size() == 90);
    return get_u32(b, 6 + offset);
}

/// VELPARAMS of channel 1 as GET_VELPARAMS carries them: min, acceleration, max.
std::string vel_params(std::int32_t acceleration, std::int32_t max)
{
    return "01 00 " + le32(0) + " " + le32(acceleration) + " " + le32(max);
}

std::string move_absolute(std::int32_t counts)
{
    return "53 04 06 00 D0 01 01 00 " + le32(counts);
}

// K10CR1: 136,533.33 microsteps per degree, 53.68 per microstep/s, 1/90.9 per microstep/s²
// (issue 37 p. 41: 7,329,109 per deg/s, 1,502 per deg/s²).
constexpr double kK10PerDeg = 409'600.0 / 3.0;

std::int32_t k10_counts(double deg)
{
    return static_cast<std::int32_t>(std::lround(deg * kK10PerDeg));
}

} // namespace

TEST_CASE("K10CR1: identity, the later generation by default, the power-up parameters the official software "
          "leaves",
          "[device][apt][today]")
{
    const auto c = loaded(unit("K10CR1", {{"serial_number", 55'000'123}}));
    CHECK(c.firmware == "issue-44.1");
    CHECK(config_of(c).stage.name == "K10CR1");
    AptHarness h(c);
    const auto info = h.send("05 00 00 00 50 01");
    CHECK(info.substr(0, 17) == "06 00 54 00 81 50");
    CHECK(info_dword(info, 0) == 55'000'123);
    CHECK(info.substr(30, 23) == "4B 31 30 43 52 31 00 00");   // "K10CR1"
    CHECK(info_word(info, 78) == 3);   // hardware version 3 (Kinesis' hardware revision)
    // PnPQ's observed values: VELPARAMS acceleration 15020 (10 deg/s²); max 10 deg/s by issue 37's
    // factor; HOMEPARAMS reverse, the reverse (home) switch, 4 deg back off = 546133.
    CHECK(h.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 " + vel_params(15'020, 73'291'093));
    CHECK(h.send("41 04 01 00 50 01") == "42 04 0E 00 81 50 01 00 02 00 01 00 " + le32(73'291'093) + " "
                                             + le32(546'133));
    // TRIGGER is its own (issue 37 p. 15); the K-Cube display block is not.
    CHECK(h.send("00 05 01 05 50 01") == "");
    CHECK(h.send("01 05 01 00 50 01") == "02 05 01 05 01 50");
    CHECK(h.send("21 05 01 00 50 01") == "");
}

TEST_CASE("K10CR1: a 90 degree move takes the trapezoid of its power-up VELPARAMS, and it turns past 360 degrees "
          "without end",
          "[device][apt][today]")
{
    AptHarness h(loaded(unit("K10CR1")));
    // 10 deg/s, 10 deg/s²: 1 s up (5 deg), 8 s at speed, 1 s down: 10 s.
    CHECK(h.send(move_absolute(k10_counts(90))) == "");
    std::string done;
    const int ms = ms_until_reply(h, done, 12'000);
    CHECK(ms >= 9'990);
    CHECK(ms <= 10'010);
    REQUIRE(frames(done).size() == 1);
    CHECK(done.substr(0, 17) == "64 04 0E 00 81 50");   // MOVE_COMPLETED with its status
    CHECK(position_of(done) == k10_counts(90));
    // Two turns and a quarter: the counter keeps counting (QMI k10crx.py: it overflows after 43 turns).
    CHECK(h.send(move_absolute(k10_counts(810))) == "");
    h.advance_ms(80'000);
    CHECK(position_of(h.take()) == k10_counts(810));
    CHECK(position_of(h.send("11 04 01 00 50 01")) == k10_counts(810));
}

TEST_CASE("K10CR1: MOVE_HOME turns in reverse to the home switch, backs off 4 degrees and counts from there",
          "[device][apt][today]")
{
    AptHarness h(loaded(unit("K10CR1")));
    CHECK(h.send(move_absolute(k10_counts(30))) == "");
    h.advance_ms(5'000);
    h.take();
    CHECK(h.send("43 04 01 00 50 01") == "");
    h.advance_ms(500);
    CHECK((h.device().channel().status_bits() & status::kHoming) != 0);
    h.advance_ms(40'000);   // it stood half a turn from the switch at power-up (motor_channel.cpp): 210 deg at 10 deg/s
    CHECK(h.take() == "44 04 01 00 01 50");   // MOVE_HOMED
    CHECK(position_of(h.send("11 04 01 00 50 01")) == 0);
    CHECK((h.device().channel().status_bits() & status::kHomed) != 0);
}

TEST_CASE("LTS150 and LTS300: 409,600 microsteps per mm, homing to the reverse switch, the forward limit switch at "
          "the end of the travel",
          "[device][apt][today]")
{
    for (const auto& [model, travel] : {std::pair{"LTS150", 150}, std::pair{"LTS300", 300}}) {
        INFO(model);
        AptHarness h(loaded(unit(model)));
        const auto info = h.send("05 00 00 00 50 01");
        CHECK(info_dword(info, 0) == 45'000'001);
        CHECK(info_word(info, 78) == 3);
        // Issue 37 p. 41: 21,987,328 per mm/s, 4,506 per mm/s²; 20 mm/s and 20 mm/s² at power-up.
        CHECK(h.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 " + vel_params(90'122, 439'746'560));
        // It stands mid-travel at power-up, counting from 0 there (motor_channel.cpp).
        CHECK(h.send("57 04 01 01 50 01") == "");   // MOVE_VELOCITY forward, to the end
        h.advance_ms(travel * 1'000 / 40 + 2'000);
        const auto out = frames(h.take());
        REQUIRE(out.size() == 1);
        CHECK(out[0].substr(0, 17) == "64 04 0E 00 81 50");   // MOVE_COMPLETED on the switch
        CHECK((status_of(out[0]) & status::kForwardHardLimit) != 0);
        const auto at = position_of(out[0]);
        CHECK(at <= travel / 2 * 409'600);
        CHECK(at >= travel / 2 * 409'600 - 409'600);
        CHECK(h.send("43 04 01 00 50 01") == "");
        h.advance_ms(travel * 1'000 / 2 + 5'000);   // back at 2 mm/s
        CHECK(h.take() == "44 04 01 00 01 50");
        CHECK(position_of(h.send("11 04 01 00 50 01")) == 0);
    }
}

TEST_CASE("KBD101: identity, brushless scaling on the DDS stages, the K-Cube blocks its issue lists",
          "[device][apt][today]")
{
    const auto c = loaded(unit("KBD101", {{"stage", "DDS100"}}));
    AptHarness h(c);
    const auto info = h.send("05 00 00 00 50 01");
    CHECK(info_dword(info, 0) == 28'000'001);
    CHECK(info_word(info, 12) == 44);                 // type: brushless DC controller (issue 37 p. 53)
    CHECK(info_dword(info, 14) == 0x0002'0008);       // firmware 2.0.8 (amsikking/thorlabs_DDS100)
    // DDS100: 2,000 counts per mm; 500 mm/s and 5,000 mm/s² in 13,421.8 per mm/s and 1.37439 per mm/s².
    CHECK(h.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 " + vel_params(6'872, 6'710'900));
    // 10 mm at 500 mm/s, 5000 mm/s²: 0.1 s up, 0.1 s down cover 50 mm: a triangle of 2 × sqrt(10/5000) s.
    CHECK(h.send(move_absolute(20'000)) == "");
    std::string done;
    const int ms = ms_until_reply(h, done, 2'000);
    CHECK(ms >= 85);
    CHECK(ms <= 95);
    CHECK(position_of(done) == 20'000);
    // Thorlabs' own KBD101 trigger example: TRIG1 a relative-move input, TRIG2 an in-motion output.
    CHECK(h.send("23 05 16 00 D0 01 01 00 02 00 01 00 0B 00 01 00 00 00 00 00 00 00 00 00 00 00 00 00") == "");
    CHECK(h.send("24 05 01 00 50 01") == "25 05 16 00 81 50 01 00 02 00 01 00 0B 00 01 00 00 00 00 00 00 00 00 00 00 00 "
                                         "00 00");
    CHECK(h.send("27 05 01 00 50 01").substr(0, 17) == "28 05 2E 00 81 50");   // POSTRIGPARAMS
    CHECK(h.send("01 05 01 00 50 01") == "");   // TRIGGER: the racks' (issue 37 p. 22), ignored

    for (const auto& [stage, per_mm, travel] :
         {std::tuple{"DDS220", 20'000, 220}, std::tuple{"DDS300", 20'000, 300}, std::tuple{"DDS600", 20'000, 600}}) {
        INFO(stage);
        const auto s = config_of(loaded(unit("KBD101", {{"stage", stage}}))).stage;
        CHECK(s.counts_per_mm == per_mm);
        CHECK(s.travel_mm == travel);
    }
}

TEST_CASE("KBD101 + DDR25: a brushless rotation stage turns without end and homes forward to its switch, counting "
          "from there",
          "[device][apt][today]")
{
    AptHarness h(loaded(unit("KBD101", {{"stage", "DDR25"}})));
    // 4,000 counts per degree: 100 deg/s, 1,000 deg/s² at power-up.
    CHECK(h.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 " + vel_params(2'749, 2'684'360));
    CHECK(h.send(move_absolute(4'000 * 540)) == "");   // a turn and a half
    h.advance_ms(7'000);
    CHECK(position_of(h.take()) == 4'000 * 540);
    // It stood half a turn from its switch at power-up; 540° on, the switch is 0°... forward from here.
    CHECK(h.send("43 04 01 00 50 01") == "");
    h.advance_ms(40'000);
    CHECK(h.take() == "44 04 01 00 01 50");
    CHECK(position_of(h.send("11 04 01 00 50 01")) == 0);
    // PMDSTAGEAXISPARAMS cannot narrow an endless stage: ignored, the block as before.
    const auto before = h.send("F1 04 01 00 50 01");
    // The same block as a SET (to 0x50 from the host) with the travel narrowed to 0..90 degrees.
    auto set = bytes(before);
    REQUIRE(set.size() == 80);
    set[0] = '\xF0';
    set[4] = '\xD0';
    set[5] = '\x01';
    const auto put = [&set](std::size_t at, std::int32_t v) {
        std::string le;
        put_i32(le, v);
        set.replace(at, 4, le);
    };
    put(6 + 28, 0);   // MinPos, MaxPos (p. 75)
    put(6 + 32, 4'000 * 90);
    CHECK(h.send(hex(set)) == "");
    CHECK(h.send("F1 04 01 00 50 01") == before);
}

TEST_CASE("rig loader: the integrated units name no stage, have the later generation only, and keep their stages "
          "to themselves",
          "[device][apt][today][config]")
{
    CHECK(load_error(unit("K10CR1", {{"stage", "PRM1-Z8"}}))
          == "rig.json: /devices/0/apt/stage: K10CR1 is an integrated stage: its keys are serial_number, eeprom");
    auto issue3 = unit("LTS150");
    issue3["firmware"] = "issue-3";
    CHECK(load_error(issue3) == "rig.json: /devices/0/firmware: the LTS150 was made after the 2012 manual: it has the "
                                "later generation only (expected \"issue-44.1\")");
    CHECK(load_error(unit("KST101", {{"stage", "K10CR1"}}))
          == "rig.json: /devices/0/apt/stage: stage \"K10CR1\" is the stage built into the K10CR1, which no other "
             "controller drives");
    CHECK(load_error(unit("KBD101")) == "rig.json: /devices/0/apt/stage: required key missing (the default MTS50-Z8 is "
                                        "not a stage for a KBD101)");
    CHECK(load_error(unit("KBD101", {{"stage", "ZST225B"}})).find("has another kind of motor than a KBD101")
          != std::string::npos);
    CHECK(load_error(unit("K10CR1", {{"serial_number", 27'000'001}})).find("(the model's serial prefix)")
          != std::string::npos);
}

TEST_CASE("MFF101: names itself MFF002, flips to position 1 or 2 by MOVE_JOG in its transit time, reports "
          "the position in its status bits",
          "[device][apt][today][flipper]")
{
    const auto c = loaded(unit("MFF101"));
    CHECK(c.firmware == "issue-44.1");
    AptHarness h(c);
    const auto info = h.send("05 00 00 00 50 01");
    CHECK(info_dword(info, 0) == 37'000'001);
    CHECK(info.substr(30, 23) == "4D 46 46 30 30 32 00 00");   // "MFF002", as a real MFF101 says
    CHECK(info_dword(info, 14) == 0x0001'0003);
    // At power-up it stands at position 1 (the rig's "flipper": {"position": 1}).
    CHECK(h.send("29 04 01 00 50 01") == "2A 04 06 00 81 50 01 00 01 00 00 00");
    // To position 2: 500 ms (issue 37's example transit time), moving toward 2 meanwhile.
    CHECK(h.send("6A 04 01 02 50 01") == "");
    h.advance_ms(250);
    CHECK(h.send("29 04 01 00 50 01") == "2A 04 06 00 81 50 01 00 20 00 00 00");
    std::string done;
    const int ms = ms_until_reply(h, done, 1'000);
    CHECK(ms == 250);
    CHECK(done == "64 04 0E 00 81 50 01 00 00 00 00 00 00 00 00 00 02 00 00 00");   // MOVE_COMPLETED at 2
    CHECK(h.send("29 04 01 00 50 01") == "2A 04 06 00 81 50 01 00 02 00 00 00");
    // A jog to where it is: done at once, MOVE_COMPLETED right behind it.
    CHECK(h.send("6A 04 01 02 50 01") == "64 04 0E 00 81 50 01 00 00 00 00 00 00 00 00 00 02 00 00 00");
    // Another direction is no position: ignored.
    CHECK(h.send("6A 04 01 03 50 01") == "");
    h.advance_ms(1'000);
    CHECK(h.take() == "");
    // Back to 1, turned around half way: back at 2 after as long as it travelled.
    CHECK(h.send("6A 04 01 01 50 01") == "");
    h.advance_ms(100);
    CHECK(h.send("29 04 01 00 50 01") == "2A 04 06 00 81 50 01 00 10 00 00 00");
    CHECK(h.send("6A 04 01 02 50 01") == "");
    CHECK(ms_until_reply(h, done, 1'000) == 100);
    CHECK(done.substr(48) == "02 00 00 00");
}

TEST_CASE("MFF102: MFF_OPERPARAMS sets the transit time (300..2800 ms) and the I/O ports, is saved by "
          "EEPROMPARAMS, and the rest of the motor messages are not its own",
          "[device][apt][today][flipper]")
{
    AptHarness h(loaded(unit("MFF102", {{"flipper", {{"position", 2}}}, {"serial_number", 37'000'042}})));
    CHECK(h.send("29 04 01 00 50 01") == "2A 04 06 00 81 50 01 00 02 00 00 00");
    const std::string unused = " 00 00 00 00 00 00 00 00";
    const std::string example = "01 00 F4 01 00 00 FC 01 00 00 01 00 01 00 C8 00 00 00 01 00 01 00 C8 00 00 00" + unused;
    CHECK(h.send("11 05 01 00 50 01") == "12 05 22 00 81 50 " + example);
    // 1500 ms (ADC as a client computes it: 10^7 × 1500^-1.591 = 87), I/O 1 an at-position output.
    const std::string slow = "01 00 DC 05 00 00 57 00 00 00 03 00 10 00 64 00 00 00 01 00 01 00 C8 00 00 00" + unused;
    CHECK(h.send("10 05 22 00 D0 01 " + slow) == "");
    CHECK(h.send("11 05 01 00 50 01") == "12 05 22 00 81 50 " + slow);
    CHECK(h.send("6A 04 01 01 50 01") == "");
    std::string done;
    CHECK(ms_until_reply(h, done, 3'000) == 1'500);
    // Out of range (100 ms): ignored, the block stays.
    CHECK(h.send("10 05 22 00 D0 01 01 00 64 00 00 00 57 00 00 00 03 00 10 00 64 00 00 00 01 00 01 00 C8 00 00 00"
                 + unused)
          == "");
    CHECK(h.send("11 05 01 00 50 01") == "12 05 22 00 81 50 " + slow);
    // Saved: MOT_SET_EEPROMPARAMS for 0x0510.
    CHECK(h.send("B9 04 04 00 D0 01 01 00 10 05") == "");
    // Not on its list (issue 37 p. 20): MOVE_HOME, VELPARAMS, STATUSUPDATE.
    CHECK(h.send("43 04 01 00 50 01") == "");
    CHECK(h.send("14 04 01 00 50 01") == "");
    CHECK(h.send("80 04 01 00 50 01") == "");
    h.advance_ms(5'000);
    CHECK(h.take() == "");
}

TEST_CASE("rig loader: a flip mount's \"flipper\" object holds its power-up position, 1 or 2",
          "[device][apt][today][flipper][config]")
{
    CHECK(config_of(loaded(unit("MFF101", {{"flipper", {{"position", 2}}}}))).flipper.position == 2);
    CHECK(load_error(unit("MFF101", {{"flipper", {{"position", 3}}}}))
          == "rig.json: /devices/0/apt/flipper/position: expected an integer 1..2, got 3");
    CHECK(load_error(unit("MFF101", {{"stage", "DDS100"}}))
          == "rig.json: /devices/0/apt/stage: MFF101 is a flip mount: its keys are flipper, serial_number, eeprom");
}

TEST_CASE("MPC320: paddles addressed as bits 1, 2, 4, moved at POL_PARAMS' velocity, each move ending with the "
          "header-only MOVE_COMPLETED",
          "[device][apt][today][polariser]")
{
    AptHarness h(loaded(unit("MPC320")));
    const auto info = h.send("05 00 00 00 50 01");
    CHECK(info_dword(info, 0) == 38'000'001);
    CHECK(info.substr(30, 23) == "4D 50 43 33 32 30 00 00");   // "MPC320"
    // POL_PARAMS at power-up: issue 37's example, 50 % of 400 deg/s, home 0, jog steps 25.
    CHECK(h.send("31 05 00 00 50 01") == "32 05 0C 00 81 50 00 00 32 00 00 00 19 00 19 00 19 00");
    // Paddle 2 (bit 0x02) to 685 counts (85 deg) at 200 deg/s: 425 ms.
    CHECK(h.send("53 04 06 00 D0 01 02 00 " + le32(685)) == "");
    h.advance_ms(200);
    const auto mid = bytes(h.send("90 04 02 00 50 01"));   // REQ_DCSTATUSUPDATE, paddle 2
    REQUIRE(mid.size() == 20);
    CHECK(get_u16(mid, 6) == 2);
    CHECK(get_i32(mid, 8) == 322);   // 40 deg
    CHECK((get_u32(mid, 16) & 0x10) != 0);   // moving up
    std::string done;
    CHECK(ms_until_reply(h, done, 1'000) == 225);
    CHECK(done == "64 04 02 00 01 50");   // MOVE_COMPLETED, paddle 2, header-only (PnPQ reads 6 bytes)
    CHECK(get_i32(bytes(h.send("11 04 02 00 50 01")), 8) == 685);
    CHECK(get_i32(bytes(h.send("11 04 01 00 50 01")), 8) == 0);   // paddle 1 did not move
    // Channel 3 is not a paddle: bits 1, 2, 4 only (the pyLabLib report of paddle 3 not moving).
    CHECK(h.send("53 04 06 00 D0 01 03 00 " + le32(100)) == "");
    CHECK(h.send("53 04 06 00 D0 01 08 00 " + le32(100)) == "");
    h.advance_ms(1'000);
    CHECK(h.take() == "");
    // Jog paddle 3 (bit 0x04) up one step, 25 counts; past 1370 is refused.
    CHECK(h.send("6A 04 04 01 50 01") == "");
    h.advance_ms(100);
    CHECK(h.take() == "64 04 04 00 01 50");
    CHECK(get_i32(bytes(h.send("11 04 04 00 50 01")), 8) == 25);
    CHECK(h.send("53 04 06 00 D0 01 01 00 " + le32(1371)) == "");
    h.advance_ms(1'000);
    CHECK(h.take() == "");
}

TEST_CASE("MPC320: MOVE_HOME takes the paddles of the mask to the home position, CHANENABLESTATE sets the enabled "
          "set, POL_PARAMS are ranged, saved and restored to the factory's",
          "[device][apt][today][polariser]")
{
    AptHarness h(loaded(unit("MPC320", {{"serial_number", 38'000'005}})));
    // Home 649 counts (the home pyLabLib's issue 72 reads), velocity 100 %, jog steps 50.
    CHECK(h.send("30 05 0C 00 D0 01 00 00 64 00 89 02 32 00 32 00 32 00") == "");
    CHECK(h.send("43 04 07 00 50 01") == "");   // MOVE_HOME all three
    h.advance_ms(50);
    CHECK((get_u32(bytes(h.send("90 04 01 00 50 01")), 16) & 0x200) != 0);   // homing
    h.advance_ms(250);   // 80.5 deg at 400 deg/s: 202 ms
    CHECK(h.take() == "44 04 01 00 01 50 44 04 02 00 01 50 44 04 04 00 01 50");
    CHECK(get_i32(bytes(h.send("11 04 04 00 50 01")), 8) == 649);
    CHECK((get_u32(bytes(h.send("90 04 04 00 50 01")), 16) & 0x400) != 0);   // homed
    // Enable paddles 1 and 3 only: 2 is disabled and does not move.
    CHECK(h.send("10 02 05 01 50 01") == "");
    CHECK(h.send("11 02 02 00 50 01") == "12 02 02 00 01 50");   // disabled: 0 (QMI: the MPC320 answers 0)
    CHECK(h.send("11 02 05 00 50 01") == "12 02 05 01 01 50");
    CHECK(h.send("6A 04 02 01 50 01") == "");
    h.advance_ms(500);
    CHECK(h.take() == "");
    // Velocity 5 % is out of range (10..100): ignored.
    CHECK(h.send("30 05 0C 00 D0 01 00 00 05 00 00 00 19 00 19 00 19 00") == "");
    CHECK(h.send("31 05 00 00 50 01") == "32 05 0C 00 81 50 00 00 64 00 89 02 32 00 32 00 32 00");
    CHECK(h.send("B9 04 04 00 D0 01 01 00 30 05") == "");   // saved
    CHECK(h.send("86 06 01 00 50 01") == "");                // RESTOREFACTORYSETTINGS
    CHECK(h.send("31 05 00 00 50 01") == "32 05 0C 00 81 50 00 00 32 00 00 00 19 00 19 00 19 00");
}

TEST_CASE("MPC220: two paddles, bits 1 and 2, MOVE_STOP ends a move where it is with a MOVE_STOPPED",
          "[device][apt][today][polariser]")
{
    AptHarness h(loaded(unit("MPC220")));
    CHECK(h.send("53 04 06 00 D0 01 04 00 " + le32(100)) == "");   // no paddle 3
    h.advance_ms(500);
    CHECK(h.take() == "");
    CHECK(h.send("53 04 06 00 D0 01 01 00 " + le32(1370)) == "");   // 170 deg: 850 ms
    h.advance_ms(425);
    CHECK(h.send("65 04 01 02 50 01") == "66 04 01 00 01 50");   // MOVE_STOP: MOVE_STOPPED right away
    const auto at = get_i32(bytes(h.send("11 04 01 00 50 01")), 8);
    CHECK(at >= 680);
    CHECK(at <= 690);
    h.advance_ms(1'000);
    CHECK(h.take() == "");
}

} // namespace test_apt_units_of_today
