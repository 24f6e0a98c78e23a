#include "emulator/mcs/channel.hpp"

#include <algorithm>
#include <cmath>

namespace rigsim::mcs {

Channel::Channel(const McsChannelConfig& config, const Clock& clock)
    : clock_(clock),
      sensor_(config.sensor_type == "none" ? nullptr : sensor_type_by_symbol(config.sensor_type)),
      travel_min_nm_(static_cast<double>(config.travel_min_nm)),
      travel_max_nm_(static_cast<double>(config.travel_max_nm)),
      zero_offset_nm_(static_cast<double>(config.start_position_nm)),
      max_speed_nm_per_s_(static_cast<double>(config.max_speed_nm_per_s)),
      speed_nm_per_s_(static_cast<std::int32_t>(config.closed_loop_speed_nm_per_s)),
      acceleration_um_per_s2_(static_cast<std::int32_t>(config.closed_loop_acceleration_um_per_s2)),
      state_(static_cast<double>(config.start_position_nm), 0.0)
{
    // Acceleration control needs speed control (SCLA, 2.5.1): a configured acceleration
    // without a speed runs at the stage's top speed.
    if (acceleration_um_per_s2_ > 0 && speed_nm_per_s_ == 0)
        speed_nm_per_s_ = static_cast<std::int32_t>(std::min<double>(max_speed_nm_per_s_, kMaxClosedLoopSpeed));
}

ChannelStatus Channel::status() const
{
    switch (motion_) {
    case Motion::Idle:
        return ChannelStatus::Stopped;
    case Motion::Targeting:
        return ChannelStatus::Targeting;
    case Motion::Holding:
        return ChannelStatus::Holding;
    }
    return ChannelStatus::Stopped;
}

std::optional<ErrorCode> Channel::set_sensor_type(std::int32_t code)
{
    const auto* type = sensor_type_by_code(code);
    if (!type)
        return ErrorCode::InvalidParameter;
    stop();   // "If this command is issued, the positioner is implicitly stopped." (SST)
    sensor_ = type;
    return std::nullopt;
}

std::optional<ErrorCode> Channel::check_linear_sensor() const
{
    if (!sensor_)
        return ErrorCode::NoSensorPresent;
    if (sensor_->kind != SensorKind::Linear)
        return ErrorCode::WrongSensorType;
    return std::nullopt;
}

std::int64_t Channel::position_nm() const
{
    return std::llround(state_[0] - zero_offset_nm_);
}

std::optional<ErrorCode> Channel::move_absolute(std::int64_t position_nm, std::int32_t hold_ms)
{
    if (auto err = check_linear_sensor())
        return err;
    return start_move(static_cast<double>(position_nm) + zero_offset_nm_, hold_ms);
}

std::optional<ErrorCode> Channel::move_relative(std::int64_t distance_nm, std::int32_t hold_ms)
{
    if (auto err = check_linear_sensor())
        return err;
    // MPR: "If a relative positioning command is issued before a previous one has
    // finished, normally the relative targets are accumulated."
    const double base = motion_ == Motion::Targeting ? target_physical_nm_ : state_[0];
    return start_move(base + static_cast<double>(distance_nm), hold_ms);
}

std::optional<ErrorCode> Channel::start_move(double target_physical_nm, std::int32_t hold_ms)
{
    if (hold_ms < 0 || hold_ms > kHoldForever_ms)
        return ErrorCode::InvalidParameter;
    const Ticks now = clock_.now();
    sample(now);
    target_physical_nm_ = target_physical_nm;
    // A target beyond a mechanical end stop: the stage runs into the stop and the move
    // is aborted there (MPA: "If a mechanical end stop is detected ... aborted").
    const double reachable = std::clamp(target_physical_nm, travel_min_nm_, travel_max_nm_);
    end_stop_hit_ = reachable != target_physical_nm;
    const double speed = speed_nm_per_s_ > 0
        ? std::min<double>(speed_nm_per_s_, max_speed_nm_per_s_) : max_speed_nm_per_s_;
    const double acceleration = acceleration_um_per_s2_ * 1000.0;   // µm/s² -> nm/s²
    profile_ = models::TrapezoidProfile::plan(state_, reachable, speed, acceleration);
    hold_ms_ = hold_ms;
    move_start_ = now;
    move_end_ = now + static_cast<Ticks>(std::ceil(profile_.duration() * clock_.tick_hz() - 1e-9));
    motion_ = Motion::Targeting;
    if (move_end_ <= now)
        arrive(now);
    return std::nullopt;
}

void Channel::sample(Ticks now)
{
    if (motion_ != Motion::Targeting)
        return;
    state_ = profile_.sample(clock_.seconds(now - move_start_));
}

void Channel::arrive(Ticks now)
{
    state_ = models::AxisState(profile_.target(), 0.0);
    if (end_stop_hit_ || hold_ms_ == 0) {
        motion_ = Motion::Idle;
        return;
    }
    motion_ = Motion::Holding;
    hold_until_ = hold_ms_ == kHoldForever_ms ? kNever : now + clock_.ticks_from_ms(hold_ms_);
}

void Channel::stop()
{
    sample(clock_.now());
    state_[1] = 0;
    motion_ = Motion::Idle;
}

std::optional<ErrorCode> Channel::set_closed_loop_speed(std::int32_t speed_nm_per_s)
{
    if (speed_nm_per_s < 0 || speed_nm_per_s > kMaxClosedLoopSpeed)
        return ErrorCode::InvalidParameter;
    speed_nm_per_s_ = speed_nm_per_s;
    if (speed_nm_per_s_ == 0)
        acceleration_um_per_s2_ = 0;   // acceleration control needs speed control (2.5.1)
    return std::nullopt;
}

std::optional<ErrorCode> Channel::set_closed_loop_acceleration(std::int32_t acceleration_um_per_s2)
{
    if (acceleration_um_per_s2 < 0 || acceleration_um_per_s2 > kMaxClosedLoopAcceleration)
        return ErrorCode::InvalidParameter;
    acceleration_um_per_s2_ = acceleration_um_per_s2;
    // "Enabling acceleration control will implicitly enable the speed control should it
    // be inactive" (SCLA): it starts at the stage's top speed.
    if (acceleration_um_per_s2_ > 0 && speed_nm_per_s_ == 0)
        speed_nm_per_s_ = static_cast<std::int32_t>(std::min<double>(max_speed_nm_per_s_, kMaxClosedLoopSpeed));
    return std::nullopt;
}

Ticks Channel::next_change(Ticks now) const
{
    switch (motion_) {
    case Motion::Idle:
        return kNever;
    case Motion::Targeting:
        return now + 1;
    case Motion::Holding:
        return hold_until_;
    }
    return kNever;
}

void Channel::tick(Ticks now)
{
    switch (motion_) {
    case Motion::Idle:
        return;
    case Motion::Targeting:
        if (now >= move_end_)
            arrive(now);
        else
            sample(now);
        return;
    case Motion::Holding:
        if (now >= hold_until_)
            motion_ = Motion::Idle;
        return;
    }
}

} // namespace rigsim::mcs
