#include "models/gripper.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace rigsim::models {

Gripper::Gripper(const Clock& clock, GripperConfig config) : clock_(clock), config_(config)
{
    if (config_.stiffness_dun_per_cv <= 0)
        throw std::invalid_argument("gripper stiffness_dun_per_cv must be positive");
    if (config_.contact_cv < 0)
        throw std::invalid_argument("gripper contact_cv must not be negative");
}

double Gripper::voltage_cv() const
{
    if (!ramping_)
        return voltage_cv_;
    const Ticks now = clock_.now();
    if (now >= ramp_end_)
        return ramp_to_cv_;
    const double step = ramp_cv_per_tick_ * static_cast<double>(now - ramp_start_);
    return ramp_to_cv_ >= voltage_cv_ ? voltage_cv_ + step : voltage_cv_ - step;
}

void Gripper::ramp_to(double target_cv, std::int32_t speed_v_per_s)
{
    const Ticks now = clock_.now();
    voltage_cv_ = voltage_cv();
    ramp_to_cv_ = target_cv;
    ramp_cv_per_tick_ = speed_v_per_s * 100.0 / clock_.tick_hz();   // V/s -> 1/100 V per tick
    ramp_start_ = now;
    ramp_end_ = now + static_cast<Ticks>(std::ceil(std::abs(target_cv - voltage_cv_) / ramp_cv_per_tick_ - 1e-9));
    ramping_ = true;
    if (ramp_end_ <= now) {   // nowhere to go: done at once
        on_event(now);
        return;
    }
    reschedule();
}

void Gripper::hold()
{
    voltage_cv_ = voltage_cv();
    ramping_ = false;
    reschedule();
}

void Gripper::set_voltage(double cv)
{
    voltage_cv_ = cv;
    ramping_ = false;
    reschedule();
}

double Gripper::force_dun() const
{
    return std::max(0.0, voltage_cv() - config_.contact_cv) * config_.stiffness_dun_per_cv;
}

Ticks Gripper::next_event(Ticks now) const
{
    return ramping_ ? std::max(ramp_end_, now + 1) : kNever;
}

void Gripper::on_event(Ticks now)
{
    if (!ramping_ || now < ramp_end_)
        return;
    voltage_cv_ = ramp_to_cv_;
    ramping_ = false;
    reschedule();
    if (listener_)
        listener_();
}

} // namespace rigsim::models
