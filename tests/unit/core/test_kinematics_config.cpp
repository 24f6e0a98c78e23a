// The rig JSON's "kinematics" section (emulator/core/kinematics_config.cpp): a valid tree read
// parent first with its pointers, and every check with its exact pointer and message.
#include "emulator/core/kinematics_config.hpp"
#include "emulator/daemon/rig_families.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace test_kinematics_config {

using nlohmann::json;
using rigsim::ConfigError;
using rigsim::JointKind;
using rigsim::KinematicsConfig;

namespace {

/// An MCS stack (three linear channels and a goniometer) and a KDC101 with a rotation stage.
json devices()
{
    return json::parse(R"([
        {"name": "stack", "protocol": "mcs",
         "mcs": {"channels": [{}, {}, {}, {"sensor_type": "G605S"}]}},
        {"name": "apt_rot", "protocol": "apt", "model": "KDC101", "apt": {"stage": "PRM1-Z8"}}])");
}

/// The plan's example: a rotation stage on the table, X on it, a goniometer on X, a bracket and
/// a sample.
json kinematics()
{
    return json::parse(R"({
      "frames": [
        {"name": "table"},
        {"name": "rot", "parent": "table",
         "offset": {"translation_mm": [0, 0, 50], "rpy_deg": [0, 0, 0]},
         "axis": {"device": "apt_rot", "channel": 0},
         "joint": {"type": "revolute", "axis": [0, 0, 2], "point_mm": [1, 0, 0]},
         "box_mm": {"min": [-30, -30, -10], "max": [30, 30, 0]}},
        {"name": "gonio", "parent": "x", "axis": {"device": "stack", "channel": 3},
         "joint": {"type": "goniometer", "axis": [1, 0, 0], "centre_mm": [0, 0, 40]},
         "box_mm": {"min": [-5, -5, 0], "max": [5, 5, 3]}},
        {"name": "x", "parent": "rot", "axis": {"device": "stack", "channel": 0},
         "joint": {"type": "prismatic", "axis": [1, 0, 0]},
         "box_mm": {"min": [-10, -10, 0], "max": [10, 10, 5]}},
        {"name": "bracket", "parent": "x", "offset": {"quaternion": [0, 0, 0, 1]},
         "box_mm": {"min": [0, 0, 0], "max": [1, 1, 1]}}
      ],
      "tools": [{"name": "sample", "parent": "gonio", "offset": {"translation_mm": [0, 0, 40]}}]
    })");
}

json rig_with(const json& k)
{
    return json{{"devices", devices()}, {"kinematics", k}};
}

KinematicsConfig load(const json& k)
{
    const auto rig = rigsim::parse_rig_config(rig_with(k).dump(), "rig.json");
    REQUIRE(rig.kinematics);
    return *rig.kinematics;
}

/// The ConfigError message for the rig with "kinematics" `k`, or "(no error)".
std::string error_of(const json& k)
{
    try {
        rigsim::parse_rig_config(rig_with(k).dump(), "rig.json");
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "(no error)";
}

/// A frame object of kinematics()["frames"] by name.
json& frame(json& k, const std::string& name)
{
    for (auto& f : k["frames"])
        if (f["name"] == name)
            return f;
    FAIL("no frame " << name);
    throw;
}

std::vector<std::string> names(const KinematicsConfig& c)
{
    std::vector<std::string> out;
    for (const auto& f : c.frames)
        out.push_back(f.name);
    return out;
}

} // namespace

TEST_CASE("kinematics config: absent means no frames", "[unit][config]")
{
    const auto rig = rigsim::parse_rig_config(json{{"devices", devices()}}.dump(), "rig.json");
    CHECK_FALSE(rig.kinematics);
}

