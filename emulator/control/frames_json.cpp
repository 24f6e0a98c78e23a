#include "emulator/control/frames_json.hpp"

namespace rigsim::control {

namespace {

using nlohmann::json;

/// -0.0 prints as -0.0: a frame at the origin reads 0.
double clean(double v)
{
    return v == 0.0 ? 0.0 : v;
}

json triple(const Eigen::Vector3d& v)
{
    return json::array({clean(v.x()), clean(v.y()), clean(v.z())});
}

const char* joint_type_name(models::JointType t)
{
    switch (t) {
    case models::JointType::Fixed:
        return "fixed";
    case models::JointType::Prismatic:
        return "prismatic";
    case models::JointType::Revolute:
        return "revolute";
    case models::JointType::Goniometer:
        return "goniometer";
    }
    return "fixed";
}

const JointAxis* axis_of(const std::vector<std::optional<JointAxis>>& axes, std::size_t frame)
{
    return frame < axes.size() && axes[frame] ? &*axes[frame] : nullptr;
}

} // namespace

json placement_json(const Eigen::Isometry3d& pose)
{
    Eigen::Quaterniond q(pose.rotation());
    q.normalize();
    // q and -q are one rotation: the one with w > 0 is shown; at w == 0 (a half turn) the one
    // whose first non-zero of x, y, z is positive.
    const double lead = q.w() != 0 ? q.w() : q.x() != 0 ? q.x() : q.y() != 0 ? q.y() : q.z();
    if (lead < 0)
        q.coeffs() = -q.coeffs();
    return json{{"position_mm", triple(pose.translation())},
                {"quaternion", json::array({clean(q.w()), clean(q.x()), clean(q.y()), clean(q.z())})},
                {"rpy_deg", triple(models::rpy_deg_from_quaternion(q))}};
}

json frame_json(const models::Kinematics& k, std::size_t frame, const JointAxis* axis)
{
    const bool root = frame == 0;
    json joint = nullptr;
    if (k.joint(frame).type != models::JointType::Fixed)
        joint = json{{"type", joint_type_name(k.joint(frame).type)},
                     {"device", axis ? json(axis->device) : json(nullptr)},
                     {"channel", axis ? json(axis->channel) : json(nullptr)},
                     {"position", clean(k.joint_position(frame))}};
    return json{{"name", k.name(frame)},
                {"parent", root ? json(nullptr) : json(k.name(k.parent(frame)))},
                {"tool", k.is_tool(frame)},
                {"joint", std::move(joint)},
                {"world", placement_json(k.world_pose(frame))},
                {"parent_relative", placement_json(k.parent_pose(frame))}};
}

json frames_json(const models::Kinematics& k, const std::vector<std::optional<JointAxis>>& axes,
                 const std::vector<Contact>& contacts)
{
    auto frames = json::array();
    auto tools = json::array();
    for (std::size_t i = 0; i < k.size(); ++i)
        (k.is_tool(i) ? tools : frames).push_back(frame_json(k, i, axis_of(axes, i)));
    auto collisions = json::array();
    for (const auto& [a, b] : contacts)
        collisions.push_back(json{{"frames", json::array({k.name(a), k.name(b)})}});
    return json{{"frames", std::move(frames)}, {"tools", std::move(tools)}, {"collisions", std::move(collisions)}};
}

json no_frames_json()
{
    return json{{"frames", json::array()}, {"tools", json::array()}, {"collisions", json::array()}};
}

std::vector<Contact> contacts_now(const models::Kinematics& k, const std::vector<Contact>& pairs)
{
    std::vector<Contact> out;
    for (const auto& [a, b] : pairs) {
        const auto& box_a = k.box(a);
        const auto& box_b = k.box(b);
        if (box_a && box_b && models::boxes_overlap(*box_a, k.world_pose(a), *box_b, k.world_pose(b)))
            out.emplace_back(a, b);
    }
    return out;
}

} // namespace rigsim::control
