#include "emulator/mcs/channel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rigsim::mcs {

Channel::Channel(int index, const McsChannelConfig& config, models::World& world, const std::string& /*key*/)
    : index_(index), clock_(world.clock()), config_(config),
      sensor_(config.sensor_type == "none" ? nullptr : sensor_type_by_symbol(config.sensor_type)),
      sensor_mode_(SensorMode::Enabled),
      travel_min_nm_(static_cast<double>(config.travel_min_nm)),
      travel_max_nm_(static_cast<double>(config.travel_max_nm)),
      reference_nm_(0.0),
      unknown_base_nm_(static_cast<double>(config.start_position_nm)),
      speed_nm_per_s_(0),
      acceleration_um_per_s2_(0),
      state_(static_cast<double>(config.start_position_nm), 0.0),
      jitter_state_(0x9e3779b9u ^ static_cast<std::uint32_t>(index))
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
    limit_.reset();   // "The range limit is not saved to non-volatile memory" (2.3.4)
    reference_legs_.clear();
    report_on_triggered_ = false;
    es_mode_ = es_default_mode_;
    locked_ = false;
    low_vibration_ = false;
    broadcast_stop_ = false;
    broadcast_request_ = false;
    forced_slip_ = true;
    digital_in_mode_ = {};
    digital_in_edge_ = {};
    counter_source_ = 0;
    counter_ = 0;
    capture_source_ = 0;
    capture_ = {};
    queue_.clear();
    atc_source_.reset();
    triggered_.clear();
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
        return locked_ ? ChannelStatus::Locked : ChannelStatus::Stopped;
    case Motion::MoveDelay:
        return ChannelStatus::MoveDelay;
    case Motion::Targeting:
        return ChannelStatus::Targeting;
    case Motion::Holding:
        return ChannelStatus::Holding;
    case Motion::Referencing:
        return ChannelStatus::FindingReferenceMark;
    case Motion::Calibrating:
        return ChannelStatus::Calibrating;
    case Motion::Stepping:
        return ChannelStatus::Stepping;
    case Motion::Scanning:
        return ChannelStatus::Scanning;
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

void Channel::post_error(ErrorCode code)
{
    // emplace with an explicit alternative: GCC 12 -O2 misreads push_back(Error{...})
    // as copying an uninitialised std::string of the Answer alternative.
    events_.emplace_back(std::in_place_type<Error>, Error{index_, code});
}

bool Channel::angular() const
{
    return sensor_ && sensor_->kind != SensorKind::Linear;
}

bool Channel::endless() const
{
    return sensor_ && sensor_->kind == SensorKind::Rotary && sensor_->reference != ReferenceType::EndStop;
}

double Channel::travel_min() const
{
    if (endless())
        return -std::numeric_limits<double>::infinity();
    return angular() ? static_cast<double>(config_.travel_min_udeg) : travel_min_nm_;
}

double Channel::travel_max() const
{
    if (endless())
        return std::numeric_limits<double>::infinity();
    return angular() ? static_cast<double>(config_.travel_max_udeg) : travel_max_nm_;
}

std::pair<double, double> Channel::physical_limit() const
{
    double lo = travel_min();
    double hi = travel_max();
    if (limit_ && limit_->first < limit_->second) {
        double a = physical_from_logical(static_cast<double>(limit_->first));
        double b = physical_from_logical(static_cast<double>(limit_->second));
        if (a > b)
            std::swap(a, b);   // an inverted scale turns the limit around
        lo = std::max(lo, a);
        hi = std::min(hi, b);
    }
    return {lo, hi};
}

std::optional<ErrorCode> Channel::check_angular_sensor() const
{
    if (!sensor_)
        return ErrorCode::NoSensorPresent;
    if (sensor_mode_ == SensorMode::Disabled)
        return ErrorCode::SensorDisabled;
    if (sensor_->kind == SensorKind::Linear)
        return ErrorCode::WrongSensorType;
    return std::nullopt;
}

std::optional<ErrorCode> Channel::check_move(std::int32_t hold_ms) const
{
    if (locked_)
        return ErrorCode::MovementLocked;   // 2.2.1: "all movement commands will return 146"
    if (hold_ms < 0 || hold_ms > kHoldForever_ms)
        return ErrorCode::InvalidParameter;
    return std::nullopt;
}

std::pair<std::int64_t, std::int64_t> Channel::range_limit() const
{
    return limit_ ? *limit_ : std::pair<std::int64_t, std::int64_t>{0, 0};
}

