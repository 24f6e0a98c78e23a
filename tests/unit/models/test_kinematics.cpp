// models::Kinematics: frames composed as world_T_parent · offset · joint(q), against
// transforms computed by hand (the expected numbers are written out, not derived with Eigen);
// the lazy update (only frames whose chain moved are recomputed); roll/pitch/yaw; the
// separating-axis test of two oriented boxes.

#include "models/kinematics.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

namespace test_kinematics {

using namespace rigsim::models;
using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

constexpr double kTol = 1e-9;
const double kS2 = std::sqrt(2.0);        // √2
const double kHalfS2 = std::sqrt(2.0) / 2;   // sin 45° = cos 45°
const double kHalfS3 = std::sqrt(3.0) / 2;   // cos 30°

Matrix3d mat(double a, double b, double c, double d, double e, double f, double g, double h, double i)
{
    Matrix3d m;
    m << a, b, c, d, e, f, g, h, i;
    return m;
}

const Matrix3d kI = Matrix3d::Identity();
const Matrix3d kRx90 = mat(1, 0, 0, 0, 0, -1, 0, 1, 0);
const Matrix3d kRy90 = mat(0, 0, 1, 0, 1, 0, -1, 0, 0);
const Matrix3d kRz90 = mat(0, -1, 0, 1, 0, 0, 0, 0, 1);
/// x → y, y → z, z → x: Rz(90)·Rx(90), and 120° about (1, 1, 1).
const Matrix3d kCycle = mat(0, 0, 1, 1, 0, 0, 0, 1, 0);

template <typename A, typename B>
void check_near(const A& actual, const B& expected)
{
    INFO("actual:\n" << actual << "\nexpected:\n" << expected);
    CHECK((actual - expected).cwiseAbs().maxCoeff() <= kTol);
}

void check_pose(const Isometry3d& pose, const Vector3d& position_mm, const Matrix3d& rotation)
{
    check_near(pose.translation(), position_mm);
    check_near(pose.linear(), rotation);
}

Isometry3d at(double x, double y, double z)
{
    return Isometry3d(Eigen::Translation3d(x, y, z));
}

Isometry3d placed(double x, double y, double z, const Matrix3d& rotation)
{
    Isometry3d t = at(x, y, z);
    t.linear() = rotation;
    return t;
}

Joint moving(JointType type, const Vector3d& axis, const Vector3d& point_mm = Vector3d::Zero())
{
    Joint j;
    j.type = type;
    j.axis = axis;
    j.point_mm = point_mm;
    return j;
}

Joint prismatic(const Vector3d& axis) { return moving(JointType::Prismatic, axis); }
Joint revolute(const Vector3d& axis, const Vector3d& point_mm) { return moving(JointType::Revolute, axis, point_mm); }
Joint goniometer(const Vector3d& axis, const Vector3d& centre_mm)
{
    return moving(JointType::Goniometer, axis, centre_mm);
}

const Vector3d kX = Vector3d::UnitX();
const Vector3d kY = Vector3d::UnitY();
const Vector3d kZ = Vector3d::UnitZ();

} // namespace

TEST_CASE("kinematics: a prismatic XYZ stack adds its offsets and travels", "[unit][models][kinematics]")
{
    double qx = 5, qy = -3, qz = 7;
    Kinematics k("table");
    const auto x = k.add_frame("x", 0, at(10, 0, 0), prismatic(kX), [&] { return qx; });
    const auto y = k.add_frame("y", x, at(0, 0, 20), prismatic(kY), [&] { return qy; });
    const auto z = k.add_frame("z", y, Isometry3d::Identity(), prismatic(kZ), [&] { return qz; });
    REQUIRE(k.update() == 4);

    check_pose(k.world_pose(0), Vector3d(0, 0, 0), kI);
    check_pose(k.world_pose(x), Vector3d(15, 0, 0), kI);
    check_pose(k.world_pose(y), Vector3d(15, -3, 20), kI);
    check_pose(k.world_pose(z), Vector3d(15, -3, 27), kI);
    check_pose(k.parent_pose(y), Vector3d(0, -3, 20), kI);
    check_pose(k.parent_pose(z), Vector3d(0, 0, 7), kI);
    CHECK(k.joint_position(y) == -3);
    CHECK(k.joints_below(z) == 3);
    CHECK(k.joints_below(0) == 0);

    qx = -2.5;
    CHECK(k.update() == 3);
    check_pose(k.world_pose(z), Vector3d(7.5, -3, 27), kI);
}

