#include "models/inertial_drive.hpp"

#include <algorithm>
#include <cmath>

namespace rigsim::models {

namespace {

/// The pulses of a run asked for without an end: more than any test lasts (at 2,000 a second,
/// 15,000 years).
constexpr double kEndless = 1e15;

} // namespace

InertialDrive::InertialDrive(const Clock& clock, const InertialDriveConfig& config)
    : clock_(clock), config_(config),
      base_nm_(std::clamp(config.start_nm, config.travel_min_nm, config.travel_max_nm)),
      voltage_v_(config.reference_voltage_v)
{
}

std::int64_t InertialDrive::run_pulses_at(Ticks now) const
{
    if (!running_ && end_ == start_)
        return 0;
    const Ticks at = std::min(now, end_);
    if (at <= start_)
        return 0;
    const double t = static_cast<double>(at - start_) / static_cast<double>(clock_.tick_hz());
    const double made = at >= end_ && !endless_ ? profile_.target() : profile_.sample(t).position;
    return static_cast<std::int64_t>(std::floor(made + 1e-9));
}

double InertialDrive::pulse_nm() const
{
    const double length = direction_ > 0 ? config_.step_forward_nm : config_.step_reverse_nm;
    const double voltage = config_.reference_voltage_v > 0 ? voltage_v_ / config_.reference_voltage_v : 1.0;
    return std::max(0.0, length * voltage * (1.0 - slip_));
}

double InertialDrive::stop_min_nm() const
{
    double lo = obstacle_min_nm_ ? std::max(config_.travel_min_nm, *obstacle_min_nm_) : config_.travel_min_nm;
    if (stalled_at_nm_)
        lo = std::max(lo, *stalled_at_nm_);
    return lo;
}

double InertialDrive::stop_max_nm() const
{
    double hi = obstacle_max_nm_ ? std::min(config_.travel_max_nm, *obstacle_max_nm_) : config_.travel_max_nm;
    if (stalled_at_nm_)
        hi = std::min(hi, *stalled_at_nm_);
    return hi;
}

std::int64_t InertialDrive::pulses() const
{
    return pulses_before_ + direction_ * run_pulses_at(clock_.now());
}

double InertialDrive::position_nm() const
{
    const auto made = run_pulses_at(clock_.now()) - base_pulses_;
    const double at = base_nm_ + direction_ * static_cast<double>(made) * pulse_nm();
    return std::clamp(at, stop_min_nm(), std::max(stop_min_nm(), stop_max_nm()));
}

bool InertialDrive::running() const
{
    return running_ && clock_.now() < end_;
}

double InertialDrive::rate_per_s() const
{
    if (!running())
        return 0;
    const double t = static_cast<double>(clock_.now() - start_) / static_cast<double>(clock_.tick_hz());
    return std::abs(profile_.sample(t).velocity);
}

double InertialDrive::si_velocity() const
{
    const double at = position_nm();
    // Pushing against a stop: pulses, no motion.
    if ((direction_ > 0 && at >= stop_max_nm()) || (direction_ < 0 && at <= stop_min_nm()))
        return 0;
    return direction_ * rate_per_s() * pulse_nm() * 1e-9;
}

void InertialDrive::run(int direction, std::optional<std::int64_t> pulses, double rate_per_s, double accel_per_s2,
                        double voltage_v)
{
    finish_due();
    stop();
    direction_ = direction >= 0 ? 1 : -1;
    voltage_v_ = voltage_v;
    endless_ = !pulses;
    const double target = pulses ? static_cast<double>(*pulses) : kEndless;
    profile_ = MotionProfile::plan({0, 0}, target, std::max(rate_per_s, 1e-9), std::max(accel_per_s2, 0.0));
    start_ = clock_.now();
    const double ticks = std::ceil(profile_.duration() * static_cast<double>(clock_.tick_hz()) - 1e-9);
    end_ = endless_ ? kNever : start_ + std::max<Ticks>(1, static_cast<Ticks>(ticks));
    running_ = true;
    base_pulses_ = 0;
    reschedule();
}

void InertialDrive::finish_due()
{
    // A run whose end tick has come but whom the world has not woken yet (a command in the same
    // tick) ends first: its listener hears of it.
    if (running_ && !endless_ && clock_.now() >= end_)
        on_event(clock_.now());
}

void InertialDrive::stop()
{
    finish_due();
    if (!running_ && start_ == end_) {   // at rest (or just ended): nothing to cut short
        reschedule();
        return;
    }
    const double at = position_nm();
    pulses_before_ = pulses();
    running_ = false;
    start_ = end_ = clock_.now();
    base_nm_ = at;
    base_pulses_ = 0;
    reschedule();
}

void InertialDrive::place(double nm)
{
    stop();
    base_nm_ = std::clamp(nm, config_.travel_min_nm, config_.travel_max_nm);
    reschedule();
}

void InertialDrive::rebase()
{
    base_nm_ = position_nm();
    base_pulses_ = run_pulses_at(clock_.now());
}

Ticks InertialDrive::next_event(Ticks now) const
{
    return running_ && !endless_ ? std::max(end_, now) : kNever;
}

void InertialDrive::on_event(Ticks now)
{
    if (!running_ || endless_ || now < end_)
        return;
    // The run is over: its pulses are counted and the screw rests where they left it.
    const double at = position_nm();
    pulses_before_ += direction_ * run_pulses_at(end_);
    running_ = false;
    start_ = end_ = now;
    base_nm_ = at;
    base_pulses_ = 0;
    reschedule();
    listener_(now);
}

std::optional<std::string> InertialDrive::refuses(BodyFault& fault) const
{
    switch (fault.kind) {
    case PhysicalFault::Stall:
        return std::nullopt;
    case PhysicalFault::Slip:
        if (fault.slip_steps)
            return "counts: a piezo inertia actuator slips by a fraction of each pulse, not by counts (fraction)";
        if (!fault.slip_fraction)
            fault.slip_fraction = 0.5;
        if (*fault.slip_fraction >= 1)
            return "fraction: a number from 0 up to (not including) 1 is required";
        return std::nullopt;
    case PhysicalFault::LimitSwitch:
        return "\"kind\": limit_switch: a piezo inertia actuator has no limit switches (its end stops are mechanical; "
               "use stall)";
    case PhysicalFault::SensorFailure:
        return "\"kind\": sensor_failure: a piezo inertia actuator has no sensor (the controller counts pulses)";
    }
    return std::nullopt;
}

void InertialDrive::apply_faults()
{
    rebase();
    slip_ = faults().slip_fraction;
    stalled_at_nm_ = faults().stalled ? std::optional<double>(base_nm_) : std::nullopt;
    reschedule();
}

void InertialDrive::si_set_obstacles(std::optional<double> min, std::optional<double> max)
{
    rebase();
    obstacle_min_nm_ = min ? std::optional<double>(*min * 1e9) : std::nullopt;
    obstacle_max_nm_ = max ? std::optional<double>(*max * 1e9) : std::nullopt;
    base_nm_ = std::clamp(base_nm_, stop_min_nm(), std::max(stop_min_nm(), stop_max_nm()));
    reschedule();
}

} // namespace rigsim::models
