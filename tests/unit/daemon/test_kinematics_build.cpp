// build_kinematics (emulator/daemon/rig_kinematics.cpp) on frames the loader let through but
// models::Kinematics refuses: a ConfigError at the frame's pointer, not a bare
// std::invalid_argument (which --check-config and the rig's start-up would not report as a
// config error).
#include "emulator/core/config_reader.hpp"
#include "emulator/daemon/rig_kinematics.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

namespace test_kinematics_build {

using rigsim::ConfigError;
using rigsim::FrameConfig;
using rigsim::KinematicsConfig;

namespace {

/// A table and one fixed frame "a" on it, as the loader would give them.
KinematicsConfig table_and_frame()
{
    KinematicsConfig c;
    c.source = "rig.json";
    FrameConfig table;
    table.name = "table";
    table.pointer = "/kinematics/frames/0";
    FrameConfig a;
    a.name = "a";
    a.pointer = "/kinematics/frames/1";
    c.frames = {table, a};
    return c;
}

/// The error building `c` raises, or "(no error)".
std::string error_of(const KinematicsConfig& c)
{
    try {
        rigsim::Clock clock;
        rigsim::models::World world(clock);
        rigsim::build_kinematics(c, [](std::string_view) { return nullptr; }, world);
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "(no error)";
}

} // namespace

TEST_CASE("kinematics build: a frame the model refuses is a config error at its pointer", "[unit][config]")
{
    auto c = table_and_frame();
    CHECK(error_of(c) == "(no error)");
    c.frames[1].translation_mm[0] = std::numeric_limits<double>::infinity();
    CHECK(error_of(c) == "rig.json: /kinematics/frames/1: frame \"a\": the offset is not finite");
    c = table_and_frame();
    c.frames[1].tool = true;
    c.frames[1].pointer = "/kinematics/tools/0";
    c.frames[1].translation_mm[2] = std::nan("");
    CHECK(error_of(c) == "rig.json: /kinematics/tools/0: frame \"a\": the offset is not finite");
    c = table_and_frame();
    c.frames[1].box_mm = rigsim::FrameBoxConfig{{0, 0, 0}, {1, 1, std::numeric_limits<double>::infinity()}};
    CHECK(error_of(c) == "rig.json: /kinematics/frames/1: frame \"a\": the box is not finite");
}

} // namespace test_kinematics_build
