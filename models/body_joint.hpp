#pragma once
// A body of the world as the joint of a kinematic chain (models/kinematics.hpp) and as a drive
// the collision watch stops (models/collision_watch.hpp), through the body's physical face: the
// same for every body whatever device moves it. Joints count mm and degrees (the rig JSON's
// units); the face counts metres and radians.

#include "models/body.hpp"
#include "models/collision_watch.hpp"
#include "models/kinematics.hpp"

namespace rigsim::models {

/// Whether a body of `kind` may drive a joint of `type`: a body that travels along a line a
/// prismatic joint, a rotation stage a revolute one, a goniometer a goniometer or revolute one.
bool body_suits(BodyKind kind, JointType type);

/// Reads `body`'s position in joint units: mm along a line, degrees about an axis
/// (std::invalid_argument for a body without travel). The body must outlive the reader.
JointReader joint_reader(const Body& body);

/// How the collision watch reads and stops `body` (velocity in mm/s or degrees/s; obstacles
/// unless the body pushes on). std::invalid_argument for a body without travel.
JointDrive joint_drive(Body& body);

} // namespace rigsim::models
