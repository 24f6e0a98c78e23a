// The KIM101 and TIM101 piezo inertia motor controllers (docs/protocol/apt.md "Units of today",
// Thorlabs' protocol issue 37 p. 370-406): channels as bits 1, 2, 4, 8, the sub-messages of
// PZMOT_SET/REQ/GET_PARAMS per model, moves and jogs as pulses at the drive and jog step rates,
// forward and reverse steps of different lengths, the enabled channels, the status updates and
// their cut-off after 10 without PZMOT_ACK_STATUSUPDATE. Bytes in -> bytes out on the stepped clock.
#include "apt_harness.hpp"

#include "models/inertial_drive.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace test_apt_pzmot {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;
using nlohmann::json;

namespace {

json unit(const char* model, json apt = json::object())
{
    return json{{"name", "unit"}, {"protocol", "apt"}, {"model", model}, {"apt", std::move(apt)}};
}


/// Channel `c`'s (1..4) screw position in nm.
double screw_nm(AptHarness& h, int c)
{
    const auto* drive = h.world().find_as<models::InertialDrive>("unit/" + std::to_string(c));
    REQUIRE(drive != nullptr);
    return drive->position_nm();
}

/// PZMOT_GET_STATUSUPDATE's block of channel `c` (1..4): its position and status bits.
std::int32_t status_position(const std::string& hex_frame, int c)
{
    const auto b = bytes(hex_frame);
    REQUIRE(b.size() == 62);
    return get_i32(b, 6 + 14 * (c - 1) + 2);
}
std::uint32_t status_bits(const std::string& hex_frame, int c)
{
    const auto b = bytes(hex_frame);
    REQUIRE(b.size() == 62);
    return get_u32(b, 6 + 14 * (c - 1) + 10);
}

} // namespace

TEST_CASE("KIM101: its identity, MOVE_ABSOLUTE at the drive's step rate, MOVE_COMPLETED with the counter",
          "[device][apt][today][pzmot]")
{
    AptHarness h(loaded_apt_device(unit("KIM101")));
    const auto info = bytes(h.send("05 00 00 00 50 01"));
    REQUIRE(info.size() == 90);
    CHECK(get_u32(info, 6) == 97'000'001);
    CHECK(hex(info.substr(10, 8)) == "4B 49 4D 31 30 31 00 00");   // "KIM101"
    // DriveOPParams at power-up: issue 37's example bytes (110 V, 500 steps/s, 100,000 steps/s²).
    CHECK(h.send("C1 08 07 01 50 01") == "C2 08 0E 00 81 50 07 00 01 00 6E 00 F4 01 00 00 A0 86 01 00");
    // 1000 steps forward at 500/s after a 5 ms ramp: 2.005 s.
    CHECK(h.send("D4 08 06 00 D0 01 01 00 " + le32(1000)) == "");
    h.advance_ms(1000);
    const auto mid = h.send("E0 08 01 00 50 01");
    CHECK(status_position(mid, 1) == 498);   // 1.25 steps in the ramp, 497.5 after
    CHECK(status_bits(mid, 1) == 0x80000110u);   // enabled, connected, moving forward
    CHECK(status_bits(mid, 2) == 0x00000100u);   // not enabled
    std::string done;
    CHECK(ms_until_reply(h, done, 2000) == 1005);
    CHECK(done == "D6 08 0E 00 81 50 01 00 E8 03 00 00 00 00 00 00 00 00 00 00");
    CHECK(screw_nm(h, 1) == Approx(6.5e6 + 1000 * 20.0));
    // Back to 0: the counter reads 0, the screw stands 1000 × (20 - 18) nm further.
    CHECK(h.send("D4 08 06 00 D0 01 01 00 " + le32(0)) == "");
    CHECK(ms_until_reply(h, done, 3000) == 2005);
    CHECK(done == "D6 08 0E 00 81 50 01 00 00 00 00 00 00 00 00 00 00 00 00 00");
    CHECK(screw_nm(h, 1) == Approx(6.5e6 + 2000.0));
    // A move to where it stands ends at once (pyLabLib and infn-epics stop a channel so).
    CHECK(h.send("D4 08 06 00 D0 01 01 00 " + le32(0)) == "D6 08 0E 00 81 50 01 00 00 00 00 00 00 00 00 00 00 00 00 00");
}

