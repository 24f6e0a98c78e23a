// APT DC servo T-Cube/K-Cube: bytes in -> bytes out on a stepped clock (hex transcripts).
#include "apt_harness.hpp"

#include <cstdio>
#include <unistd.h>
#include <stdlib.h>

namespace test_apt_dc_servo {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;

TEST_CASE("HW_REQ_INFO answers the 84-byte info packet of the model", "[device][apt]")
{
    AptHarness h;
    const auto reply = bytes([&] { return h.send("05 00 00 00 50 01"); }());
    REQUIRE(reply.size() == 90);
    CHECK(hex(reply.substr(0, 6)) == "06 00 54 00 81 50");
    CHECK(get_u32(reply, 6) == 83'000'001);                 // prefix 83: TDC001 (manual 2.2)
    CHECK(reply.substr(10, 8) == std::string("TDC001\0\0", 8));
    CHECK(get_u16(reply, 88) == 1);                         // one channel
}

TEST_CASE("a single unit acts on 0x50, 0x11 and 0x21 and ignores other modules", "[device][apt]")
{
    AptHarness h;
    CHECK(h.send("11 04 01 00 50 01") == "12 04 06 00 81 50 01 00 00 00 00 00");   // REQ_POSCOUNTER
    CHECK(h.send("11 04 01 00 11 01") == "12 04 06 00 81 50 01 00 00 00 00 00");
    CHECK(h.send("11 04 01 00 21 01") == "12 04 06 00 81 50 01 00 00 00 00 00");
    CHECK(h.send("11 04 01 00 22 01") == "");                                      // bay 1: absent
    CHECK(h.send("11 04 02 00 50 01") == "");                                      // channel 2: absent
}

TEST_CASE("MOVE_ABSOLUTE runs the trapezoid and reports MOVE_COMPLETED", "[device][apt]")
{
    AptHarness h;
    // VELPARAMS: acceleration 1.5 mm/s² (393), max 2.4 mm/s (1841682) at 34,304 counts/mm.
    const auto vel = h.send("14 04 01 00 50 01");
    CHECK(vel == "15 04 0E 00 81 50 01 00 00 00 00 00 89 01 00 00 12 1A 1C 00");
    // Move to 1 mm: 34304 counts = 00 86 00 00.
    CHECK(h.send("53 04 06 00 D0 01 01 00 00 86 00 00") == "");
    h.advance_ms(500);
    const auto mid = h.send("11 04 01 00 50 01");
    const auto p = position_of(mid);
    CHECK(p > 0);
    CHECK(p < 34'304);
    CHECK(h.send("29 04 01 00 50 01").substr(0, 35) == "2A 04 06 00 81 50 01 00 10 01 00 80");   // moving forward
    h.advance_ms(1500);                                      // T = d/v + v/a = 0.42 + 1.6 s
    const auto done = h.take();
    REQUIRE(done.size() == 20 * 3 - 1);
    CHECK(done.substr(0, 17) == "64 04 0E 00 81 50");        // MOVE_COMPLETED with status
    CHECK(position_of(h.send("11 04 01 00 50 01")) == 34'304);
}

TEST_CASE("MOVE_HOME drives to the reverse limit, backs off, zeroes and sends MOVE_HOMED", "[device][apt]")
{
    AptHarness h;
    CHECK(h.send("43 04 01 00 50 01") == "");
    h.advance_ms(1000);
    CHECK((h.device().channel().status_bits() & status::kHoming) != 0);
    h.advance_ms(30'000);                                    // 25 mm at 1 mm/s, then 0.3 mm back
    CHECK(h.take() == "44 04 01 00 01 50");
    CHECK(position_of(h.send("11 04 01 00 50 01")) == 0);
    CHECK((h.device().channel().status_bits() & status::kHomed) != 0);
}

namespace {

/// The clock millisecond at which MOVE_HOMED arrives after MOVE_HOME at 0, with MOVE_HOME
/// sent again every `resend_ms` (0: never) while waiting, as drivers do.
std::int64_t homed_at_ms(std::int64_t resend_ms)
{
    AptHarness h;
    CHECK(h.send("43 04 01 00 50 01") == "");
    for (std::int64_t t_ms = 1; t_ms <= 60'000; ++t_ms) {
        h.advance_ms(1);
        if (h.take() == "44 04 01 00 01 50")
            return t_ms;
        if (resend_ms > 0 && t_ms % resend_ms == 0)
            CHECK(h.send("43 04 01 00 50 01") == "");
    }
    return -1;
}

} // namespace

TEST_CASE("MOVE_HOME while homing is ignored: re-sent every 500 ms, MOVE_HOMED comes at the same tick", "[device][apt]")
{
    const auto undisturbed_ms = homed_at_ms(0);
    REQUIRE(undisturbed_ms > 0);
    CHECK(homed_at_ms(500) == undisturbed_ms);
    CHECK(homed_at_ms(3000) == undisturbed_ms);
}

TEST_CASE("MOVE_STOP always answers MOVE_STOPPED, even when still", "[device][apt]")
{
    AptHarness h;
    const auto r = h.send("65 04 01 01 50 01");
    CHECK(r.substr(0, 17) == "66 04 0E 00 81 50");
    CHECK(h.send("48 04 06 00 D0 01 01 00 00 86 00 00") == "");   // relative 1 mm
    h.advance_ms(300);
    const auto s = h.send("65 04 01 01 50 01");                   // immediate stop
    CHECK(s.substr(0, 17) == "66 04 0E 00 81 50");
    h.advance_ms(3000);
    CHECK(h.take() == "");                                         // no MOVE_COMPLETED after a stop
}

TEST_CASE("status updates: none before START_UPDATEMSGS, every 100 ms after, 50 without ACK", "[device][apt]")
{
    AptHarness h;
    h.advance_ms(1000);
    CHECK(h.take() == "");
    CHECK(h.send("11 00 00 00 50 01") == "");                    // HW_START_UPDATEMSGS
    h.advance_ms(99);
    CHECK(h.take() == "");
    h.advance_ms(1);
    CHECK(h.take().substr(0, 17) == "91 04 0E 00 81 50");        // MOT_GET_DCSTATUSUPDATE
    h.advance_ms(4900);                                          // 50 updates in all
    CHECK(h.take().size() == 49 * 20 * 3 - 1);        // 49 more frames of 20 bytes, as hex
    h.advance_ms(1000);
    CHECK(h.take() == "");                                       // no server alive: silent
    CHECK(h.send("92 04 00 00 50 01") == "");                    // MOT_ACK_DCSTATUSUPDATE
    h.advance_ms(200);
    CHECK(h.take().size() == 2 * 20 * 3 - 1);
    CHECK(h.send("12 00 00 00 50 01") == "");                    // HW_STOP_UPDATEMSGS
    h.advance_ms(1000);
    CHECK(h.take() == "");
}

TEST_CASE("parameters round-trip, out-of-range ones are ignored", "[device][apt]")
{
    AptHarness h;
    CHECK(h.send("13 04 0E 00 D0 01 01 00 00 00 00 00 10 00 00 00 00 10 00 00") == "");
    CHECK(h.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 01 00 00 00 00 00 10 00 00 00 00 10 00 00");
    CHECK(h.send("13 04 0E 00 D0 01 01 00 00 00 00 00 00 00 00 00 00 10 00 00") == "");   // zero acceleration
    CHECK(h.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 01 00 00 00 00 00 10 00 00 00 00 10 00 00");
    CHECK(h.send("40 04 0E 00 D0 01 01 00 02 00 01 00 00 10 00 00 00 02 00 00") == "");   // HOMEPARAMS
    CHECK(h.send("41 04 01 00 50 01") == "42 04 0E 00 81 50 01 00 02 00 01 00 00 10 00 00 00 02 00 00");
    CHECK(h.send("10 04 06 00 D0 01 01 00 40 0D 03 00") == "");   // SET_POSCOUNTER 200000
    CHECK(h.send("11 04 01 00 50 01") == "12 04 06 00 81 50 01 00 40 0D 03 00");
    CHECK(h.send("10 02 01 02 50 01") == "");                      // channel disabled
    CHECK(h.send("11 02 01 00 50 01") == "12 02 01 02 01 50");
    CHECK(h.send("53 04 06 00 D0 01 01 00 00 00 00 00") == "");   // does not move
    h.advance_ms(5000);
    CHECK(h.take() == "");
    CHECK(h.send("18 00 00 00 50 01") == "");                      // HW_NO_FLASH_PROGRAMMING
}

TEST_CASE("HUB_REQ_BAYUSED: a standalone cube answers -1", "[device][apt]")
{
    AptHarness h;
    CHECK(h.send("65 00 00 00 50 01") == "66 00 FF 00 01 50");
}

TEST_CASE("garbage and unknown messages are skipped without an answer", "[device][apt]")
{
    AptHarness h;
    CHECK(h.send("FF 00 13 37 99 11 04 01 00 50 01") == "12 04 06 00 81 50 01 00 00 00 00 00");
    CHECK(h.send("99 99 00 00 50 01 11 04 01 00 50 01") == "12 04 06 00 81 50 01 00 00 00 00 00");
    CHECK(h.send("64 04 0E 00 50 01") == "");                      // a GET sent by a host: ignored
}

TEST_CASE("software limits (LIMSWITCHPARAMS) stop moves, backlash (GENMOVEPARAMS) overshoots reverse moves", "[device][apt]")
{
    AptHarness h;
    // Soft limits -0.5 mm .. +0.5 mm (17152 counts), profiled stop at limit (mode 3).
    CHECK(h.send("23 04 10 00 D0 01 01 00 02 00 02 00 00 43 00 00 00 BD FF FF 03 00") == "");
    CHECK(h.send("24 04 01 00 50 01") == "25 04 10 00 81 50 01 00 02 00 02 00 00 43 00 00 00 BD FF FF 03 00");
    CHECK(h.send("53 04 06 00 D0 01 01 00 00 86 00 00") == "");   // to +1 mm: stops at +0.5 mm
    h.advance_ms(3000);
    CHECK(h.take().substr(0, 17) == "64 04 0E 00 81 50");
    CHECK(position_of(h.send("11 04 01 00 50 01")) == 17'152);
    CHECK((h.device().channel().status_bits() & status::kForwardSoftLimit) != 0);
    CHECK(h.send("23 04 10 00 D0 01 01 00 02 00 02 00 00 00 00 00 00 00 00 00 01 00") == "");   // ignore
    // Backlash 0.1 mm: a reverse move goes 0.1 mm past the target and comes back.
    CHECK(h.send("3A 04 06 00 D0 01 01 00 00 0D 00 00") == "");   // 3328 counts
    CHECK(h.send("3B 04 01 00 50 01") == "3C 04 06 00 81 50 01 00 00 0D 00 00");
    CHECK(h.send("53 04 06 00 D0 01 01 00 00 00 00 00") == "");   // back to 0
    std::int32_t lowest = 17'152;
    for (int i = 0; i < 300; ++i) {
        h.advance_ms(10);
        lowest = std::min(lowest, h.device().channel().position());
    }
    CHECK(lowest <= -3'000);                                        // overshot by about the backlash
    const auto completed = h.take();
    CHECK(completed.size() == 20 * 3 - 1);                          // one MOVE_COMPLETED, at the end
    CHECK(completed.substr(0, 17) == "64 04 0E 00 81 50");
    CHECK(position_of(h.send("11 04 01 00 50 01")) == 0);
}

TEST_CASE("single-channel units take channel 0 as their channel 1, answers carry channel 1", "[device][apt]")
{
    for (const char* model : {"TDC001", "KDC101"}) {
        INFO(model);
        AptHarness h(apt_cube(model, "MTS50-Z8"));
        // REQ_POSCOUNTER for channel 0: GET_POSCOUNTER for channel 1.
        CHECK(h.send("11 04 00 00 50 01") == "12 04 06 00 81 50 01 00 00 00 00 00");
        // SET_MOVERELPARAMS for channel 0 (10,000 counts), read back.
        CHECK(h.send("45 04 06 00 D0 01 00 00 10 27 00 00") == "");
        CHECK(h.send("46 04 00 00 50 01") == "47 04 06 00 81 50 01 00 10 27 00 00");
        // MOVE_ABSOLUTE (long form) for channel 0 to 1 mm: the stage moves.
        CHECK(h.send("53 04 06 00 D0 01 00 00 00 86 00 00") == "");
        h.advance_ms(3000);
        CHECK(h.take().substr(0, 17) == "64 04 0E 00 81 50");
        CHECK(position_of(h.send("11 04 01 00 50 01")) == 34'304);
        // Header-only: MOD_REQ_CHANENABLESTATE and MOVE_JOG for channel 0.
        CHECK(h.send("11 02 00 00 50 01") == "12 02 01 01 01 50");
        CHECK(h.send("6A 04 00 02 50 01") == "");
        h.advance_ms(3000);
        CHECK(position_of(h.send("11 04 01 00 50 01")) == 34'304 - 3'430);   // one jog step back
        CHECK(h.send("11 04 02 00 50 01") == "");                              // channel 2: still ignored
    }
    for (const char* model : {"TST001", "KST101"}) {
        INFO(model);
        AptHarness h(apt_cube(model, "DRV001"));
        CHECK(h.send("11 04 00 00 50 01") == "12 04 06 00 81 50 01 00 00 00 00 00");
    }
    // A rack bay keeps the manual's rule: channel 1 only.
    AptHarness rack(apt_rack("BBD203", {"MLS203-X", "MLS203-Y", "MLS203-X"}));
    CHECK(rack.send("11 04 00 00 21 01") == "");
    CHECK(rack.send("11 04 01 00 21 01") == "12 04 06 00 81 21 01 00 00 00 00 00");
}

TEST_CASE("a BBD203 rack: motherboard at 0x11, bays at 0x21+, replies carry the bay", "[device][apt][rack]")
{
    AptHarness h(apt_rack("BBD203", {"MLS203-X", "MLS203-Y"}));
    // The motherboard: its info (type 45, 2 bays) and which bays are used (p. 23: from 0).
    const auto info = bytes(h.send("05 00 00 00 11 01"));
    REQUIRE(info.size() == 90);
    CHECK(hex(info.substr(0, 6)) == "06 00 54 00 81 11");
    CHECK(get_u32(info, 6) == 73'000'001);
    CHECK(get_u16(info, 18) == 45);
    CHECK(get_u16(info, 88) == 3);                                 // three channels built in
    CHECK(h.send("60 00 00 00 11 01") == "61 00 00 01 01 11");
    CHECK(h.send("60 00 01 00 11 01") == "61 00 01 01 01 11");
    CHECK(h.send("60 00 02 00 11 01") == "61 00 02 01 01 11");    // bay 2: built in, no stage
    CHECK(h.send("60 00 03 00 11 01") == "61 00 03 02 01 11");    // no bay 3
    // A bay's card: type 44, one channel, its own address as the source.
    const auto card = bytes(h.send("05 00 00 00 22 01"));
    REQUIRE(card.size() == 90);
    CHECK(hex(card.substr(0, 6)) == "06 00 54 00 81 22");
    CHECK(get_u16(card, 18) == 44);
    // The manual's VELPARAMS example for MLS203 bay 2 (p. 30): accel 10 mm/s², 99 mm/s.
    CHECK(h.send("13 04 0E 00 A2 01 01 00 00 00 00 00 89 00 00 00 9E C0 CA 00") == "");
    CHECK(h.send("14 04 01 00 22 01") == "15 04 0E 00 81 22 01 00 00 00 00 00 89 00 00 00 9E C0 CA 00");
    // The manual's MOVE_RELATIVE example: bay 2 by 10 mm (200,000 counts).
    CHECK(h.send("48 04 06 00 A2 01 01 00 40 0D 03 00") == "");
    h.advance_ms(20'000);
    const auto done = h.take();
    CHECK(done.substr(0, 17) == "64 04 0E 00 81 22");
    CHECK(position_of(h.send("11 04 01 00 22 01")) == 200'000);
    CHECK(position_of(h.send("11 04 01 00 21 01")) == 0);        // bay 0 did not move
    CHECK(h.send("11 04 01 00 23 01") == "");                      // absent bay: ignored
    CHECK(h.send("11 04 01 00 50 01") == "");                      // not a single unit
}

TEST_CASE("a built-in rack channel without a stage: bay occupied, card answers, motor not connected", "[device][apt][rack]")
{
    for (const auto& [model, stage] : {std::pair<const char*, const char*>{"BBD203", "MLS203-X"}, {"BSC203", "DRV001"}}) {
        INFO(model);
        AptHarness h(apt_rack(model, {stage}));
        // p.23: bays 1 and 2 are occupied (their cards are built in); there is no bay 3.
        CHECK(h.send("60 00 01 00 11 01") == "61 00 01 01 01 11");
        CHECK(h.send("60 00 02 00 11 01") == "61 00 02 01 01 11");
        CHECK(h.send("60 00 03 00 11 01") == "61 00 03 02 01 11");
        CHECK(get_u16(bytes(h.send("05 00 00 00 11 01")), 88) == 3);
        // The card in bay 2 identifies itself (one channel, its own address) ...
        const auto card = bytes(h.send("05 00 00 00 23 01"));
        REQUIRE(card.size() == 90);
        CHECK(hex(card.substr(0, 6)) == "06 00 54 00 81 23");
        CHECK(get_u16(card, 88) == 1);
        // ... reports no motor connected (p.77: bit 0x100 clear) ...
        CHECK(h.send("29 04 01 00 23 01") == "2A 04 06 00 81 23 01 00 00 00 00 00");
        CHECK(h.send("80 04 01 00 23 01") == "81 04 0E 00 81 23 01 00 00 00 00 00 00 00 00 00 00 00 00 00");
        // ... and moves nothing.
        CHECK(h.send("48 04 06 00 A3 01 01 00 40 0D 03 00") == "");
        h.advance_ms(5000);
        CHECK(h.take() == "");
        // The bay with a stage reports its motor connected.
        CHECK((get_u32(bytes(h.send("29 04 01 00 21 01")), 8) & status::kMotorConnected) != 0);
    }
}

TEST_CASE("MOT_SET_EEPROMPARAMS saves the last SET of a message, a new device restores it", "[device][apt][eeprom]")
{
    char dir_template[] = "/tmp/rigsim-eeprom-XXXXXX";
    REQUIRE(::mkdtemp(dir_template));
    const std::string path = std::string(dir_template) + "/state.json";
    {
        StateStore store(path);
        Clock clock;
        models::World world(clock);
        AptDevice device(tdc001(), world, std::make_shared<spdlog::logger>("apt", std::make_shared<spdlog::sinks::null_sink_st>()), &store);
        std::string out;
        auto session = device.open_session([&](std::string_view b) { out.append(b); }, "test");
        session->receive(bytes("13 04 0E 00 D0 01 01 00 00 00 00 00 10 00 00 00 00 10 00 00"));   // VELPARAMS
        session->receive(bytes("13 04 0E 00 D0 01 01 00 00 00 00 00 00 00 00 00 00 20 00 00"));   // ignored: not saved
        session->receive(bytes("3A 04 06 00 D0 01 01 00 00 0D 00 00"));                           // backlash
        session->receive(bytes("B9 04 04 00 D0 01 01 00 13 04"));                                 // save VELPARAMS only
    }
    StateStore reloaded(path);                                     // the daemon restarts
    Clock clock;
    models::World world(clock);
    AptDevice device(tdc001(), world, std::make_shared<spdlog::logger>("apt", std::make_shared<spdlog::sinks::null_sink_st>()), &reloaded);
    device.power_up();                                             // the rig's start-up: EEPROM restored
    std::string out;
    auto session = device.open_session([&](std::string_view b) { out.append(b); }, "test");
    session->receive(bytes("14 04 01 00 50 01"));
    CHECK(hex(out) == "15 04 0E 00 81 50 01 00 00 00 00 00 10 00 00 00 00 10 00 00");
    out.clear();
    session->receive(bytes("3B 04 01 00 50 01"));                  // backlash was not saved
    CHECK(hex(out) == "3C 04 06 00 81 50 01 00 00 00 00 00");
    std::remove(path.c_str());
    ::rmdir(dir_template);
}

TEST_CASE("BBD203 bays keep their PMD parameter trios and report their stage", "[device][apt][rack]")
{
    AptHarness h(apt_rack("BBD203", {"MLS203-X", "MLS203-Y"}));
    // PMDPROFILEMODEPARAMS (0x04E3/E4/E5): zeros until set, then what was set.
    const auto before = bytes(h.send("E4 04 01 00 21 01"));
    REQUIRE(before.size() >= 6);
    CHECK(hex(before.substr(0, 6)) == "E5 04 0C 00 81 21");
    CHECK(before.substr(8) == std::string(10, '\0'));
    CHECK(h.send("E3 04 0C 00 A1 01 01 00 02 00 10 00 00 00 20 00 00 00") == "");
    CHECK(h.send("E4 04 01 00 21 01") == "E5 04 0C 00 81 21 01 00 02 00 10 00 00 00 20 00 00 00");
    CHECK(h.send("E4 04 01 00 22 01").substr(24) == "00 00 00 00 00 00 00 00 00 00");   // bay 1 unchanged
    // PMDSTAGEAXISPARAMS: the stage of bay 1, MLS203-Y: 20,000 counts per mm, 75 mm.
    const auto axis = bytes(h.send("F1 04 01 00 22 01"));
    REQUIRE(axis.size() == 80);
    CHECK(get_u16(axis, 8) == 0x11);
    // p. 76's example but for the serial number: "MLS203 Y Axis", 20,000 counts per unit,
    // MinPos 0, MaxPos 1,500,000, MaxAccn = MaxDec 27,488, MaxVel 26,843,546.
    CHECK(hex(axis.substr(12, 16)) == "4D 4C 53 32 30 33 20 59 20 41 78 69 73 00 00 00");
    CHECK(hex(axis.substr(32, 24)) == "20 4E 00 00 00 00 00 00 60 E3 16 00 60 6B 00 00 60 6B 00 00 9A 99 99 01");
    // SET may only narrow the travel: max position -> 1 mm.
    std::string set = axis.substr(6);
    std::string frame = encode_with_data(MGMSG_MOT_SET_PMDSTAGEAXISPARAMS, 0x22, 0x01, set);
    const auto narrowed_max = get_i32(axis, 36) + 20'000;   // min + 1 mm
    frame[6 + 34] = static_cast<char>(narrowed_max & 0xff);   // MaxPos: data offset 34 (p. 75)
    frame[6 + 35] = static_cast<char>((narrowed_max >> 8) & 0xff);
    frame[6 + 36] = static_cast<char>((narrowed_max >> 16) & 0xff);
    frame[6 + 37] = static_cast<char>((narrowed_max >> 24) & 0xff);
    CHECK(h.send(hex(frame)) == "");
    CHECK(get_i32(bytes(h.send("F1 04 01 00 22 01")), 40) == narrowed_max);
}

TEST_CASE("stepper cubes: microsteps, MOT_GET_STATUSUPDATE, no DC messages", "[device][apt][stepper]")
{
    AptHarness h(apt_cube("KST101", "DRV014"));
    const auto info = bytes(h.send("05 00 00 00 50 01"));
    REQUIRE(info.size() == 90);
    CHECK(get_u32(info, 6) == 26'000'001);
    // VELPARAMS in microsteps/s (p. 29): 2 mm/s = 51200, 4 mm/s² = 102400.
    CHECK(h.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 01 00 00 00 00 00 00 90 01 00 00 C8 00 00");
    CHECK(h.send("48 04 06 00 D0 01 01 00 00 64 00 00") == "");   // 25600 microsteps = 1 mm
    h.advance_ms(2000);
    const auto done = h.take();
    CHECK(done.substr(0, 17) == "64 04 0E 00 81 50");
    CHECK(get_i32(bytes(done), 8) == 25'600);                      // MOTSTATUS: position
    CHECK(get_i32(bytes(done), 12) == 25'600);                     // ... and encoder count
    CHECK(h.send("11 00 00 00 50 01") == "");                      // updates: MOT_GET_STATUSUPDATE
    h.advance_ms(100);
    CHECK(h.take().substr(0, 17) == "81 04 0E 00 81 50");
    CHECK(h.send("90 04 01 00 50 01") == "");                      // REQ_DCSTATUSUPDATE: ignored
}

TEST_CASE("a BSC203 stepper rack: three bays, MOTSTATUS from each bay", "[device][apt][rack][stepper]")
{
    AptHarness h(apt_rack("BSC203", {"DRV001", "DRV001", "ZST225B"}));
    CHECK(get_u16(bytes(h.send("05 00 00 00 11 01")), 88) == 3);
    CHECK(h.send("60 00 02 00 11 01") == "61 00 02 01 01 11");
    CHECK(h.send("48 04 06 00 A3 01 01 00 00 64 00 00") == "");     // bay 2 (ZST225B) by 25,600 microsteps
    h.advance_ms(2000);
    const auto done = h.take();
    CHECK(done.substr(0, 17) == "64 04 0E 00 81 23");
    CHECK(get_i32(bytes(done), 12) == 25'600);
    CHECK(h.send("11 00 00 00 11 01") == "");                       // updates from every bay
    h.advance_ms(100);
    const auto updates = h.take();
    CHECK(updates.size() == 3 * 20 * 3 - 1);
    CHECK(updates.find("81 04 0E 00 81 21") != std::string::npos);
    CHECK(updates.find("81 04 0E 00 81 23") != std::string::npos);
}

} // namespace test_apt_dc_servo
