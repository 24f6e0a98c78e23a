// APT firmware generations (docs/protocol/apt.md, "Firmware generations"): what "issue-44.1"
// changes against the manual's "issue-3" for the motor controllers, bytes in -> bytes out on the
// stepped clock: the Trinamic steppers' microsteps and velocity scaling, the DC servo cubes'
// unchanged scaling, the status update each model sends, HW_GET_INFO's later fields, and the
// rig loader's check of the power-up velocities in the later units.
#include "apt_harness.hpp"

#include "emulator/core/config_reader.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

namespace test_apt_firmware {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;

namespace {

/// A single unit driving the shipped `stage`, following firmware generation `fw`.
DeviceConfig cube(const std::string& model, const std::string& stage, Firmware fw)
{
    auto c = apt_cube(model, stage);
    c.firmware = std::string(firmware_name(fw));
    config_of(c).firmware = fw;
    return c;
}

std::string vel_params(std::int32_t min, std::int32_t acceleration, std::int32_t max)
{
    return "01 00 " + le32(min) + " " + le32(acceleration) + " " + le32(max);
}

/// MOT_SET_VELPARAMS for channel 1.
std::string set_vel_params(std::int32_t acceleration, std::int32_t max)
{
    return "13 04 0E 00 D0 01 " + vel_params(0, acceleration, max);
}

/// MOT_MOVE_RELATIVE for channel 1 by `counts`.
std::string move_relative(std::int32_t counts)
{
    return "48 04 06 00 D0 01 01 00 " + le32(counts);
}

/// The 16-bit word at data offset `offset` of a HW_GET_INFO reply (hex).
std::uint16_t info_word(const std::string& reply_hex, std::size_t offset)
{
    const auto b = bytes(reply_hex);
    REQUIRE(b.size() == 90);
    return get_u16(b, 6 + offset);
}

// KST101 + DRV014: 25,600 microsteps/mm in the manual's generation, 16 times that (2048
// microsteps per full step rather than 128) in the later one.
constexpr std::int32_t kManualPerMm = 25'600;
constexpr std::int32_t kLaterPerMm = 409'600;
// The later scaling: 53.68 per microstep/s, 53.68 × 204.94e-6 per microstep/s².
constexpr double kLaterVelocity = 53.68;
constexpr double kLaterAcceleration = 53.68 * 204.94e-6;

std::int32_t later_velocity(double mm_s)
{
    return static_cast<std::int32_t>(std::lround(mm_s * kLaterPerMm * kLaterVelocity));
}

std::int32_t later_acceleration(double mm_s2)
{
    return static_cast<std::int32_t>(std::lround(mm_s2 * kLaterPerMm * kLaterAcceleration));
}

} // namespace

TEST_CASE("KST101 power-up VELPARAMS: microsteps/s in the manual's generation, 53.68 per later microstep/s in "
          "issue-44.1",
          "[device][apt][firmware]")
{
    // DRV014: 2 mm/s, 4 mm/s².
    AptHarness manual(cube("KST101", "DRV014", Firmware::Issue3));
    CHECK(manual.send("14 04 01 00 50 01")
          == "15 04 0E 00 81 50 " + vel_params(0, 4 * kManualPerMm, 2 * kManualPerMm));

    AptHarness later(cube("KST101", "DRV014", Firmware::Issue44_1));
    CHECK(later_velocity(2) == 43'974'656);
    CHECK(later_acceleration(4) == 18'024);
    CHECK(later.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 " + vel_params(0, 18'024, 43'974'656));
    // HOMEPARAMS' velocity (1 mm/s) and JOGPARAMS' step (0.1 mm) in the later units too.
    const auto home = bytes(later.send("41 04 01 00 50 01"));
    REQUIRE(home.size() == 20);
    CHECK(get_i32(home, 12) == later_velocity(1));
    const auto jog = bytes(later.send("17 04 01 00 50 01"));
    REQUIRE(jog.size() == 28);
    CHECK(get_i32(jog, 10) == kLaterPerMm / 10);
}

TEST_CASE("BSC203 at issue-44.1: every bay counts the later microsteps and scales VELPARAMS as the KST101",
          "[device][apt][firmware]")
{
    auto c = apt_rack("BSC203", {"DRV001", "DRV014"});
    c.firmware = "issue-44.1";
    config_of(c).firmware = Firmware::Issue44_1;
    AptHarness h(c);
    CHECK(h.send("14 04 01 00 22 01") == "15 04 0E 00 81 22 " + vel_params(0, 18'024, 43'974'656));
    // TST001 stays the manual's: it is not one of the later issue's Trinamic steppers.
    AptHarness tst(cube("TST001", "DRV014", Firmware::Issue44_1));
    CHECK(tst.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 " + vel_params(0, 4 * kManualPerMm, 2 * kManualPerMm));
}

TEST_CASE("KST101 at issue-44.1: VELPARAMS set in the later units round-trip, and a 1 mm move takes the time "
          "they mean on the clock",
          "[device][apt][firmware]")
{
    // 1 mm/s, 4 mm/s² in each generation's units: the same trapezoid, 1 mm in 1 s + v/a = 1.25 s.
    struct Case {
        Firmware fw;
        std::int32_t per_mm, acceleration, velocity;
    };
    for (const auto& k : {Case{Firmware::Issue3, kManualPerMm, 4 * kManualPerMm, kManualPerMm},
                          Case{Firmware::Issue44_1, kLaterPerMm, later_acceleration(4), later_velocity(1)}}) {
        INFO("firmware " << firmware_name(k.fw));
        AptHarness h(cube("KST101", "DRV014", k.fw));
        CHECK(h.send(set_vel_params(k.acceleration, k.velocity)) == "");
        CHECK(h.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 " + vel_params(0, k.acceleration, k.velocity));
        CHECK(h.send(move_relative(k.per_mm)) == "");
        std::string completed;
        const int ms = ms_until_reply(h, completed, 5000);
        CHECK(ms >= 1245);
        CHECK(ms <= 1255);
        REQUIRE(frames(completed).size() == 1);
        CHECK(completed.substr(0, 17) == "64 04 0E 00 81 50");   // MOVE_COMPLETED
        CHECK(position_of(completed) == k.per_mm);
    }
}

TEST_CASE("KST101 at issue-44.1: VELPARAMS of the manual's units crawl (a microstep/s is 53.68 later units)",
          "[device][apt][firmware]")
{
    AptHarness h(cube("KST101", "DRV014", Firmware::Issue44_1));
    // 25,600 "microsteps/s" (and 102,400 /s²) as a manual client means 1 mm/s: on the later unit
    // 25,600 / 53.68 = 476.9 of its microsteps/s, 1.16 µm/s.
    CHECK(h.send(set_vel_params(4 * kManualPerMm, kManualPerMm)) == "");
    CHECK(h.send(move_relative(kLaterPerMm)) == "");
    h.advance_ms(2000);
    CHECK(h.take() == "");   // no MOVE_COMPLETED
    const auto p = position_of(h.send("11 04 01 00 50 01"));
    CHECK(p >= 945);         // 2 s × 476.9 = 954 microsteps (2.3 µm)
    CHECK(p <= 955);
}

TEST_CASE("DC servo cubes: the same VELPARAMS scaling (T = 2048 / 6e6 s) in both generations",
          "[device][apt][firmware]")
{
    for (const auto* model : {"TDC001", "KDC101"}) {
        INFO(model);
        AptHarness manual(cube(model, "MTS50-Z8", Firmware::Issue3));
        AptHarness later(cube(model, "MTS50-Z8", Firmware::Issue44_1));
        const auto reply = manual.send("14 04 01 00 50 01");
        CHECK(later.send("14 04 01 00 50 01") == reply);
        // MTS50-Z8: 2.4 mm/s × 34,304 counts/mm × 2048/6e6 × 65536.
        const auto b = bytes(reply);
        REQUIRE(b.size() == 20);
        CHECK(get_i32(b, 16) == std::lround(2.4 * 34'304 * 2048.0 / 6e6 * 65536.0));
    }
}

TEST_CASE("status updates per model in both generations: K-Cube stepper MOT_GET_STATUSUPDATE, DC cube "
          "MOT_GET_DCSTATUSUPDATE, positions in the generation's counts",
          "[device][apt][firmware]")
{
    for (const auto fw : {Firmware::Issue3, Firmware::Issue44_1}) {
        INFO("firmware " << firmware_name(fw));
        const std::int32_t per_mm = fw == Firmware::Issue3 ? kManualPerMm : kLaterPerMm;
        AptHarness st(cube("KST101", "DRV014", fw));
        CHECK(st.send(move_relative(per_mm / 10)) == "");
        st.advance_ms(3000);
        REQUIRE(frames(st.take()).size() == 1);
        CHECK(st.send("11 00 00 00 50 01") == "");   // HW_START_UPDATEMSGS
        st.advance_ms(100);
        const auto updates = frames(st.take());
        REQUIRE(updates.size() == 1);
        CHECK(updates[0].substr(0, 17) == "81 04 0E 00 81 50");
        CHECK(position_of(updates[0]) == per_mm / 10);

        AptHarness dc(cube("KDC101", "MTS50-Z8", fw));
        CHECK(dc.send("11 00 00 00 50 01") == "");
        dc.advance_ms(100);
        const auto dc_updates = frames(dc.take());
        REQUIRE(dc_updates.size() == 1);
        CHECK(dc_updates[0].substr(0, 17) == "91 04 0E 00 81 50");
        // The later issue's name of the reserved word: motor current; no current model: 0.
        CHECK(get_u16(bytes(dc_updates[0]), 12) == 0);
    }
}

TEST_CASE("HW_GET_INFO at issue-44.1: stage type word (DC servo cubes), hardware version 1, modification state "
          "0, where the manual's generation leaves those bytes of its notes 0",
          "[device][apt][firmware]")
{
    struct Case {
        const char* model;
        const char* stage;
        std::uint16_t stage_type;
    };
    for (const auto& k : {Case{"KDC101", "MTS50-Z8", 8}, Case{"TDC001", "MTS25-Z8", 7}, Case{"KDC101", "Z825B", 9},
                          Case{"KDC101", "PRM1-Z8", 6}, Case{"KDC101", "Z812B", 10}, Case{"KST101", "ZST225B", 0}}) {
        INFO(k.model << " " << k.stage);
        AptHarness manual(cube(k.model, k.stage, Firmware::Issue3));
        const auto before = manual.send("05 00 00 00 50 01");
        CHECK(info_word(before, 76) == 0);
        CHECK(info_word(before, 78) == 0);
        CHECK(info_word(before, 80) == 0);
        CHECK(info_word(before, 82) == 1);

        AptHarness later(cube(k.model, k.stage, Firmware::Issue44_1));
        const auto after = later.send("05 00 00 00 50 01");
        CHECK(info_word(after, 76) == k.stage_type);
        CHECK(info_word(after, 78) == 1);
        CHECK(info_word(after, 80) == 0);
        CHECK(info_word(after, 82) == 1);
        // Everything before the later fields is the manual's: serial, model, type, version, notes.
        CHECK(after.substr(0, 3 * (6 + 76)) == before.substr(0, 3 * (6 + 76)));
    }
}

TEST_CASE("HW_GET_INFO at issue-44.1 on a rack: motherboard and cards carry hardware version 1 and no stage type",
          "[device][apt][firmware]")
{
    auto c = apt_rack("BSC203", {"DRV001", "ZST225B"});
    c.firmware = "issue-44.1";
    config_of(c).firmware = Firmware::Issue44_1;
    AptHarness h(c);
    const auto board = h.send("05 00 00 00 11 01");
    CHECK(info_word(board, 76) == 0);
    CHECK(info_word(board, 78) == 1);
    CHECK(info_word(board, 82) == 3);
    const auto card = h.send("05 00 00 00 22 01");
    CHECK(info_word(card, 76) == 0);
    CHECK(info_word(card, 78) == 1);
    CHECK(info_word(card, 82) == 1);
}

TEST_CASE("rig loader: a KST101 stage's power-up velocity is checked in the generation's units",
          "[device][apt][firmware][config]")
{
    // 100 mm/s: 2,560,000 microsteps/s in the manual's units; 100 × 409,600 × 53.68 = 2.2e9 in
    // the later ones, past a long.
    const auto device = [](const char* firmware) {
        return nlohmann::json{
            {"name", "kst"}, {"protocol", "apt"}, {"model", "KST101"}, {"firmware", firmware},
            {"apt",
             {{"stage",
               {{"kind", "linear"}, {"motor", "stepper"}, {"travel_mm", 25}, {"counts_per_mm", 25600},
                {"max_velocity_mm_s", 100}, {"acceleration_mm_s2", 4}, {"home_velocity_mm_s", 1}}}}}};
    };
    DeviceConfig manual;
    manual.name = "kst";
    manual.protocol = "apt";
    manual.model = "KST101";
    manual.firmware = "issue-3";
    REQUIRE_NOTHROW(load_device_section(ConfigReader("rig.json"), device("issue-3"), "/devices/0", manual));
    CHECK(config_of(manual).firmware == Firmware::Issue3);

    DeviceConfig later = manual;
    later.firmware = "issue-44.1";
    std::string error;
    try {
        load_device_section(ConfigReader("rig.json"), device("issue-44.1"), "/devices/0", later);
    } catch (const std::exception& e) {
        error = e.what();
    }
    CHECK(error == "rig.json: /devices/0/apt/stage/max_velocity_mm_s: gives 2198732800 APT units on a KST101 "
                   "(7.1 scaling): expected 1..2147483647");
}

TEST_CASE("rig loader: a KST101 stage's travel must fit the position counter in the generation's microsteps",
          "[device][apt][firmware][config]")
{
    // 6,000 mm at 25,600 microsteps/mm: 153,600,000 counts in the manual's generation, 16 times
    // that (2,457,600,000) in the later one.
    const auto device = [](const char* firmware) {
        return nlohmann::json{
            {"name", "kst"}, {"protocol", "apt"}, {"model", "KST101"}, {"firmware", firmware},
            {"apt",
             {{"stage",
               {{"kind", "linear"}, {"motor", "stepper"}, {"travel_mm", 6000}, {"counts_per_mm", 25600},
                {"max_velocity_mm_s", 1}, {"acceleration_mm_s2", 4}, {"home_velocity_mm_s", 1}}}}}};
    };
    DeviceConfig manual;
    manual.name = "kst";
    manual.protocol = "apt";
    manual.model = "KST101";
    manual.firmware = "issue-3";
    REQUIRE_NOTHROW(load_device_section(ConfigReader("rig.json"), device("issue-3"), "/devices/0", manual));

    DeviceConfig later = manual;
    later.firmware = "issue-44.1";
    std::string error;
    try {
        load_device_section(ConfigReader("rig.json"), device("issue-44.1"), "/devices/0", later);
    } catch (const std::exception& e) {
        error = e.what();
    }
    CHECK(error == "rig.json: /devices/0/apt/stage/travel_mm: the travel is 2457600000 counts on a KST101 at "
                   "firmware issue-44.1 (16 x the stage's counts): expected at most 2147483647 (the 32-bit position "
                   "counter)");
}

} // namespace test_apt_firmware