TEST_CASE("KIM101: channels are bits 1, 2, 4, 8, only the enabled ones move, ChanEnableMode's pairs",
          "[device][apt][today][pzmot]")
{
    AptHarness h(loaded_apt_device(unit("KIM101")));
    // Channel 3 as the index 3 (InstrumentKit issue 372): no single bit, ignored.
    CHECK(h.send("D4 08 06 00 D0 01 03 00 " + le32(100)) == "");
    // Channel 3 as its bit, 0x04: not enabled (channel 1 is, at power-up): ignored.
    CHECK(h.send("D4 08 06 00 D0 01 04 00 " + le32(100)) == "");
    h.advance_ms(1000);
    CHECK(h.take() == "");
    CHECK(h.send("C1 08 2B 00 50 01") == "C2 08 04 00 81 50 2B 00 01 00");
    // Mode 6: channels 3 and 4 (p. 394); channel 1 no more.
    CHECK(h.send("C0 08 04 00 D0 01 2B 00 06 00") == "");
    CHECK(h.send("C1 08 2B 00 50 01") == "C2 08 04 00 81 50 2B 00 06 00");
    CHECK(h.send("11 02 01 00 50 01") == "12 02 01 02 01 50");
    CHECK(h.send("11 02 04 00 50 01") == "12 02 04 01 01 50");
    CHECK(h.send("D4 08 06 00 D0 01 04 00 " + le32(100)) == "");
    CHECK(h.send("D4 08 06 00 D0 01 08 00 " + le32(-100)) == "");
    CHECK(h.send("D4 08 06 00 D0 01 01 00 " + le32(100)) == "");   // channel 1: ignored
    h.advance_ms(300);
    const auto ends = frames(h.take());
    REQUIRE(ends.size() == 2);
    CHECK(ends[0] == "D6 08 0E 00 81 50 04 00 64 00 00 00 00 00 00 00 00 00 00 00");
    CHECK(ends[1] == "D6 08 0E 00 81 50 08 00 9C FF FF FF 00 00 00 00 00 00 00 00");
    CHECK(screw_nm(h, 1) == Approx(6.5e6));
    CHECK(screw_nm(h, 3) == Approx(6.5e6 + 2000));
    CHECK(screw_nm(h, 4) == Approx(6.5e6 - 1800));
    // Mode 7 is out of range (0..6): ignored. MOD_SET_CHANENABLESTATE selects channel 2 alone.
    CHECK(h.send("C0 08 04 00 D0 01 2B 00 07 00") == "");
    CHECK(h.send("C1 08 2B 00 50 01") == "C2 08 04 00 81 50 2B 00 06 00");
    CHECK(h.send("10 02 02 01 50 01") == "");
    CHECK(h.send("C1 08 2B 00 50 01") == "C2 08 04 00 81 50 2B 00 02 00");
}

TEST_CASE("KIM101: jog steps of KCubeJogParams, forward and reverse, a continuous jog until MOVE_STOP",
          "[device][apt][today][pzmot]")
{
    AptHarness h(loaded_apt_device(unit("KIM101")));
    // Power-up jog: issue 37's example, single steps of 250 forward and 260 reverse at 500/s.
    CHECK(h.send("C1 08 2D 01 50 01")
          == "C2 08 16 00 81 50 2D 00 01 00 02 00 FA 00 00 00 04 01 00 00 F4 01 00 00 A0 86 01 00");
    CHECK(h.send("D9 08 01 01 50 01") == "");
    h.advance_ms(100);
    CHECK((status_bits(h.send("E0 08 01 00 50 01"), 1) & 0x40) != 0);   // jogging forward
    std::string done;
    CHECK(ms_until_reply(h, done, 1000) == 405);
    CHECK(done == "D6 08 0E 00 81 50 01 00 FA 00 00 00 00 00 00 00 00 00 00 00");
    CHECK(h.send("D9 08 01 02 50 01") == "");
    CHECK(ms_until_reply(h, done, 1000) == 525);
    CHECK(done == "D6 08 0E 00 81 50 01 00 F6 FF FF FF 00 00 00 00 00 00 00 00");   // -10
    CHECK(screw_nm(h, 1) == Approx(6.5e6 + 250 * 20.0 - 260 * 18.0));
    // Continuous jog at 1000 steps/s, in reverse, stopped by MOT_MOVE_STOP after 1 s.
    CHECK(h.send("C0 08 16 00 D0 01 2D 00 01 00 01 00 FA 00 00 00 04 01 00 00 E8 03 00 00 A0 86 01 00") == "");
    CHECK(h.send("D9 08 01 02 50 01") == "");
    h.advance_ms(1000);
    CHECK((status_bits(h.send("E0 08 01 00 50 01"), 1) & 0x80) != 0);   // jogging reverse
    const auto stopped = bytes(h.send("65 04 01 01 50 01"));
    REQUIRE(stopped.size() == 20);
    CHECK(get_u16(stopped, 0) == 0x08D6);
    CHECK(get_i32(stopped, 8) == -10 - 995);   // 5 steps in the 10 ms ramp, then 990
    h.advance_ms(1000);
    CHECK(h.take() == "");
    // InstrumentKit's stop: MOVE_JOG with direction 0.
    CHECK(h.send("D9 08 01 01 50 01") == "");
    h.advance_ms(500);
    CHECK(frames(h.send("D9 08 01 00 50 01")).size() == 1);
}