TEST_CASE("kinematics config: a valid tree is listed parent first with its pointers", "[unit][config]")
{
    const auto c = load(kinematics());
    CHECK(c.source == "rig.json");
    // x comes after gonio in the file but is its parent; the tool goes after its parent too.
    CHECK(names(c) == std::vector<std::string>{"table", "rot", "x", "gonio", "bracket", "sample"});
    const auto& f = c.frames;
    CHECK(f[0].pointer == "/kinematics/frames/0");
    CHECK(f[0].parent == 0);
    CHECK(f[1].pointer == "/kinematics/frames/1");
    CHECK(f[1].parent == 0);
    CHECK(f[2].pointer == "/kinematics/frames/3");
    CHECK(f[2].parent == 1);
    CHECK(f[3].pointer == "/kinematics/frames/2");
    CHECK(f[3].parent == 2);
    CHECK(f[4].pointer == "/kinematics/frames/4");
    CHECK(f[4].parent == 2);
    CHECK(f[5].pointer == "/kinematics/tools/0");
    CHECK(f[5].parent == 3);
    CHECK(f[5].tool);
    CHECK_FALSE(f[3].tool);

    CHECK(f[1].translation_mm == rigsim::Vector3{0, 0, 50});
    REQUIRE(f[1].rpy_deg);
    CHECK_FALSE(f[1].quaternion);
    CHECK(f[1].joint == JointKind::Revolute);
    CHECK(f[1].joint_axis == rigsim::Vector3{0, 0, 1});   // made unit
    CHECK(f[1].joint_point_mm == rigsim::Vector3{1, 0, 0});
    REQUIRE(f[1].axis);
    CHECK(f[1].axis->device == "apt_rot");
    CHECK(f[1].axis->channel == 0);
    REQUIRE(f[1].box_mm);
    CHECK(f[1].box_mm->min == rigsim::Vector3{-30, -30, -10});
    CHECK(f[3].joint == JointKind::Goniometer);
    CHECK(f[3].joint_point_mm == rigsim::Vector3{0, 0, 40});
    CHECK(f[2].joint == JointKind::Prismatic);
    CHECK(f[4].joint == JointKind::Fixed);
    CHECK_FALSE(f[4].axis);
    REQUIRE(f[4].quaternion);
    CHECK((*f[4].quaternion == std::array<double, 4>{0, 0, 0, 1}));
    CHECK(f[5].translation_mm == rigsim::Vector3{0, 0, 40});
}

TEST_CASE("kinematics config: collisions auto pairs boxes a moving joint separates, parent and child aside",
          "[unit][config]")
{
    // Boxes: rot (1), x (2), gonio (3), bracket (4). rot-x, x-gonio, x-bracket: parent and child.
    // rot-gonio: x and gonio move between them. rot-bracket: x moves. gonio-bracket: gonio moves.
    using Pairs = std::vector<std::pair<std::size_t, std::size_t>>;
    CHECK(load(kinematics()).collisions == Pairs{{1, 3}, {1, 4}, {3, 4}});
    auto k = kinematics();
    k["collisions"] = "auto";
    CHECK(load(k).collisions == Pairs{{1, 3}, {1, 4}, {3, 4}});
    // Two fixed brackets on one frame: nothing moves between them.
    k = kinematics();
    k["frames"].push_back(json::parse(R"({"name": "b2", "parent": "x", "box_mm": {"min": [0,0,0], "max": [1,1,1]}})"));
    CHECK(load(k).collisions == Pairs{{1, 3}, {1, 4}, {1, 5}, {3, 4}, {3, 5}});
    k["collisions"] = json::parse(R"([["bracket", "rot"], ["b2", "gonio"]])");
    CHECK(load(k).collisions == Pairs{{1, 4}, {3, 5}});
    k["collisions"] = json::array();
    CHECK(load(k).collisions.empty());
}