std::optional<ErrorCode> Channel::set_range_limit(std::int64_t min, std::int64_t max)
{
    // 2.3.4: "The range limit may only be set if the positioner knows its physical position."
    if (!known_)
        return ErrorCode::PhysicalPositionUnknown;
    if (min == max)
        limit_.reset();   // "If both parameters have the same value then the ... limit is disabled."
    else
        limit_ = std::make_pair(min, max);
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

std::int64_t Channel::position() const
{
    return std::llround(logical_from_physical(state_[0]));
}

double Channel::top_speed() const
{
    // SCLF caps the driving frequency; the stage's top speed scales with it.
    return static_cast<double>(config_.max_speed_nm_per_s) * max_frequency_hz_ / kMaxFrequency_hz;
}

std::optional<ErrorCode> Channel::move_absolute(std::int64_t position, std::int32_t hold_ms)
{
    if (auto err = check_move(hold_ms))
        return err;
    const double target = physical_from_logical(static_cast<double>(position));
    begin_movement([this, target, hold_ms](Ticks now) { start_closed_loop(target, hold_ms, now); });
    return std::nullopt;
}

std::optional<ErrorCode> Channel::move_relative(std::int64_t distance, std::int32_t hold_ms)
{
    if (auto err = check_move(hold_ms))
        return err;
    sample(clock_.now());
    // MPR/SARP: "If relative position commands are to be accumulated all new relative
    // position commands are added to the previous target position."
    const bool accumulate = accumulate_relative_ && motion_ == Motion::Targeting;
    const double base = accumulate ? target_physical_nm_ : state_[0];
    const double delta = scale_inverted_ && known_ ? -static_cast<double>(distance)
                                                   : static_cast<double>(distance);
    const double target = base + delta;
    begin_movement([this, target, hold_ms](Ticks now) { start_closed_loop(target, hold_ms, now); });
    return std::nullopt;
}

std::optional<ErrorCode> Channel::move_angle_absolute(std::int64_t position_udeg, std::int32_t hold_ms)
{
    return move_absolute(position_udeg, hold_ms);
}

std::optional<ErrorCode> Channel::move_angle_relative(std::int64_t distance_udeg, std::int32_t hold_ms)
{
    return move_relative(distance_udeg, hold_ms);
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

void Channel::start_closed_loop(double target_physical, std::int32_t hold_ms, Ticks now)
{
    sample(now);
    state_[1] = 0;
    target_physical_nm_ = target_physical;
    hold_ms_ = hold_ms;
    const double here = state_[0];
    // 2.3.4: a movement stops at the software range limit (147 in async mode); from
    // outside the limit only movements back toward it are allowed; a limit whose maximum
    // is below its minimum allows no movement at all.
    if (limit_ && limit_->first > limit_->second) {
        motion_ = Motion::Idle;
        post_error(ErrorCode::RangeLimitReached);
        return;
    }
    const auto [lo, hi] = physical_limit();
    const bool outward = (here <= lo && target_physical < here) || (here >= hi && target_physical > here);
    if (limit_ && outward) {
        motion_ = Motion::Idle;
        post_error(ErrorCode::RangeLimitReached);
        return;
    }
    double reachable = target_physical;
    if (limit_) {
        const auto [llo, lhi] = physical_limit();
        reachable = std::clamp(reachable, std::min(llo, here), std::max(lhi, here));
    }
    limit_hit_ = reachable != target_physical;
    // A target beyond a mechanical end stop: the stage runs into the stop and the move
    // is aborted there (MPA: "If a mechanical end stop is detected ... aborted").
    const double clamped = std::clamp(reachable, travel_min(), travel_max());
    end_stop_hit_ = clamped != reachable;
    if (end_stop_hit_)
        limit_hit_ = false;
    const double speed = speed_nm_per_s_ > 0 ? std::min<double>(speed_nm_per_s_, top_speed()) : top_speed();
    const double acceleration = acceleration_um_per_s2_ * 1000.0;   // µm/s² (m°/s²) -> nm/s² (µ°/s²)
    profile_ = models::MotionProfile::plan(state_, clamped, speed, acceleration);
    move_start_ = now;
    move_end_ = now + static_cast<Ticks>(std::ceil(profile_.duration() * clock_.tick_hz() - 1e-9));
    motion_ = Motion::Targeting;
    if (move_end_ <= now)
        arrive(now);
}

void Channel::start_leg(double to, double speed, Ticks now)
{
    profile_ = models::MotionProfile::plan(models::AxisState(state_[0], 0.0), to, speed, 0.0);
    move_start_ = now;
    move_end_ = now + static_cast<Ticks>(std::ceil(profile_.duration() * clock_.tick_hz() - 1e-9));
}

void Channel::sample(Ticks now)
{
    if (motion_ != Motion::Targeting && motion_ != Motion::Referencing)
        return;
    state_ = profile_.sample(clock_.seconds(now - move_start_));
}

void Channel::arrive(Ticks now)
{
    state_ = models::AxisState(profile_.target(), 0.0);
    if (end_stop_hit_ || limit_hit_) {
        // 142: "generated in asynchronous mode if the target position of a closed-loop
        // command could not be reached, because a mechanical end stop was detected";
        // 147 likewise at a software range limit (2.3.4).
        motion_ = Motion::Idle;
        post_error(end_stop_hit_ ? ErrorCode::EndStopReached : ErrorCode::RangeLimitReached);
        if (end_stop_hit_ && broadcast_stop_)
            broadcast_request_ = true;   // 2.2.3: an end stop halts every channel
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

std::optional<ErrorCode> Channel::find_reference(std::int32_t direction, std::int32_t hold_ms, std::int32_t auto_zero)
{
    if (!sensor_)
        return ErrorCode::NoSensorPresent;
    if (sensor_mode_ == SensorMode::Disabled)
        return ErrorCode::SensorDisabled;
    if ((direction != 0 && direction != 1) || (auto_zero != 0 && auto_zero != 1))
        return ErrorCode::InvalidParameter;
    if (auto err = check_move(hold_ms))
        return err;
    if (sensor_->reference == ReferenceType::None)
        return ErrorCode::CouldNotFindReferenceMark;   // appendix 4.3: "cannot be referenced"
    begin_movement([this, direction, hold_ms, auto_zero](Ticks now) {
        sample(now);
        state_[1] = 0;
        hold_ms_ = hold_ms;
        auto_zero_ = auto_zero == 1;
        // Searching runs at the closed-loop speed if one is set, else at 1 mm/s (1°/s).
        search_speed_ = speed_nm_per_s_ > 0 ? std::min<double>(speed_nm_per_s_, top_speed())
                                            : std::min(1'000'000.0, top_speed());
        const double here = state_[0];
        // End stops and range limits both turn the search around (2.3.4).
        const auto [lo, hi] = physical_limit();
        // End-stop types ignore the direction parameter and use the safe direction (SSD).
        const double dir = sensor_->reference == ReferenceType::EndStop ? (safe_direction_ == 0 ? 1.0 : -1.0)
                                                                        : (direction == 0 ? 1.0 : -1.0);
        plan_reference_search(here, dir, lo, hi);
        motion_ = Motion::Referencing;
        next_reference_leg(now);
    });
    return std::nullopt;
}

void Channel::plan_reference_search(double here, double dir, double lo, double hi)
{
    const double step = static_cast<double>(config_.coded_mark_spacing);
    const double mark = static_cast<double>(config_.reference_position);
    reference_legs_.clear();
    reference_found_ = false;
    const double end_ahead = dir > 0 ? hi : lo;
    const double end_behind = dir > 0 ? lo : hi;
    switch (sensor_->reference) {
    case ReferenceType::None:
        break;
    case ReferenceType::EndStop:
        reference_legs_ = {end_ahead};
        reference_found_ = true;
        reference_point_ = end_ahead;
        break;
    case ReferenceType::Mark:
        if (endless()) {   // a mark every revolution: at most one turn away
            const double turn = 360'000'000.0;
            const double k = dir > 0 ? std::ceil((here - mark) / turn) : std::floor((here - mark) / turn);
            reference_point_ = mark + k * turn;
            reference_legs_ = {reference_point_};
            reference_found_ = true;
        } else if (mark >= lo && mark <= hi) {
            if ((mark - here) * dir < 0)
                reference_legs_.push_back(end_ahead);   // reverse at the end stop
            reference_legs_.push_back(mark);
            reference_point_ = mark;
            reference_found_ = true;
        } else {
            reference_legs_ = {end_ahead, end_behind};   // the mark lies outside: 144
        }
        break;
    case ReferenceType::DistanceCodedMarks: {
        // Two neighbouring marks give the position (2.3.3): stop at the second one met.
        auto second_mark = [&](double from, double d, double bound) -> std::optional<double> {
            double first = d > 0 ? mark + std::floor((from - mark) / step + 1) * step
                                 : mark + std::ceil((from - mark) / step - 1) * step;
            const double second = first + d * step;
            if (std::isinf(bound) || (second - bound) * d <= 0)
                return second;
            return std::nullopt;
        };
        if (auto m = second_mark(here, dir, end_ahead)) {
            reference_legs_ = {*m};
        } else if (auto back = second_mark(end_ahead, -dir, end_behind)) {
            reference_legs_ = {end_ahead, *back};
        } else {
            reference_legs_ = {end_ahead, end_behind};
            break;
        }
        reference_point_ = mark;   // the marks' code gives the absolute position
        reference_found_ = true;
        break;
    }
    }
}

void Channel::next_reference_leg(Ticks now)
{
    if (!reference_legs_.empty()) {
        const double to = reference_legs_.front();
        reference_legs_.erase(reference_legs_.begin());
        start_leg(to, search_speed_, now);
        if (move_end_ > now)
            return;
        state_[0] = to;
        next_reference_leg(now);
        return;
    }
    state_[1] = 0;
    if (!reference_found_) {
        // "If a second end stop is detected before the reference mark is found the search
        // will abort unsuccessfully" (2.3.3): 144 in async mode, status 0.
        motion_ = Motion::Idle;
        post_error(ErrorCode::CouldNotFindReferenceMark);
        return;
    }
    become_known(endless() ? reference_point_ : reference_point_, auto_zero_);
    profile_ = models::MotionProfile::plan(state_, state_[0], 1.0, 0.0);
    end_stop_hit_ = false;
    limit_hit_ = false;
    arrive(now);
}

void Channel::become_known(double reference_physical, bool auto_zero)
{
    known_ = true;
    reference_nm_ = reference_physical;
    if (auto_zero) {   // "the current position resp. angle is set to zero"
        const double relative = state_[0] - reference_nm_;
        scale_offset_ = static_cast<std::int32_t>(-std::llround(scale_inverted_ ? -relative : relative));
    }
}

bool Channel::displace(double delta)
{
    const double before_logical = logical_from_physical(state_[0]);
    const auto [lo, hi] = physical_limit();
    const double target = state_[0] + delta;
    const double reached = std::clamp(target, std::min(lo, state_[0]), std::max(hi, state_[0]));
    state_[0] = reached;
    if (sensor_mode_ == SensorMode::Disabled && sensor_) {
        // 2.3.2: "the positioner cannot track its position during the movement".
        known_ = false;
        unknown_base_nm_ = state_[0] - before_logical;
    }
    if (reached == target)
        return true;
    const bool at_limit = limit_ && !(reached <= travel_min() || reached >= travel_max());
    if (at_limit) {   // 2.3.4: open-loop movements stop at the range limit too
        motion_ = Motion::Idle;
        post_error(ErrorCode::RangeLimitReached);
        return false;
    }
    return true;   // against a mechanical end stop the steps go on, without moving
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
    begin_movement([this, steps, amplitude, frequency_hz](Ticks now) {
        sample(now);
        state_[1] = 0;
        motion_ = Motion::Stepping;
        step_start_ = now;
        steps_total_ = std::abs(steps) == 30'000 ? 0 : std::abs(steps);   // ±30000: unbounded
        steps_done_ = 0;
        step_dir_ = steps > 0 ? 1.0 : -1.0;
        step_width_ = static_cast<double>(config_.step_width_nm) * amplitude / 4095.0;
        step_frequency_hz_ = frequency_hz;
    });
    return std::nullopt;
}

void Channel::step_until(Ticks now)
{
    const double due = std::floor(clock_.seconds(now - step_start_) * step_frequency_hz_ + 1e-9);
    auto target = static_cast<std::int64_t>(due);
    if (steps_total_ > 0)
        target = std::min(target, steps_total_);
    const double jitter = static_cast<double>(config_.step_jitter_percent) / 100.0;
    while (steps_done_ < target && motion_ == Motion::Stepping) {
        ++steps_done_;
        // A stick-slip step is never exactly the same twice: open-loop positions drift.
        jitter_state_ = jitter_state_ * 1664525u + 1013904223u;
        const double u = static_cast<double>(jitter_state_ >> 8) / static_cast<double>(1u << 24) * 2.0 - 1.0;
        if (!displace(step_dir_ * step_width_ * (1.0 + jitter * u)))
            return;
    }
    if (motion_ == Motion::Stepping && steps_total_ > 0 && steps_done_ >= steps_total_) {
        motion_ = Motion::Idle;
        finish_movement();
    }
}

std::int32_t Channel::voltage_level() const
{
    return static_cast<std::int32_t>(std::lround(scan_level_));
}

std::optional<ErrorCode> Channel::scan_absolute(std::int32_t target, std::int64_t speed)
{
    if (locked_)
        return ErrorCode::MovementLocked;
    if (target < 0 || target > 4095 || speed < 1 || speed > 4'095'000'000LL)
        return ErrorCode::InvalidParameter;
    begin_movement([this, target, speed](Ticks now) {
        sample(now);
        state_[1] = 0;
        if (motion_ == Motion::Scanning)
            scan_until(now);
        motion_ = Motion::Scanning;
        scan_start_ = now;
        scan_from_ = scan_level_;
        scan_target_ = target;
        scan_speed_ = static_cast<double>(speed);
        scan_until(now);
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
    const auto target = static_cast<std::int32_t>(std::clamp(std::lround(scan_level_) + diff, 0L, 4095L));
    return scan_absolute(target, speed);
}

void Channel::scan_until(Ticks now)
{
    const double t = clock_.seconds(now - scan_start_);
    const double span = scan_target_ - scan_from_;
    const double done = std::min(std::abs(span), t * scan_speed_);
    const double level = scan_from_ + std::copysign(done, span);
    const double delta = (level - scan_level_) * static_cast<double>(config_.scan_range_nm) / 4095.0;
    scan_level_ = level;
    // Scans are not limited by the software range limit (2.3.4) but by the end stops.
    state_[0] = std::clamp(state_[0] + delta, travel_min(), travel_max());
    if (done >= std::abs(span)) {
        motion_ = Motion::Idle;
        finish_movement();
    }
}

std::optional<ErrorCode> Channel::calibrate()
{
    if (locked_)
        return ErrorCode::MovementLocked;
    if (!sensor_)
        return ErrorCode::NoSensorPresent;
    if (sensor_mode_ == SensorMode::Disabled)
        return ErrorCode::SensorDisabled;
    begin_movement([this](Ticks now) {
        sample(now);
        state_[1] = 0;
        motion_ = Motion::Calibrating;
        calibrate_until_ = now + clock_.ticks_from_ms(config_.calibration_ms);
        if (calibrate_until_ <= now)
            tick(now);
    });
    return std::nullopt;
}

void Channel::stop()
{
    if (motion_ == Motion::Stepping) {
        // MST: "the current step is completed before the positioner is stopped".
        step_until(clock_.now());
        if (motion_ == Motion::Stepping && (steps_total_ == 0 || steps_done_ < steps_total_)) {
            const Ticks elapsed = clock_.now() - step_start_;
            if (clock_.seconds(elapsed) * step_frequency_hz_ > static_cast<double>(steps_done_)) {
                ++steps_done_;
                displace(step_dir_ * step_width_);
            }
        }
    }
    if (motion_ == Motion::Scanning)
        scan_until(clock_.now());
    sample(clock_.now());
    state_[1] = 0;
    motion_ = Motion::Idle;
    pending_start_ = nullptr;
    reference_legs_.clear();
}

std::optional<ErrorCode> Channel::set_position(std::int64_t position)
{
    if (!sensor_)
        return ErrorCode::NoSensorPresent;
    if (sensor_mode_ == SensorMode::Disabled)
        return ErrorCode::SensorDisabled;
    // 3.2 SP: on a rotary positioner the angle is 0 .. 359,999,999 µ° (revolution 0).
    if (angular() && (position < 0 || position > 359'999'999))
        return ErrorCode::InvalidParameter;
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

bool Channel::take_broadcast_request()
{
    const bool r = broadcast_request_;
    broadcast_request_ = false;
    return r;
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
            events_.push_back(Answer{"T" + std::to_string(index_)});
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

Ticks Channel::next_change(Ticks now) const
{
    switch (motion_) {
    case Motion::Idle:
        return kNever;
    case Motion::MoveDelay:
        return std::max(delay_until_, now + 1);
    case Motion::Targeting:
    case Motion::Referencing:
        return now + 1;
    case Motion::Holding:
        return hold_until_;
    case Motion::Calibrating:
        return std::max(calibrate_until_, now + 1);
    case Motion::Stepping:
    case Motion::Scanning:
        return now + 1;
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
    case Motion::Referencing:
        if (now >= move_end_) {
            state_ = models::AxisState(profile_.target(), 0.0);
            next_reference_leg(now);
        } else {
            sample(now);
        }
        return;
    case Motion::Calibrating:
        if (now >= calibrate_until_) {
            // CS: end-stop types are moved to the end stop in the safe direction.
            if (sensor_ && sensor_->reference == ReferenceType::EndStop)
                state_[0] = safe_direction_ == 0 ? travel_max() : travel_min();
            calibrated_ = true;
            motion_ = Motion::Idle;
            finish_movement();
        }
        return;
    case Motion::Stepping:
        step_until(now);
        return;
    case Motion::Scanning:
        scan_until(now);
        return;
    }
}

} // namespace rigsim::mcs