TEST_CASE("KIM101: the sub-messages it takes, their ranges, the position counter, the status updates' cut-off",
          "[device][apt][today][pzmot]")
{
    AptHarness h(loaded_apt_device(unit("KIM101")));
    // PosCounts: the counter of channel 2 (bit 0x02) reads 5000 from here.
    CHECK(h.send("C0 08 0C 00 D0 01 05 00 02 00 88 13 00 00 00 00 00 00") == "");
    CHECK(h.send("C1 08 05 02 50 01") == "C2 08 0C 00 81 50 05 00 02 00 88 13 00 00 00 00 00 00");
    CHECK(h.send("C1 08 05 01 50 01") == "C2 08 0C 00 81 50 05 00 01 00 00 00 00 00 00 00 00 00");
    // DriveOPParams: 130 V is past 85..125: ignored; 90 V, 1000/s, 50,000/s² taken.
    CHECK(h.send("C0 08 0E 00 D0 01 07 00 01 00 82 00 E8 03 00 00 50 C3 00 00") == "");
    CHECK(h.send("C1 08 07 01 50 01") == "C2 08 0E 00 81 50 07 00 01 00 6E 00 F4 01 00 00 A0 86 01 00");
    CHECK(h.send("C0 08 0E 00 D0 01 07 00 01 00 5A 00 E8 03 00 00 50 C3 00 00") == "");
    CHECK(h.send("C1 08 07 01 50 01") == "C2 08 0E 00 81 50 07 00 01 00 5A 00 E8 03 00 00 50 C3 00 00");
    // The TIM101's jog block (0x09) is not the KIM101's; HomeParams (0x0F) is REQ/GET only; a
    // sub-message no unit has (infn-epics' 0x40) is ignored.
    CHECK(h.send("C1 08 09 01 50 01") == "");
    CHECK(h.send("C1 08 0F 01 50 01") == "C2 08 10 00 81 50 0F 00 01 00 02 00 01 00 F4 01 00 00 00 00 00 00");
    CHECK(h.send("C0 08 10 00 D0 01 0F 00 01 00 01 00 01 00 F4 01 00 00 00 00 00 00") == "");
    CHECK(h.send("C0 08 0A 00 D0 01 40 00 00 00 00 00 00 00 00 00") == "");
    // The trigger ports (0x17) are the unit's: no channel word.
    CHECK(h.send("C0 08 1A 00 D0 01 17 00 01 00 02 00 0A 00 01 00 0B 00 02 00 00 00 00 00 00 00 00 00 00 00 00 00")
          == "");
    CHECK(h.send("C1 08 17 00 50 01")
          == "C2 08 1A 00 81 50 17 00 01 00 02 00 0A 00 01 00 0B 00 02 00 00 00 00 00 00 00 00 00 00 00 00 00");
    // Status updates every 100 ms; without PZMOT_ACK_STATUSUPDATE they stop after 10 (p. 406).
    CHECK(h.send("11 00 00 00 50 01") == "");
    h.advance_ms(2000);
    auto updates = frames(h.take());
    CHECK(updates.size() == 10);
    CHECK(status_position(updates.back(), 2) == 5000);
    CHECK(h.send("E2 08 00 00 50 01") == "");
    h.advance_ms(300);
    CHECK(frames(h.take()).size() == 3);
}