TEST_CASE("kinematics config: keys and types", "[unit][config]")
{
    auto k = kinematics();
    k["colour"] = 1;
    CHECK(error_of(k) == "rig.json: /kinematics: unknown key \"colour\" (allowed: frames, tools, collisions)");
    CHECK(error_of(json::object()) == "rig.json: /kinematics/frames: required key missing");
    CHECK(error_of(json{{"frames", json::array()}}) ==
          "rig.json: /kinematics/frames: expected a non-empty array of frames, got []");
    k = kinematics();
    k["tools"] = 3;
    CHECK(error_of(k) == "rig.json: /kinematics/tools: expected an array of tool points, got 3");
    k = kinematics();
    frame(k, "x")["mass"] = 1;
    CHECK(error_of(k) ==
          "rig.json: /kinematics/frames/3: unknown key \"mass\" (allowed: name, parent, offset, axis, joint, box_mm)");
    k = kinematics();
    k["tools"][0]["axis"] = json::object();
    CHECK(error_of(k) ==
          "rig.json: /kinematics/tools/0: unknown key \"axis\" (allowed: name, parent, offset, box_mm)");
    k = kinematics();
    k["tools"][0].erase("parent");
    CHECK(error_of(k) == "rig.json: /kinematics/tools/0/parent: required key missing (a tool point sits on a frame)");
    k = kinematics();
    frame(k, "x")["name"] = "a b";
    CHECK(error_of(k) ==
          "rig.json: /kinematics/frames/3/name: expected a frame name of 1..64 characters [A-Za-z0-9_.-], got \"a b\"");
    k = kinematics();
    frame(k, "x")["offset"]["spin"] = 1;
    CHECK(error_of(k) == "rig.json: /kinematics/frames/3/offset: unknown key \"spin\" (allowed: translation_mm, rpy_deg, "
                         "quaternion)");
    k = kinematics();
    frame(k, "x")["joint"]["point_mm"] = json::array({0, 0, 0});
    CHECK(error_of(k) == "rig.json: /kinematics/frames/3/joint: unknown key \"point_mm\" (allowed: type, axis)");
    k = kinematics();
    frame(k, "x")["joint"]["type"] = "helical";
    CHECK(error_of(k) == "rig.json: /kinematics/frames/3/joint/type: unknown joint type \"helical\" (expected "
                         "\"fixed\", \"prismatic\", \"revolute\" or \"goniometer\")");
    k = kinematics();
    frame(k, "x")["axis"]["channel"] = 1.5;
    CHECK(error_of(k) == "rig.json: /kinematics/frames/3/axis/channel: expected an integer 0..255, got 1.5");
    k = kinematics();
    frame(k, "x")["axis"].erase("device");
    CHECK(error_of(k) == "rig.json: /kinematics/frames/3/axis/device: required key missing");
    k = kinematics();
    frame(k, "rot")["box_mm"].erase("max");
    CHECK(error_of(k) == "rig.json: /kinematics/frames/1/box_mm/max: required key missing");
}

TEST_CASE("kinematics config: numbers are finite, vectors of the right length", "[unit][config]")
{
    auto k = kinematics();
    frame(k, "rot")["offset"]["translation_mm"] = json::array({0, "nan", 0});
    CHECK(error_of(k) == "rig.json: /kinematics/frames/1/offset/translation_mm/1: expected a finite number, got \"nan\"");
    k = kinematics();
    frame(k, "rot")["offset"]["rpy_deg"] = json::array({0, 0, "inf"});
    CHECK(error_of(k) == "rig.json: /kinematics/frames/1/offset/rpy_deg/2: expected a finite number, got \"inf\"");
    k = kinematics();
    frame(k, "rot")["offset"]["translation_mm"] = json::array({0, 0});
    CHECK(error_of(k) ==
          "rig.json: /kinematics/frames/1/offset/translation_mm: expected an array of 3 numbers, got an array of 2 elements");
    k = kinematics();
    frame(k, "bracket")["offset"]["quaternion"] = json::array({1, 0, 0});
    CHECK(error_of(k) ==
          "rig.json: /kinematics/frames/4/offset/quaternion: expected an array of 4 numbers, got an array of 3 elements");
    // A number too large for a double is refused where it stands, by the parser.
    auto text = rig_with(kinematics()).dump();
    const auto at = text.find("[0,0,50]");
    REQUIRE(at != std::string::npos);
    text.replace(at, 8, "[0,0,1e400]");
    std::string message = "(no error)";
    try {
        rigsim::parse_rig_config(text, "rig.json");
    } catch (const ConfigError& e) {
        message = e.what();
    }
    CHECK(message == "rig.json: /kinematics/frames/1/offset/translation_mm/2: number overflow parsing '1e400' (not a "
                     "finite number)");
}

