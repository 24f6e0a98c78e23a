#include "emulator/daemon/rig_kinematics.hpp"

#include "emulator/core/config_reader.hpp"
#include "emulator/core/event_bus.hpp"
#include "models/body_joint.hpp"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <memory>
#include <stdexcept>
#include <string>

namespace rigsim {

namespace {

/// What a stage of `kind` is called in an error (a piezo actuator extends along a line).
std::string_view stage_name(models::BodyKind kind)
{
    return kind == models::BodyKind::PiezoActuator ? "linear" : models::body_kind_name(kind);
}

models::JointType joint_type(JointKind kind)
{
    switch (kind) {
    case JointKind::Fixed:
        return models::JointType::Fixed;
    case JointKind::Prismatic:
        return models::JointType::Prismatic;
    case JointKind::Revolute:
        return models::JointType::Revolute;
    case JointKind::Goniometer:
        return models::JointType::Goniometer;
    }
    return models::JointType::Fixed;
}

Eigen::Vector3d vector_of(const Vector3& v)
{
    return {v[0], v[1], v[2]};
}

Eigen::Isometry3d offset_of(const FrameConfig& f)
{
    Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
    offset.translation() = vector_of(f.translation_mm);
    if (f.quaternion) {
        const auto& q = *f.quaternion;
        offset.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
    } else if (f.rpy_deg) {
        const auto& r = *f.rpy_deg;
        offset.linear() = models::quaternion_from_rpy_deg(r[0], r[1], r[2]).toRotationMatrix();
    }
    return offset;
}

/// The body that drives frame `f`'s joint; throws ConfigError at the frame's pointer.
JointBinding bind(const KinematicsConfig& config, const FrameConfig& f, const SurfaceOf& surface_of,
                  const models::World& world)
{
    const auto& axis = *f.axis;
    const auto axis_pointer = pointer_to(f.pointer, "axis");
    const auto what = axis.device + " channel " + std::to_string(axis.channel);
    JointBinding b;
    Refused refused;
    if (auto* surface = surface_of(axis.device))
        refused = surface->axis_body_key(axis.channel, b.body_key);
    else
        refused = Refusal{400, "this device has no axis to mount"};
    if (refused)
        fail(config.source, refused->status == 404 ? pointer_to(axis_pointer, "channel") : axis_pointer,
             "device " + quote(axis.device) + ": " + refused->message);
    b.body = world.find(b.body_key);
    if (!b.body || b.body->travel() == models::Travel::None)
        fail(config.source, axis_pointer, "device " + quote(axis.device) + ": " + what + " moves nothing");
    if (!models::body_suits(b.body->kind(), joint_type(f.joint)))
        fail(config.source, pointer_to(pointer_to(f.pointer, "joint"), "type"),
             std::string("a ") + joint_kind_name(f.joint) + " joint on a " + std::string(stage_name(b.body->kind()))
                 + " stage (" + what + ")");
    b.position = models::joint_reader(*b.body);
    b.drive = models::joint_drive(*b.body);
    return b;
}

/// Runs `add`, a models::Kinematics call for frame `f`; the std::invalid_argument it throws on a
/// frame the loader let through becomes a ConfigError at the frame's pointer.
template <typename Add>
void at_frame(const KinematicsConfig& config, const FrameConfig& f, Add&& add)
{
    try {
        add();
    } catch (const std::invalid_argument& e) {
        fail(config.source, f.pointer, e.what());
    }
}

} // namespace

RigKinematics build_kinematics(const KinematicsConfig& config, const SurfaceOf& surface_of, const models::World& world)
{
    RigKinematics out;
    const auto& frames = config.frames;
    out.kinematics = std::make_unique<models::Kinematics>(frames.at(0).name);
    out.bindings.resize(frames.size());
    for (std::size_t i = 1; i < frames.size(); ++i) {
        const auto& f = frames[i];
        if (f.tool) {
            at_frame(config, f, [&] { out.kinematics->add_tool(f.name, f.parent, offset_of(f)); });
            continue;
        }
        models::Joint joint;
        joint.type = joint_type(f.joint);
        joint.axis = vector_of(f.joint_axis);
        joint.point_mm = vector_of(f.joint_point_mm);
        models::JointReader reader;
        if (f.axis) {
            out.bindings[i] = bind(config, f, surface_of, world);
            reader = out.bindings[i].position;
        }
        at_frame(config, f, [&] { out.kinematics->add_frame(f.name, f.parent, offset_of(f), joint, std::move(reader)); });
    }
    for (std::size_t i = 0; i < frames.size(); ++i)
        if (const auto& b = frames[i].box_mm)
            at_frame(config, frames[i], [&] {
                out.kinematics->set_box(i, Eigen::AlignedBox3d(vector_of(b->min), vector_of(b->max)));
            });
    out.kinematics->update();
    return out;
}

nlohmann::json collision_json(const models::Kinematics& kinematics, const KinematicsConfig& config,
                              const models::Contact& contact)
{
    const auto joints = [&](const std::vector<models::ContactJoint>& list) {
        auto out = nlohmann::json::array();
        for (const auto& j : list) {
            const auto& axis = config.frames[j.frame].axis;
            out.push_back({{"device", axis ? axis->device : std::string()},
                           {"channel", axis ? axis->channel : 0},
                           {"position", j.position}});
        }
        return out;
    };
    return {{"frames", {kinematics.name(contact.frame_a), kinematics.name(contact.frame_b)}},
            {"stopped", joints(contact.stopped)},
            {"not_stopped", joints(contact.not_stopped)}};
}

models::CollisionWatch* watch_collisions(models::World& world, RigKinematics& rig, const KinematicsConfig& config,
                                         EventBus& events)
{
    if (config.collisions.empty())
        return nullptr;
    std::vector<models::JointDrive> drives(rig.bindings.size());
    for (std::size_t i = 0; i < drives.size(); ++i)
        drives[i] = rig.bindings[i].drive;
    auto& watch = world.emplace<models::CollisionWatch>("rig/collisions", *rig.kinematics, config.collisions,
                                                        std::move(drives));
    watch.link(world);   // after World::link_all: the watch is the last body
    const models::Kinematics* kinematics = rig.kinematics.get();
    auto kept = std::make_shared<const KinematicsConfig>(config);   // the rig's config is gone after start-up
    watch.set_listener([kinematics, kept, &events, &world](const models::Contact& c) {
        if (events.wants("", "collision"))
            events.publish("", "collision", world.clock().seconds(world.now()) * 1000.0,
                           collision_json(*kinematics, *kept, c));
    });
    return &watch;
}

} // namespace rigsim
