#include "models/kinematics.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace rigsim::models {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadPerDeg = kPi / 180;
constexpr double kDegPerRad = 180 / kPi;
/// A moving joint's axis: |norm - 1| at most this.
constexpr double kAxisNormTolerance = 1e-9;
/// An offset's linear part: every entry of RᵀR - I at most this (a rotation built from a
/// quaternion that is unit within 1e-6 passes; a scale or a shear does not).
constexpr double kRotationTolerance = 1e-5;
/// Below this cos(pitch) the roll/pitch/yaw decomposition is at gimbal lock.
constexpr double kGimbalLockCos = 1e-9;
/// Padding of the rotation entries of the separating-axis test (parallel edges).
constexpr double kSatEpsilon = 1e-9;

bool is_moving(JointType type)
{
    switch (type) {
    case JointType::Fixed:
        return false;
    case JointType::Prismatic:
    case JointType::Revolute:
    case JointType::Goniometer:
        return true;
    }
    return false;
}

/// An angle in degrees from atan2 (in [-180, 180]) brought into (-180, 180], without -0.
double half_open_deg(double deg)
{
    if (deg <= -180 + 1e-9)
        return 180;
    return deg + 0.0;
}

std::invalid_argument frame_error(const std::string& name, const std::string& what)
{
    return std::invalid_argument("frame \"" + name + "\": " + what);
}

} // namespace

Eigen::Isometry3d joint_transform(const Joint& joint, double q)
{
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    switch (joint.type) {
    case JointType::Fixed:
        break;
    case JointType::Prismatic:
        t.translation() = q * joint.axis;
        break;
    case JointType::Revolute:
    case JointType::Goniometer: {
        // Translation(p) · AngleAxis · Translation(-p): the point p stays where it is.
        const Eigen::Matrix3d r = Eigen::AngleAxisd(q * kRadPerDeg, joint.axis).toRotationMatrix();
        t.linear() = r;
        t.translation() = joint.point_mm - r * joint.point_mm;
        break;
    }
    }
    return t;
}

