#pragma once
// The frames of a rig's kinematics as the control API shows them (GET /api/frames, the "frames"
// event; docs/control-api.md "Frames"): each frame's and tool point's placement in the world and
// relative to its parent, its joint and the channel that drives it, and the contacts now.

#include "models/kinematics.hpp"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rigsim::control {

/// The channel that drives a frame's joint, as the rig JSON's "axis" names it.
struct JointAxis {
    std::string device;
    std::size_t channel = 0;
};

/// Two frames (indices) whose boxes touch or overlap now.
using Contact = std::pair<std::size_t, std::size_t>;

/// {"position_mm": [x,y,z], "quaternion": [w,x,y,z] (unit, w >= 0), "rpy_deg": [r,p,y]} of `pose`.
nlohmann::json placement_json(const Eigen::Isometry3d& pose);

/// One frame or tool point as of the last update(): {"name", "parent" (null for the root), "tool",
/// "joint" ({"type", "device", "channel", "position"}, null for a fixed frame), "world",
/// "parent_relative"}. `axis`: the channel driving its joint (nullptr for a fixed joint).
nlohmann::json frame_json(const models::Kinematics& k, std::size_t frame, const JointAxis* axis);

/// GET /api/frames: {"frames": [...], "tools": [...], "collisions": [{"frames": [a, b]}...]}, in
/// index order. `axes[i]`: frame i's channel (std::nullopt for a fixed frame; shorter: none).
nlohmann::json frames_json(const models::Kinematics& k, const std::vector<std::optional<JointAxis>>& axes,
                           const std::vector<Contact>& contacts);

/// The answer for a rig without kinematics: every list empty.
nlohmann::json no_frames_json();

/// The pairs of `pairs` whose declared boxes touch or overlap at the poses of the last update()
/// (a pair of which a frame has no box is never in contact).
std::vector<Contact> contacts_now(const models::Kinematics& k, const std::vector<Contact>& pairs);

} // namespace rigsim::control