TEST_CASE("kinematics: a revolute joint turns about an axis through its point", "[unit][models][kinematics]")
{
    double q = 90;
    Kinematics k("table");
    const auto rot = k.add_frame("rot", 0, at(0, 0, 50), revolute(kZ, Vector3d(10, 0, 0)), [&] { return q; });
    const auto pin = k.add_tool("pin", rot, at(10, 0, 0));   // on the rotation axis
    const auto tip = k.add_tool("tip", rot, at(11, 0, 0));
    k.update();

    // origin → p + Rz(90)·(-p) = (10, 0, 0) + (0, -10, 0)
    check_pose(k.world_pose(rot), Vector3d(10, -10, 50), kRz90);
    check_pose(k.parent_pose(rot), Vector3d(10, -10, 50), kRz90);   // offset · joint: on the table, as in the world
    check_pose(k.world_pose(pin), Vector3d(10, 0, 50), kRz90);
    check_pose(k.world_pose(tip), Vector3d(10, 1, 50), kRz90);
    CHECK(k.is_tool(pin));
    CHECK_FALSE(k.is_tool(rot));

    q = 30;   // origin → (10 - 10 cos 30°, -10 sin 30°, 0)
    k.update();
    check_pose(k.world_pose(rot), Vector3d(10 - 10 * kHalfS3, -5, 50), mat(kHalfS3, -0.5, 0, 0.5, kHalfS3, 0, 0, 0, 1));
    check_near(k.world_pose(pin).translation(), Vector3d(10, 0, 50));

    q = -90;   // Rz(-90)·(-10, 0, 0) = (0, 10, 0)
    k.update();
    check_pose(k.world_pose(rot), Vector3d(10, 10, 50), mat(0, 1, 0, -1, 0, 0, 0, 0, 1));
    check_near(k.world_pose(pin).translation(), Vector3d(10, 0, 50));
}

TEST_CASE("kinematics: a goniometer tilts about a centre above the stage, which stays put",
          "[unit][models][kinematics]")
{
    double q = 30;
    Kinematics k("table");
    const auto g = k.add_frame("gonio", 0, at(0, 0, 10), goniometer(kX, Vector3d(0, 0, 40)), [&] { return q; });
    const auto centre = k.add_tool("centre", g, at(0, 0, 40));
    const auto sample = k.add_tool("sample", g, at(0, 0, 45));
    k.update();

    // origin → c + Rx(30)·(-c), c = (0, 0, 40): (0, 0, 40) + (0, 20, -40 cos 30°); + offset z 10
    const Matrix3d rx30 = mat(1, 0, 0, 0, kHalfS3, -0.5, 0, 0.5, kHalfS3);
    check_pose(k.world_pose(g), Vector3d(0, 20, 50 - 40 * kHalfS3), rx30);
    check_pose(k.world_pose(centre), Vector3d(0, 0, 50), rx30);
    // 5 mm above the centre: (0, -5 sin 30°, 5 cos 30°) from it
    check_pose(k.world_pose(sample), Vector3d(0, -2.5, 50 + 5 * kHalfS3), rx30);

    q = -45;
    k.update();
    const Matrix3d rx_45 = mat(1, 0, 0, 0, kHalfS2, kHalfS2, 0, -kHalfS2, kHalfS2);
    check_pose(k.world_pose(centre), Vector3d(0, 0, 50), rx_45);
    check_pose(k.world_pose(sample), Vector3d(0, 5 * kHalfS2, 50 + 5 * kHalfS2), rx_45);
}

