#include "emulator/mcs2/channel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rigsim::mcs2 {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// A full turn in n°: the marks of a rotary stage repeat with it.
constexpr double kTurn = 360'000'000'000.0;
/// REFERENCE_MARK (bit 15) is set within this distance of a mark, unit.
constexpr double kMarkWidth = 1'000'000;   // 1 µm

models::BodyKind kind_of(Motion m)
{
    switch (m) {
    case Motion::Linear:
        return models::BodyKind::Linear;
    case Motion::Rotary:
        return models::BodyKind::Rotary;
    case Motion::Goniometer:
        return models::BodyKind::Goniometer;
    }
    return models::BodyKind::Linear;
}

const PositionerType& type_or_default(std::int32_t code)
{
    const auto* t = positioner_type(code);
    return t ? *t : *positioner_type(300);
}

models::StickSlipConfig body_config(int index, const ChannelConfig& c)
{
    models::StickSlipConfig s;
    s.start_position_nm = static_cast<double>(c.start_position) / 1000.0;
    s.step_width_nm = static_cast<double>(c.step_width) / 1000.0;
    s.step_jitter_fraction = static_cast<double>(c.step_jitter_percent) / 100.0;
    s.jitter_seed = 0x85ebca6bu ^ static_cast<std::uint32_t>(index);
    s.scan_range_nm = static_cast<double>(c.scan_range) / 1000.0;
    s.drift_nm_per_s = static_cast<double>(c.drift) / 1000.0;
    s.kind = kind_of(type_or_default(c.positioner_type).motion);
    return s;
}

/// The tuning a predefined type starts with (4.8; the PID values are not published: rigsim's).
Channel::Tuning tuning_of(const PositionerType& t)
{
    const bool linear = t.motion == Motion::Linear;
    return {static_cast<std::int64_t>(t.motion),
            0,
            linear ? 2 : 3,
            linear ? -12 : -9,
            0,
            static_cast<std::int64_t>(t.reference),
            1000,
            0,
            0,
            10,
            0,
            100'000'000,
            1000,
            0,
            0};
}

} // namespace

Channel::Channel(int index, const ChannelConfig& config, models::World& world, const std::string& key)
    : clock_(world.clock()), config_(config),
      body_(world.emplace<models::StickSlipPositioner>(key, world.clock(), body_config(index, config))),
      type_(&type_or_default(config.positioner_type)), type_code_(type_->code)
{
    body_.set_listener([this] { body_event_ = true; });
    restore_defaults();
    power_up();
}

Channel::~Channel()
{
    body_.set_listener(nullptr);   // the body stays in the world, which outlives the device
}

void Channel::restore_defaults()
{
    type_ = &type_or_default(config_.positioner_type);
    type_code_ = type_->code;
    modified_ = false;
    slots_ = {};
    sensor_power_ = SensorPower::Enabled;
    loop_input_ = 1;
    scale_offset_ = 0;
    inverted_ = false;
    calibrated_ = true;   // a unit comes calibrated for the positioner it was shipped with
    settings_.control_options = 0;
    settings_.safe_direction = 0;
    settings_.max_frequency = 18500;
    apply_type();
}

void Channel::apply_type()
{
    tuning_ = tuning_of(*type_);
    body_.set_kind(kind_of(type_->motion));
    const bool endless = type_->motion == Motion::Rotary && type_->reference != Reference::EndStop;
    const double default_min = type_->motion == Motion::Goniometer ? -10e9 : -10.5e9;
    travel_min_ = endless ? -kInf : static_cast<double>(config_.travel_min.value_or(static_cast<std::int64_t>(default_min)));
    travel_max_ = endless ? kInf : static_cast<double>(config_.travel_max.value_or(static_cast<std::int64_t>(-default_min)));
    if (config_.travel_min && config_.travel_max && !endless) {
        travel_min_ = static_cast<double>(*config_.travel_min);
        travel_max_ = static_cast<double>(*config_.travel_max);
    }
    if (body_.motion() == models::StickSlipPositioner::Motion::Rest)
        body_.set_travel(travel_min_ / 1000.0, travel_max_ / 1000.0);
}

