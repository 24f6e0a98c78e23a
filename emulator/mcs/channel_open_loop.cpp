// MCS channel: open-loop movement (MST, 3.3), stepping with the sensor disabled (2.3.2) and
// scanning (MSCA/MSCR, GVL). The rest of the channel is in channel.cpp.
#include "emulator/mcs/channel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace rigsim::mcs {

bool Channel::blind_stepped() const
{
    return blind_logical_ && body_.steps_done() > 0;
}

void Channel::commit_blind()
{
    // 2.3.2: "the positioner cannot track its position during the movement": once a step
    // is made blind, the position is unknown and reads what it read when the steps began.
    if (!blind_stepped())
        return;
    known_ = false;
    unknown_base_nm_ = body_.position_nm() - *blind_logical_;
}

std::optional<ErrorCode> Channel::move_steps(std::int32_t steps, std::int32_t amplitude, std::int32_t frequency_hz)
{
    if (locked_)
        return ErrorCode::MovementLocked;
    if (steps < -30'000 || steps > 30'000 || amplitude < 0 || amplitude > 4095 || frequency_hz < 1
        || frequency_hz > kMaxFrequency_hz)
        return ErrorCode::InvalidParameter;
    if (steps == 0) {   // "A value of 0 stops the positioner"
        stop();
        return std::nullopt;
    }
    begin_movement([this, steps, amplitude, frequency_hz](Ticks) {
        // SPL/SAL: the limit "affects open-loop as well as closed-loop movements" (3.2); an
        // empty one allows no step, not even the first (147, 4.2).
        if (stop_at_empty_limit(ErrorCode::RangeLimitReached))
            return;
        body_.halt();
        motion_ = Motion::Stepping;
        if (sensor_ && sensor_mode_ == SensorMode::Disabled)
            blind_logical_ = logical_from_physical(body_.position_nm());
        models::StepBurst burst;
        burst.steps = std::abs(steps) == 30'000 ? 0 : std::abs(steps);   // ±30000: unbounded
        burst.direction = steps > 0 ? 1.0 : -1.0;
        burst.amplitude_levels = amplitude;
        burst.frequency_hz = frequency_hz;
        burst.limit = step_limit();
        body_.start_burst(burst);
    });
    return std::nullopt;
}

void Channel::end_burst(bool limit_met)
{
    commit_blind();
    blind_logical_.reset();
    motion_ = Motion::Idle;
    if (limit_met)
        post_error(ErrorCode::RangeLimitReached);   // 2.3.4: open-loop movements stop there too
    else
        finish_movement();
}

std::int32_t Channel::voltage_level() const
{
    return static_cast<std::int32_t>(std::lround(body_.scan_level()));
}

std::optional<ErrorCode> Channel::scan_absolute(std::int32_t target, std::int64_t speed)
{
    if (locked_)
        return ErrorCode::MovementLocked;
    if (target < 0 || target > 4095 || speed < 1 || speed > 4'095'000'000LL)
        return ErrorCode::InvalidParameter;
    begin_movement([this, target, speed](Ticks) {
        motion_ = Motion::Scanning;
        if (body_.start_scan(target, static_cast<double>(speed))) {
            motion_ = Motion::Idle;
            finish_movement();
        }
    });
    return std::nullopt;
}

std::optional<ErrorCode> Channel::scan_relative(std::int32_t diff, std::int64_t speed)
{
    if (locked_)
        return ErrorCode::MovementLocked;
    if (diff < -4095 || diff > 4095 || speed < 1 || speed > 4'095'000'000LL)
        return ErrorCode::InvalidParameter;
    // "If the resulting absolute scan target exceeds the valid range of 0..4,095 the scan
    // movement will stop at the boundary."
    const auto target = static_cast<std::int32_t>(std::clamp(std::lround(body_.scan_level()) + diff, 0L, 4095L));
    return scan_absolute(target, speed);
}

} // namespace rigsim::mcs