TEST_CASE("kinematics: a chain of depth 5 mixing every joint kind", "[unit][models][kinematics]")
{
    double qa = 10, qb = 90, qc = 3, qd = 90, qe = 2;
    Kinematics k("table");
    const auto a = k.add_frame("a", 0, at(0, 0, 5), prismatic(kX), [&] { return qa; });
    const auto b = k.add_frame("b", a, at(0, 0, 10), revolute(kZ, Vector3d::Zero()), [&] { return qb; });
    const auto c = k.add_frame("c", b, Isometry3d::Identity(), prismatic(kX), [&] { return qc; });
    const auto d = k.add_frame("d", c, Isometry3d::Identity(), goniometer(kX, Vector3d(0, 0, 20)), [&] { return qd; });
    const auto e = k.add_frame("e", d, Isometry3d::Identity(), prismatic(kZ), [&] { return qe; });
    const auto tool = k.add_tool("tool", e, at(0, 0, 1));
    CHECK(k.update() == 7);

    check_pose(k.world_pose(a), Vector3d(10, 0, 5), kI);
    check_pose(k.world_pose(b), Vector3d(10, 0, 15), kRz90);
    check_pose(k.world_pose(c), Vector3d(10, 3, 15), kRz90);   // b's x is the world's y
    // d on c: origin → (0, 0, 20) + Rx(90)·(0, 0, -20) = (0, 20, 20); Rz(90)·(0, 20, 20) = (-20, 0, 20)
    check_pose(k.parent_pose(d), Vector3d(0, 20, 20), kRx90);
    check_pose(k.world_pose(d), Vector3d(-10, 3, 35), kCycle);
    check_pose(k.world_pose(e), Vector3d(-8, 3, 35), kCycle);   // d's z is the world's x
    check_pose(k.world_pose(tool), Vector3d(-7, 3, 35), kCycle);
    CHECK(k.joints_below(tool) == 5);
    CHECK(k.joints_below(c) == 3);
    CHECK(k.parent(tool) == e);
    CHECK(k.parent(0) == 0);
}

TEST_CASE("kinematics: offsets rotated by roll/pitch/yaw and by a quaternion", "[unit][models][kinematics]")
{
    check_near(quaternion_from_rpy_deg(90, 0, 0).toRotationMatrix(), kRx90);
    check_near(quaternion_from_rpy_deg(0, 90, 0).toRotationMatrix(), kRy90);
    check_near(quaternion_from_rpy_deg(0, 0, 90).toRotationMatrix(), kRz90);
    check_near(quaternion_from_rpy_deg(90, 0, 90).toRotationMatrix(), kCycle);
    // Ry(90)·Rx(90): roll first, then pitch (Rx(90)·Ry(90) would be another rotation)
    check_near(quaternion_from_rpy_deg(90, 90, 0).toRotationMatrix(), mat(0, 1, 0, 0, 0, -1, -1, 0, 0));
    const Eigen::Quaterniond q = quaternion_from_rpy_deg(90, 0, 90);
    check_near(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()), Eigen::Vector4d(0.5, 0.5, 0.5, 0.5));

    double qp = 4;
    Kinematics k("table");
    Isometry3d rolled = at(1, 2, 3);
    rolled.linear() = quaternion_from_rpy_deg(90, 0, 0).toRotationMatrix();
    const auto bracket = k.add_frame("bracket", 0, rolled, Joint{});
    const auto on_bracket = k.add_tool("on_bracket", bracket, at(0, 1, 0));
    Isometry3d turned = at(0, 0, 100);
    turned.linear() = Eigen::Quaterniond(0.5, 0.5, 0.5, 0.5).toRotationMatrix();
    const auto mount = k.add_frame("mount", 0, turned, Joint{});
    const auto on_mount = k.add_tool("on_mount", mount, at(1, 0, 0));
    Isometry3d yawed = Isometry3d::Identity();
    yawed.linear() = quaternion_from_rpy_deg(0, 0, 90).toRotationMatrix();
    const auto slide = k.add_frame("slide", 0, yawed, prismatic(kX), [&] { return qp; });
    k.update();

    check_pose(k.world_pose(on_bracket), Vector3d(1, 2, 4), kRx90);
    check_pose(k.world_pose(on_mount), Vector3d(0, 1, 100), kCycle);
    // the joint's axis is in the mount's coordinates: x after a 90° yaw is the world's y
    check_pose(k.world_pose(slide), Vector3d(0, 4, 0), kRz90);
}