void Channel::power_up()
{
    motion_ = Activity::Idle;
    pending_ = nullptr;
    body_.halt();
    body_.set_closed_loop_hold(false);
    body_.set_travel(travel_min_ / 1000.0, travel_max_ / 1000.0);
    body_event_ = false;
    referenced_ = false;
    unknown_base_ = physical_now();   // "After power-up the position is incremental and starts at zero" (2.7)
    frozen_.reset();
    if (modified_) {   // unsaved tuning is lost at power-down (2.5.1)
        modified_ = false;
        tuning_ = tuning_of(*type_);
    }
    write_protected_ = true;
    streaming_ = false;
    braking_ = false;
    move_acceleration_ = 0;
    const auto max_frequency = settings_.max_frequency;
    const auto control_options = settings_.control_options;
    const auto safe_direction = settings_.safe_direction;
    settings_ = ChannelSettings{};
    settings_.max_frequency = max_frequency;
    settings_.control_options = control_options;
    settings_.safe_direction = safe_direction;
    amplifier_ = true;
    power_supply_ = true;
    locked_ = false;
    actuator_mode_ = 0;
    error_ = 0;
    sticky_ = 0;
    target_ = 0;
    distance_to_mark_ = 0;
    arrival_error_.reset();
    outcome_ = "";
}

std::string Channel::type_name() const
{
    if (modified_)
        return "modified";
    if (type_code_ >= 250 && type_code_ <= 253)
        return "CUSTOM" + std::to_string(type_code_ - 250);
    return std::string(type_->name);
}

std::optional<Error> Channel::set_type(std::int64_t code)
{
    const PositionerType* t = nullptr;
    std::optional<Tuning> tuning;
    if (code >= 250 && code <= 253) {
        const auto& slot = slots_[static_cast<std::size_t>(code - 250)];
        if (!slot)
            return Error::InvalidParameter;
        t = slot->base;
        tuning = slot->tuning;
    } else if (code >= std::numeric_limits<std::int32_t>::min() && code <= std::numeric_limits<std::int32_t>::max()) {
        t = positioner_type(static_cast<std::int32_t>(code));
    }
    if (!t)
        return Error::InvalidParameter;
    stop();
    type_ = t;
    type_code_ = static_cast<std::int32_t>(code);
    modified_ = false;
    calibrated_ = false;   // "clears IS_CALIBRATED and IS_REFERENCED" (4.4.6)
    set_referenced(false);
    apply_type();
    if (tuning)
        tuning_ = *tuning;
    return std::nullopt;
}

std::optional<Error> Channel::set_tuning(std::size_t i, std::int64_t value)
{
    if (write_protected_)
        return Error::PermissionDenied;
    if (i >= kTuningCount)
        return Error::InvalidParameter;
    tuning_[i] = value;
    modified_ = true;   // Positioner Type reads 0, its name "modified" until saved (2.5.1)
    return std::nullopt;
}

std::optional<Error> Channel::save_tuning(std::int64_t slot)
{
    if (write_protected_)
        return Error::PermissionDenied;
    if (slot < 250 || slot > 253)
        return Error::InvalidParameter;
    slots_[static_cast<std::size_t>(slot - 250)] = Slot{type_, tuning_};
    modified_ = false;
    type_code_ = static_cast<std::int32_t>(slot);
    return std::nullopt;
}

std::optional<Error> Channel::set_sensor_power(std::int64_t mode)
{
    if (mode < 0 || mode > 2)
        return Error::InvalidParameter;
    const auto m = static_cast<SensorPower>(mode);
    if (m == sensor_power_)
        return std::nullopt;
    if (m == SensorPower::Disabled) {
        frozen_ = logical_from_physical(physical_now());   // the reading stops (2.9)
        if (motion_ == Activity::Targeting || motion_ == Activity::Holding || motion_ == Activity::Referencing ||
            motion_ == Activity::Calibrating || motion_ == Activity::MoveDelay)
            finish(Error::SensorDisabled, "sensor_disabled");
    } else if (sensor_power_ == SensorPower::Disabled && frozen_) {
        // Moved while blind: the stage lost its position without an error; the reading goes on
        // from where it stopped (2.9).
        if (std::abs(logical_from_physical(physical_now()) - *frozen_) > 0.5) {
            referenced_ = false;
            unknown_base_ = physical_now() - *frozen_;
        }
        frozen_.reset();
    }
    sensor_power_ = m;
    return std::nullopt;
}

void Channel::set_amplifier(bool on)
{
    if (!on && motion_ != Activity::Idle)
        finish(Error::AmplifierDisabled, "stopped");
    amplifier_ = on;
}

void Channel::set_power_supply(bool on)
{
    if (!on && motion_ != Activity::Idle)
        finish(Error::PowerSupplyDisabled, "stopped");
    power_supply_ = on;
}

std::optional<Error> Channel::set_loop_input(std::int64_t input)
{
    if (input < 0 || input > 2)
        return Error::InvalidParameter;
    if (input == 2)   // the aux input is the I/O module's or the sensor module's: rigsim's MCS2 has neither
        return Error::NoIomPresent;
    if (input == 0 && (motion_ == Activity::Targeting || motion_ == Activity::Holding ||
                       motion_ == Activity::Referencing || motion_ == Activity::Calibrating ||
                       (motion_ == Activity::MoveDelay && pending_motion_ != Activity::Stepping)))
        finish(Error::ControlLoopInputDisabled, "stopped");
    loop_input_ = static_cast<std::int32_t>(input);
    return std::nullopt;
}

