#pragma once
// The rig's frames (rig JSON "kinematics") built into models::Kinematics, each joint bound to
// the world body its device's channel moves (ControlSurface::axis_body_key()) and read and
// stopped through that body's physical face (models/body_joint.hpp), the same for every family.
// The checks that need the devices run here: the channel exists and moves something, and the
// joint suits the body (a linear stage or a piezo drives a prismatic joint, a rotary one a
// revolute joint, a goniometer a goniometer or revolute joint). Errors name the frame's JSON
// pointer, as the loader's do.

#include "emulator/core/control_surface.hpp"
#include "emulator/core/kinematics_config.hpp"
#include "models/body_joint.hpp"
#include "models/collision_watch.hpp"
#include "models/kinematics.hpp"
#include "models/world.hpp"

#include <nlohmann/json_fwd.hpp>

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace rigsim {

class EventBus;

/// What drives one joint of a kinematic chain: a body of the world, read and stopped through its
/// physical face (models/body_joint.hpp) in joint units.
struct JointBinding {
    std::string body_key;           ///< the world body the channel moves ("<device>/<channel>")
    models::Body* body = nullptr;   ///< that body (the world's: it outlives a device's power cycle)
    models::JointReader position;   ///< now: mm (a body along a line) or degrees (one that turns)
    /// How the collision watch reads its velocity (mm/s or degrees/s) and sets its obstacles
    /// (empty: a piezo, which pushes on).
    models::JointDrive drive;
};

/// The frames of a rig and what drives their joints.
struct RigKinematics {
    std::unique_ptr<models::Kinematics> kinematics;
    /// Indexed like the frames of `kinematics`; an empty binding for a fixed frame or a tool.
    std::vector<JointBinding> bindings;
};

/// The control surface of the device named `name` (nullptr: a device without one).
using SurfaceOf = std::function<ControlSurface*(std::string_view name)>;

/// Build the frames of `config` (poses computed once), binding every moving joint to the body
/// of `world` its channel moves; throws ConfigError naming the frame's pointer when the device refuses the channel,
/// the joint does not suit the stage, or models::Kinematics refuses the frame.
RigKinematics build_kinematics(const KinematicsConfig& config, const SurfaceOf& surface_of, const models::World& world);

/// The collision watch of the rig's frames, a body of `world` under "rig/collisions" watching
/// `config.collisions` (nullptr when there are none), each joint stopped through its binding.
/// Every contact is published on `events` as a "collision" event (collision_json).
models::CollisionWatch* watch_collisions(models::World& world, RigKinematics& rig, const KinematicsConfig& config,
                                         EventBus& events);

/// A "collision" event's data: {"frames": [a, b], "stopped": [{"device", "channel", "position"}],
/// "not_stopped": [...]} (positions in mm or degrees, where the joint stood at the contact).
nlohmann::json collision_json(const models::Kinematics& kinematics, const KinematicsConfig& config,
                              const models::Contact& contact);

} // namespace rigsim