TEST_CASE("kinematics: roll/pitch/yaw round trip, ranges and gimbal lock", "[unit][models][kinematics]")
{
    for (double r : {-170.0, -90.0, -30.0, 0.0, 45.0, 120.0, 180.0})
        for (double p : {-89.5, -45.0, 0.0, 30.0, 89.5})
            for (double y : {-179.0, -60.0, 0.0, 90.0, 180.0}) {
                INFO("rpy " << r << " " << p << " " << y);
                const Eigen::Quaterniond q = quaternion_from_rpy_deg(r, p, y);
                check_near(rpy_deg_from_quaternion(q), Vector3d(r, p, y));
                Eigen::Quaterniond minus_q(-q.w(), -q.x(), -q.y(), -q.z());   // the same rotation
                check_near(rpy_deg_from_quaternion(minus_q), Vector3d(r, p, y));
            }

    check_near(rpy_deg_from_quaternion(Eigen::Quaterniond(0.5, 0.5, 0.5, 0.5)), Vector3d(90, 0, 90));
    check_near(rpy_deg_from_quaternion(Eigen::Quaterniond(0, 0, 0, 2)), Vector3d(0, 0, 180));   // not unit
    check_near(rpy_deg_from_quaternion(quaternion_from_rpy_deg(0, 0, -180)), Vector3d(0, 0, 180));
    check_near(rpy_deg_from_quaternion(quaternion_from_rpy_deg(-180, 0, 0)), Vector3d(180, 0, 0));
    check_near(rpy_deg_from_quaternion(quaternion_from_rpy_deg(190, 0, -200)), Vector3d(-170, 0, 160));

    // Pitch ±90: only yaw - roll (at +90) or yaw + roll (at -90) is defined; roll reported 0.
    struct Lock {
        Vector3d in, out;
    };
    for (const Lock& c : {Lock{{30, 90, 50}, {0, 90, 20}}, Lock{{30, -90, 50}, {0, -90, 80}},
                          Lock{{0, 90, 0}, {0, 90, 0}}, Lock{{-170, 90, 170}, {0, 90, -20}},
                          Lock{{100, -90, 100}, {0, -90, -160}}}) {
        INFO("rpy " << c.in.transpose());
        const Eigen::Quaterniond q = quaternion_from_rpy_deg(c.in(0), c.in(1), c.in(2));
        const Vector3d rpy = rpy_deg_from_quaternion(q);
        check_near(rpy, c.out);
        CHECK(quaternion_from_rpy_deg(rpy(0), rpy(1), rpy(2)).angularDistance(q) <= kTol);
    }
}

