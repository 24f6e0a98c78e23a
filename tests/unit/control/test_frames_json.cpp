// The frames of a hand-built kinematic tree as the control API shows them (frames_json,
// FrameBook): every placement against a hand-computed transform (1e-9), the quaternion's sign,
// the joints' channels, the contacts, and which frames changed since the last event.
#include "emulator/control/frame_book.hpp"
#include "emulator/control/frames_json.hpp"
#include "models/kinematics.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace test_frames_json {

using namespace rigsim;
using namespace rigsim::control;
using nlohmann::json;

namespace {

constexpr double kTol = 1e-9;
const double kPi = std::acos(-1.0);
const double kRootHalf = std::sqrt(0.5);

double deg(double d)
{
    return d * kPi / 180.0;
}

void check_triple(const json& got, double x, double y, double z)
{
    REQUIRE(got.size() == 3);
    CHECK(got[0].get<double>() == Approx(x).margin(kTol));
    CHECK(got[1].get<double>() == Approx(y).margin(kTol));
    CHECK(got[2].get<double>() == Approx(z).margin(kTol));
}

void check_quaternion(const json& got, double w, double x, double y, double z)
{
    REQUIRE(got.size() == 4);
    CHECK(got[0].get<double>() == Approx(w).margin(kTol));
    CHECK(got[1].get<double>() == Approx(x).margin(kTol));
    CHECK(got[2].get<double>() == Approx(y).margin(kTol));
    CHECK(got[3].get<double>() == Approx(z).margin(kTol));
}

Eigen::Isometry3d translation(double x, double y, double z)
{
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.translation() = Eigen::Vector3d(x, y, z);
    return t;
}

/// table (root); rot: 50 mm up, revolute about z through (10, 0, 0) (apt_rot/0); x: prismatic
/// along x on rot (stack/1); gonio: goniometer about x, centre 40 mm above x (stack/2);
/// bracket: fixed on the table, turned 270 degrees about z; sample: a tool 40 mm above x.
struct Tree {
    Tree()
    {
        rot = k.add_frame("rot", 0, translation(0, 0, 50),
                          models::Joint{models::JointType::Revolute, Eigen::Vector3d::UnitZ(), {10, 0, 0}},
                          [this] { return q_rot; });
        x = k.add_frame("x", rot, Eigen::Isometry3d::Identity(),
                        models::Joint{models::JointType::Prismatic, Eigen::Vector3d::UnitX(), {0, 0, 0}},
                        [this] { return q_x; });
        gonio = k.add_frame("gonio", x, Eigen::Isometry3d::Identity(),
                            models::Joint{models::JointType::Goniometer, Eigen::Vector3d::UnitX(), {0, 0, 40}},
                            [this] { return q_gonio; });
        Eigen::Isometry3d turned = Eigen::Isometry3d::Identity();
        turned.linear() = Eigen::AngleAxisd(deg(270), Eigen::Vector3d::UnitZ()).toRotationMatrix();
        bracket = k.add_frame("bracket", 0, turned, models::Joint{});
        sample = k.add_tool("sample", x, translation(0, 0, 40));
        axes.resize(k.size());
        axes[rot] = JointAxis{"apt_rot", 0};
        axes[x] = JointAxis{"stack", 1};
        axes[gonio] = JointAxis{"stack", 2};
    }

    double q_rot = 90, q_x = 2, q_gonio = 30;
    models::Kinematics k{"table"};
    std::size_t rot = 0, x = 0, gonio = 0, bracket = 0, sample = 0;
    std::vector<std::optional<JointAxis>> axes;
};

const json& named(const json& list, const std::string& name)
{
    for (const auto& f : list)
        if (f["name"] == name)
            return f;
    FAIL("no frame " << name << " in " << list.dump());
    return list;
}

} // namespace

