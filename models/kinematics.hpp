#pragma once
// Kinematic chains: the frames of a rig (the table, every stage's moving part, tool points)
// as a tree of rigid transforms composed with Eigen::Isometry3d.
//
// A frame sits on its parent at a fixed offset, then moves by its joint:
//   world_T_frame = world_T_parent · offset · joint(q)
// - fixed:       identity (the table, a bracket, a tool point);
// - prismatic:   translation by q mm along a unit vector;
// - revolute:    rotation by q degrees about a unit axis through a point;
// - goniometer:  the same about a centre of rotation above the stage (its own kind, so that
//                a goniometer stage can only drive a goniometer joint).
// Vectors and points of a joint are in the coordinates of the frame's mount (the parent's
// frame after the offset). Lengths in mm, angles in degrees.
//
// q is read from the axis that drives the joint (a reader the rig builds from the device's
// channel: the physical position of the carriage, not the controller's counters). Poses are
// computed on demand: update() reads every joint once and recomputes only the frames whose
// joint or an ancestor's joint changed since the last update.

#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rigsim::models {

enum class JointType { Fixed, Prismatic, Revolute, Goniometer };

/// How a frame moves on its mount.
struct Joint {
    JointType type = JointType::Fixed;
    /// Prismatic: the direction of travel; revolute, goniometer: the rotation axis (unit).
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
    /// Revolute: a point on the rotation axis; goniometer: the centre of rotation (mm).
    Eigen::Vector3d point_mm = Eigen::Vector3d::Zero();
};

/// Reads a joint's position now: mm (prismatic) or degrees (revolute, goniometer).
using JointReader = std::function<double()>;

/// The transform a joint adds at position `q` (mm or degrees).
Eigen::Isometry3d joint_transform(const Joint& joint, double q);

/// Rotation from roll, pitch, yaw in degrees: R = Rz(yaw) · Ry(pitch) · Rx(roll).
Eigen::Quaterniond quaternion_from_rpy_deg(double roll_deg, double pitch_deg, double yaw_deg);
/// Roll, pitch, yaw in degrees of `q` (the inverse of quaternion_from_rpy_deg; pitch in
/// [-90, 90], roll and yaw in (-180, 180]; at pitch ±90 roll is 0).
/// `q` need not be normalised. At gimbal lock (cos(pitch) < 1e-9) the rotation has one free
/// angle, reported as yaw with roll 0; an angle within 1e-9° of -180 is reported as 180.
Eigen::Vector3d rpy_deg_from_quaternion(const Eigen::Quaterniond& q);

/// Whether two boxes, each given in its frame's coordinates and placed by that frame's world
/// pose, overlap (touching counts; separating-axis test on the 15 axes of two boxes).
/// Nearly parallel edges make their cross-product axes degenerate: every rotation entry is
/// padded by 1e-9, so boxes closer than about 1e-9 of their size count as touching.
bool boxes_overlap(const Eigen::AlignedBox3d& a, const Eigen::Isometry3d& world_T_a,
                   const Eigen::AlignedBox3d& b, const Eigen::Isometry3d& world_T_b);

/// The frames of a rig. Frame 0 is the root (the table, fixed in the world).
class Kinematics {
public:
    explicit Kinematics(std::string root_name);

    /// Adds a frame under `parent` (an index already added: frames come parent first) and
    /// returns its index. `q` is required unless the joint is fixed. std::invalid_argument for a
    /// taken name, an unknown parent, a non-unit joint axis or a missing reader.
    /// Also refused: a NaN or infinite entry in the offset or the joint, an offset whose linear
    /// part is not a rotation (within 1e-5: a scale or a mirror), a reader on a fixed joint.
    /// A moving joint's axis must have a norm within 1e-9 of 1; it is stored normalised.
    /// Nothing is added when it throws. The new frame's pose is computed by the next update().
    std::size_t add_frame(std::string name, std::size_t parent, const Eigen::Isometry3d& offset,
                          const Joint& joint, JointReader q = {});
    /// Adds a tool point (a fixed frame that is reported as a tool: a sample, a fibre tip).
    std::size_t add_tool(std::string name, std::size_t parent, const Eigen::Isometry3d& offset);
    /// Declares the frame's bounding box (its own coordinates, mm). std::invalid_argument for
    /// an unknown frame, an empty box (min > max) or a NaN or infinite corner.
    void set_box(std::size_t frame, const Eigen::AlignedBox3d& box_mm);

    std::size_t size() const { return frames_.size(); }
    std::optional<std::size_t> find(std::string_view name) const;
    const std::string& name(std::size_t frame) const { return frames_[frame].name; }
    /// The parent's index (the root's is itself).
    std::size_t parent(std::size_t frame) const { return frames_[frame].parent; }
    bool is_tool(std::size_t frame) const { return frames_[frame].tool; }
    const Joint& joint(std::size_t frame) const { return frames_[frame].joint; }
    const Eigen::Isometry3d& offset(std::size_t frame) const { return frames_[frame].offset; }
    const std::optional<Eigen::AlignedBox3d>& box(std::size_t frame) const { return frames_[frame].box; }
    /// Joints between `frame` and the root (its depth in moving axes).
    std::size_t joints_below(std::size_t frame) const;

    /// Read every joint and recompute the poses that changed. Returns how many frames it
    /// recomputed.
    /// Each reader is called once. A frame is recomputed when its q differs from the last
    /// update's, when its parent was recomputed in this update, or when it is new (the first
    /// update recomputes every frame).
    std::size_t update();
    /// Whether the last update() recomputed the frame's pose (false before the first one).
    bool recomputed(std::size_t frame) const { return dirty_[frame] != 0; }
    /// The joint position used by the last update() (0 for a fixed joint).
    double joint_position(std::size_t frame) const { return frames_[frame].q; }
    /// The frame's pose in the world as of the last update().
    const Eigen::Isometry3d& world_pose(std::size_t frame) const { return frames_[frame].world; }
    /// The frame's pose relative to its parent as of the last update(): offset · joint(q).
    const Eigen::Isometry3d& parent_pose(std::size_t frame) const { return frames_[frame].local; }
    /// Frames recomputed by every update() so far.
    std::uint64_t recomputed_total() const { return recomputed_total_; }

private:
    struct Frame {
        std::string name;
        std::size_t parent = 0;
        Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
        Joint joint;
        JointReader reader;
        bool tool = false;
        std::optional<Eigen::AlignedBox3d> box;
        double q = 0;
        Eigen::Isometry3d local = Eigen::Isometry3d::Identity();
        Eigen::Isometry3d world = Eigen::Isometry3d::Identity();
    };
    /// Checks of add_frame and add_tool; throws std::invalid_argument.
    void check_new_frame(const std::string& name, std::size_t parent, const Eigen::Isometry3d& offset) const;
    /// offset · joint(q) of a frame at its q.
    static Eigen::Isometry3d local_pose(const Frame& f);

    std::vector<Frame> frames_;
    std::vector<unsigned char> dirty_;                         ///< recomputed by the last update()
    std::map<std::string, std::size_t, std::less<>> by_name_;
    std::size_t computed_ = 0;                                 ///< frames [0, computed_) have a pose
    std::uint64_t recomputed_total_ = 0;
};

} // namespace rigsim::models
