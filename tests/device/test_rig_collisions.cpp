// Collisions in a whole rig (the rig JSON's "kinematics" with boxes and "collisions": "auto"):
// each device's channel driven over its own protocol into a wall stops at contact as at its own
// end stop (an APT DC servo stalls, an APT stepper loses microsteps, an MCS channel ends blocked
// with 142), a piezo is only reported; motion away is free; every contact is a "collision"
// event and is listed by Rig::contacts() while the boxes touch.
#include "apt/apt_harness.hpp"

#include "emulator/core/event_bus.hpp"
#include "emulator/daemon/rig.hpp"
#include "emulator/daemon/rig_families.hpp"
#include "emulator/mcs/mcs_device.hpp"
#include "tests/support/temp_dir.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <boost/asio/io_context.hpp>

#include <memory>
#include <string>
#include <vector>

namespace test_rig_collisions {

using nlohmann::json;
using namespace rigsim;
using namespace rigsim::test;

namespace {

/// A KDC101 with a Z825B (DC servo, 34,304 counts/mm, 12.5 mm at power-up), a KST101 with a
/// DRV014 (stepper, 25,600 microsteps/mm, 25 mm at power-up), a one-channel MCS (0 at power-up)
/// and a TPZ001 piezo driver. Each drives a 2 mm cube along x on its own lane (y = 0, 100, 200,
/// 300), placed so that it stands at x = 0; a 2 mm wall ahead of each: the servo's, stepper's
/// and MCS's at x = 5 (touched at x = 3 mm), the piezo's at x = 2.005 (touched at 5 µm).
json rig_json()
{
    return json::parse(R"({
      "devices": [
        {"name": "kdc", "protocol": "apt", "model": "KDC101", "apt": {"stage": "Z825B"}},
        {"name": "kst", "protocol": "apt", "model": "KST101", "apt": {"stage": "DRV014"}},
        {"name": "stack", "protocol": "mcs", "mcs": {"channels": [{}]}},
        {"name": "tpz", "protocol": "apt", "model": "TPZ001", "apt": {}}
      ],
      "kinematics": {
        "frames": [
          {"name": "table"},
          {"name": "servo", "parent": "table", "offset": {"translation_mm": [-12.5, 0, 0]},
           "axis": {"device": "kdc", "channel": 0}, "joint": {"type": "prismatic", "axis": [1, 0, 0]},
           "box_mm": {"min": [-1, -1, -1], "max": [1, 1, 1]}},
          {"name": "servo_wall", "parent": "table", "offset": {"translation_mm": [5, 0, 0]},
           "box_mm": {"min": [-1, -1, -1], "max": [1, 1, 1]}},
          {"name": "stepper", "parent": "table", "offset": {"translation_mm": [-25, 100, 0]},
           "axis": {"device": "kst", "channel": 0}, "joint": {"type": "prismatic", "axis": [1, 0, 0]},
           "box_mm": {"min": [-1, -1, -1], "max": [1, 1, 1]}},
          {"name": "stepper_wall", "parent": "table", "offset": {"translation_mm": [5, 100, 0]},
           "box_mm": {"min": [-1, -1, -1], "max": [1, 1, 1]}},
          {"name": "mcs", "parent": "table", "offset": {"translation_mm": [0, 200, 0]},
           "axis": {"device": "stack", "channel": 0}, "joint": {"type": "prismatic", "axis": [1, 0, 0]},
           "box_mm": {"min": [-1, -1, -1], "max": [1, 1, 1]}},
          {"name": "mcs_wall", "parent": "table", "offset": {"translation_mm": [5, 200, 0]},
           "box_mm": {"min": [-1, -1, -1], "max": [1, 1, 1]}},
          {"name": "piezo", "parent": "table", "offset": {"translation_mm": [0, 300, 0]},
           "axis": {"device": "tpz", "channel": 0}, "joint": {"type": "prismatic", "axis": [1, 0, 0]},
           "box_mm": {"min": [-1, -1, -1], "max": [1, 1, 1]}},
          {"name": "piezo_wall", "parent": "table", "offset": {"translation_mm": [2.005, 300, 0]},
           "box_mm": {"min": [-1, -1, -1], "max": [1, 1, 1]}}
        ]
      }
    })");
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

/// A rig on a paused clock, its ptys in a fresh directory, its "collision" events recorded.
struct Fixture {
    Fixture() : config(parse_rig_config(rig_json().dump(), "rig.json"))
    {
        options.pty_dir = dir.path();
        options.ephemeral_ports = true;
        options.paused = true;
        options.log_levels.global = spdlog::level::warn;
        rig = std::make_unique<Rig>(io, config, options);
        rig->events().subscribe([this](const Event& e) {
            if (e.type == "collision")
                collisions.push_back(json::parse(e.json));
        });
    }
    Device& device(const std::string& name)
    {
        for (auto& d : rig->controlled())
            if (d.endpoints.name == name)
                return dynamic_cast<Device&>(*d.surface);
        FAIL("no device " << name);
        throw;
    }
    /// A session on device `name` whose output goes to `out`.
    std::unique_ptr<Session> open(const std::string& name, std::string& out)
    {
        return device(name).open_session([&out](std::string_view b) { out.append(b); }, "test");
    }
    std::size_t frame(const std::string& name)
    {
        const auto i = rig->kinematics()->find(name);
        REQUIRE(i);
        return *i;
    }
    double q(const std::string& frame_name) { return rig->joint_bindings()[frame(frame_name)].position(); }
    void advance_ms(std::int64_t ms) { rig->clock().advance_ms(ms); }