TEST_CASE("frames_json: every joint kind's world and parent-relative placement, hand-computed", "[unit][control]")
{
    Tree t;
    t.k.update();
    const auto doc = frames_json(t.k, t.axes, {});
    REQUIRE(doc["frames"].size() == 5);
    REQUIRE(doc["tools"].size() == 1);
    CHECK(doc["collisions"] == json::array());

    const auto& table = named(doc["frames"], "table");
    CHECK(table["parent"].is_null());
    CHECK(table["tool"] == false);
    CHECK(table["joint"].is_null());
    check_triple(table["world"]["position_mm"], 0, 0, 0);
    check_quaternion(table["world"]["quaternion"], 1, 0, 0, 0);

    // Rz(90) about the line through (10, 0, 0): the origin goes to (10, -10); then 50 mm up.
    const auto& rot = named(doc["frames"], "rot");
    CHECK(rot["parent"] == "table");
    CHECK(rot["joint"] == json{{"type", "revolute"}, {"device", "apt_rot"}, {"channel", 0}, {"position", 90.0}});
    check_triple(rot["world"]["position_mm"], 10, -10, 50);
    check_quaternion(rot["world"]["quaternion"], kRootHalf, 0, 0, kRootHalf);
    check_triple(rot["world"]["rpy_deg"], 0, 0, 90);
    check_triple(rot["parent_relative"]["position_mm"], 10, -10, 50);

    // 2 mm along rot's x, which is the world's y.
    const auto& x = named(doc["frames"], "x");
    CHECK(x["joint"] == json{{"type", "prismatic"}, {"device", "stack"}, {"channel", 1}, {"position", 2.0}});
    check_triple(x["parent_relative"]["position_mm"], 2, 0, 0);
    check_quaternion(x["parent_relative"]["quaternion"], 1, 0, 0, 0);
    check_triple(x["world"]["position_mm"], 10, -8, 50);
    check_triple(x["world"]["rpy_deg"], 0, 0, 90);

    // Rx(30) about the centre c = (0, 0, 40): translation c - Rx(30) c = (0, 20, 40 - 40 cos 30).
    const double dz = 40 - 40 * std::cos(deg(30));
    const auto& gonio = named(doc["frames"], "gonio");
    CHECK(gonio["joint"]["type"] == "goniometer");
    check_triple(gonio["parent_relative"]["position_mm"], 0, 20, dz);
    check_quaternion(gonio["parent_relative"]["quaternion"], std::cos(deg(15)), std::sin(deg(15)), 0, 0);
    check_triple(gonio["parent_relative"]["rpy_deg"], 30, 0, 0);
    // World: x's pose (Rz(90), (10, -8, 50)) then that: Rz(90) (0, 20, dz) = (-20, 0, dz).
    check_triple(gonio["world"]["position_mm"], -10, -8, 50 + dz);
    const double c45 = std::cos(deg(45)), s45 = std::sin(deg(45)), c15 = std::cos(deg(15)), s15 = std::sin(deg(15));
    check_quaternion(gonio["world"]["quaternion"], c45 * c15, c45 * s15, s45 * s15, s45 * c15);
    check_triple(gonio["world"]["rpy_deg"], 30, 0, 90);

    const auto& sample = named(doc["tools"], "sample");
    CHECK(sample["tool"] == true);
    CHECK(sample["parent"] == "x");
    CHECK(sample["joint"].is_null());
    check_triple(sample["parent_relative"]["position_mm"], 0, 0, 40);
    check_triple(sample["world"]["position_mm"], 10, -8, 90);
    check_triple(sample["world"]["rpy_deg"], 0, 0, 90);
}

TEST_CASE("frames_json: a rotation shown with w >= 0 (270 degrees reads as -90), zeros without a sign", "[unit][control]")
{
    Tree t;
    t.k.update();
    const auto bracket = frame_json(t.k, t.bracket, nullptr);
    CHECK(bracket["joint"].is_null());
    check_quaternion(bracket["world"]["quaternion"], kRootHalf, 0, 0, -kRootHalf);
    check_triple(bracket["world"]["rpy_deg"], 0, 0, -90);
    CHECK(bracket["world"]["quaternion"][0].get<double>() > 0);
    CHECK(json(placement_json(Eigen::Isometry3d::Identity())).dump()
          == R"({"position_mm":[0.0,0.0,0.0],"quaternion":[1.0,0.0,0.0,0.0],"rpy_deg":[0.0,0.0,0.0]})");
    CHECK(no_frames_json() == json{{"frames", json::array()}, {"tools", json::array()}, {"collisions", json::array()}});
}

