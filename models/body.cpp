#include "models/body.hpp"

#include "models/world.hpp"

#include <stdexcept>

namespace rigsim::models {

std::string_view body_kind_name(BodyKind kind)
{
    switch (kind) {
    case BodyKind::Linear:
        return "linear";
    case BodyKind::Rotary:
        return "rotary";
    case BodyKind::Goniometer:
        return "goniometer";
    case BodyKind::PiezoActuator:
        return "piezo_actuator";
    case BodyKind::Gripper:
        return "gripper";
    case BodyKind::Solenoid:
        return "solenoid";
    case BodyKind::Flipper:
        return "flipper";
    case BodyKind::Paddle:
        return "paddle";
    case BodyKind::StrainGauge:
        return "strain_gauge";
    case BodyKind::Watch:
        return "watch";
    }
    return "linear";
}

Travel travel_of(BodyKind kind)
{
    switch (kind) {
    case BodyKind::Linear:
    case BodyKind::PiezoActuator:
        return Travel::Line;
    case BodyKind::Rotary:
    case BodyKind::Goniometer:
        return Travel::Angle;
    case BodyKind::Gripper:
    case BodyKind::Solenoid:
    case BodyKind::Flipper:
    case BodyKind::Paddle:
    case BodyKind::StrainGauge:
    case BodyKind::Watch:
        return Travel::None;
    }
    return Travel::None;
}

void Body::reschedule()
{
    if (world_)
        world_->reschedule(*this);
}

void Body::expect(Travel unit, const char* what) const
{
    const Travel has = travel();
    if (has == unit)
        return;
    const std::string body = "body \"" + key_ + "\" (" + std::string(body_kind_name(kind())) + ")";
    if (has == Travel::None)
        throw std::logic_error(body + " has no travel: " + what);
    throw std::logic_error(body + (has == Travel::Line ? " travels along a line (metres): " : " turns (radians): ")
                           + what);
}

double Body::position_m() const
{
    expect(Travel::Line, "position_m");
    return si_position();
}

double Body::angle_rad() const
{
    expect(Travel::Angle, "angle_rad");
    return si_position();
}

double Body::velocity_m_per_s() const
{
    expect(Travel::Line, "velocity_m_per_s");
    return si_velocity();
}

double Body::angular_velocity_rad_per_s() const
{
    expect(Travel::Angle, "angular_velocity_rad_per_s");
    return si_velocity();
}

TravelRange Body::travel_m() const
{
    expect(Travel::Line, "travel_m");
    return si_travel();
}

TravelRange Body::travel_rad() const
{
    expect(Travel::Angle, "travel_rad");
    return si_travel();
}

void Body::place_m(double position)
{
    expect(Travel::Line, "place_m");
    si_place(position);
}

void Body::place_rad(double angle)
{
    expect(Travel::Angle, "place_rad");
    si_place(angle);
}

void Body::set_obstacles_m(std::optional<double> min, std::optional<double> max)
{
    expect(Travel::Line, "set_obstacles_m");
    if (!stoppable())
        throw std::logic_error("body \"" + key_ + "\" cannot be stopped by an obstacle");
    si_set_obstacles(min, max);
}

void Body::set_obstacles_rad(std::optional<double> min, std::optional<double> max)
{
    expect(Travel::Angle, "set_obstacles_rad");
    if (!stoppable())
        throw std::logic_error("body \"" + key_ + "\" cannot be stopped by an obstacle");
    si_set_obstacles(min, max);
}

std::optional<std::string> Body::refuses(BodyFault& fault) const
{
    static constexpr const char* kNames[] = {"stall", "slip", "limit_switch", "sensor_failure"};
    return "\"kind\": " + std::string(kNames[static_cast<int>(fault.kind)]) + ": a "
           + std::string(body_kind_name(kind())) + " (" + key_ + ") has no such fault";
}

// The defaults: a body without travel (the public forms checked travel() first, so these run
// only on a body that declares a travel but forgot to implement it).
double Body::si_position() const
{
    throw std::logic_error("body \"" + key_ + "\" has no position");
}

double Body::si_velocity() const
{
    throw std::logic_error("body \"" + key_ + "\" has no velocity");
}

TravelRange Body::si_travel() const
{
    throw std::logic_error("body \"" + key_ + "\" has no travel range");
}

void Body::si_place(double)
{
    throw std::logic_error("body \"" + key_ + "\" cannot be placed");
}

void Body::si_set_obstacles(std::optional<double>, std::optional<double>)
{
    throw std::logic_error("body \"" + key_ + "\" cannot be stopped by an obstacle");
}

} // namespace rigsim::models