TEST_CASE("kinematics: update() recomputes only the frames whose chain moved", "[unit][models][kinematics]")
{
    double qa = 0, qb = 0, qc = 0, qd = 0, qf = 0;
    int reads = 0;
    const auto reader = [&reads](double& q) {
        return [&reads, &q] {
            ++reads;
            return q;
        };
    };
    Kinematics k("table");
    const auto a = k.add_frame("a", 0, Isometry3d::Identity(), prismatic(kX), reader(qa));
    const auto b = k.add_frame("b", a, at(0, 0, 10), revolute(kZ, Vector3d::Zero()), reader(qb));
    const auto c = k.add_frame("c", b, Isometry3d::Identity(), prismatic(kY), reader(qc));
    const auto t = k.add_tool("t", c, at(0, 0, 1));
    const auto d = k.add_frame("d", a, Isometry3d::Identity(), prismatic(kZ), reader(qd));   // a leaf
    const auto e = k.add_frame("e", 0, at(100, 0, 0), Joint{});
    const auto f = k.add_frame("f", e, Isometry3d::Identity(), prismatic(kX), reader(qf));   // another leaf
    REQUIRE(k.size() == 8);

    const auto recomputed = [&] {
        std::vector<std::size_t> out;
        for (std::size_t i = 0; i < k.size(); ++i)
            if (k.recomputed(i))
                out.push_back(i);
        return out;
    };
    using V = std::vector<std::size_t>;

    CHECK(k.update() == 8);   // the first: every frame
    CHECK(reads == 5);
    CHECK(k.update() == 0);   // nothing moved: the joints are read, nothing recomputed
    CHECK(reads == 10);
    CHECK(recomputed().empty());

    qd = 1;   // a leaf's joint: that frame alone
    CHECK(k.update() == 1);
    CHECK(recomputed() == V{d});
    check_pose(k.world_pose(d), Vector3d(0, 0, 1), kI);

    qb = 90;   // b's subtree: b, c, t
    CHECK(k.update() == 3);
    CHECK(recomputed() == V{b, c, t});

    qa = 2;   // the root's child: its whole subtree, not e or f
    CHECK(k.update() == 5);
    CHECK(recomputed() == V{a, b, c, t, d});
    check_pose(k.world_pose(t), Vector3d(2, 0, 11), kRz90);
    check_pose(k.world_pose(d), Vector3d(2, 0, 1), kI);

    qc = 5;
    qf = -1;   // two chains at once
    CHECK(k.update() == 3);
    CHECK(recomputed() == V{c, t, f});
    check_pose(k.world_pose(t), Vector3d(-3, 0, 11), kRz90);   // b's y is the world's -x
    check_pose(k.world_pose(f), Vector3d(99, 0, 0), kI);

    qc = 5;   // written again, unchanged
    CHECK(k.update() == 0);
    CHECK(reads == 35);
    CHECK(k.recomputed_total() == 8 + 0 + 1 + 3 + 5 + 3 + 0);

    const auto g = k.add_tool("g", t, at(0, 0, 1));   // added later: computed by the next update alone
    CHECK(k.update() == 1);
    CHECK(recomputed() == V{g});
    check_pose(k.world_pose(g), Vector3d(-3, 0, 12), kRz90);
}

