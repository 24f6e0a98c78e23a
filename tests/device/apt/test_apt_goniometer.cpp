// APT: stages described in the rig (docs/config.md, "APT stages") on the wire, on a stepped clock:
// a goniometer on a KDC101 homes to its limit switch and stops at its end stops, in degrees; a
// stage's limit switches and home direction are its power-up LIMSWITCHPARAMS and HOMEPARAMS.
#include "apt_harness.hpp"
#include "emulator/control/body_state.hpp"

#include "emulator/daemon/rig_families.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

namespace test_apt_goniometer {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;
using nlohmann::json;

namespace {

constexpr double kRadPerDeg = M_PI / 180.0;

/// ±10°, 1,000 counts per degree: the counter reads 0 mid-range (0°) at power-up.
json gonio_stage()
{
    return {{"name", "GONIO-10"},
            {"kind", "goniometer"},
            {"motor", "dc_servo"},
            {"angle_range_deg", {-10, 10}},
            {"counts_per_deg", 1000},
            {"max_velocity_deg_s", 2},
            {"acceleration_deg_s2", 4},
            {"home_velocity_deg_s", 1},
            {"home_offset_deg", 0.5}};
}

/// A one-device rig read as the daemon reads it: `model` driving the stage object `stage`.
DeviceConfig unit_with(const std::string& model, const json& stage)
{
    const json rig{
        {"devices", {{{"name", "cube"}, {"protocol", "apt"}, {"model", model}, {"apt", {{"stage", stage}}}}}}};
    return parse_rig_config(rig.dump(), "rig.json").devices.at(0);
}

std::string le32(std::int32_t v)
{
    std::string d;
    put_i32(d, v);
    return hex(d);
}

std::uint32_t status_of(const std::string& frame_hex)
{
    return get_u32(bytes(frame_hex), 16);
}

json channel(AptHarness& h)
{
    json out = json::object();
    rigsim::control::describe_device(h.device(), &h.world(), out);   // as the control API does
    return out["channels"].at(0);
}

std::int32_t position_counter(AptHarness& h)
{
    return position_of(h.send("11 04 01 00 50 01"));   // REQ_POSCOUNTER
}

} // namespace

TEST_CASE("goniometer: a KDC101 stage object is a goniometer channel in degrees with end stops at its range",
          "[device][apt][stage][goniometer]")
{
    AptHarness h(unit_with("KDC101", gonio_stage()));
    const json c = channel(h);
    CHECK(c["kind"] == "goniometer");
    CHECK(c["stage"] == "GONIO-10");
    CHECK(c["si_unit"] == "rad");
    CHECK(c["position_si"].get<double>() == Approx(0.0).margin(1e-12));   // mid-range at power-up
    CHECK(c["limits"]["travel"]["min_si"].get<double>() == Approx(-10 * kRadPerDeg));
    CHECK(c["limits"]["travel"]["max_si"].get<double>() == Approx(10 * kRadPerDeg));
    CHECK(position_counter(h) == 0);
    // Placed outside its range: refused, naming the range.
    const auto refused = h.device().patch_channel(0, {{"position_si", 11 * kRadPerDeg}});
    REQUIRE(refused);
    CHECK(refused->status == 400);
    CHECK(refused->message.find("angle range of the goniometer GONIO-10") != std::string::npos);
}

TEST_CASE("goniometer: homing runs to the reverse limit switch and backs off, moves stop at the end stops",
          "[device][apt][stage][goniometer]")
{
    AptHarness h(unit_with("KDC101", gonio_stage()));
    CHECK(h.send("43 04 01 00 50 01") == "");   // MOVE_HOME
    h.advance_ms(5'000);
    CHECK(h.take() == "");                       // 10° at 1°/s: still on the way
    CHECK(channel(h)["position_si"].get<double>() < -4 * kRadPerDeg);
    h.advance_ms(10'000);
    CHECK(h.take() == "44 04 01 00 01 50");      // MOVE_HOMED
    json c = channel(h);
    CHECK(c["referenced"] == true);
    CHECK(c["position_si"].get<double>() == Approx(-9.5 * kRadPerDeg));   // the switch at -10°, 0.5° back
    CHECK(position_counter(h) == 0);

    // Past the forward end (+19.5° from home): the forward limit switch stops the move at +10°.
    CHECK(h.send("53 04 06 00 D0 01 01 00 " + le32(30'000)) == "");   // MOVE_ABSOLUTE
    h.advance_ms(20'000);
    auto out = frames(h.take());
    REQUIRE(out.size() == 1);
    CHECK(out[0].substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(19'500));   // MOVE_COMPLETED
    CHECK((status_of(out[0]) & status::kForwardHardLimit) != 0);
    CHECK((status_of(out[0]) & status::kCurrentLimit) == 0);
    CHECK(channel(h)["position_si"].get<double>() == Approx(10 * kRadPerDeg));

    // And back past the reverse end.
    CHECK(h.send("48 04 06 00 D0 01 01 00 " + le32(-50'000)) == "");   // MOVE_RELATIVE
    h.advance_ms(20'000);
    out = frames(h.take());
    REQUIRE(out.size() == 1);
    CHECK(out[0].substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(-500));
    CHECK((status_of(out[0]) & status::kReverseHardLimit) != 0);
    c = channel(h);
    CHECK(c["position_si"].get<double>() == Approx(-10 * kRadPerDeg));
    CHECK(c["limits"]["switch_pressed"] == json{{"forward", false}, {"reverse", true}});
}

TEST_CASE("goniometer: with its switch ignored the DC motor stalls at the end stop", "[device][apt][stage][goniometer]")
{
    AptHarness h(unit_with("KDC101", gonio_stage()));
    // SET_LIMSWITCHPARAMS: CW (forward) ignored, CCW makes on contact, no soft limits.
    CHECK(h.send("23 04 10 00 D0 01 01 00 01 00 02 00 00 00 00 00 00 00 00 00 01 00") == "");
    CHECK(h.send("57 04 01 01 50 01") == "");   // MOVE_VELOCITY forward
    h.advance_ms(20'000);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 2);
    CHECK(out[0].substr(0, 17) == "81 00 44 00 81 50");   // HW_RICHRESPONSE: motor stalled
    CHECK(out[1].substr(0, 35) == "66 04 0E 00 81 50 01 00 " + le32(10'000));   // MOVE_STOPPED at +10°
    CHECK((status_of(out[1]) & status::kCurrentLimit) != 0);
}

TEST_CASE("stage object: limit_switches and home_direction are the power-up LIMSWITCHPARAMS and HOMEPARAMS",
          "[device][apt][stage]")
{
    json stage = gonio_stage();
    stage["limit_switches"] = "forward";   // homes forward by default: the only switch
    AptHarness h(unit_with("KDC101", stage));
    // GET_LIMSWITCHPARAMS: CW (forward) 2 makes on contact, CCW 1 none; soft limits 0, mode 1.
    CHECK(h.send("24 04 01 00 50 01") == "25 04 10 00 81 50 01 00 02 00 01 00 00 00 00 00 00 00 00 00 01 00");
    // GET_HOMEPARAMS: direction 1 (forward), limit switch 4 (forward), 1°/s, 0.5° = 500 counts.
    // 1°/s = 1,000 counts/s × 2048 / 6 MHz × 65,536 (7.1) = 22,370.
    CHECK(h.send("41 04 01 00 50 01") == "42 04 0E 00 81 50 01 00 01 00 04 00 " + le32(22'370) + " " + le32(500));
    CHECK(h.send("43 04 01 00 50 01") == "");
    h.advance_ms(20'000);
    CHECK(h.take() == "44 04 01 00 01 50");
    CHECK(channel(h)["position_si"].get<double>() == Approx(9.5 * kRadPerDeg));   // the switch at +10°, 0.5° back
    // Reverse has no switch: a move there runs into the end stop and stalls.
    CHECK(h.send("57 04 01 02 50 01") == "");   // MOVE_VELOCITY reverse
    h.advance_ms(30'000);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 2);
    CHECK(out[1].substr(0, 17) == "66 04 0E 00 81 50");
    CHECK(channel(h)["position_si"].get<double>() == Approx(-10 * kRadPerDeg));
}

TEST_CASE("stage object: a linear stepper stage on a TST001 keeps its own figures on the wire", "[device][apt][stage]")
{
    const json stage{{"kind", "linear"},        {"motor", "stepper"},        {"travel_mm", 8},
                     {"counts_per_mm", 51'200}, {"max_velocity_mm_s", 1},    {"acceleration_mm_s2", 2},
                     {"home_velocity_mm_s", 0.5}, {"home_direction", "forward"}};
    AptHarness h(unit_with("TST001", stage));
    // VELPARAMS in microsteps/s and /s² (p. 29): 51,200 and 102,400.
    CHECK(h.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 01 00 00 00 00 00 " + le32(102'400) + " " + le32(51'200));
    const auto home = h.send("41 04 01 00 50 01");
    CHECK(home == "42 04 0E 00 81 50 01 00 01 00 04 00 " + le32(25'600) + " " + le32(0));
    json c = channel(h);
    CHECK(c["kind"] == "linear");
    CHECK(c["stage"] == "");
    CHECK(c["limits"]["travel"]["max"] == 409'600);
}

} // namespace test_apt_goniometer
