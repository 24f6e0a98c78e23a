#pragma once
// The rig's frames as the control API serves them (GET /api/frames, the "frames" event;
// docs/control-api.md "Frames"): the kinematics, which channel drives each joint, the pairs that
// may collide, and the poses last published, so that an event carries only what changed.

#include "emulator/control/frames_json.hpp"
#include "emulator/core/control_surface.hpp"
#include "emulator/daemon/rig.hpp"
#include "models/kinematics.hpp"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <optional>
#include <string_view>
#include <vector>

namespace rigsim::control {

/// What the rig's "kinematics" section built (nullptr kinematics: the rig has none).
struct FrameSource {
    models::Kinematics* kinematics = nullptr;
    std::vector<std::optional<JointAxis>> axes;   ///< per frame index: the channel of its joint
    std::vector<Contact> collision_pairs;         ///< the pairs checked for contact
};

/// The device and channel of each joint binding (indexed like the frames; an empty binding, a
/// fixed frame's, gives std::nullopt): the channel of `devices` whose
/// ControlSurface::axis_body_key() is the same world body. A binding no channel drives also gives std::nullopt.
std::vector<std::optional<JointAxis>> joint_axes(const std::vector<JointBinding>& bindings,
                                                 const std::vector<ControlledDevice>& devices);

class FrameBook {
public:
    /// Reads every joint once: the poses now are the baseline of changed().
    explicit FrameBook(FrameSource source);
    /// The poses now become the baseline of changed() (a stream starts: what moved while no one
    /// listened was never published, and is not a change for the new stream).
    void rebase();

    bool empty() const { return source_.kinematics == nullptr; }
    /// GET /api/frames at the clock's now.
    nlohmann::json all();
    /// GET /api/frames/{name}; std::nullopt when no frame or tool point has that name.
    std::optional<nlohmann::json> one(std::string_view name);
    /// The frames and tool points whose world or parent-relative pose changed since the last
    /// call (or the baseline), as frame objects in index order; an empty array when none did.
    nlohmann::json changed();

private:
    FrameSource source_;
    std::vector<Eigen::Isometry3d> published_world_;
    std::vector<Eigen::Isometry3d> published_local_;
};

} // namespace rigsim::control
