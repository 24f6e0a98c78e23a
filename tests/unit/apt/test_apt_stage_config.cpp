// A motor controller's stage in the rig (docs/config.md, "APT stages"): a shipped stage's name or
// an inline stage object, on a single unit and in a rack bay; each refusal names its JSON pointer.
#include "emulator/apt/config.hpp"
#include "emulator/daemon/rig_families.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <string>

namespace test_apt_stage_config {

namespace {

using nlohmann::json;
using namespace rigsim::apt;

json rig_of(const std::string& model, json apt)
{
    return {{"devices", {{{"name", "u"}, {"protocol", "apt"}, {"model", model}, {"apt", std::move(apt)}}}}};
}

std::string error_of(const json& rig)
{
    try {
        rigsim::parse_rig_config(rig.dump(), "rig.json");
    } catch (const rigsim::ConfigError& e) {
        return e.what();
    }
    return "(no error)";
}

AptConfig apt_of(const json& rig)
{
    return config_of(rigsim::parse_rig_config(rig.dump(), "rig.json").devices.at(0));
}

json stepper_stage()
{
    return {{"name", "LAB-8"},
            {"kind", "linear"},
            {"motor", "stepper"},
            {"travel_mm", 8},
            {"counts_per_mm", 51'200},
            {"max_velocity_mm_s", 1},
            {"acceleration_mm_s2", 2},
            {"home_velocity_mm_s", 0.5}};
}

json gonio_stage()
{
    return {{"kind", "goniometer"},          {"motor", "dc_servo"},          {"angle_range_deg", {-5, 15}},
            {"counts_per_deg", 2'000},       {"max_velocity_deg_s", 2},      {"acceleration_deg_s2", 2},
            {"home_velocity_deg_s", 1},      {"home_offset_deg", 0.25}};
}

/// A single TDC001 with `stage` as its stage object.
std::string tdc_error(const json& stage)
{
    return error_of(rig_of("TDC001", {{"stage", stage}}));
}

} // namespace

TEST_CASE("apt stage: an inline stage object on a single unit and in rack bays", "[unit][apt][config][stages]")
{
    const auto gonio = apt_of(rig_of("KDC101", {{"stage", gonio_stage()}})).stage;
    CHECK(gonio.name.empty());
    CHECK(gonio.kind == StageKind::Goniometer);
    CHECK(gonio.angle_min_deg == -5);
    CHECK(gonio.angle_max_deg == 15);
    CHECK(gonio.counts_per_mm == 2'000);
    CHECK(gonio.home_offset_mm == 0.25);
    CHECK(gonio.limit_switches == LimitSwitches::Both);
    CHECK_FALSE(gonio.home_forward);

    const auto rack = apt_of(rig_of("BSC203", {{"bays", {"DRV001", stepper_stage(), "ZST225B"}}}));
    REQUIRE(rack.bays.size() == 3);
    CHECK(rack.bays[0].name == "DRV001");
    CHECK(rack.bays[1].name == "LAB-8");
    CHECK(rack.bays[1].travel_mm == 8);
    CHECK(rack.bays[1].counts_per_mm == 51'200);
    CHECK(rack.bays[2].travel_mm == 25);
    // A name still picks the shipped stage; no stage at all the default MTS50-Z8.
    CHECK(apt_of(rig_of("TDC001", json::object())).stage.name == "MTS50-Z8");
    CHECK(apt_of(rig_of("KDC101", {{"stage", "PRM1-Z8"}})).stage.kind == StageKind::Rotary);
}

TEST_CASE("apt stage: each refusal names the pointer inside the stage object", "[unit][apt][config][stages]")
{
    // The brief's example: a negative count in a rack bay.
    auto bad = stepper_stage();
    bad["counts_per_mm"] = -3;
    CHECK(error_of(rig_of("BSC203", {{"bays", {"DRV001", bad}}}))
          == "rig.json: /devices/0/apt/bays/1/counts_per_mm: expected a number > 0, got -3");

    auto unknown = gonio_stage();
    unknown["colour"] = "red";
    CHECK(tdc_error(unknown).rfind("rig.json: /devices/0/apt/stage: unknown key \"colour\" (allowed: name, about, kind, "
                                   "motor, travel_mm, angle_range_deg, ",
                                   0)
          == 0);

    auto kind = gonio_stage();
    kind["kind"] = "spherical";
    CHECK(tdc_error(kind)
          == "rig.json: /devices/0/apt/stage/kind: expected \"linear\", \"rotary\" or \"goniometer\", got \"spherical\"");

    // The stage's motor against the controller's.
    CHECK(error_of(rig_of("BBD203", {{"bays", {"MLS203-X", stepper_stage()}}}))
          == "rig.json: /devices/0/apt/bays/1/motor: expected \"brushless\" (the motor a BBD203 drives), got \"stepper\"");
    CHECK(error_of(rig_of("TDC001", {{"stage", stepper_stage()}}))
          == "rig.json: /devices/0/apt/stage/motor: expected \"dc_servo\" (the motor a TDC001 drives), got \"stepper\"");

    auto shipped = stepper_stage();
    shipped["name"] = "DRV001";
    CHECK(error_of(rig_of("TST001", {{"stage", shipped}}))
          == "rig.json: /devices/0/apt/stage/name: \"DRV001\" names the shipped stage DRV001: use the name alone or another name");

    auto rotary = gonio_stage();
    rotary["kind"] = "rotary";
    CHECK(tdc_error(rotary)
          == "rig.json: /devices/0/apt/stage/angle_range_deg: a rotary stage turns without end: it has no angle range "
             "(a goniometer has one)");

    auto no_range = gonio_stage();
    no_range.erase("angle_range_deg");
    CHECK(tdc_error(no_range)
          == "rig.json: /devices/0/apt/stage/angle_range_deg: required key missing (a goniometer's end stops: [min, max] "
             "in degrees)");
}

TEST_CASE("apt stage: an empty name or pmd_part_number is refused", "[unit][apt][config][stages]")
{
    auto unnamed = stepper_stage();
    unnamed["name"] = "";
    CHECK(error_of(rig_of("TST001", {{"stage", unnamed}}))
          == "rig.json: /devices/0/apt/stage/name: expected a name of 1..64 characters, got \"\"");
    auto brushless = stepper_stage();
    brushless["motor"] = "brushless";
    brushless["pmd_part_number"] = "LAB 8";
    CHECK(error_of(rig_of("BBD203", {{"bays", {brushless}}})) == "(no error)");
    brushless["pmd_part_number"] = "";
    CHECK(error_of(rig_of("BBD203", {{"bays", {brushless}}}))
          == "rig.json: /devices/0/apt/bays/0/pmd_part_number: expected a string of 1..16 characters, got \"\"");
}

TEST_CASE("apt stage: units, ranges, switches and the controller's APT units", "[unit][apt][config][stages]")
{
    auto mm_key = gonio_stage();
    mm_key["counts_per_mm"] = 2'000;
    mm_key.erase("counts_per_deg");
    CHECK(tdc_error(mm_key)
          == "rig.json: /devices/0/apt/stage/counts_per_mm: a goniometer's unit is the degree: counts_per_deg, not "
             "counts_per_mm");

    auto travel = gonio_stage();
    travel["travel_mm"] = 10;
    CHECK(tdc_error(travel)
          == "rig.json: /devices/0/apt/stage/travel_mm: a goniometer's travel is its angle_range_deg, not travel_mm");

    auto reversed = gonio_stage();
    reversed["angle_range_deg"] = {5, 5};
    CHECK(tdc_error(reversed) == "rig.json: /devices/0/apt/stage/angle_range_deg: expected min < max, got [5,5]");
    reversed["angle_range_deg"] = {-5, "10"};
    CHECK(tdc_error(reversed) == "rig.json: /devices/0/apt/stage/angle_range_deg/1: expected a number -360..360, got \"10\"");

    auto huge = stepper_stage();
    huge["travel_mm"] = 100'000;
    CHECK(error_of(rig_of("TST001", {{"stage", huge}}))
          == "rig.json: /devices/0/apt/stage/travel_mm: the travel is 5120000000 counts at 51200 counts_per_mm: expected "
             "at most 2147483647 (the 32-bit position counter)");

    auto offset = stepper_stage();
    offset["home_offset_mm"] = 9;
    CHECK(error_of(rig_of("TST001", {{"stage", offset}}))
          == "rig.json: /devices/0/apt/stage/home_offset_mm: expected a number 0..8 (within travel_mm), got 9");

    // A brushless rotation stage (a DDR25) is a stage like any other: it homes forward to its switch.
    auto brushless_rotary = gonio_stage();
    brushless_rotary["kind"] = "rotary";
    brushless_rotary["motor"] = "brushless";
    brushless_rotary.erase("angle_range_deg");
    brushless_rotary.erase("limit_switches");
    brushless_rotary.erase("home_direction");
    CHECK(error_of(rig_of("BBD203", {{"bays", {brushless_rotary}}})) == "(no error)");

    auto switches = gonio_stage();
    switches["limit_switches"] = "reverse";
    switches["home_direction"] = "forward";
    CHECK(tdc_error(switches)
          == "rig.json: /devices/0/apt/stage/home_direction: homing runs to the forward limit switch, and this stage has "
             "none there (limit_switches \"reverse\")");
    switches.erase("home_direction");
    CHECK(tdc_error(switches) == "(no error)");

    auto pmd = stepper_stage();
    pmd["pmd_stage_id"] = 3;
    CHECK(error_of(rig_of("TST001", {{"stage", pmd}}))
          == "rig.json: /devices/0/apt/stage/pmd_stage_id: PMD stage parameters (MOT_GET_PMDSTAGEAXISPARAMS, p. 75) "
             "belong to a brushless stage, not a stepper one");

    // 0.001 mm/s² × 51,200 microsteps/mm on a stepper (1 unit per microstep/s²) rounds to 0.
    auto slow = stepper_stage();
    slow["acceleration_mm_s2"] = 0.000001;
    CHECK(error_of(rig_of("TST001", {{"stage", slow}}))
          == "rig.json: /devices/0/apt/stage/acceleration_mm_s2: gives 0 APT units on a TST001 (7.1 scaling): expected "
             "1..2147483647");

    CHECK(error_of(rig_of("TST001", {{"stage", 42}}))
          == "rig.json: /devices/0/apt/stage: expected the name of a shipped stage or a stage object, got 42");
    CHECK(error_of(rig_of("TST001", {{"stage", "MTS99"}})).find("(expected one of DDR25, DDS100,") != std::string::npos);
}

} // namespace test_apt_stage_config