std::optional<Error> Channel::set_actuator_mode(std::int64_t mode)
{
    if (mode < 0 || mode > 2)
        return Error::InvalidParameter;
    if (moving())
        return Error::BusyMoving;
    if (mode == 2)   // low vibration needs a feature permission rigsim's unit has not bought (2.19)
        return Error::PermissionDenied;
    actuator_mode_ = static_cast<std::int32_t>(mode);
    return std::nullopt;
}

std::optional<Error> Channel::set_velocity(std::int64_t v)
{
    if (v < 0 || v > 100'000'000'000)
        return Error::InvalidParameter;
    if (moving() && (v == 0) != (settings_.velocity == 0))   // enabling/disabling while moving (4.4.15)
        return Error::BusyMoving;
    settings_.velocity = v;
    return std::nullopt;
}

std::optional<Error> Channel::set_acceleration(std::int64_t a)
{
    if (a < 0 || a > 10'000'000'000'000)
        return Error::InvalidParameter;
    if (moving() && (a == 0) != (settings_.acceleration == 0))
        return Error::BusyMoving;
    settings_.acceleration = a;
    return std::nullopt;
}

std::optional<Error> Channel::set_hold_time(std::int64_t ms)
{
    if (ms == -1)
        ms = 0xffffffffLL;   // SA_CTL_INFINITE as a signed 32-bit value (errata)
    if (ms < 0 || ms > 0xffffffffLL)
        return Error::InvalidParameter;
    settings_.hold_ms = ms;
    return std::nullopt;
}

// ---- scale (2.7.5) ----

double Channel::logical_from_physical(double physical) const
{
    if (!referenced_)
        return physical - unknown_base_;
    const double rel = physical - reference_point_;
    return (inverted_ ? -rel : rel) + static_cast<double>(scale_offset_);
}

double Channel::physical_from_logical(double logical) const
{
    if (!referenced_)
        return logical + unknown_base_;
    const double rel = logical - static_cast<double>(scale_offset_);
    return reference_point_ + (inverted_ ? -rel : rel);
}

std::int64_t Channel::position() const
{
    if (frozen_)
        return std::llround(*frozen_);
    return std::llround(logical_from_physical(physical_now()));
}

std::optional<Error> Channel::set_position(std::int64_t p)
{
    if (!has_sensor())
        return Error::NoSensorPresent;
    if (sensor_power_ == SensorPower::Disabled)
        return Error::SensorDisabled;
    const double here = physical_now();
    if (referenced_) {
        const double rel = here - reference_point_;
        scale_offset_ = p - std::llround(inverted_ ? -rel : rel);   // non-volatile (11.5)
    } else {
        unknown_base_ = here - static_cast<double>(p);   // the offset is not written (11.5)
    }
    const auto shift = p - position();
    (void)shift;
    target_ = p;
    return std::nullopt;
}

void Channel::set_scale_offset(std::int64_t offset)
{
    // Known position: immediate; unknown: stored, in effect once referenced (11.5).
    const double here = physical_now();
    const double before = logical_from_physical(here);
    scale_offset_ = offset;
    if (referenced_)
        target_ += std::llround(logical_from_physical(here) - before);
}

void Channel::set_scale_inverted(bool inverted)
{
    inverted_ = inverted;
    if (referenced_)
        target_ = position();
}

std::int64_t Channel::scan_position() const
{
    return std::llround(body_.scan_level() * 65535.0 / 4095.0);
}

std::optional<Error> Channel::sensor_value(std::int64_t& out) const
{
    if (!has_sensor())
        return Error::NoSensorPresent;
    if (sensor_power_ == SensorPower::Disabled)
        return Error::SensorDisabled;
    out = position();
    return std::nullopt;
}

std::uint32_t Channel::state_word() const
{
    std::uint32_t s = sticky_;
    switch (motion_) {
    case Activity::Idle:
        break;
    case Activity::MoveDelay:
        s |= state::kMoveDelayed;
        if (pending_motion_ == Activity::Targeting || pending_motion_ == Activity::Referencing)
            s |= state::kClosedLoopActive;
        break;
    case Activity::Targeting:
        s |= state::kActivelyMoving | state::kClosedLoopActive;
        break;
    case Activity::Holding:
        s |= state::kClosedLoopActive;
        break;
    case Activity::Calibrating:
        s |= state::kActivelyMoving | state::kCalibrating;
        break;
    case Activity::Referencing:
        s |= state::kActivelyMoving | state::kClosedLoopActive | state::kReferencing;
        break;
    case Activity::Stepping:
    case Activity::Scanning:
        s |= state::kActivelyMoving;
        break;
    }
    if (has_sensor())
        s |= state::kSensorPresent;
    if (calibrated_)
        s |= state::kIsCalibrated;
    if (streaming_)
        s |= state::kIsStreaming;
    if (referenced_)
        s |= state::kIsReferenced;
    if (has_sensor() && sensor_power_ != SensorPower::Disabled && type_->reference != Reference::EndStop) {
        const double here = physical_now();
        const double r = static_cast<double>(config_.reference_position);
        double nearest = r;
        if (type_->reference == Reference::DistanceCoded)
            nearest = r + std::round((here - r) / static_cast<double>(config_.coded_mark_spacing)) *
                              static_cast<double>(config_.coded_mark_spacing);
        else if (travel_min_ == -kInf)
            nearest = r + std::round((here - r) / kTurn) * kTurn;
        if (std::abs(here - nearest) <= kMarkWidth)
            s |= state::kReferenceMark;
    }
    return s;
}

// ---- movements ----

std::optional<Error> Channel::movement_refused(bool closed_loop) const
{
    if (locked_)
        return Error::MovementLocked;
    if (!power_supply_)
        return Error::PowerSupplyDisabled;
    if (!amplifier_)
        return Error::AmplifierDisabled;
    if (closed_loop) {
        if (!has_sensor())
            return Error::NoSensorPresent;
        if (sensor_power_ == SensorPower::Disabled)
            return Error::SensorDisabled;
        if (loop_input_ == 0)
            return Error::ControlLoopInputDisabled;
    }
    return std::nullopt;
}

void Channel::fail(Error e)
{
    error_ = static_cast<std::int32_t>(e);
    sticky_ |= state::kMovementFailed;
}

double Channel::top_speed() const
{
    // Without velocity control the stage runs as fast as it can, capped by the max closed-loop
    // frequency (10.2.1): the configured top speed at the default 18.5 kHz, in proportion below it.
    const double cap = static_cast<double>(config_.max_speed) * std::min(1.0, static_cast<double>(settings_.max_frequency) / 18500.0);
    return settings_.velocity > 0 ? std::min(cap, static_cast<double>(settings_.velocity)) : cap;
}

void Channel::begin(Activity motion, std::function<void()> start)
{
    // A new movement ends the last one's flags (2.8.3: "cleared by a new movement or stop command").
    sticky_ = 0;
    error_ = 0;
    braking_ = false;
    arrival_error_.reset();
    outcome_ = "";
    body_.set_closed_loop_hold(false);
    if (sensor_power_ == SensorPower::PowerSave && motion != Activity::Stepping && motion != Activity::Scanning) {
        body_.halt();
        motion_ = Activity::MoveDelay;
        pending_motion_ = motion;
        pending_ = std::move(start);
        delay_until_ = clock_.now() + clock_.ticks_from_ms(kSensorPowerUp_ms);
        return;
    }
    motion_ = motion;
    start();
}

std::optional<Error> Channel::move(MoveMode mode, std::int64_t value)
{
    if (streaming_) {
        fail(Error::BusyStreaming);
        return Error::BusyStreaming;
    }
    const bool closed = mode == MoveMode::ClAbsolute || mode == MoveMode::ClRelative;
    if (const auto e = movement_refused(closed)) {
        fail(*e);
        return e;
    }
    switch (mode) {
    case MoveMode::ClAbsolute:
    case MoveMode::ClRelative: {
        double target = static_cast<double>(value);
        if (mode == MoveMode::ClRelative) {
            if (value == 0) {   // abort and hold the position here (2.6.4)
                begin(Activity::Holding, [this] {
                    body_.halt();
                    target_ = position();
                    arrive(clock_.now());
                });
                return std::nullopt;
            }
            const bool accumulate = (settings_.control_options & 0x01) == 0;
            // While a first stop brakes, the target is where the braking ends.
            const double base = accumulate && (motion_ == Activity::Targeting || motion_ == Activity::Holding ||
                                               motion_ == Activity::MoveDelay)
                                    ? static_cast<double>(target_)
                                    : static_cast<double>(position());
            target = base + static_cast<double>(value);
        }
        if (std::abs(target) > 100e12) {
            fail(Error::InvalidParameter);
            return Error::InvalidParameter;
        }
        const double here = logical_from_physical(physical_now());
        if (range_limited()) {
            const auto lo = static_cast<double>(settings_.range_min);
            const auto hi = static_cast<double>(settings_.range_max);
            // Outside the range only moves back into it are allowed (2.12).
            if ((here < lo && target < here) || (here > hi && target > here)) {
                fail(Error::RangeLimitReached);
                sticky_ |= state::kRangeLimitReached;
                return Error::RangeLimitReached;
            }
        }
        target_ = std::llround(target);   // at the command: a relative move during the delay adds to it
        begin(Activity::Targeting, [this, target] { start_closed_loop(target); });
        return std::nullopt;
    }
    case MoveMode::ScanAbsolute:
    case MoveMode::ScanRelative: {
        std::int64_t level = value;
        if (mode == MoveMode::ScanRelative) {
            if (value < -65535 || value > 65535) {
                fail(Error::InvalidParameter);
                return Error::InvalidParameter;
            }
            level = std::clamp<std::int64_t>(scan_position() + value, 0, 65535);   // stops at the boundary
        } else if (value < 0 || value > 65535) {
            fail(Error::InvalidParameter);
            return Error::InvalidParameter;
        }
        begin(Activity::Scanning, [this, level] {
            const double speed = static_cast<double>(settings_.scan_velocity) * 4095.0 / 65535.0;
            target_ = level;
            if (body_.start_scan(static_cast<double>(level) * 4095.0 / 65535.0, speed))
                finish(Error::None, "completed");
        });
        return std::nullopt;
    }
    case MoveMode::Step: {
        if (value < -100'000 || value > 100'000) {
            fail(Error::InvalidParameter);
            return Error::InvalidParameter;
        }
        if (value == 0) {
            stop();
            return std::nullopt;
        }
        begin(Activity::Stepping, [this, value] {
            models::StepBurst b;
            b.steps = std::abs(value);
            b.direction = value > 0 ? 1.0 : -1.0;
            b.amplitude_levels =
                std::max<std::int32_t>(1, static_cast<std::int32_t>(std::lround(static_cast<double>(settings_.step_amplitude) * 4095.0 / 65535.0)));
            b.frequency_hz = static_cast<double>(settings_.step_frequency);
            if (range_limited() && referenced_) {
                const double a = physical_from_logical(static_cast<double>(settings_.range_min)) / 1000.0;
                const double c = physical_from_logical(static_cast<double>(settings_.range_max)) / 1000.0;
                b.limit.active = true;
                b.limit.min_nm = std::min(a, c);
                b.limit.max_nm = std::max(a, c);
            }
            if (sensor_power_ == SensorPower::Disabled)
                referenced_ = false;   // moved blind: the physical position is lost (2.9)
            body_.start_burst(b);
        });
        return std::nullopt;
    }
    }
    return std::nullopt;
}

void Channel::start_closed_loop(double target_logical)
{
    target_ = std::llround(target_logical);
    double bounded = target_logical;
    if (range_limited())
        bounded = std::clamp(bounded, static_cast<double>(settings_.range_min), static_cast<double>(settings_.range_max));
    double physical = physical_from_logical(bounded);
    const double lo = body_.stop_min_nm() * 1000.0;
    const double hi = body_.stop_max_nm() * 1000.0;
    if (bounded != target_logical)
        arrival_error_ = Error::RangeLimitReached;
    if (physical < lo || physical > hi) {
        physical = std::clamp(physical, lo, hi);
        arrival_error_ = Error::EndStopReached;
    }
    const double accel = settings_.velocity > 0 ? static_cast<double>(settings_.acceleration) : 0.0;
    move_acceleration_ = accel;   // a first stop brakes at it (:ACC may change while the move runs)
    const Ticks end = body_.move_to(physical / 1000.0, top_speed() / 1000.0, accel / 1000.0);
    if (end <= clock_.now())
        arrive(clock_.now());
}

void Channel::arrive(Ticks now)
{
    if (braking_) {   // a first stop's braking is over: stopped, no holding
        finish(Error::Aborted, "stopped");
        target_ = position();
        return;
    }
    if (arrival_error_) {
        const auto e = *arrival_error_;
        sticky_ |= e == Error::EndStopReached ? state::kEndStopReached : state::kRangeLimitReached;
        if (e == Error::EndStopReached)
            end_stop_event_ = true;
        finish(e, e == Error::EndStopReached ? "end_stop" : "range_limit");
        return;
    }
    outcome_ = "completed";
    if (streaming_) {   // between frames: the target is held until the next frame
        motion_ = Activity::Holding;
        body_.set_closed_loop_hold(true);
        hold_until_ = kNever;
        return;
    }
    // "The closed-loop movement is considered finished as soon as the target position is reached"
    // (2.6.4); then the channel holds it for the hold time.
    if (settings_.hold_ms == 0) {
        motion_ = Activity::Idle;
        return;
    }
    motion_ = Activity::Holding;
    body_.set_closed_loop_hold(true);
    hold_until_ = settings_.hold_ms == 0xffffffffLL ? kNever : now + clock_.ticks_from_ms(settings_.hold_ms);
}

void Channel::finish(Error result, const char* outcome)
{
    braking_ = false;
    if (motion_ != Activity::Idle && motion_ != Activity::Holding)
        body_.halt();
    body_.set_closed_loop_hold(false);
    motion_ = Activity::Idle;
    pending_ = nullptr;
    if (result != Error::None)
        error_ = static_cast<std::int32_t>(result);
    outcome_ = outcome;
}

void Channel::stop()
{
    if (streaming_)   // the stream moves it (the controller refuses :STOP# with BUSY_STREAMING)
        return;
    if (motion_ == Activity::Idle) {
        sticky_ &= ~(state::kEndStopReached | state::kRangeLimitReached | state::kFollowingLimitReached);
        return;
    }
    const bool was_moving = moving();
    // A search that runs on past its mark (Continue On Reference Found, 2.7.2) "must be stopped
    // manually": the reference it passed stands.
    if (motion_ == Activity::Referencing && found_at_ &&
        (physical_now() - found_at_->first) * found_at_->second >= 0) {
        body_.halt();
        commit_reference();
        finish(Error::None, "completed");
        target_ = position();
        return;
    }
    // With acceleration control the first stop brakes to zero velocity; a second one stops hard
    // (2.6.5). The movement's result is ABORTED, at the time the stop arrived.
    if (motion_ == Activity::Targeting && move_acceleration_ > 0 && !braking_) {
        braking_ = true;
        error_ = static_cast<std::int32_t>(Error::Aborted);
        outcome_ = "stopped";
        arrival_error_.reset();
        double rest_nm = 0;
        if (body_.decelerate(move_acceleration_ / 1000.0, &rest_nm) > clock_.now()) {
            target_ = std::llround(logical_from_physical(rest_nm * 1000.0));
            return;
        }
    }
    if (motion_ == Activity::Stepping)
        body_.stop_burst();
    else
        body_.halt();
    finish(was_moving ? Error::Aborted : Error::None, "stopped");
    sticky_ &= ~(state::kEndStopReached | state::kRangeLimitReached | state::kFollowingLimitReached);
    target_ = position();
}

void Channel::set_streaming(bool on)
{
    streaming_ = on;
    if (!on && motion_ != Activity::Idle) {
        body_.halt();
        body_.set_closed_loop_hold(false);
        motion_ = Activity::Idle;
        target_ = position();
    }
}

void Channel::stream_to(double target, Ticks duration, bool interpolate)
{
    sticky_ = 0;
    arrival_error_.reset();
    braking_ = false;
    motion_ = Activity::Targeting;
    target_ = std::llround(target);
    const double here = physical_now();
    double physical = std::clamp(physical_from_logical(target), body_.stop_min_nm() * 1000.0, body_.stop_max_nm() * 1000.0);
    const double seconds = clock_.seconds(std::max<Ticks>(duration, 1));
    // At the frame's pace, but no faster than the stage goes: a frame too far lags behind.
    const double speed = interpolate ? std::min(std::abs(physical - here) / seconds, top_speed()) : top_speed();
    if (speed <= 0 || body_.move_to(physical / 1000.0, speed / 1000.0, 0.0) <= clock_.now()) {
        motion_ = Activity::Holding;   // at the frame's target already
        body_.set_closed_loop_hold(true);
        hold_until_ = kNever;
    }
}

void Channel::stream_failed(Error e)
{
    set_streaming(false);
    error_ = static_cast<std::int32_t>(e);
    outcome_ = "stopped";
}

std::optional<Error> Channel::calibrate()
{
    if (streaming_) {
        fail(Error::BusyStreaming);
        return Error::BusyStreaming;
    }
    if (const auto e = movement_refused(true)) {
        fail(*e);
        return e;
    }
    if (loop_input_ == 2) {
        fail(Error::InvalidControlLoopInput);
        return Error::InvalidControlLoopInput;
    }
    if (settings_.calibration_options & 0x04) {   // advanced sensor correction: a feature permission (2.19)
        fail(Error::PermissionDenied);
        return Error::PermissionDenied;
    }
    begin(Activity::Calibrating, [this] {
        body_.halt();
        calibrated_ = false;   // the data are made anew: the guide's example reads 37 meanwhile (6.3.7)
        calibrate_until_ = clock_.now() + clock_.ticks_from_ms(config_.calibration_ms);
    });
    return std::nullopt;
}

std::optional<Error> Channel::reference()
{
    if (streaming_) {
        fail(Error::BusyStreaming);
        return Error::BusyStreaming;
    }
    if (const auto e = movement_refused(true)) {
        fail(*e);
        return e;
    }
    if (type_->reference == Reference::EndStop && !calibrated_) {   // "calibrated first" (2.7.4)
        fail(Error::NotCalibrated);
        return Error::NotCalibrated;
    }
    begin(Activity::Referencing, [this] { plan_reference(); });
    return std::nullopt;
}

void Channel::plan_reference()
{
    const double here = physical_now();
    reference_start_ = here;
    reference_found_ = false;
    const auto opts = settings_.referencing_options;
    double lo = travel_min_;
    double hi = travel_max_;
    if (range_limited()) {   // the range limit acts as end stops for referencing (2.12)
        const double a = physical_from_logical(static_cast<double>(settings_.range_min));
        const double b = physical_from_logical(static_cast<double>(settings_.range_max));
        lo = std::max(lo, std::min(a, b));
        hi = std::min(hi, std::max(a, b));
    }
    const double speed = top_speed();
    std::vector<double> legs;   // physical positions, unit
    double found_at = 0;
    double pass_dir = 1;
    found_at_.reset();

    if (type_->reference == Reference::EndStop) {
        // Towards the end stop of the safe direction, then a short way back off it (2.7.4).
        const double d = settings_.safe_direction == 0 ? 1.0 : -1.0;
        const double end = d > 0 ? hi : lo;
        legs = {end, end - d * kOvershoot};
        found_at = end;
        pending_point_ = end;
        reference_found_ = true;
    } else {
        const double d0 = (opts & 0x01) ? -1.0 : 1.0;
        const bool abort_on_end = opts & 0x08;
        const bool coded = type_->reference == Reference::DistanceCoded;
        const double r = static_cast<double>(config_.reference_position);
        const double period = coded ? static_cast<double>(config_.coded_mark_spacing) : (lo == -kInf ? kTurn : 0.0);
        // The first mark at or past `from` in direction `d`, within the travel; nullopt if none.
        const auto mark_ahead = [&](double from, double d) -> std::optional<double> {
            double m = r;
            if (period > 0) {
                const double k = d > 0 ? std::ceil((from - r) / period) : std::floor((from - r) / period);
                m = r + k * period;
            } else if ((d > 0 && r < from) || (d < 0 && r > from)) {
                return std::nullopt;
            }
            if (m < lo || m > hi)
                return std::nullopt;
            return m;
        };
        std::optional<double> found;
        double from = here;
        for (int pass = 0; pass < 2 && !found; ++pass) {
            const double d = pass == 0 ? d0 : -d0;
            if (const auto m1 = mark_ahead(from, d)) {
                if (!coded) {
                    found = *m1;
                    pass_dir = d;
                } else {
                    // Two adjacent marks (2.7.3): on past the first, or back (Reverse Direction).
                    const double d2 = (opts & 0x02) ? -d : d;
                    const double m2 = *m1 + d2 * period;
                    if (m2 >= lo && m2 <= hi) {
                        if (d2 != d)
                            legs.push_back(*m1 + d * kOvershoot);
                        found = m2;
                        pass_dir = d2;
                    }
                }
            }
            if (!found) {
                const double end = d > 0 ? hi : lo;
                if (std::isinf(end))
                    break;
                legs.push_back(end);   // to the end stop, then the other way (2.7.2)
                from = end;
                if (abort_on_end)
                    break;
            }
        }
        if (found) {
            found_at = *found;
            // Distance-coded marks tell which mark this is: the physical zero stays at r. An endless
            // rotary stage's marks do not: the mark found is 0.
            pending_point_ = period > 0 && !coded ? *found : r;
            reference_found_ = true;
            const double over = std::clamp(*found + pass_dir * kOvershoot, lo, hi);
            if (opts & 0x20) {   // Stop On Reference Found: stop past it, without returning (bit 5 wins)
                legs.push_back(over);
            } else if (opts & 0x10) {   // Continue On Reference Found: on to the end stop
                legs.push_back(pass_dir > 0 ? std::min(hi, *found + 1e15) : std::max(lo, *found - 1e15));
            } else {
                legs.push_back(over);
                legs.push_back(*found);
            }
        }
    }
    pending_distance_ = reference_found_ ? std::llround(found_at - here) : 0;
    if (reference_found_)
        found_at_ = std::make_pair(found_at, pass_dir);
    pending_offset_.reset();
    if (reference_found_ && (opts & 0x04)) {   // Auto Zero: the position reads 0 where the reference was found
        const double rel = found_at - pending_point_;
        pending_offset_ = -std::llround(inverted_ ? -rel : rel);
    }
    for (auto& l : legs)
        l /= 1000.0;
    if (!body_.start_legs(std::move(legs), speed / 1000.0))
        end_reference();
}

void Channel::end_reference()
{
    if (!reference_found_) {
        sticky_ |= state::kEndStopReached;
        finish(Error::EndStopReached, "reference_not_found");
        return;
    }
    commit_reference();
    target_ = position();
    finish(Error::None, "completed");
}

void Channel::commit_reference()
{
    reference_point_ = pending_point_;
    distance_to_mark_ = pending_distance_;
    if (pending_offset_)
        scale_offset_ = *pending_offset_;   // non-volatile (2.7.5)
    referenced_ = true;
}

void Channel::set_referenced(bool known)
{
    if (known == referenced_)
        return;
    const double here = physical_now();
    if (known) {
        reference_point_ = static_cast<double>(config_.reference_position);
    } else {
        unknown_base_ = here - logical_from_physical(here);   // the reading stays where it is
    }
    referenced_ = known;
}

void Channel::set_sensor_failed(bool failed)
{
    if (failed == sensor_failed_)
        return;
    sensor_failed_ = failed;
    if (failed) {
        if (motion_ == Activity::Targeting || motion_ == Activity::Holding || motion_ == Activity::Referencing ||
            motion_ == Activity::Calibrating || motion_ == Activity::MoveDelay)
            finish(Error::NoSensorPresent, "sensor_failure");
        set_referenced(false);
    } else {
        referenced_ = false;
        unknown_base_ = physical_now();   // repaired: the reading starts again at 0
    }
}

// ---- time ----

Ticks Channel::next_change(Ticks now) const
{
    if (body_event_)
        return now + 1;
    switch (motion_) {
    case Activity::MoveDelay:
        return std::max(delay_until_, now + 1);
    case Activity::Holding:
        return hold_until_;
    case Activity::Calibrating:
        return std::max(calibrate_until_, now + 1);
    case Activity::Idle:
    case Activity::Targeting:
    case Activity::Referencing:
    case Activity::Stepping:
    case Activity::Scanning:
        return kNever;   // idle, or moving: the body wakes at the movement's events
    }
    return kNever;
}

void Channel::tick(Ticks now)
{
    if (body_event_) {
        body_event_ = false;
        on_body_event(now);
    }
    switch (motion_) {
    case Activity::MoveDelay:
        if (now >= delay_until_) {
            motion_ = pending_motion_;
            auto start = std::move(pending_);
            pending_ = nullptr;
            if (start)
                start();
        }
        break;
    case Activity::Holding:
        if (now >= hold_until_) {   // the hold time is over: the channel stops (2.6.4)
            body_.set_closed_loop_hold(false);
            motion_ = Activity::Idle;
        }
        break;
    case Activity::Calibrating:
        if (now >= calibrate_until_) {
            if (type_->reference == Reference::EndStop) {
                // The calibration of an end-stop type ends at the end stop of the safe direction.
                body_.place((settings_.safe_direction == 0 ? travel_max_ : travel_min_) / 1000.0);
            }
            calibrated_ = true;
            // Detect Distance Code Inversion (option bit 1, 2.6.1) learns how the stage's coded
            // marks run: rigsim's run as the type says, not inverted.
            if ((settings_.calibration_options & 0x02) && type_->reference == Reference::DistanceCoded)
                code_inversion_detected_ = true;
            finish(Error::None, "completed");
        }
        break;
    case Activity::Idle:
    case Activity::Targeting:
    case Activity::Referencing:
    case Activity::Stepping:
    case Activity::Scanning:
        break;
    }
}

void Channel::on_body_event(Ticks now)
{
    using O = models::StickSlipPositioner::Outcome;
    switch (body_.take_outcome()) {
    case O::None:
        return;
    case O::Arrived:
        if (motion_ == Activity::Targeting)
            arrive(now);
        else if (motion_ == Activity::Referencing)
            end_reference();
        return;
    case O::BurstDone:
        if (motion_ == Activity::Stepping)
            finish(Error::None, "completed");
        return;
    case O::LimitMet:
        if (motion_ == Activity::Stepping) {
            sticky_ |= state::kRangeLimitReached;
            finish(Error::RangeLimitReached, "range_limit");
        }
        return;
    case O::ScanDone:
        if (motion_ == Activity::Scanning)
            finish(Error::None, "completed");
        return;
    case O::Blocked:
        // A stall or an obstacle: the end-stop detection stops the channel (2.6.4, 4.8.12).
        if (motion_ == Activity::Targeting || motion_ == Activity::Holding || motion_ == Activity::Referencing) {
            sticky_ |= state::kEndStopReached;
            end_stop_event_ = true;
            finish(Error::EndStopReached, "stalled");
        }
        return;
    }
}

} // namespace rigsim::mcs2
