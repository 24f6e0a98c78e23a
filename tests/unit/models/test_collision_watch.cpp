// models::CollisionWatch: boxes of frames tested on every tick while a joint between them moves;
// a new contact stops the moving joints at their position, as at their own end stops; the watch
// sleeps while nothing it watches moves. Real models::Axis bodies, hand-built Kinematics.

#include "models/axis.hpp"
#include "models/collision_watch.hpp"
#include "models/kinematics.hpp"
#include "models/world.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <optional>
#include <utility>
#include <vector>

namespace test_collision_watch {

using namespace rigsim;
using namespace rigsim::models;

namespace {

using Events = std::vector<std::pair<AxisEvent, Ticks>>;
constexpr double kCountsPerMm = 1000;   // 1 count = 1 µm

AxisConfig linear(Drive drive, double start_mm = 0)
{
    AxisConfig c;
    c.drive = drive;
    c.travel_min_counts = -50'000;
    c.travel_max_counts = 50'000;
    c.start_position_counts = start_mm * kCountsPerMm;
    return c;
}

Eigen::AlignedBox3d cube(double half_mm, Eigen::Vector3d centre = Eigen::Vector3d::Zero())
{
    const Eigen::Vector3d h = Eigen::Vector3d::Constant(half_mm);
    return {centre - h, centre + h};
}

Eigen::Isometry3d at(double x, double y, double z)
{
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.translation() = Eigen::Vector3d(x, y, z);
    return t;
}

Joint prismatic(Eigen::Vector3d axis)
{
    return Joint{JointType::Prismatic, axis, Eigen::Vector3d::Zero()};
}

/// A world of axes and the frames they drive (index = frame; the root and fixed frames have none).
struct Rig {
    Rig() : world(clock), kin("table") {}

    Axis& add_axis(const std::string& key, const AxisConfig& config)
    {
        Axis& a = world.emplace<Axis>(key, clock, config);
        a.set_listener([this, &a](AxisEvent e) { events.emplace_back(a.key(), e, clock.now()); });
        return a;
    }
    /// A frame under `parent` moved by `axis` along `direction`, with a cube box.
    std::size_t add_stage(const std::string& name, std::size_t parent, Axis& axis, Eigen::Vector3d direction,
                          double half_mm, const Eigen::Isometry3d& offset = Eigen::Isometry3d::Identity(),
                          bool stoppable = true)
    {
        const std::size_t f = kin.add_frame(name, parent, offset, prismatic(direction),
                                            [&axis] { return axis.position_counts() / kCountsPerMm; });
        kin.set_box(f, cube(half_mm));
        drives.resize(f + 1);
        drives[f].body_key = axis.key();
        drives[f].velocity = [&axis] { return axis.velocity_counts_per_s() / kCountsPerMm; };
        if (stoppable)
            drives[f].set_obstacles = [&axis](std::optional<double> min, std::optional<double> max) {
                const auto counts = [](std::optional<double> mm) {
                    return mm ? std::optional<double>(*mm * kCountsPerMm) : std::nullopt;
                };
                axis.set_obstacles(counts(min), counts(max));
            };
        return f;
    }
    std::size_t add_block(const std::string& name, std::size_t parent, const Eigen::Isometry3d& offset,
                          double half_mm)
    {
        const std::size_t f = kin.add_frame(name, parent, offset, Joint{});
        kin.set_box(f, cube(half_mm));
        drives.resize(f + 1);
        return f;
    }
    CollisionWatch& watch(std::vector<FramePair> pairs)
    {
        drives.resize(kin.size());
        CollisionWatch& w = world.emplace<CollisionWatch>("collisions", kin, std::move(pairs), drives);
        w.set_listener([this](const Contact& c) { contacts.push_back(c); });
        world.link_all();
        return w;
    }

