#include "models/body_joint.hpp"

#include <stdexcept>

namespace rigsim::models {

namespace {

/// Joint units (mm or degrees) per SI unit (m or rad) of `body`; std::invalid_argument for a
/// body without travel.
double joint_per_si(const Body& body)
{
    constexpr double pi = 3.14159265358979323846;
    switch (body.travel()) {
    case Travel::Line:
        return 1e3;   // mm per m
    case Travel::Angle:
        return 180.0 / pi;   // degrees per radian
    case Travel::None:
        break;
    }
    throw std::invalid_argument("body \"" + body.key() + "\" (" + std::string(body_kind_name(body.kind()))
                                + ") moves nothing a joint could follow");
}

} // namespace

bool body_suits(BodyKind kind, JointType type)
{
    switch (kind) {
    case BodyKind::Linear:
    case BodyKind::PiezoActuator:
        return type == JointType::Prismatic;
    case BodyKind::Rotary:
        return type == JointType::Revolute;
    case BodyKind::Goniometer:
        return type == JointType::Goniometer || type == JointType::Revolute;
    case BodyKind::Gripper:
    case BodyKind::Solenoid:
    case BodyKind::Flipper:
    case BodyKind::Paddle:
    case BodyKind::StrainGauge:
    case BodyKind::Watch:
        break;
    }
    return false;
}

// A body's kind may change after the joint was bound (an MCS channel told of another positioner
// type): every read asks the body how it travels now. mm per m and degrees per radian keep the
// joint's numbers where the body's own resolution is the same (nm and µ° both read as 1e-6).

namespace {

double joint_position(const Body& b)
{
    return b.travel() == Travel::Line ? b.position_m() * joint_per_si(b) : b.angle_rad() * joint_per_si(b);
}

double joint_velocity(const Body& b)
{
    return b.travel() == Travel::Line ? b.velocity_m_per_s() * joint_per_si(b)
                                      : b.angular_velocity_rad_per_s() * joint_per_si(b);
}

} // namespace

JointReader joint_reader(const Body& body)
{
    joint_per_si(body);   // std::invalid_argument now for a body without travel
    const Body* b = &body;
    return [b] { return joint_position(*b); };
}

JointDrive joint_drive(Body& body)
{
    joint_per_si(body);
    Body* b = &body;
    JointDrive d;
    d.body_key = body.key();
    d.velocity = [b] { return joint_velocity(*b); };
    if (!body.stoppable())
        return d;   // it pushes on: a contact only reports it
    d.set_obstacles = [b](std::optional<double> min, std::optional<double> max) {
        const double k = joint_per_si(*b);
        const auto si = [k](std::optional<double> q) { return q ? std::optional<double>(*q / k) : std::nullopt; };
        if (b->travel() == Travel::Line)
            b->set_obstacles_m(si(min), si(max));
        else
            b->set_obstacles_rad(si(min), si(max));
    };
    return d;
}

} // namespace rigsim::models