TEST_CASE("TIM101: MOD_SET_CHANENABLESTATE selects the channel that moves, TIM_JogParams' one step size, no "
          "KIM sub-messages",
          "[device][apt][today][pzmot]")
{
    AptHarness h(loaded_apt_device(unit("TIM101", {{"serial_number", 65'000'042},
                                                   {"actuators", json::array({json::object(),
                                                                              {{"step_forward_nm", 30},
                                                                               {"step_reverse_nm", 25}}})}})));
    const auto info = bytes(h.send("05 00 00 00 50 01"));
    REQUIRE(info.size() == 90);
    CHECK(get_u32(info, 6) == 65'000'042);
    CHECK(h.send("C1 08 2B 00 50 01") == "");   // ChanEnableMode is the KIM's (p. 394)
    CHECK(h.send("C1 08 2D 01 50 01") == "");
    CHECK(h.send("C1 08 09 02 50 01")
          == "C2 08 12 00 81 50 09 00 02 00 02 00 FA 00 00 00 F4 01 00 00 A0 86 01 00");
    CHECK(h.send("D9 08 02 02 50 01") == "");   // channel 2: not selected
    h.advance_ms(1000);
    CHECK(h.take() == "");
    CHECK(h.send("10 02 02 01 50 01") == "");
    CHECK(h.send("11 02 01 00 50 01") == "12 02 01 02 01 50");
    CHECK(h.send("11 02 02 00 50 01") == "12 02 02 01 01 50");
    CHECK(h.send("D9 08 02 02 50 01") == "");
    std::string done;
    CHECK(ms_until_reply(h, done, 1000) == 505);
    CHECK(done == "D6 08 0E 00 81 50 02 00 06 FF FF FF 00 00 00 00 00 00 00 00");   // -250
    CHECK(screw_nm(h, 2) == Approx(6.5e6 - 250 * 25.0));
    // Channel 1 is no more selected: its move is ignored.
    CHECK(h.send("D4 08 06 00 D0 01 01 00 " + le32(100)) == "");
    h.advance_ms(1000);
    CHECK(h.take() == "");
}

TEST_CASE("KIM101/TIM101: the rig's actuators, refused with the JSON pointer", "[device][apt][today][pzmot]")
{
    CHECK(apt_load_error(unit("KIM101", {{"actuators", json::array({json::object(), json::object(), json::object(),
                                                               json::object(), json::object()})}}))
          == "rig.json: /devices/0/apt/actuators: expected an array of 1..4 actuator objects, got an array of 5 "
             "elements");
    CHECK(apt_load_error(unit("KIM101", {{"actuators", json::array({{{"travel_mm", 25}, {"position_mm", 30}}})}}))
          == "rig.json: /devices/0/apt/actuators/0/position_mm: expected a number from 0 to travel_mm, got 30");
    CHECK(apt_load_error(unit("TIM101", {{"actuators", json::array({{{"stroke", 1}}})}})).find("/devices/0/apt/actuators/0")
          != std::string::npos);
    CHECK(apt_load_error(unit("KIM101", {{"stage", "PIA13"}})).find("its keys are actuators, serial_number")
          != std::string::npos);
    CHECK(apt_load_error(unit("KIM101", {{"serial_number", 65'000'001}})).find("serial_number") != std::string::npos);
    CHECK(apt_load_error(unit("KIM101", {{"actuators", json::array({{{"travel_mm", 50}, {"position_mm", 0}}})}})) == "");
}

TEST_CASE("KIM101: a stall on an actuator holds its screw while the pulses are counted, no reference to lose",
          "[device][apt][today][pzmot]")
{
    AptHarness h(loaded_apt_device(unit("KIM101")));
    std::string key;
    DeviceFault stall;
    stall.kind = FaultKind::Stall;
    stall.channel = 0;
    REQUIRE_FALSE(h.device().fault_body(stall, key));
    CHECK(key == "unit/1");
    DeviceFault lost;
    lost.kind = FaultKind::ReferenceLost;
    CHECK(h.device().fault_body(lost, key));
    DeviceFault past;
    past.channel = 4;
    CHECK(h.device().fault_body(past, key)->status == 404);
    h.world().add_fault(1, key, models::BodyFault{});
    CHECK(h.send("D4 08 06 00 D0 01 01 00 " + le32(100)) == "");
    h.advance_ms(205);
    CHECK(frames(h.take()).size() == 1);
    CHECK(screw_nm(h, 1) == Approx(6.5e6));   // stalled: the counter says 100, the screw did not move
    CHECK(status_position(h.send("E0 08 01 00 50 01"), 1) == 100);
}

} // namespace test_apt_pzmot
