// APT: the rest of the stage catalogue (PRM1-Z8 rotation, DRV014, DDSM100), S-curve profiles
// (MOT_SET_PMDPROFILEMODEPARAMS) and the fault the emulator models (a motor stalled against
// its end stop: HW_RESPONSE / HW_RICHRESPONSE), bytes in -> bytes out on a stepped clock.
#include "apt_harness.hpp"

#include <cmath>
#include <vector>

namespace test_apt_stages_faults {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;

namespace {

// SET_LIMSWITCHPARAMS: CW (forward) switch ignored, CCW makes on contact, no soft limits.
constexpr const char* kIgnoreForwardSwitch = "23 04 10 00 D0 01 01 00 01 00 02 00 00 00 00 00 00 00 00 00 01 00";

} // namespace

TEST_CASE("a move past an ignored limit switch stalls the DC motor: KDC101 sends HW_RICHRESPONSE", "[device][apt][fault]")
{
    AptHarness h(apt_cube("KDC101", "Z825B"));   // 25 mm: the counter reads 0 mid-travel, the end is +428,800
    CHECK(h.send(kIgnoreForwardSwitch) == "");
    CHECK(h.send("53 04 06 00 D0 01 01 00 " + le32(500'000)) == "");
    h.advance_ms(10'000);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 2);
    // HW_RICHRESPONSE: MsgIdent 0x0453 (the MOVE_ABSOLUTE), code 1, notes char[64].
    const auto rich = bytes(out[0]);
    REQUIRE(rich.size() == 74);
    CHECK(hex(rich.substr(0, 10)) == "81 00 44 00 81 50 53 04 01 00");
    CHECK(rich.substr(10, 13) == "Motor stalled");
    CHECK(rich.back() == '\0');
    // MOVE_STOPPED at the end stop: current limit reached, no limit switch bit.
    CHECK(out[1].substr(0, 35) == "66 04 0E 00 81 50 01 00 " + le32(428'800));
    CHECK(status_of(out[1]) == (status::kMotorConnected | status::kCurrentLimit | status::kSettled | status::kEnabled));
    CHECK(h.send("11 04 01 00 50 01") == "12 04 06 00 81 50 01 00 " + le32(428'800));
    // The next move clears the stall bit.
    CHECK(h.send("48 04 06 00 D0 01 01 00 " + le32(-34'304)) == "");
    h.advance_ms(3'000);
    const auto done = frames(h.take());
    REQUIRE(done.size() == 1);
    CHECK(done[0].substr(0, 17) == "64 04 0E 00 81 50");
    CHECK((status_of(done[0]) & status::kCurrentLimit) == 0);
}

TEST_CASE("TDC001 reports the stall with the manual's HW_RESPONSE, SUSPEND_ENDOFMOVEMSGS silences it", "[device][apt][fault]")
{
    AptHarness h;   // TDC001 + MTS50-Z8: the end is +857,600 counts away
    CHECK(h.send(kIgnoreForwardSwitch) == "");
    CHECK(h.send("57 04 01 01 50 01") == "");   // MOVE_VELOCITY forward
    h.advance_ms(30'000);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 2);
    CHECK(out[0] == "80 00 00 00 01 50");
    CHECK(out[1].substr(0, 35) == "66 04 0E 00 81 50 01 00 " + le32(857'600));
    CHECK((status_of(out[1]) & status::kCurrentLimit) != 0);

    CHECK(h.send("6B 04 00 00 50 01") == "");   // SUSPEND: no error messages either (p. 82)
    CHECK(h.send("57 04 01 01 50 01") == "");
    h.advance_ms(1'000);
    CHECK(h.take() == "");
    CHECK((h.device().channel().status_bits() & status::kCurrentLimit) != 0);
    CHECK(h.send("6C 04 00 00 50 01") == "");   // RESUME: they come again
    CHECK(h.send("57 04 01 01 50 01") == "");
    h.advance_ms(1'000);
    const auto again = frames(h.take());
    REQUIRE(again.size() == 2);
    CHECK(again[0] == "80 00 00 00 01 50");
    CHECK(again[1].substr(0, 17) == "66 04 0E 00 81 50");
}

TEST_CASE("with its limit switch making contact the axis stops at the switch without a fault", "[device][apt][fault]")
{
    AptHarness h;
    CHECK(h.send("57 04 01 01 50 01") == "");
    h.advance_ms(30'000);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 1);
    CHECK(out[0].substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(857'600));
    CHECK((status_of(out[0]) & status::kForwardHardLimit) != 0);
    CHECK((status_of(out[0]) & status::kCurrentLimit) == 0);
}

TEST_CASE("a BBD203 bay that runs into its end stop: motion error, HW_RESPONSE from the motherboard", "[device][apt][fault][rack]")
{
    AptHarness h(apt_rack("BBD203", {"MLS203-X", "MLS203-Y"}));
    CHECK(h.send("23 04 10 00 A2 01 01 00 02 00 01 00 00 00 00 00 00 00 00 00 01 00") == "");   // bay 1: CCW ignored
    CHECK(h.send("57 04 01 02 22 01") == "");   // MOVE_VELOCITY reverse, bay 1 (Y, 75 mm)
    h.advance_ms(3'000);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 2);
    CHECK(out[0] == "80 00 00 00 01 11");   // p. 19: "TX 80, 00, 00, 00, 01, 11"
    CHECK(out[1].substr(0, 35) == "66 04 0E 00 81 22 01 00 " + le32(-750'000));
    CHECK((status_of(out[1]) & status::kMotionError) != 0);
    CHECK((status_of(out[1]) & status::kReverseHardLimit) == 0);   // the switch is ignored
    // The other bay is untouched.
    CHECK(h.send("11 04 01 00 21 01") == "12 04 06 00 81 21 01 00 00 00 00 00");
}

TEST_CASE("a stepper against its end stop loses steps: the counter counts them, no fault", "[device][apt][fault][stepper]")
{
    AptHarness h(apt_cube("KST101", "DRV014"));   // 50 mm at 25,600 microsteps/mm: the end is +640,000
    CHECK(h.send(kIgnoreForwardSwitch) == "");
    CHECK(h.send("53 04 06 00 D0 01 01 00 " + le32(700'000)) == "");
    h.advance_ms(20'000);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 1);
    CHECK(out[0].substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(700'000));   // MOVE_COMPLETED
    // The carriage stands at the end stop, 60,000 microsteps short of where the counter says:
    // at the reverse switch the counter reads -580,000 where it read -640,000 before.
    CHECK(h.send("57 04 01 02 50 01") == "");   // MOVE_VELOCITY reverse
    h.advance_ms(40'000);
    const auto back = frames(h.take());
    REQUIRE(back.size() == 1);
    CHECK(back[0].substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(-580'000));
    CHECK((status_of(back[0]) & status::kReverseHardLimit) != 0);
}

TEST_CASE("PRM1-Z8 turns without end and homes on its switch once per turn", "[device][apt][stage]")
{
    AptHarness h(apt_cube("KDC101", "PRM1-Z8"));
    constexpr double kCountsPerDeg = 1'919.6418;
    // VELPARAMS: 10 deg/s and 10 deg/s² in the DC servo scaling.
    const auto vel = bytes(h.send("14 04 01 00 50 01"));
    CHECK(get_i32(vel, 16) == std::lround(10 * kCountsPerDeg * 2048.0 / 6e6 * 65536));
    // Two turns forward: no limit on the way.
    const auto two_turns = static_cast<std::int32_t>(std::lround(720 * kCountsPerDeg));
    CHECK(h.send("48 04 06 00 D0 01 01 00 " + le32(two_turns)) == "");
    h.advance_ms(80'000);
    const auto moved = frames(h.take());
    REQUIRE(moved.size() == 1);
    CHECK(moved[0].substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(two_turns));
    CHECK((status_of(moved[0]) & (status::kForwardHardLimit | status::kReverseHardLimit)) == 0);
    // Home (reverse): power-up stood half a turn past a switch, and two turns on it is half
    // a turn past the next one: 180 degrees back to it, 4 degrees forward, the counter reads 0.
    CHECK(h.send("43 04 01 00 50 01") == "");
    h.advance_ms(15'000);
    CHECK(h.take() == "");   // 18 s at 10 deg/s: still homing
    h.advance_ms(10'000);
    CHECK(h.take() == "44 04 01 00 01 50");
    CHECK(h.send("11 04 01 00 50 01") == "12 04 06 00 81 50 01 00 00 00 00 00");
    CHECK((h.device().channel().status_bits() & status::kHomed) != 0);
}

TEST_CASE("DRV014 and DDSM100: travel, encoder resolution and power-up velocities", "[device][apt][stage]")
{
    AptHarness kst(apt_cube("KST101", "DRV014"));
    CHECK(kst.device().channel().max_position() == 1'280'000);   // 50 mm
    CHECK(kst.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 01 00 00 00 00 00 00 90 01 00 00 C8 00 00");

    AptHarness bbd(apt_rack("BBD203", {"DDSM100"}));
    // 500 mm/s and 5,000 mm/s² at 2,000 counts/mm in the PMD scaling of 7.1 (per count).
    const auto vel = bytes(bbd.send("14 04 01 00 21 01"));
    CHECK(get_i32(vel, 16) == 6'710'900);
    CHECK(get_i32(vel, 12) == 6'872);
    const auto axis = bytes(bbd.send("F1 04 01 00 21 01"));   // REQ_PMDSTAGEAXISPARAMS
    REQUIRE(axis.size() == 80);
    CHECK(get_u16(axis, 8) == 0);                               // no stage ID in the manual
    CHECK(axis.substr(12, 7) == "DDSM100");
    CHECK(get_u32(axis, 32) == 2'000);
    CHECK(get_i32(axis, 36) == 0);
    CHECK(get_i32(axis, 40) == 200'000);
    CHECK(get_i32(axis, 44) == 6'872);        // MaxAccn: the power-up acceleration
    CHECK(get_i32(axis, 52) == 6'710'900);    // MaxVel
}

TEST_CASE("PMDPROFILEMODEPARAMS S-curve: the move takes a/j longer than the trapezoid", "[device][apt][scurve][rack]")
{
    AptHarness h(apt_rack("BBD203", {"MLS203-X", "MLS203-X"}));
    // p. 69's example: S-curve, jerk 10,000 mm/s³ (922337), for bay 1 only.
    CHECK(h.send("E3 04 0C 00 A2 01 01 00 02 00 E1 12 0E 00 00 00 00 00") == "");
    CHECK(h.send("E4 04 01 00 22 01") == "E5 04 0C 00 81 22 01 00 02 00 E1 12 0E 00 00 00 00 00");
    CHECK(h.send("E3 04 0C 00 A1 01 01 00 01 00 E1 12 0E 00 00 00 00 00") == "");   // mode 1: none
    CHECK(h.send("E4 04 01 00 21 01") == "E5 04 0C 00 81 21 01 00 00 00 00 00 00 00 00 00 00 00");
    // 50 mm at 100 mm/s and 500 mm/s²: trapezoid 0.5 + 0.2 = 0.7 s; S-curve + a/j = 0.05 s.
    CHECK(h.send("48 04 06 00 A1 01 01 00 " + le32(1'000'000)) == "");
    CHECK(h.send("48 04 06 00 A2 01 01 00 " + le32(1'000'000)) == "");
    h.advance_ms(701);
    auto out = frames(h.take());
    REQUIRE(out.size() == 1);
    CHECK(out[0].substr(0, 17) == "64 04 0E 00 81 21");
    h.advance_ms(740 - 701);
    CHECK(h.take() == "");
    h.advance_ms(12);
    out = frames(h.take());
    REQUIRE(out.size() == 1);
    CHECK(out[0].substr(0, 35) == "64 04 0E 00 81 22 01 00 " + le32(1'000'000));
}

TEST_CASE("S-curve ramps start gently: after 20 ms the S-curve axis trails the trapezoid", "[device][apt][scurve][rack]")
{
    AptHarness h(apt_rack("BBD203", {"MLS203-X", "MLS203-X"}));
    CHECK(h.send("E3 04 0C 00 A2 01 01 00 02 00 E1 12 0E 00 00 00 00 00") == "");
    CHECK(h.send("48 04 06 00 A1 01 01 00 " + le32(1'000'000)) == "");
    CHECK(h.send("48 04 06 00 A2 01 01 00 " + le32(1'000'000)) == "");
    h.advance_ms(20);
    // Trapezoid: a t²/2 = 500 × 0.02² / 2 mm = 0.1 mm = 2,000 counts.
    // S-curve: j t³/6 = 10,000 × 0.02³ / 6 mm = 0.01333 mm = 267 counts.
    CHECK(h.device().channel(0).position() == 2'000);
    CHECK(h.device().channel(1).position() == Approx(267).margin(1));
}

TEST_CASE("a move re-targeted while running whose braking overshoots an ignored end stalls there", "[device][apt][fault]")
{
    AptHarness h;   // TDC001 + MTS50-Z8: 2.4 mm/s, 1.5 mm/s²: 1.92 mm (65,866 counts) to brake
    CHECK(h.send(kIgnoreForwardSwitch) == "");
    CHECK(h.send("57 04 01 01 50 01") == "");
    h.advance_ms(10'800);   // past 817,600: braking from there ends beyond the end (857,600)
    REQUIRE(position_of(h.send("11 04 01 00 50 01")) > 817'600);
    CHECK(h.send("53 04 06 00 D0 01 01 00 " + le32(837'600)) == "");   // a legal target
    h.advance_ms(3'000);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 2);
    CHECK(out[0] == "80 00 00 00 01 50");
    CHECK(out[1].substr(0, 35) == "66 04 0E 00 81 50 01 00 " + le32(857'600));
}

TEST_CASE("a stepper stopped while pushing against its end stop keeps the steps it lost", "[device][apt][fault][stepper]")
{
    AptHarness h(apt_cube("KST101", "DRV014"));   // end stops at -640,000 and +640,000
    CHECK(h.send(kIgnoreForwardSwitch) == "");
    CHECK(h.send("57 04 01 01 50 01") == "");
    h.advance_ms(15'000);                      // 30 mm at 2 mm/s: 5 mm into the stop
    CHECK(h.send("65 04 01 01 50 01").substr(0, 17) == "66 04 0E 00 81 50");   // immediate stop
    const auto counted = position_of(h.send("11 04 01 00 50 01"));
    CHECK(counted > 640'000 + 100'000);
    CHECK(h.send("57 04 01 02 50 01") == "");  // to the reverse switch: 1,280,000 microsteps away
    h.advance_ms(60'000);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 1);
    CHECK(get_i32(bytes(out[0]), 8) == counted - 1'280'000);
}

TEST_CASE("a stepper's backlash overshoot into an ignored end still ends on the commanded count", "[device][apt][fault][stepper]")
{
    AptHarness h(apt_cube("KST101", "DRV014"));
    CHECK(h.send("23 04 10 00 D0 01 01 00 02 00 01 00 00 00 00 00 00 00 00 00 01 00") == "");   // CCW ignored
    CHECK(h.send("3A 04 06 00 D0 01 01 00 " + le32(1'000)) == "");                               // backlash
    CHECK(h.send("53 04 06 00 D0 01 01 00 " + le32(-639'990)) == "");
    h.advance_ms(30'000);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 1);
    CHECK(out[0].substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(-639'990));
}

TEST_CASE("homing a stepper whose home switch is ignored ends in MOVE_STOPPED, not homed", "[device][apt][fault][stepper]")
{
    AptHarness h(apt_cube("TST001", "DRV001"));
    CHECK(h.send("23 04 10 00 D0 01 01 00 02 00 01 00 00 00 00 00 00 00 00 00 01 00") == "");   // CCW ignored
    CHECK(h.send("43 04 01 00 50 01") == "");
    h.advance_ms(60'000);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 1);
    CHECK(out[0].substr(0, 17) == "66 04 0E 00 81 50");
    CHECK((status_of(out[0]) & status::kHomed) == 0);
}

TEST_CASE("LIMSWITCHPARAMS modes outside the manual's are ignored", "[device][apt][fault]")
{
    AptHarness h;
    const std::string before = h.send("24 04 01 00 50 01");
    CHECK(h.send("23 04 10 00 D0 01 01 00 00 00 02 00 00 00 00 00 00 00 00 00 01 00") == "");   // CW 0
    CHECK(h.send("23 04 10 00 D0 01 01 00 02 00 07 00 00 00 00 00 00 00 00 00 01 00") == "");   // CCW 7
    CHECK(h.send("23 04 10 00 D0 01 01 00 02 00 02 00 00 00 00 00 00 00 00 00 04 00") == "");   // soft 4
    CHECK(h.send("24 04 01 00 50 01") == before);
    CHECK(h.send("23 04 10 00 D0 01 01 00 82 00 82 00 00 00 00 00 00 00 00 00 83 00") == "");   // swapped: fine
    CHECK(h.send("24 04 01 00 50 01") == "25 04 10 00 81 50 01 00 82 00 82 00 00 00 00 00 00 00 00 00 83 00");
}

TEST_CASE("a narrowed travel stops a brushless bay at its new limit, not at the end stop", "[device][apt][rack]")
{
    AptHarness h(apt_rack("BBD203", {"MLS203-X"}));
    std::string axis = bytes(h.send("F1 04 01 00 21 01")).substr(6);
    std::string max;
    put_i32(max, 1'000'000);   // 50 mm of 110
    axis.replace(34, 4, max);
    CHECK(h.send(hex(encode_with_data(MGMSG_MOT_SET_PMDSTAGEAXISPARAMS, 0x21, 0x01, axis))) == "");
    CHECK(h.send("43 04 01 00 21 01") == "");   // homes forward: at the limit the counter reads 50 mm
    h.advance_ms(30'000);
    CHECK(h.take() == "44 04 01 00 01 21");
    CHECK(h.send("11 04 01 00 21 01") == "12 04 06 00 81 21 01 00 " + le32(1'000'000));
}

TEST_CASE("software limit mode 2 stops dead at the limit, mode 3 brakes to it", "[device][apt]")
{
    // Soft limits ±0.5 mm (17,152 counts); a move to +1 mm. Accelerating at 1.5 mm/s² the stage
    // crosses +0.5 mm after sqrt(2 × 0.5 / 1.5) = 0.816 s; a profiled stop there takes 1.155 s.
    for (const char* mode : {"02", "03"}) {
        AptHarness h;
        CHECK(h.send(std::string("23 04 10 00 D0 01 01 00 02 00 02 00 00 43 00 00 00 BD FF FF ") + mode + " 00") == "");
        CHECK(h.send("53 04 06 00 D0 01 01 00 00 86 00 00") == "");
        h.advance_ms(850);
        const auto early = h.take();
        if (std::string(mode) == "02") {
            REQUIRE(frames(early).size() == 1);
            CHECK(early.substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(17'152));
        } else {
            CHECK(early == "");
            h.advance_ms(310);
            CHECK(h.take().substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(17'152));
        }
        // From the limit the stage moves back in.
        CHECK(h.send("53 04 06 00 D0 01 01 00 00 00 00 00") == "");
        h.advance_ms(2'000);
        CHECK(position_of(h.send("11 04 01 00 50 01")) == 0);
    }
}

} // namespace test_apt_stages_faults