    Clock clock;   // 1 kHz
    World world;
    Kinematics kin;
    std::vector<JointDrive> drives{1};
    std::vector<std::tuple<std::string, AxisEvent, Ticks>> events;
    std::vector<Contact> contacts;
};

} // namespace

TEST_CASE("collision watch: a servo driven into a box stalls at the tick the boxes touch", "[unit][models][collision]")
{
    Rig r;
    Axis& x = r.add_axis("stack/0", linear(Drive::Servo));
    const std::size_t carriage = r.add_stage("x", 0, x, Eigen::Vector3d::UnitX(), 1);
    const std::size_t wall = r.add_block("wall", 0, at(11, 0, 0), 1);   // faces at 10 and 12 mm
    CollisionWatch& w = r.watch(auto_collision_pairs(r.kin));
    REQUIRE(w.pairs() == std::vector<FramePair>{{carriage, wall}});
    r.clock.advance(5);
    CHECK_FALSE(w.awake());   // checked once at power-up, then asleep: nothing moves
    CHECK(r.world.next_change(r.clock.now()) == kNever);

    x.move_to(20'000, 10'000, 0);   // 10 mm/s from the next tick: 10 µm per tick
    CHECK(w.awake());
    r.clock.advance(2'000);
    // The carriage's face (q + 1 mm) meets the wall's (10 mm) at q = 9 mm: tick 5 + 900.
    REQUIRE(r.contacts.size() == 1);
    CHECK(r.contacts[0].frame_a == carriage);
    CHECK(r.contacts[0].frame_b == wall);
    CHECK(r.contacts[0].stopped == std::vector<ContactJoint>{{carriage, 9.0, +1}});
    CHECK(r.contacts[0].not_stopped.empty());
    CHECK(r.events == std::vector<std::tuple<std::string, AxisEvent, Ticks>>{{"stack/0", AxisEvent::Stalled, 906}});
    CHECK(x.position_counts() == 9'000);
    CHECK(x.obstacle_max_counts() == 9'000);
    CHECK_FALSE(x.obstacle_min_counts());
    CHECK(w.contacts().size() == 1);
    // Asleep again once the axis stopped: checked on every tick of the motion and no longer.
    CHECK_FALSE(w.awake());
    CHECK(w.checks() == 1 + 901);
}

TEST_CASE("collision watch: motion away is free, and parting ends the contact and its obstacle",
          "[unit][models][collision]")
{
    Rig r;
    Axis& x = r.add_axis("stack/0", linear(Drive::Servo));
    r.add_stage("x", 0, x, Eigen::Vector3d::UnitX(), 1);
    r.add_block("wall", 0, at(11, 0, 0), 1);
    CollisionWatch& w = r.watch(auto_collision_pairs(r.kin));
    x.move_to(20'000, 10'000, 0);
    r.clock.advance(2'000);
    REQUIRE(w.contacts().size() == 1);
    x.move_to(20'000, 10'000, 0);   // further in: stalls at once, where it is
    r.clock.advance(10);
    CHECK(std::get<1>(r.events.back()) == AxisEvent::Stalled);
    CHECK(x.position_counts() == 9'000);
    x.move_to(5'000, 10'000, 0);    // away
    r.clock.advance(1);
    CHECK(w.contacts().empty());    // parted on the first tick
    CHECK_FALSE(x.obstacle_max_counts());
    r.clock.advance(1'000);
    CHECK(std::get<1>(r.events.back()) == AxisEvent::Arrived);
    CHECK(x.position_counts() == 5'000);
    CHECK(r.contacts.size() == 1);
}

TEST_CASE("collision watch: a stepper driven into a box loses microsteps against it", "[unit][models][collision]")
{
    Rig r;
    Axis& x = r.add_axis("stack/0", linear(Drive::Stepper));
    r.add_stage("x", 0, x, Eigen::Vector3d::UnitX(), 1);
    r.add_block("wall", 0, at(11, 0, 0), 1);
    CollisionWatch& w = r.watch(auto_collision_pairs(r.kin));
    x.move_to(15'000, 10'000, 0);   // 1.5 s
    r.clock.advance(3'000);
    REQUIRE(r.contacts.size() == 1);
    CHECK(x.position_counts() == 9'000);
    CHECK(x.motor_position_counts() == Approx(15'000));
    CHECK(x.lost_counts() == Approx(6'000));
    REQUIRE(r.events.size() == 2);
    CHECK(std::get<1>(r.events[0]) == AxisEvent::LostSteps);
    CHECK(std::get<2>(r.events[0]) == 901);
    CHECK(std::get<1>(r.events[1]) == AxisEvent::Arrived);
    CHECK(w.contacts().size() == 1);
}

TEST_CASE("collision watch: an accelerating carriage goes in at most one tick's travel", "[unit][models][collision]")
{
    Rig r;
    Axis& x = r.add_axis("stack/0", linear(Drive::Servo, -20));
    r.add_stage("x", 0, x, Eigen::Vector3d::UnitX(), 1);
    r.add_block("wall", 0, at(11.0003, 0, 0), 1);   // touched at q = 9.0003 mm
    r.watch(auto_collision_pairs(r.kin));
    x.move_to(40'000, 30'000, 20'000);   // still accelerating at the wall
    Ticks contact = 0;
    double step_mm = 0;
    double before = x.position_counts();
    while (r.contacts.empty() && r.clock.now() < 10'000) {
        before = x.position_counts();
        r.clock.advance(1);
        contact = r.clock.now();
        step_mm = (x.position_counts() - before) / kCountsPerMm;
    }
    REQUIRE(r.contacts.size() == 1);
    const double q = r.contacts[0].stopped.at(0).position;
    CHECK(q >= 9.0003);
    CHECK(q - 9.0003 <= step_mm);
    CHECK(before / kCountsPerMm < 9.0003);   // the tick before, apart
    r.clock.advance(100);
    CHECK(x.position_counts() / kCountsPerMm == Approx(q).epsilon(1e-12));
    CHECK(std::get<2>(r.events.back()) == contact + 1);
}

TEST_CASE("collision watch: every moving joint between the two frames stops, none below their common ancestor",
          "[unit][models][collision]")
{
    Rig r;
    Axis& base = r.add_axis("base/0", linear(Drive::Servo));
    Axis& x = r.add_axis("stack/0", linear(Drive::Servo));
    Axis& y = r.add_axis("stack/1", linear(Drive::Servo, 5));
    // base (moves along z) carries both: x along X, and a post on y that moves along -X.
    const std::size_t b = r.add_stage("base", 0, base, Eigen::Vector3d::UnitZ(), 0.5, at(0, 0, -30));
    const std::size_t fx = r.add_stage("x", b, x, Eigen::Vector3d::UnitX(), 1, at(0, 0, 10));
    const std::size_t fy = r.add_stage("post", b, y, -Eigen::Vector3d::UnitX(), 1, at(10, 0, 10));
    CHECK(joints_between(r.kin, fx, fy) == std::vector<std::size_t>{fx, fy});
    r.watch({{fx, fy}});
    base.move_to(20'000, 1'000, 0);
    x.move_to(20'000, 1'000, 0);
    y.move_to(20'000, 1'000, 0);
    // x's face at q + 1, the post's at 10 - q' - 1 (q' from 5): they meet when q + (q' - 5) = 3 mm,
    // after 1.5 s.
    r.clock.advance(3'000);
    REQUIRE(r.contacts.size() == 1);
    const auto& c = r.contacts[0];
    REQUIRE(c.stopped.size() == 2);
    CHECK(c.stopped[0].frame == fx);
    CHECK(c.stopped[1].frame == fy);
    CHECK(c.stopped[0].position + c.stopped[1].position == Approx(8.0));
    CHECK(x.position_counts() == Approx(1'500));
    CHECK(y.position_counts() == Approx(6'500));
    CHECK(x.obstacle_max_counts() == Approx(1'500));
    CHECK(y.obstacle_max_counts() == Approx(6'500));
    CHECK_FALSE(base.obstacle_max_counts());   // moves both alike: runs on
    CHECK(base.moving());
}

TEST_CASE("collision watch: a joint whose axis cannot be stopped is reported and moves on", "[unit][models][collision]")
{
    Rig r;
    Axis& x = r.add_axis("piezo/0", linear(Drive::Servo));
    r.add_stage("x", 0, x, Eigen::Vector3d::UnitX(), 1, Eigen::Isometry3d::Identity(), false);
    r.add_block("wall", 0, at(11, 0, 0), 1);
    CollisionWatch& w = r.watch(auto_collision_pairs(r.kin));
    x.move_to(11'000, 10'000, 0);
    r.clock.advance(3'000);
    REQUIRE(r.contacts.size() == 1);
    CHECK(r.contacts[0].stopped.empty());
    CHECK(r.contacts[0].not_stopped == std::vector<ContactJoint>{{1, 9.0, +1}});
    CHECK(x.position_counts() == 11'000);   // pushed on into the wall
    CHECK(w.contacts().size() == 1);   // still inside the wall
}

TEST_CASE("collision watch: it sleeps until a body it watches moves", "[unit][models][collision]")
{
    Rig r;
    Axis& x = r.add_axis("stack/0", linear(Drive::Servo));
    Axis& other = r.add_axis("other/0", linear(Drive::Servo));
    r.add_stage("x", 0, x, Eigen::Vector3d::UnitX(), 1);
    r.add_block("wall", 0, at(11, 0, 0), 1);
    CollisionWatch& w = r.watch(auto_collision_pairs(r.kin));
    r.clock.advance(10);
    other.move_to(10'000, 1'000, 0);   // no joint of the rig
    CHECK_FALSE(w.awake());
    r.clock.advance(20'000);
    CHECK(w.checks() == 1);
    x.move_to(1'000, 1'000, 0);
    CHECK(w.awake());
    r.clock.advance(2'000);
    CHECK(w.checks() == 1 + 1'001);   // every tick of the motion, and the one it ended on
    CHECK(r.contacts.empty());
}

TEST_CASE("collision watch: the pairs of \"auto\" and the joints between two frames", "[unit][models][collision]")
{
    Rig r;
    Axis& x = r.add_axis("stack/0", linear(Drive::Servo));
    Axis& z = r.add_axis("stack/1", linear(Drive::Servo));
    const std::size_t fx = r.add_stage("x", 0, x, Eigen::Vector3d::UnitX(), 1);
    const std::size_t fz = r.add_stage("z", fx, z, Eigen::Vector3d::UnitZ(), 1);   // on x: parent and child
    const std::size_t clamp = r.add_block("clamp", fz, at(0, 5, 0), 1);           // rides on z
    const std::size_t sample = r.add_block("sample", fz, at(0, -5, 0), 1);        // rides on z too
    const std::size_t wall = r.add_block("wall", 0, at(20, 0, 0), 1);
    const std::size_t plain = r.kin.add_frame("bracket", fx, Eigen::Isometry3d::Identity(), Joint{});   // no box
    CHECK(joints_between(r.kin, clamp, sample).empty());
    CHECK(joints_between(r.kin, clamp, wall) == std::vector<std::size_t>{fz, fx});
    CHECK(joints_between(r.kin, wall, fx) == std::vector<std::size_t>{fx});
    // x-z: parent and child; clamp-sample: nothing between; x-clamp: z between, not parent-child.
    CHECK(auto_collision_pairs(r.kin)
          == std::vector<FramePair>{{fx, clamp}, {fx, sample}, {fx, wall}, {fz, wall}, {clamp, wall}, {sample, wall}});
    r.drives.resize(r.kin.size());
    CHECK_THROWS_AS(CollisionWatch(r.kin, {{fx, plain}}, r.drives), std::invalid_argument);
    CHECK_THROWS_AS(CollisionWatch(r.kin, {{fx, fx}}, r.drives), std::invalid_argument);
    CHECK_THROWS_AS(CollisionWatch(r.kin, {{fx, 99}}, r.drives), std::invalid_argument);
    CHECK_THROWS_AS(CollisionWatch(r.kin, {{fx, wall}}, std::vector<JointDrive>(2)), std::invalid_argument);
}

TEST_CASE("collision watch: during a contact a joint that takes the boxes deeper stops, one sliding along does not",
          "[unit][models][collision]")
{
    Rig r;
    Axis& coarse = r.add_axis("coarse/0", linear(Drive::Servo));
    Axis& lift = r.add_axis("lift/0", linear(Drive::Servo));
    Axis& x = r.add_axis("stack/0", linear(Drive::Servo));
    // table -> coarse (along X) -> lift (along Z) -> x (along X, the box); the wall on the table.
    const std::size_t fc = r.kin.add_frame("coarse", 0, Eigen::Isometry3d::Identity(), prismatic(Eigen::Vector3d::UnitX()),
                                           [&coarse] { return coarse.position_counts() / kCountsPerMm; });
    r.drives.resize(fc + 1);
    r.drives[fc].body_key = coarse.key();
    r.drives[fc].velocity = [&coarse] { return coarse.velocity_counts_per_s() / kCountsPerMm; };
    r.drives[fc].set_obstacles = [&coarse](std::optional<double> min, std::optional<double> max) {
        coarse.set_obstacles(min ? std::optional<double>(*min * kCountsPerMm) : std::nullopt,
                             max ? std::optional<double>(*max * kCountsPerMm) : std::nullopt);
    };
    const std::size_t fl = r.kin.add_frame("lift", fc, Eigen::Isometry3d::Identity(), prismatic(Eigen::Vector3d::UnitZ()),
                                           [&lift] { return lift.position_counts() / kCountsPerMm; });
    r.drives.resize(fl + 1);
    r.drives[fl].body_key = lift.key();
    r.drives[fl].velocity = [&lift] { return lift.velocity_counts_per_s() / kCountsPerMm; };
    r.drives[fl].set_obstacles = [&lift](std::optional<double> min, std::optional<double> max) {
        lift.set_obstacles(min ? std::optional<double>(*min * kCountsPerMm) : std::nullopt,
                           max ? std::optional<double>(*max * kCountsPerMm) : std::nullopt);
    };
    const std::size_t fx = r.add_stage("x", fl, x, Eigen::Vector3d::UnitX(), 1);
    const std::size_t wall = r.add_block("wall", 0, at(11, 0, 0), 1);
    CollisionWatch& w = r.watch({{fx, wall}});
    x.move_to(20'000, 10'000, 0);
    r.clock.advance(2'000);
    REQUIRE(r.contacts.size() == 1);
    CHECK(x.position_counts() == 9'000);
    // Sliding along the wall's face (the overlap is 0 along X, at its least): free.
    lift.move_to(500, 1'000, 0);
    r.clock.advance(1'000);
    CHECK(std::get<1>(r.events.back()) == AxisEvent::Arrived);
    CHECK(lift.position_counts() == 500);
    CHECK(r.contacts.size() == 1);
    CHECK_FALSE(lift.obstacle_max_counts());
    // The coarse stage pushes the carriage into the wall: stopped on the tick after it went in.
    coarse.move_to(5'000, 1'000, 0);
    const Ticks start = r.clock.now();
    r.clock.advance(1'000);
    REQUIRE(r.contacts.size() == 2);
    CHECK(r.contacts[1].stopped == std::vector<ContactJoint>{{fc, 0.001, +1}});
    CHECK(std::get<0>(r.events.back()) == "coarse/0");
    CHECK(std::get<1>(r.events.back()) == AxisEvent::Stalled);
    CHECK(std::get<2>(r.events.back()) == start + 2);
    CHECK(coarse.position_counts() == 1);   // one tick's travel: 1 µm
    REQUIRE(w.contacts().size() == 1);
    CHECK(w.contacts()[0].stopped.size() == 2);
    // Away, both: parted, both free.
    coarse.move_to(-1'000, 1'000, 0);
    x.move_to(0, 10'000, 0);
    r.clock.advance(3'000);
    CHECK(w.contacts().empty());
    CHECK_FALSE(coarse.obstacle_max_counts());
    CHECK_FALSE(x.obstacle_max_counts());
    CHECK(coarse.position_counts() == -1'000);
}

} // namespace test_collision_watch
