#pragma once
// The rig JSON's "kinematics" section (docs/config.md, "Kinematics"): the frames of the rig
// (the table, each stage's moving part, fixed brackets), the tool points on them and the
// pairs of frames checked for collisions, as plain data. The loader checks the tree (one
// root, known parents, no cycle, no name twice, limits) and every vector, and lists the
// frames parent first; the rig builds models::Kinematics from it and binds each joint to its
// device's channel (emulator/daemon/rig_kinematics.cpp), where the checks that need the devices
// (channel range, what the channel moves) run.

#include <nlohmann/json_fwd.hpp>

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rigsim {

class ConfigReader;
struct DeviceConfig;

/// At most this many frames and tools together.
constexpr std::size_t kMaxFrames = 1024;
/// At most this many mounts from the root to any frame or tool.
constexpr std::size_t kMaxFrameDepth = 64;

using Vector3 = std::array<double, 3>;

enum class JointKind { Fixed, Prismatic, Revolute, Goniometer };

/// "fixed", "prismatic", "revolute", "goniometer".
const char* joint_kind_name(JointKind kind);

/// The channel that drives a frame's joint ("axis").
struct FrameAxisConfig {
    std::string device;          ///< a device of the rig
    std::size_t channel = 0;     ///< MCS channel, APT bay (0-based, as in the control API)
};

/// An axis-aligned box in a frame's own coordinates (mm).
struct FrameBoxConfig {
    Vector3 min{};
    Vector3 max{};
};

/// One frame or tool point.
struct FrameConfig {
    std::string name;
    std::size_t parent = 0;                  ///< index in KinematicsConfig::frames (the root: 0, itself)
    bool tool = false;                       ///< listed under "tools"
    Vector3 translation_mm{};                ///< offset on the parent
    std::optional<Vector3> rpy_deg;          ///< offset rotation as roll, pitch, yaw (degrees) ...
    std::optional<std::array<double, 4>> quaternion;   ///< ... or as a unit quaternion [w, x, y, z]; neither: none
    JointKind joint = JointKind::Fixed;
    Vector3 joint_axis{1, 0, 0};             ///< unit: the direction of travel or the rotation axis
    Vector3 joint_point_mm{};                ///< revolute: a point on the axis; goniometer: the centre
    std::optional<FrameAxisConfig> axis;     ///< present exactly when the joint moves
    std::optional<FrameBoxConfig> box_mm;
    std::string pointer;                     ///< where the rig text has it: "/kinematics/frames/2"
};

struct KinematicsConfig {
    /// Parent first: frames[0] is the root; tools among the frames, each after its parent.
    std::vector<FrameConfig> frames;
    /// Pairs of frame indices (first < second) whose boxes are checked for contact.
    std::vector<std::pair<std::size_t, std::size_t>> collisions;
    /// The rig text's name, for errors found when the rig binds the joints.
    std::string source;
};

/// Validates the "kinematics" object `value` of a rig whose devices are `devices` (an axis
/// names one of them); throws ConfigError through `reader` naming the JSON pointer.
KinematicsConfig load_kinematics_config(const ConfigReader& reader, std::string_view source,
                                        const nlohmann::json& value, const std::vector<DeviceConfig>& devices);

} // namespace rigsim
