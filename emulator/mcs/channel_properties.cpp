// MCS channel: the configuration setters of 3.2 (SSC, SSD, SARP, SSWS, SCLS, SCLA, SCLF),
// properties (appendix 4.4), emergency stop (2.2.1), broadcast stop (2.2.3), event receivers
// and the command queue (2.4). The rest of the channel is in channel.cpp.
#include "emulator/mcs/channel.hpp"

#include <algorithm>

namespace rigsim::mcs {

namespace {

// Appendix 4.4 property keys: component (bits 31..24), sub component (23..16), property.
constexpr std::uint32_t key(std::uint32_t component, std::uint32_t sub, std::uint32_t property)
{
    return component << 24 | sub << 16 | property;
}

/// A trigger source selector of 4.4.1: digital input 0/1 or software trigger 0..255.
bool valid_source(std::int64_t v)
{
    return v == 512 || v == 513 || (v >= 1792 && v <= 2047);
}

} // namespace

std::optional<ErrorCode> Channel::get_property(std::uint32_t k, std::int64_t& value) const
{
    const std::uint32_t component = k >> 24, sub = (k >> 16) & 0xff, property = k & 0xffff;
    switch (component) {
    case 1:   // General
        if (sub == 1 && property == 1) { value = es_mode_; return std::nullopt; }
        if (sub == 1 && property == 45) { value = es_default_mode_; return std::nullopt; }
        if (sub == 2 && property == 1) { value = low_vibration_; return std::nullopt; }
        if (sub == 4 && property == 1) { value = broadcast_stop_; return std::nullopt; }
        if (sub == 5 && property == 17) { value = forced_slip_; return std::nullopt; }
        return sub == 1 || sub == 2 || sub == 4 || sub == 5 ? ErrorCode::InvalidProperty : ErrorCode::InvalidSubComponent;
    case 2:   // Digital In 0, 1
        if (sub > 1)
            return ErrorCode::InvalidSubComponent;
        if (property == 1) { value = digital_in_mode_[sub]; return std::nullopt; }
        if (property == 2) { value = digital_in_edge_[sub]; return std::nullopt; }
        return ErrorCode::InvalidProperty;
    case 4:   // Counter 0
        if (sub != 0)
            return ErrorCode::InvalidSubComponent;
        if (property == 3) { value = counter_source_; return std::nullopt; }
        if (property == 5) { value = counter_; return std::nullopt; }
        return ErrorCode::InvalidProperty;
    case 5:   // Capture buffer 0
        if (sub != 0)
            return ErrorCode::InvalidSubComponent;
        if (property == 3) { value = capture_source_; return std::nullopt; }
        return ErrorCode::InvalidProperty;
    case 6:   // Command queue
        if (sub != 0)
            return ErrorCode::InvalidSubComponent;
        if (property == 4) { value = static_cast<std::int64_t>(queue_.size()); return std::nullopt; }
        if (property == 6) { value = kQueueCapacity; return std::nullopt; }
        return ErrorCode::InvalidProperty;
    case 7:   // Software trigger 0..255: a trigger source only, no properties
        return ErrorCode::InvalidProperty;
    case 8:   // Sensor
        if (sub == 11 && property == 1) {
            if (!sensor_)
                return ErrorCode::NoSensorPresent;
            value = static_cast<std::int64_t>(sensor_mode_);
            return std::nullopt;
        }
        if (sub == 22 && property == 47) { value = scale_offset_; return std::nullopt; }
        if (sub == 22 && property == 19) { value = scale_inverted_; return std::nullopt; }
        return sub == 11 || sub == 22 ? ErrorCode::InvalidProperty : ErrorCode::InvalidSubComponent;
    default:
        return ErrorCode::InvalidComponent;
    }
}

std::optional<ErrorCode> Channel::set_property(std::uint32_t k, std::int64_t value)
{
    std::int64_t current = 0;
    if (auto err = get_property(k, current))
        return err;
    auto in = [value](std::int64_t lo, std::int64_t hi) { return value >= lo && value <= hi; };
    switch (k) {
    case key(1, 1, 1):
        if (!in(0, 3))
            return ErrorCode::InvalidParameter;
        es_mode_ = static_cast<std::int32_t>(value);
        locked_ = false;   // "reset by setting the operation mode to any valid value"
        return std::nullopt;
    case key(1, 1, 45):
        if (!in(0, 3))
            return ErrorCode::InvalidParameter;
        es_default_mode_ = static_cast<std::int32_t>(value);
        return std::nullopt;
    case key(1, 2, 1):
        if (!in(0, 1))
            return ErrorCode::InvalidParameter;
        if (motion_ != Motion::Idle)
            return ErrorCode::CommandNotProcessable;   // 2.2.2: "must be completely stopped"
        low_vibration_ = value == 1;
        if (low_vibration_ && acceleration_um_per_s2_ == 0)   // implicitly, with defaults (2.5.1)
            set_closed_loop_acceleration(kDefaultLowVibrationAcceleration);
        return std::nullopt;
    case key(1, 4, 1):
        if (!in(0, 1))
            return ErrorCode::InvalidParameter;
        broadcast_stop_ = value == 1;
        return std::nullopt;
    case key(1, 5, 17):
        if (!in(0, 1))
            return ErrorCode::InvalidParameter;
        forced_slip_ = value == 1;
        return std::nullopt;
    case key(2, 0, 1):
    case key(2, 1, 1):
    case key(2, 0, 2):
    case key(2, 1, 2):
        if (!in(0, 1))
            return ErrorCode::InvalidParameter;
        ((k & 0xffff) == 1 ? digital_in_mode_ : digital_in_edge_)[(k >> 16) & 0xff] = static_cast<std::int32_t>(value);
        return std::nullopt;
    case key(4, 0, 3):
        if (value != 0 && !valid_source(value))
            return ErrorCode::InvalidParameter;
        counter_source_ = static_cast<std::int32_t>(value);
        return std::nullopt;
    case key(4, 0, 5):
        if (!in(0, 2'147'483'647))   // ERRATA: "2,147,486,647" is 2^31 - 1
            return ErrorCode::InvalidParameter;
        counter_ = value;
        return std::nullopt;
    case key(5, 0, 3):
        if (value != 0 && !valid_source(value))
            return ErrorCode::InvalidParameter;
        capture_source_ = static_cast<std::int32_t>(value);
        return std::nullopt;
    case key(8, 11, 1):
        if (!in(0, 2))
            return ErrorCode::InvalidParameter;
        set_sensor_mode(static_cast<SensorMode>(value));
        return std::nullopt;
    case key(8, 22, 47):
        return set_scale(static_cast<std::int32_t>(std::clamp<std::int64_t>(value, -2'100'000'000, 2'100'000'000)),
                         scale_inverted_ ? 1 : 0);
    case key(8, 22, 19):
        if (!in(0, 1))
            return ErrorCode::InvalidParameter;
        return set_scale(scale_offset_, static_cast<std::int32_t>(value));
    default:
        return ErrorCode::InvalidProperty;   // read-only: command queue size and capacity
    }
}

void Channel::emergency_stop_edge(bool rising)
{
    // 2.2.1: 0 normal (stop), 1 restricted (stop, locked until the mode is set), 2 disabled,
    // 3 auto release (stop, locked until the rising edge).
    if (rising) {
        if (es_mode_ == 3)
            locked_ = false;
        return;
    }
    if (es_mode_ == 2)
        return;
    stop();
    if (es_mode_ == 1 || es_mode_ == 3)
        locked_ = true;
}

void Channel::set_emergency_stop_mode(std::int32_t mode)
{
    es_mode_ = mode;
    locked_ = false;   // SESM: "The locked state may be reset by any call of the SESM command"
}

void Channel::on_event(std::int32_t source)
{
    // 2.4.3 counters, 2.4.4 capture buffer 0 (position, revolution, counter 0), 2.4.5 queue.
    if (counter_source_ == source && counter_ < 2'147'483'647)
        ++counter_;
    if (capture_source_ == source) {
        std::int64_t p = position();
        std::int64_t revolution = 0;
        if (angular()) {
            revolution = p / 360'000'000;
            p %= 360'000'000;
            if (p < 0) {
                p += 360'000'000;
                --revolution;
            }
        }
        capture_ = {p, revolution, counter_};
    }
    if (!queue_.empty() && queue_.front().first == source) {
        triggered_.push_back(std::move(queue_.front().second));
        queue_.erase(queue_.begin());
        if (report_on_triggered_)
            events_.push_back(ChannelEvent{ChannelEvent::Kind::Triggered});
    }
}

std::optional<ErrorCode> Channel::enqueue(Command command)
{
    const auto source = *atc_source_;
    atc_source_.reset();
    if (queue_.size() >= kQueueCapacity)
        return ErrorCode::CommandQueueFull;
    queue_.emplace_back(source, std::move(command));
    return std::nullopt;
}

void Channel::clear_queue()
{
    queue_.clear();
    atc_source_.reset();
}

std::vector<Command> Channel::take_triggered()
{
    std::vector<Command> t;
    t.swap(triggered_);
    return t;
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
    if (speed_nm_per_s == 0 && low_vibration_ && motion_ != Motion::Idle)
        return ErrorCode::CommandNotProcessable;   // 2.5.1: low vibration can't be left while moving
    speed_nm_per_s_ = speed_nm_per_s;
    if (speed_nm_per_s_ == 0) {
        acceleration_um_per_s2_ = 0;   // acceleration control needs speed control (2.5.1)
        low_vibration_ = false;
    }
    return std::nullopt;
}

std::optional<ErrorCode> Channel::set_closed_loop_acceleration(std::int32_t acceleration_um_per_s2)
{
    if (acceleration_um_per_s2 < 0 || acceleration_um_per_s2 > kMaxClosedLoopAcceleration)
        return ErrorCode::InvalidParameter;
    if (acceleration_um_per_s2 == 0 && low_vibration_ && motion_ != Motion::Idle)
        return ErrorCode::CommandNotProcessable;
    acceleration_um_per_s2_ = acceleration_um_per_s2;
    if (acceleration_um_per_s2_ == 0)
        low_vibration_ = false;
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

} // namespace rigsim::mcs