TEST_CASE("kinematics config: zero-length joint axes, bad quaternions, rpy with quaternion", "[unit][config]")
{
    auto k = kinematics();
    frame(k, "x")["joint"]["axis"] = json::array({0, 0, 0});
    CHECK(error_of(k) == "rig.json: /kinematics/frames/3/joint/axis: expected a non-zero vector, got [0.0,0.0,0.0]");
    k = kinematics();
    frame(k, "bracket")["offset"]["quaternion"] = json::array({1, 0, 0, 0.01});
    CHECK(error_of(k) == "rig.json: /kinematics/frames/4/offset/quaternion: expected a unit quaternion [w, x, y, z] "
                         "(norm within 1e-6 of 1), got [1.0,0.0,0.0,0.01] (norm 1.0000499987500624)");
    // Within 1e-6 is accepted, and made unit.
    k = kinematics();
    frame(k, "bracket")["offset"]["quaternion"] = json::array({1.0000005, 0, 0, 0});
    const auto c = load(k);
    CHECK((*c.frames[4].quaternion)[0] == 1.0);
    k = kinematics();
    frame(k, "rot")["offset"]["quaternion"] = json::array({1, 0, 0, 0});
    CHECK(error_of(k) == "rig.json: /kinematics/frames/1/offset: rpy_deg and quaternion both give the rotation: keep one");
}

TEST_CASE("kinematics config: a joint axis of any non-zero length, huge or tiny, is made unit", "[unit][config]")
{
    auto k = kinematics();
    frame(k, "x")["joint"]["axis"] = json::array({1e200, 1e200, 0});
    auto c = load(k);
    REQUIRE(c.frames[2].name == "x");
    CHECK(c.frames[2].joint_axis[0] == Approx(std::sqrt(0.5)));
    CHECK(c.frames[2].joint_axis[1] == Approx(std::sqrt(0.5)));
    CHECK(c.frames[2].joint_axis[2] == 0.0);
    k = kinematics();
    frame(k, "x")["joint"]["axis"] = json::array({1e-13, 0, 0});
    c = load(k);
    CHECK(c.frames[2].joint_axis == rigsim::Vector3{1, 0, 0});
    k = kinematics();
    frame(k, "x")["joint"]["axis"] = json::array({0, -5e-324, 0});
    c = load(k);
    CHECK(c.frames[2].joint_axis == rigsim::Vector3{0, -1, 0});
}

TEST_CASE("kinematics config: lengths are at most 1 km in magnitude", "[unit][config]")
{
    auto k = kinematics();
    frame(k, "rot")["offset"]["translation_mm"] = json::array({1e308, 0, 0});
    CHECK(error_of(k) == "rig.json: /kinematics/frames/1/offset/translation_mm/0: expected a number of at most 1000000 "
                         "mm in magnitude, got 1e+308");
    k = kinematics();
    frame(k, "rot")["joint"]["point_mm"] = json::array({0, -1000000.5, 0});
    CHECK(error_of(k) == "rig.json: /kinematics/frames/1/joint/point_mm/1: expected a number of at most 1000000 "
                         "mm in magnitude, got -1000000.5");
    k = kinematics();
    frame(k, "gonio")["joint"]["centre_mm"] = json::array({0, 0, 2e6});
    CHECK(error_of(k) == "rig.json: /kinematics/frames/2/joint/centre_mm/2: expected a number of at most 1000000 "
                         "mm in magnitude, got 2000000.0");
    k = kinematics();
    frame(k, "x")["box_mm"]["max"] = json::array({10, 10, 1e7});
    CHECK(error_of(k) == "rig.json: /kinematics/frames/3/box_mm/max/2: expected a number of at most 1000000 "
                         "mm in magnitude, got 10000000.0");
    k = kinematics();
    frame(k, "x")["box_mm"]["min"] = json::array({-1e9, -10, 0});
    CHECK(error_of(k) == "rig.json: /kinematics/frames/3/box_mm/min/0: expected a number of at most 1000000 "
                         "mm in magnitude, got -1000000000.0");
    k = kinematics();
    k["tools"][0]["offset"]["translation_mm"] = json::array({0, 0, 1e6 + 1});
    CHECK(error_of(k) == "rig.json: /kinematics/tools/0/offset/translation_mm/2: expected a number of at most 1000000 "
                         "mm in magnitude, got 1000001.0");
    // 1 km itself is allowed.
    k = kinematics();
    frame(k, "rot")["offset"]["translation_mm"] = json::array({-1e6, 1e6, 0});
    CHECK(load(k).frames[1].translation_mm == rigsim::Vector3{-1e6, 1e6, 0});
}