TEST_CASE("frames_json: a half turn (w == 0) shown with the first non-zero of x, y, z positive", "[unit][control]")
{
    // Half a turn about (-1, 2, 0)/sqrt(5): R = 2 n n^T - I, exact and symmetric, so w is 0 exactly.
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    Eigen::Matrix3d r;
    r << -0.6, -0.8, 0, -0.8, 0.6, 0, 0, 0, -1;
    pose.linear() = r;
    const auto q = placement_json(pose)["quaternion"];
    CHECK(q[0].get<double>() == 0.0);
    CHECK_FALSE(std::signbit(q[0].get<double>()));
    check_quaternion(q, 0, 1 / std::sqrt(5.0), -2 / std::sqrt(5.0), 0);
    CHECK(q[1].get<double>() > 0);
    // About (0, -1, 1)/sqrt(2): x is 0, y leads.
    r << -1, 0, 0, 0, 0, -1, 0, -1, 0;
    pose.linear() = r;
    const auto q2 = placement_json(pose)["quaternion"];
    check_quaternion(q2, 0, 0, std::sqrt(0.5), -std::sqrt(0.5));
    CHECK(q2[2].get<double>() > 0);
}

TEST_CASE("frames_json: a moving joint whose channel is not known names none", "[unit][control]")
{
    Tree t;
    t.k.update();
    const auto rot = frame_json(t.k, t.rot, nullptr);
    CHECK(rot["joint"] == json{{"type", "revolute"}, {"device", nullptr}, {"channel", nullptr}, {"position", 90.0}});
}

TEST_CASE("contacts_now: the pairs whose boxes touch at the last update, listed by name", "[unit][control]")
{
    Tree t;
    // x's box reaches 39 mm above it, the sample's 1 mm below it (40 mm above x): they touch.
    t.k.set_box(t.x, Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 39)));
    t.k.set_box(t.sample, Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1)));
    t.k.set_box(t.bracket, Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1)));
    t.k.update();
    const std::vector<Contact> pairs{{t.x, t.sample}, {t.bracket, t.sample}, {t.rot, t.sample}};
    const auto contacts = contacts_now(t.k, pairs);
    REQUIRE(contacts == std::vector<Contact>{{t.x, t.sample}});
    CHECK(frames_json(t.k, t.axes, contacts)["collisions"] == json::array({json{{"frames", {"x", "sample"}}}}));
}

TEST_CASE("FrameBook: one frame by name, and the frames that changed since the last event", "[unit][control]")
{
    Tree t;
    FrameBook book(FrameSource{&t.k, t.axes, {}});
    CHECK_FALSE(book.empty());
    CHECK(book.changed() == json::array());   // the baseline is the poses at construction

    REQUIRE(book.one("sample"));
    check_triple((*book.one("sample"))["world"]["position_mm"], 10, -8, 90);
    CHECK_FALSE(book.one("nope"));
    CHECK(book.all()["tools"][0]["name"] == "sample");

    t.q_x = 3;   // x, the goniometer on it and the sample move; rot, the table and the bracket do not
    const auto moved = book.changed();
    std::vector<std::string> names;
    for (const auto& f : moved)
        names.push_back(f["name"].get<std::string>());
    CHECK(names == std::vector<std::string>{"x", "gonio", "sample"});
    check_triple(moved[2]["world"]["position_mm"], 10, -7, 90);
    CHECK(book.changed() == json::array());   // published once

    t.q_gonio = 45;
    book.all();   // a GET in between updates the poses: the event still has the change
    const auto tilted = book.changed();
    REQUIRE(tilted.size() == 1);
    CHECK(tilted[0]["name"] == "gonio");
}

TEST_CASE("FrameBook: a rig without kinematics has no frames and never changes", "[unit][control]")
{
    FrameBook book(FrameSource{});
    CHECK(book.empty());
    CHECK(book.all() == no_frames_json());
    CHECK_FALSE(book.one("table"));
    CHECK(book.changed() == json::array());
}

} // namespace test_frames_json