TEST_CASE("kinematics: add_frame refuses what would make a wrong tree, and adds nothing",
          "[unit][models][kinematics]")
{
    using Catch::Matchers::Contains;
    double q = 0;
    const JointReader reader = [&q] { return q; };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    Kinematics k("table");
    const auto x = k.add_frame("x", 0, Isometry3d::Identity(), prismatic(kX), reader);
    k.add_tool("tip", x, at(0, 0, 1));
    REQUIRE(k.size() == 3);

    CHECK_THROWS_WITH(k.add_frame("x", 0, Isometry3d::Identity(), Joint{}), Contains("\"x\"") && Contains("taken"));
    CHECK_THROWS_WITH(k.add_frame("table", 0, Isometry3d::Identity(), Joint{}), Contains("taken"));
    CHECK_THROWS_WITH(k.add_tool("tip", 0, Isometry3d::Identity()), Contains("taken"));   // one namespace
    CHECK_THROWS_WITH(k.add_frame("y", 3, Isometry3d::Identity(), Joint{}), Contains("no parent frame 3"));
    CHECK_THROWS_WITH(k.add_tool("y", 99, Isometry3d::Identity()), Contains("no parent frame 99"));
    CHECK_THROWS_WITH(k.add_frame("y", 0, Isometry3d::Identity(), prismatic(Vector3d::Zero()), reader),
                      Contains("zero-length"));
    CHECK_THROWS_WITH(k.add_frame("y", 0, Isometry3d::Identity(), revolute(Vector3d(0, 0, 1.1), Vector3d::Zero()),
                                  reader),
                      Contains("not a unit vector"));
    CHECK_THROWS_WITH(k.add_frame("y", 0, Isometry3d::Identity(), prismatic(Vector3d(1 + 2e-9, 0, 0)), reader),
                      Contains("not a unit vector"));
    CHECK_THROWS_WITH(k.add_frame("y", 0, Isometry3d::Identity(), goniometer(Vector3d(0.6, 0.8, 1e-4), Vector3d::Zero()),
                                  reader),
                      Contains("not a unit vector"));
    CHECK_THROWS_WITH(k.add_frame("y", 0, Isometry3d::Identity(), prismatic(kX)), Contains("needs a reader"));
    CHECK_THROWS_WITH(k.add_frame("y", 0, Isometry3d::Identity(), Joint{}, reader), Contains("fixed joint takes no reader"));
    CHECK_THROWS_WITH(k.add_frame("y", 0, at(nan, 0, 0), Joint{}), Contains("offset is not finite"));
    Isometry3d infinite_rotation = Isometry3d::Identity();
    infinite_rotation.linear()(1, 2) = inf;
    CHECK_THROWS_WITH(k.add_tool("y", 0, infinite_rotation), Contains("offset is not finite"));
    CHECK_THROWS_WITH(k.add_frame("y", 0, Isometry3d::Identity(), prismatic(Vector3d(nan, 0, 0)), reader),
                      Contains("not finite"));
    CHECK_THROWS_WITH(k.add_frame("y", 0, Isometry3d::Identity(), revolute(kZ, Vector3d(0, inf, 0)), reader),
                      Contains("not finite"));
    Isometry3d scaled = Isometry3d::Identity();
    scaled.linear() *= 2;
    CHECK_THROWS_WITH(k.add_frame("y", 0, scaled, Joint{}), Contains("not a rotation"));
    Isometry3d mirrored = Isometry3d::Identity();
    mirrored.linear()(2, 2) = -1;
    CHECK_THROWS_WITH(k.add_frame("y", 0, mirrored, Joint{}), Contains("not a rotation"));
    CHECK_THROWS_AS(k.add_frame("y", 0, Isometry3d::Identity(), prismatic(kX)), std::invalid_argument);

    CHECK(k.size() == 3);
    CHECK_FALSE(k.find("y"));
    CHECK(k.find("tip") == std::optional<std::size_t>(2));
    CHECK(k.update() == 3);

    // within the tolerance: 1 ± 5e-10 is a unit vector, stored normalised
    const auto y = k.add_frame("y", 0, Isometry3d::Identity(), prismatic(Vector3d(0, 1 + 5e-10, 0)), reader);
    CHECK(k.joint(y).axis == Vector3d(0, 1, 0));

    CHECK_THROWS_WITH(k.set_box(99, Eigen::AlignedBox3d(Vector3d::Zero(), Vector3d::Ones())), Contains("no frame 99"));
    CHECK_THROWS_WITH(k.set_box(x, Eigen::AlignedBox3d(Vector3d(0, 2, 0), Vector3d(1, 1, 1))), Contains("min exceeds"));
    CHECK_THROWS_WITH(k.set_box(x, Eigen::AlignedBox3d(Vector3d(0, 0, -inf), Vector3d::Ones())), Contains("not finite"));
    CHECK_FALSE(k.box(x));
    k.set_box(x, Eigen::AlignedBox3d(Vector3d(-1, -2, -3), Vector3d(1, 2, 0)));
    REQUIRE(k.box(x));
    CHECK(k.box(x)->max() == Vector3d(1, 2, 0));
}