TEST_CASE("kinematics config: a name made only of dots is refused", "[unit][config]")
{
    for (const char* dots : {".", "..", "..."}) {
        auto k = kinematics();
        frame(k, "x")["name"] = dots;
        CHECK(error_of(k) == "rig.json: /kinematics/frames/3/name: a frame name made only of dots is no URL path "
                             "segment (/api/frames/<name>), got \"" + std::string(dots) + "\"");
        k = kinematics();
        k["tools"][0]["name"] = dots;
        CHECK(error_of(k) == "rig.json: /kinematics/tools/0/name: a frame name made only of dots is no URL path "
                             "segment (/api/frames/<name>), got \"" + std::string(dots) + "\"");
    }
    // Dots among other characters are fine.
    auto k = kinematics();
    k["tools"][0]["name"] = "..tip.";
    CHECK(load(k).frames.back().name == "..tip.");
}

TEST_CASE("kinematics config: an axis needs a moving joint and a moving joint an axis", "[unit][config]")
{
    auto k = kinematics();
    frame(k, "x").erase("axis");
    CHECK(error_of(k) == "rig.json: /kinematics/frames/3/axis: required key missing (a prismatic joint is driven by a "
                         "device's channel)");
    k = kinematics();
    frame(k, "x").erase("joint");
    CHECK(error_of(k) == "rig.json: /kinematics/frames/3/joint: required key missing (a frame with an \"axis\" has a "
                         "moving joint: prismatic, revolute or goniometer)");
    k = kinematics();
    frame(k, "x")["joint"] = json{{"type", "fixed"}};
    CHECK(error_of(k) == "rig.json: /kinematics/frames/3/joint/type: a fixed joint is driven by no axis "
                         "(/kinematics/frames/3/axis is given): expected prismatic, revolute or goniometer");
    k = kinematics();
    frame(k, "gonio")["joint"].erase("centre_mm");
    CHECK(error_of(k) == "rig.json: /kinematics/frames/2/joint/centre_mm: required key missing");
    k = kinematics();
    frame(k, "x")["joint"].erase("axis");
    CHECK(error_of(k) == "rig.json: /kinematics/frames/3/joint/axis: required key missing");
    // A fixed joint may be written out.
    k = kinematics();
    frame(k, "bracket")["joint"] = json{{"type", "fixed"}};
    CHECK(load(k).frames[4].joint == JointKind::Fixed);
}

TEST_CASE("kinematics config: axes name a device of the rig, each driving one frame", "[unit][config]")
{
    auto k = kinematics();
    frame(k, "x")["axis"]["device"] = "nope";
    CHECK(error_of(k) == "rig.json: /kinematics/frames/3/axis/device: no device named \"nope\" in the rig");
    k = kinematics();
    frame(k, "x")["axis"] = json{{"device", "apt_rot"}, {"channel", 0}};
    CHECK(error_of(k) == "rig.json: /kinematics/frames/3/axis: device \"apt_rot\" channel 0 already drives "
                         "/kinematics/frames/1/axis: one axis drives one frame");
}

TEST_CASE("kinematics config: boxes have min <= max", "[unit][config]")
{
    auto k = kinematics();
    frame(k, "rot")["box_mm"]["min"] = json::array({-30, 31, -10});
    CHECK(error_of(k) == "rig.json: /kinematics/frames/1/box_mm: expected min <= max in every coordinate, got min "
                         "[-30.0,31.0,-10.0] and max [30.0,30.0,0.0]");
    // A flat box is a box.
    frame(k, "rot")["box_mm"]["min"] = json::array({-30, 30, -10});
    CHECK(load(k).frames[1].box_mm->min[1] == 30);
}

TEST_CASE("kinematics config: one root", "[unit][config]")
{
    auto k = kinematics();
    frame(k, "bracket").erase("parent");
    frame(k, "bracket").erase("offset");
    CHECK(error_of(k) == "rig.json: /kinematics/frames/4: a second root (a frame without \"parent\"): "
                         "/kinematics/frames/0 is the root; every other frame names its parent");
    k = kinematics();
    frame(k, "table")["parent"] = "sample";
    CHECK(error_of(k) == "rig.json: /kinematics/frames: no root: every frame names a \"parent\"; exactly one (the "
                         "table) must have none");
    k = kinematics();
    frame(k, "table")["axis"] = json{{"device", "stack"}, {"channel", 1}};
    CHECK(error_of(k) == "rig.json: /kinematics/frames/0/axis: the root frame (the one without \"parent\") is the "
                         "world's origin: it takes no axis");
    k = kinematics();
    frame(k, "table")["offset"] = json::object();
    CHECK(error_of(k) == "rig.json: /kinematics/frames/0/offset: the root frame (the one without \"parent\") is the "
                         "world's origin: it takes no offset");
}

