#include "emulator/mcs/channel.hpp"

#include <algorithm>
#include <cmath>

namespace rigsim::mcs {

Channel::Channel(int index, const McsChannelConfig& config, const Clock& clock)
    : index_(index), clock_(clock), config_(config),
      sensor_(config.sensor_type == "none" ? nullptr : sensor_type_by_symbol(config.sensor_type)),
      sensor_mode_(SensorMode::Enabled),
      travel_min_nm_(static_cast<double>(config.travel_min_nm)),
      travel_max_nm_(static_cast<double>(config.travel_max_nm)),
      reference_nm_(0.0),
      unknown_base_nm_(static_cast<double>(config.start_position_nm)),
      speed_nm_per_s_(0),
      acceleration_um_per_s2_(0),
      state_(static_cast<double>(config.start_position_nm), 0.0)
{
    reset();
}

void Channel::reset()
{
    motion_ = Motion::Idle;
    pending_start_ = nullptr;
    state_[1] = 0;
    known_ = false;
    unknown_base_nm_ = state_[0];   // "It simply assumes its starting position as the zero position."
    accumulate_relative_ = true;
    step_while_scan_ = true;
    report_on_complete_ = false;
    max_frequency_hz_ = kMaxFrequency_hz;
    speed_nm_per_s_ = static_cast<std::int32_t>(config_.closed_loop_speed_nm_per_s);
    acceleration_um_per_s2_ = static_cast<std::int32_t>(config_.closed_loop_acceleration_um_per_s2);
    // Acceleration control needs speed control (SCLA, 2.5.1): a configured acceleration
    // without a speed runs at the stage's top speed.
    if (acceleration_um_per_s2_ > 0 && speed_nm_per_s_ == 0)
        speed_nm_per_s_ = static_cast<std::int32_t>(std::min<double>(top_speed(), kMaxClosedLoopSpeed));
    events_.clear();
}

ChannelStatus Channel::status() const
{
    switch (motion_) {
    case Motion::Idle:
        return ChannelStatus::Stopped;
    case Motion::MoveDelay:
        return ChannelStatus::MoveDelay;
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

void Channel::set_sensor_mode(SensorMode mode)
{
    stop();   // SSE: "all positioner channels of the system are implicitly stopped"
    sensor_mode_ = mode;
}

std::optional<ErrorCode> Channel::check_linear_sensor() const
{
    if (!sensor_)
        return ErrorCode::NoSensorPresent;
    if (sensor_mode_ == SensorMode::Disabled)
        return ErrorCode::SensorDisabled;
    if (sensor_->kind != SensorKind::Linear)
        return ErrorCode::WrongSensorType;
    return std::nullopt;
}

double Channel::logical_from_physical(double physical) const
{
    if (!known_)
        return physical - unknown_base_nm_;
    const double relative = physical - reference_nm_;
    return (scale_inverted_ ? -relative : relative) + scale_offset_;
}

double Channel::physical_from_logical(double logical) const
{
    if (!known_)
        return logical + unknown_base_nm_;
    const double relative = logical - scale_offset_;
    return (scale_inverted_ ? -relative : relative) + reference_nm_;
}

std::int64_t Channel::position_nm() const
{
    return std::llround(logical_from_physical(state_[0]));
}

double Channel::top_speed() const
{
    // SCLF caps the driving frequency; the stage's top speed scales with it.
    return static_cast<double>(config_.max_speed_nm_per_s) * max_frequency_hz_ / kMaxFrequency_hz;
}

std::optional<ErrorCode> Channel::move_absolute(std::int64_t position_nm, std::int32_t hold_ms)
{
    if (auto err = check_linear_sensor())
        return err;
    if (hold_ms < 0 || hold_ms > kHoldForever_ms)
        return ErrorCode::InvalidParameter;
    const double target = physical_from_logical(static_cast<double>(position_nm));
    begin_movement([this, target, hold_ms](Ticks now) { start_closed_loop(target, hold_ms, now); });
    return std::nullopt;
}

std::optional<ErrorCode> Channel::move_relative(std::int64_t distance_nm, std::int32_t hold_ms)
{
    if (auto err = check_linear_sensor())
        return err;
    if (hold_ms < 0 || hold_ms > kHoldForever_ms)
        return ErrorCode::InvalidParameter;
    sample(clock_.now());
    // MPR/SARP: "If relative position commands are to be accumulated all new relative
    // position commands are added to the previous target position."
    const bool accumulate = accumulate_relative_ && motion_ == Motion::Targeting;
    const double base = accumulate ? target_physical_nm_ : state_[0];
    const double delta = scale_inverted_ && known_ ? -static_cast<double>(distance_nm)
                                                   : static_cast<double>(distance_nm);
    const double target = base + delta;
    begin_movement([this, target, hold_ms](Ticks now) { start_closed_loop(target, hold_ms, now); });
    return std::nullopt;
}

void Channel::begin_movement(std::function<void(Ticks)> start)
{
    const Ticks now = clock_.now();
    // Power save (2.3.2): from standstill the sensor powers up first; status 5 meanwhile.
    if (sensor_mode_ == SensorMode::PowerSave && (motion_ == Motion::Idle || motion_ == Motion::MoveDelay)) {
        pending_start_ = std::move(start);
        if (motion_ != Motion::MoveDelay)
            delay_until_ = now + clock_.ticks_from_ms(kSensorPowerUp_ms);
        motion_ = Motion::MoveDelay;
        return;
    }
    start(now);
}

void Channel::start_closed_loop(double target_physical_nm, std::int32_t hold_ms, Ticks now)
{
    sample(now);
    target_physical_nm_ = target_physical_nm;
    // A target beyond a mechanical end stop: the stage runs into the stop and the move
    // is aborted there (MPA: "If a mechanical end stop is detected ... aborted").
    const double reachable = std::clamp(target_physical_nm, travel_min_nm_, travel_max_nm_);
    end_stop_hit_ = reachable != target_physical_nm;
    const double speed = speed_nm_per_s_ > 0 ? std::min<double>(speed_nm_per_s_, top_speed()) : top_speed();
    const double acceleration = acceleration_um_per_s2_ * 1000.0;   // µm/s² -> nm/s²
    profile_ = models::TrapezoidProfile::plan(state_, reachable, speed, acceleration);
    hold_ms_ = hold_ms;
    move_start_ = now;
    move_end_ = now + static_cast<Ticks>(std::ceil(profile_.duration() * clock_.tick_hz() - 1e-9));
    motion_ = Motion::Targeting;
    if (move_end_ <= now)
        arrive(now);
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
    if (end_stop_hit_) {
        // 142: "generated in asynchronous mode if the target position of a closed-loop
        // command could not be reached, because a mechanical end stop was detected".
        motion_ = Motion::Idle;
        events_.push_back(Error{index_, ErrorCode::EndStopReached});
        return;
    }
    if (hold_ms_ == 0) {
        motion_ = Motion::Idle;
        finish_movement();
        return;
    }
    motion_ = Motion::Holding;
    hold_until_ = hold_ms_ == kHoldForever_ms ? kNever : now + clock_.ticks_from_ms(hold_ms_);
}

void Channel::finish_movement()
{
    // SRC: the "completed" answer string (the manual gives no format: rigsim sends C<ch>,
    // docs/protocol/mcs.md).
    if (report_on_complete_)
        events_.push_back(Answer{"C" + std::to_string(index_)});
}

void Channel::stop()
{
    sample(clock_.now());
    state_[1] = 0;
    motion_ = Motion::Idle;
    pending_start_ = nullptr;
}

std::optional<ErrorCode> Channel::set_position(std::int64_t position)
{
    if (!sensor_)
        return ErrorCode::NoSensorPresent;
    if (sensor_mode_ == SensorMode::Disabled)
        return ErrorCode::SensorDisabled;
    sample(clock_.now());
    // 2.3.3: known physical position -> the offset is rewritten (non-volatile);
    // unknown -> only the current, volatile shift changes.
    if (known_) {
        const double relative = state_[0] - reference_nm_;
        const double offset = static_cast<double>(position) - (scale_inverted_ ? -relative : relative);
        scale_offset_ = static_cast<std::int32_t>(std::clamp(std::llround(offset), -2'000'000'000LL, 2'000'000'000LL));
    } else {
        unknown_base_nm_ = state_[0] - static_cast<double>(position);
    }
    return std::nullopt;
}

std::optional<ErrorCode> Channel::set_scale(std::int32_t offset, std::int32_t inverted)
{
    if (inverted != 0 && inverted != 1)
        return ErrorCode::InvalidParameter;
    if (offset < -2'000'000'000 || offset > 2'000'000'000)   // channel property range (4.4)
        return ErrorCode::InvalidParameter;
    scale_offset_ = offset;
    scale_inverted_ = inverted == 1;
    return std::nullopt;
}

std::optional<ErrorCode> Channel::set_safe_direction(std::int32_t direction)
{
    if (direction != 0 && direction != 1)
        return ErrorCode::InvalidParameter;
    safe_direction_ = direction;
    return std::nullopt;
}

std::optional<ErrorCode> Channel::set_accumulate_relative(std::int32_t accumulate)
{
    if (accumulate != 0 && accumulate != 1)
        return ErrorCode::InvalidParameter;
    accumulate_relative_ = accumulate == 1;
    return std::nullopt;
}

std::optional<ErrorCode> Channel::set_step_while_scan(std::int32_t step)
{
    if (step != 0 && step != 1)
        return ErrorCode::InvalidParameter;
    step_while_scan_ = step == 1;
    return std::nullopt;
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
        speed_nm_per_s_ = static_cast<std::int32_t>(std::min<double>(top_speed(), kMaxClosedLoopSpeed));
    return std::nullopt;
}

std::optional<ErrorCode> Channel::set_closed_loop_max_frequency(std::int32_t frequency_hz)
{
    if (frequency_hz < kMinFrequency_hz || frequency_hz > kMaxFrequency_hz)
        return ErrorCode::InvalidParameter;
    max_frequency_hz_ = frequency_hz;
    return std::nullopt;
}

Ticks Channel::next_change(Ticks now) const
{
    switch (motion_) {
    case Motion::Idle:
        return kNever;
    case Motion::MoveDelay:
        return std::max(delay_until_, now + 1);
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
    case Motion::MoveDelay:
        if (now >= delay_until_ && pending_start_) {
            auto start = std::move(pending_start_);
            pending_start_ = nullptr;
            motion_ = Motion::Idle;
            start(now);
        }
        return;
    case Motion::Targeting:
        if (now >= move_end_)
            arrive(now);
        else
            sample(now);
        return;
    case Motion::Holding:
        if (now >= hold_until_) {
            motion_ = Motion::Idle;
            finish_movement();
        }
        return;
    }
}

} // namespace rigsim::mcs