    test::TempDir dir;
    boost::asio::io_context io;
    RigConfig config;
    RigOptions options;
    std::unique_ptr<Rig> rig;
    std::vector<json> collisions;
};

} // namespace

TEST_CASE("rig collisions: an APT DC servo driven into a box stalls at contact, as at its end stop",
          "[device][kinematics][collision]")
{
    Fixture f;
    REQUIRE(f.q("servo") == Approx(12.5));
    // "auto": every two boxes with a moving joint between them: all but the walls' 6 pairs of 28.
    CHECK(f.rig->collision_pairs().size() == 22);
    CHECK(f.rig->collision_pairs() == models::auto_collision_pairs(*f.rig->kinematics()));
    std::string out;
    auto session = f.open("kdc", out);
    session->receive(bytes("53 04 06 00 D0 01 01 00 " + le32(300'000)));   // MOVE_ABSOLUTE: 8.7 mm on
    f.advance_ms(10'000);
    const auto msgs = frames(hex(out));
    REQUIRE(msgs.size() == 2);
    // The KDC101's stall against an end stop: HW_RICHRESPONSE "Motor stalled", MOVE_STOPPED with the
    // current limit bit and no limit switch bit.
    const auto rich = bytes(msgs[0]);
    REQUIRE(rich.size() == 74);
    CHECK(hex(rich.substr(0, 10)) == "81 00 44 00 81 50 53 04 01 00");
    CHECK(rich.substr(10, 13) == "Motor stalled");
    CHECK(msgs[1].substr(0, 23) == "66 04 0E 00 81 50 01 00");
    const std::int32_t stopped = get_i32(bytes(msgs[1]), 8);
    // Touched at 3 mm (102,912 counts) on, in by at most one tick's travel (2.3 mm/s: 80 counts).
    CHECK(stopped >= 102'912);
    CHECK(stopped <= 102'912 + 80);
    CHECK(status_of(msgs[1]) == (status::kMotorConnected | status::kCurrentLimit | status::kSettled | status::kEnabled));
    REQUIRE(f.collisions.size() == 1);
    CHECK(f.collisions[0]["frames"] == json{"servo", "servo_wall"});
    REQUIRE(f.collisions[0]["stopped"].size() == 1);
    CHECK(f.collisions[0]["stopped"][0]["device"] == "kdc");
    CHECK(f.collisions[0]["stopped"][0]["channel"] == 0);
    CHECK(f.collisions[0]["stopped"][0]["position"].get<double>() == Approx(12.5 + stopped / 34'304.0));
    CHECK(f.collisions[0]["not_stopped"].empty());
    CHECK(f.rig->contacts() == std::vector<std::pair<std::size_t, std::size_t>>{{f.frame("servo"), f.frame("servo_wall")}});

    // Away: free; the contact ends.
    out.clear();
    session->receive(bytes("53 04 06 00 D0 01 01 00 " + le32(0)));
    f.advance_ms(10'000);
    const auto back = frames(hex(out));
    REQUIRE(back.size() == 1);
    CHECK(back[0].substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(0));
    CHECK((status_of(back[0]) & status::kCurrentLimit) == 0);
    CHECK(f.rig->contacts().empty());
    CHECK(f.collisions.size() == 1);
}

TEST_CASE("rig collisions: an APT stepper driven into a box loses microsteps, its counter runs on",
          "[device][kinematics][collision]")
{
    Fixture f;
    REQUIRE(f.q("stepper") == Approx(25));
    std::string out;
    auto session = f.open("kst", out);
    session->receive(bytes("53 04 06 00 D0 01 01 00 " + le32(200'000)));   // 7.8 mm on
    f.advance_ms(30'000);
    const auto msgs = frames(hex(out));
    REQUIRE(msgs.size() == 1);
    CHECK(msgs[0].substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(200'000));   // MOVE_COMPLETED, no fault
    CHECK((status_of(msgs[0]) & (status::kCurrentLimit | status::kMotionError)) == 0);
    // The carriage stands at the wall (touched at 3 mm on), the counter 4.8 mm further.
    CHECK(f.q("stepper") >= 28);
    CHECK(f.q("stepper") < 28.01);
    REQUIRE(f.collisions.size() == 1);
    CHECK(f.collisions[0]["frames"] == json{"stepper", "stepper_wall"});
    CHECK(f.collisions[0]["stopped"][0]["device"] == "kst");
}

TEST_CASE("rig collisions: an MCS closed-loop move into a box ends blocked with 142, as under the stall fault",
          "[device][kinematics][collision]")
{
    Fixture f;
    std::string out;
    auto session = f.open("stack", out);
    session->receive(":SCM1\n:MPA0,5000000,0\n");
    CHECK(out.empty());
    f.advance_ms(2'000);
    session->receive(":GS0\n:GP0\n");
    REQUIRE(out.rfind(":E0,142\n:S0,0\n:P0,", 0) == 0);
    const long position = std::stol(out.substr(out.rfind(",") + 1));
    CHECK(position >= 3'000'000);
    CHECK(position <= 3'010'000);   // 10 mm/s: 10 µm per tick
    REQUIRE(f.collisions.size() == 1);
    CHECK(f.collisions[0]["frames"] == json{"mcs", "mcs_wall"});
    CHECK(f.collisions[0]["stopped"][0] == json{{"device", "stack"}, {"channel", 0}, {"position", position / 1e6}});
    // Away: free.
    out.clear();
    session->receive(":MPA0,0,0\n");
    f.advance_ms(2'000);
    session->receive(":GS0\n:GP0\n");
    CHECK(out == ":S0,0\n:P0,0\n");
    CHECK(f.rig->contacts().empty());
}

TEST_CASE("rig collisions: a piezo is not stopped, its contact only reported", "[device][kinematics][collision]")
{
    Fixture f;
    // PZ_SET_OUTPUTVOLTS (p. 113), channel 1, full voltage: the stack extends by its travel.
    std::string out;
    auto session = f.open("tpz", out);
    session->receive(std::string{"\x43\x06\x04\x00\xd0\x01\x01\x00\xff\x7f", 10});
    f.advance_ms(1'000);
    CHECK(f.q("piezo") > 0.010);   // pushed on through the wall's face at 5 µm
    INFO(json(f.collisions).dump());
    REQUIRE(f.collisions.size() == 1);
    CHECK(f.collisions[0]["frames"] == json{"piezo", "piezo_wall"});
    CHECK(f.collisions[0]["stopped"].empty());
    REQUIRE(f.collisions[0]["not_stopped"].size() == 1);
    CHECK(f.collisions[0]["not_stopped"][0]["device"] == "tpz");
    CHECK(f.collisions[0]["not_stopped"][0]["position"].get<double>() >= 0.005);
    CHECK(f.rig->contacts().size() == 1);
}

} // namespace test_rig_collisions