Eigen::Quaterniond quaternion_from_rpy_deg(double roll_deg, double pitch_deg, double yaw_deg)
{
    return Eigen::Quaterniond(Eigen::AngleAxisd(yaw_deg * kRadPerDeg, Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(pitch_deg * kRadPerDeg, Eigen::Vector3d::UnitY()) *
                              Eigen::AngleAxisd(roll_deg * kRadPerDeg, Eigen::Vector3d::UnitX()));
}

Eigen::Vector3d rpy_deg_from_quaternion(const Eigen::Quaterniond& q)
{
    // R = Rz(yaw) · Ry(pitch) · Rx(roll):
    //   R(2,0) = -sin p, R(2,1) = cos p sin r, R(2,2) = cos p cos r,
    //   R(0,0) = cos y cos p, R(1,0) = sin y cos p.
    // At cos p = 0 only yaw - roll (p = 90°) or yaw + roll (p = -90°) is defined:
    //   R(0,1) = -sin(yaw ∓ roll), R(1,1) = cos(yaw ∓ roll); reported with roll 0.
    const Eigen::Matrix3d r = q.normalized().toRotationMatrix();
    const double cos_pitch = std::hypot(r(0, 0), r(1, 0));
    const double pitch = std::atan2(-r(2, 0), cos_pitch);
    double roll = 0;
    double yaw = 0;
    if (cos_pitch < kGimbalLockCos) {
        yaw = std::atan2(-r(0, 1), r(1, 1));
    } else {
        roll = std::atan2(r(2, 1), r(2, 2));
        yaw = std::atan2(r(1, 0), r(0, 0));
    }
    return {half_open_deg(roll * kDegPerRad), pitch * kDegPerRad + 0.0, half_open_deg(yaw * kDegPerRad)};
}

bool boxes_overlap(const Eigen::AlignedBox3d& a, const Eigen::Isometry3d& world_T_a,
                   const Eigen::AlignedBox3d& b, const Eigen::Isometry3d& world_T_b)
{
    // Oriented boxes (Gottschalk et al., "OBBTree", 1996; Ericson, Real-Time Collision
    // Detection, 4.4.1), worked in the axes of box a: R takes b's axes into a's, t is the
    // centre of b seen from the centre of a. Separated when some axis L has
    // |t·L| > ra + rb; touching (equal) is an overlap.
    const Eigen::Vector3d ea = a.sizes() / 2;
    const Eigen::Vector3d eb = b.sizes() / 2;
    const Eigen::Matrix3d ra_world = world_T_a.linear();
    const Eigen::Matrix3d r = ra_world.transpose() * world_T_b.linear();
    const Eigen::Vector3d t = ra_world.transpose() * (world_T_b * b.center() - world_T_a * a.center());
    // Padded: for parallel edges the cross-product axes are near zero and only rounding is
    // left; the padding keeps rounding from separating boxes that overlap.
    const Eigen::Matrix3d abs_r = r.cwiseAbs().array() + kSatEpsilon;

    for (int i = 0; i < 3; ++i)   // a's face normals
        if (std::abs(t(i)) > ea(i) + eb.dot(abs_r.row(i)))
            return false;
    for (int j = 0; j < 3; ++j)   // b's face normals
        if (std::abs(t.dot(r.col(j))) > ea.dot(abs_r.col(j)) + eb(j))
            return false;
    for (int i = 0; i < 3; ++i) {   // a's edge i × b's edge j
        const int i1 = (i + 1) % 3;
        const int i2 = (i + 2) % 3;
        for (int j = 0; j < 3; ++j) {
            const int j1 = (j + 1) % 3;
            const int j2 = (j + 2) % 3;
            const double rad_a = ea(i1) * abs_r(i2, j) + ea(i2) * abs_r(i1, j);
            const double rad_b = eb(j1) * abs_r(i, j2) + eb(j2) * abs_r(i, j1);
            const double dist = std::abs(t(i2) * r(i1, j) - t(i1) * r(i2, j));
            if (dist > rad_a + rad_b)
                return false;
        }
    }
    return true;
}

Kinematics::Kinematics(std::string root_name)
{
    Frame root;
    root.name = std::move(root_name);
    by_name_.emplace(root.name, 0);
    frames_.push_back(std::move(root));
    dirty_.push_back(false);
}

void Kinematics::check_new_frame(const std::string& name, std::size_t parent, const Eigen::Isometry3d& offset) const
{
    if (by_name_.count(name))
        throw frame_error(name, "the name is taken");
    if (parent >= frames_.size())
        throw frame_error(name, "no parent frame " + std::to_string(parent) + " (" +
                                    std::to_string(frames_.size()) + " frames so far)");
    if (!offset.matrix().allFinite())
        throw frame_error(name, "the offset is not finite");
    const Eigen::Matrix3d l = offset.linear();
    if (!(l.transpose() * l - Eigen::Matrix3d::Identity()).isZero(kRotationTolerance) || l.determinant() < 0)
        throw frame_error(name, "the offset's rotation is not a rotation (a scale, shear or mirror)");
}

std::size_t Kinematics::add_frame(std::string name, std::size_t parent, const Eigen::Isometry3d& offset,
                                  const Joint& joint, JointReader q)
{
    check_new_frame(name, parent, offset);
    if (!joint.axis.allFinite() || !joint.point_mm.allFinite())
        throw frame_error(name, "the joint's axis or point is not finite");
    Joint stored = joint;
    if (is_moving(joint.type)) {
        const double norm = joint.axis.norm();
        if (norm == 0)
            throw frame_error(name, "the joint axis is zero-length");
        if (std::abs(norm - 1) > kAxisNormTolerance)
            throw frame_error(name, "the joint axis is not a unit vector (norm " + std::to_string(norm) + ")");
        if (!q)
            throw frame_error(name, "a moving joint needs a reader");
        stored.axis = joint.axis / norm;
    } else if (q) {
        throw frame_error(name, "a fixed joint takes no reader");
    }

    Frame f;
    f.name = std::move(name);
    f.parent = parent;
    f.offset = offset;
    f.joint = stored;
    f.reader = std::move(q);
    f.local = offset;
    const std::size_t index = frames_.size();
    frames_.reserve(index + 1);
    dirty_.reserve(index + 1);
    by_name_.emplace(f.name, index);   // may throw: nothing added yet
    frames_.push_back(std::move(f));
    dirty_.push_back(false);
    return index;
}

std::size_t Kinematics::add_tool(std::string name, std::size_t parent, const Eigen::Isometry3d& offset)
{
    const std::size_t index = add_frame(std::move(name), parent, offset, Joint{});
    frames_[index].tool = true;
    return index;
}

void Kinematics::set_box(std::size_t frame, const Eigen::AlignedBox3d& box_mm)
{
    if (frame >= frames_.size())
        throw std::invalid_argument("no frame " + std::to_string(frame) + " (" + std::to_string(frames_.size()) +
                                    " frames)");
    if (!box_mm.min().allFinite() || !box_mm.max().allFinite())
        throw frame_error(frames_[frame].name, "the box is not finite");
    if ((box_mm.min().array() > box_mm.max().array()).any())
        throw frame_error(frames_[frame].name, "the box's min exceeds its max");
    frames_[frame].box = box_mm;
}

std::optional<std::size_t> Kinematics::find(std::string_view name) const
{
    const auto it = by_name_.find(name);
    if (it == by_name_.end())
        return std::nullopt;
    return it->second;
}

std::size_t Kinematics::joints_below(std::size_t frame) const
{
    std::size_t n = 0;
    for (std::size_t i = frame; i != 0; i = frames_[i].parent)
        if (is_moving(frames_[i].joint.type))
            ++n;
    return n;
}

Eigen::Isometry3d Kinematics::local_pose(const Frame& f)
{
    switch (f.joint.type) {
    case JointType::Fixed:
        return f.offset;
    case JointType::Prismatic: {   // offset · Translation(q·axis), without the product
        Eigen::Isometry3d t = f.offset;
        t.translation() += f.offset.linear() * (f.q * f.joint.axis);
        return t;
    }
    case JointType::Revolute:
    case JointType::Goniometer:
        return f.offset * joint_transform(f.joint, f.q);
    }
    return f.offset;
}

std::size_t Kinematics::update()
{
    std::size_t recomputed = 0;
    dirty_[0] = computed_ == 0;   // the root, fixed in the world: computed once
    if (dirty_[0])
        ++recomputed;
    for (std::size_t i = 1; i < frames_.size(); ++i) {
        Frame& f = frames_[i];
        bool changed = i >= computed_ || dirty_[f.parent];
        if (f.reader) {
            const double q = f.reader();
            if (q != f.q) {
                f.q = q;
                changed = true;
            }
        }
        dirty_[i] = changed;
        if (!changed)
            continue;
        f.local = local_pose(f);
        f.world = frames_[f.parent].world * f.local;
        ++recomputed;
    }
    computed_ = frames_.size();
    recomputed_total_ += recomputed;
    return recomputed;
}

} // namespace rigsim::models