TEST_CASE("kinematics config: parents exist, no cycles, no name twice", "[unit][config]")
{
    auto k = kinematics();
    frame(k, "x")["parent"] = "rotor";
    CHECK(error_of(k) == "rig.json: /kinematics/frames/3/parent: no frame named \"rotor\"");
    k = kinematics();
    frame(k, "rot")["parent"] = "gonio";
    CHECK(error_of(k) ==
          "rig.json: /kinematics/frames/1/parent: mount cycle: rot -> gonio -> x -> rot (each frame sits on the next)");
    k = kinematics();
    frame(k, "bracket")["parent"] = "bracket";
    CHECK(error_of(k) == "rig.json: /kinematics/frames/4/parent: mount cycle: bracket -> bracket (each frame sits on "
                         "the next)");
    k = kinematics();
    k["tools"][0]["name"] = "x";
    CHECK(error_of(k) == "rig.json: /kinematics/tools/0/name: name \"x\" is already used by /kinematics/frames/3");
    k = kinematics();
    frame(k, "bracket")["name"] = "rot";
    CHECK(error_of(k) == "rig.json: /kinematics/frames/4/name: name \"rot\" is already used by /kinematics/frames/1");
}

TEST_CASE("kinematics config: at most 1024 frames and tools, chains at most 64 deep", "[unit][config]")
{
    auto k = kinematics();
    for (int i = 0; i < 1024 - 6 + 1; ++i)
        k["tools"].push_back(json{{"name", "t" + std::to_string(i)}, {"parent", "table"}});
    CHECK(error_of(k) == "rig.json: /kinematics: at most 1024 frames and tools together, got 1025");
    k["tools"].erase(k["tools"].size() - 1);
    CHECK(load(k).frames.size() == 1024);

    // A chain of 64 mounts above the root is the deepest.
    k = json{{"frames", json::array({json{{"name", "f0"}}})}};
    for (int i = 1; i <= 64; ++i)
        k["frames"].push_back(json{{"name", "f" + std::to_string(i)}, {"parent", "f" + std::to_string(i - 1)}});
    CHECK(load(k).frames.size() == 65);
    k["tools"] = json::array({json{{"name", "tip"}, {"parent", "f64"}}});
    CHECK(error_of(k) == "rig.json: /kinematics/tools/0/parent: frame \"tip\" is 65 mounts above the root (at most 64)");
}

TEST_CASE("kinematics config: explicit collision pairs", "[unit][config]")
{
    auto k = kinematics();
    k["collisions"] = "none";
    CHECK(error_of(k) ==
          "rig.json: /kinematics/collisions: expected \"auto\" or an array of pairs of frame names, got \"none\"");
    k["collisions"] = json::parse(R"([["rot", "gonio", "x"]])");
    CHECK(error_of(k) == "rig.json: /kinematics/collisions/0: expected a pair of frame names, got an array of 3 elements");
    k["collisions"] = json::parse(R"([["rot", "nope"]])");
    CHECK(error_of(k) == "rig.json: /kinematics/collisions/0/1: no frame named \"nope\"");
    k["collisions"] = json::parse(R"([["rot", "sample"]])");
    CHECK(error_of(k) == "rig.json: /kinematics/collisions/0/1: frame \"sample\" has no box_mm (/kinematics/tools/0)");
    k["collisions"] = json::parse(R"([["rot", "rot"]])");
    CHECK(error_of(k) == "rig.json: /kinematics/collisions/0: a frame does not collide with itself");
    k["collisions"] = json::parse(R"([["rot", "gonio"], ["gonio", "rot"]])");
    CHECK(error_of(k) == "rig.json: /kinematics/collisions/1: the pair is already listed at /kinematics/collisions/0");
}

} // namespace test_kinematics_config
