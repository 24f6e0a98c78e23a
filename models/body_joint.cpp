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
    case BodyKind::StrainGauge:
    case BodyKind::Watch:
        break;
    }
    return false;
}

JointReader joint_reader(const Body& body)
{
    const double k = joint_per_si(body);
    const Body* b = &body;
    if (body.travel() == Travel::Line)
        return [b, k] { return b->position_m() * k; };
    return [b, k] { return b->angle_rad() * k; };
}

JointDrive joint_drive(Body& body)
{
    const double k = joint_per_si(body);
    Body* b = &body;
    JointDrive d;
    d.body_key = body.key();
    const bool line = body.travel() == Travel::Line;
    if (line)
        d.velocity = [b, k] { return b->velocity_m_per_s() * k; };
    else
        d.velocity = [b, k] { return b->angular_velocity_rad_per_s() * k; };
    if (!body.stoppable())
        return d;   // it pushes on: a contact only reports it
    d.set_obstacles = [b, k, line](std::optional<double> min, std::optional<double> max) {
        const auto si = [k](std::optional<double> q) { return q ? std::optional<double>(*q / k) : std::nullopt; };
        if (line)
            b->set_obstacles_m(si(min), si(max));
        else
            b->set_obstacles_rad(si(min), si(max));
    };
    return d;
}

} // namespace rigsim::models