TEST_CASE("kinematics: boxes overlap by the separating-axis test, touching included", "[unit][models][kinematics]")
{
    const Eigen::AlignedBox3d cube(Vector3d(-1, -1, -1), Vector3d(1, 1, 1));
    const Isometry3d home = Isometry3d::Identity();
    const auto both_ways = [&](const Eigen::AlignedBox3d& b, const Isometry3d& world_T_b) {
        const bool ab = boxes_overlap(cube, home, b, world_T_b);
        CHECK(ab == boxes_overlap(b, world_T_b, cube, home));
        return ab;
    };

    SECTION("separated along a face normal, touching, overlapping")
    {
        CHECK_FALSE(both_ways(cube, at(2.5, 0, 0)));
        CHECK(both_ways(cube, at(2, 0, 0)));   // faces touch
        CHECK(both_ways(cube, at(2, 2, 2)));   // corners touch
        CHECK(both_ways(cube, at(1.5, -0.5, 0.3)));
        CHECK_FALSE(both_ways(cube, at(0, 0, -2 - 1e-6)));
        // a box away from its frame's origin: [10, 12] x [0, 2] x [0, 2] turned 180° about z and
        // moved by 11 in x lies at [-1, 1] x [-2, 0] x [0, 2]
        const Eigen::AlignedBox3d off(Vector3d(10, 0, 0), Vector3d(12, 2, 2));
        const Matrix3d rz180 = mat(-1, 0, 0, 0, -1, 0, 0, 0, 1);
        CHECK(both_ways(off, placed(11, 0, 0, rz180)));
        CHECK_FALSE(both_ways(off, placed(-0.5, 0, 0, rz180)));   // [-12.5, -10.5] in x
        CHECK(both_ways(off, placed(-11, 0, 0, kI)));              // [-1, 1] in x, [0, 2] in y
        CHECK_FALSE(both_ways(off, placed(-11, 0, 1.5, kI)));      // z [1.5, 3.5]
    }
    SECTION("separated along an edge-edge axis only")
    {
        // b's edges: u1 = (1/√2, 1/2, 1/2), u2 = (1/√2, -1/2, -1/2), e = (0, 1/√2, -1/√2).
        // Its edge along e faces the cube's edge along x at y = z = 1: the axis x × e ∝ (0, 1, 1)
        // separates them when the centre is beyond (0, 2, 2); no face normal does (the cube's z:
        // b reaches down to 2.1 - 1.707; b's u1: the cube's radius 1.707 + b's 1 > 2.1).
        const Matrix3d r = mat(kHalfS2, kHalfS2, 0, 0.5, -0.5, kHalfS2, 0.5, -0.5, -kHalfS2);
        CHECK_FALSE(both_ways(cube, placed(0, 2.1, 2.1, r)));
        CHECK(both_ways(cube, placed(0, 2, 2, r)));   // the two edges touch
        CHECK(both_ways(cube, placed(0, 1.9, 1.9, r)));
        CHECK_FALSE(both_ways(cube, placed(0.5, 2.01, 2.01, r)));
    }
    SECTION("rotated 45 degrees")
    {
        const Matrix3d rz45 = mat(kHalfS2, -kHalfS2, 0, kHalfS2, kHalfS2, 0, 0, 0, 1);
        // b's corner points along x, √2 from its centre
        CHECK_FALSE(both_ways(cube, placed(1 + kS2 + 0.01, 0, 0, rz45)));
        CHECK(both_ways(cube, placed(1 + kS2, 0, 0, rz45)));   // corner on the face
        CHECK(both_ways(cube, placed(1 + kS2 - 0.01, 0, 0, rz45)));
        // along the diagonal, b's face faces the cube's edge: 2√2 from it against √2 + 1
        CHECK_FALSE(both_ways(cube, placed(2, 2, 0, rz45)));
        CHECK(both_ways(cube, placed(1.6, 1.6, 0, rz45)));
    }
    SECTION("contained")
    {
        const Eigen::AlignedBox3d small(Vector3d(-0.1, -0.1, -0.1), Vector3d(0.1, 0.1, 0.1));
        Isometry3d inside = at(0.2, 0.3, -0.1);
        inside.linear() = quaternion_from_rpy_deg(30, 40, 50).toRotationMatrix();
        CHECK(both_ways(small, inside));
        CHECK(both_ways(cube, home));
        const Eigen::AlignedBox3d point(Vector3d(0.5, 0.5, 0.5), Vector3d(0.5, 0.5, 0.5));   // a point
        CHECK(both_ways(point, home));
        CHECK_FALSE(both_ways(point, at(0, 0, 0.6)));
    }
}

TEST_CASE("kinematics: joint_transform of each kind at a given q", "[unit][models][kinematics]")
{
    Joint fixed;
    check_pose(joint_transform(fixed, 123), Vector3d(0, 0, 0), kI);
    check_pose(joint_transform(prismatic(Vector3d(0.6, 0.8, 0)), -5), Vector3d(-3, -4, 0), kI);
    // 180° about the y axis through (1, 0, 0): origin → (2, 0, 0)
    check_pose(joint_transform(revolute(kY, Vector3d(1, 0, 0)), 180), Vector3d(2, 0, 0), mat(-1, 0, 0, 0, 1, 0, 0, 0, -1));
    check_pose(joint_transform(goniometer(kY, Vector3d(1, 5, 0)), 180), Vector3d(2, 0, 0), mat(-1, 0, 0, 0, 1, 0, 0, 0, -1));
    check_pose(joint_transform(revolute(kX, Vector3d::Zero()), 0), Vector3d(0, 0, 0), kI);
}

} // namespace test_kinematics
