#include "emulator/mcs/channel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace rigsim::mcs {

namespace {

models::StickSlipConfig stick_slip_config(int index, const McsChannelConfig& c)
{
    models::StickSlipConfig s;
    s.start_position_nm = static_cast<double>(c.start_position_nm);
    s.step_width_nm = static_cast<double>(c.step_width_nm);
    s.step_jitter_fraction = static_cast<double>(c.step_jitter_percent) / 100.0;
    s.jitter_seed = 0x9e3779b9u ^ static_cast<std::uint32_t>(index);
    s.scan_range_nm = static_cast<double>(c.scan_range_nm);
    s.drift_nm_per_s = static_cast<double>(c.drift_nm_per_s);
    return s;
}

} // namespace

Channel::Channel(int index, const McsChannelConfig& config, Firmware firmware, models::World& world,
                 const std::string& key)
    : index_(index), firmware_(firmware), clock_(world.clock()),
      body_(world.emplace<models::StickSlipPositioner>(key, world.clock(), stick_slip_config(index, config))),
      config_(config),
      sensor_(config.sensor_type == "none" ? nullptr : sensor_type_by_symbol(config.sensor_type)),
      sensor_mode_(SensorMode::Enabled),
      travel_min_nm_(static_cast<double>(config.travel_min_nm)),
      travel_max_nm_(static_cast<double>(config.travel_max_nm)),
      reference_nm_(0.0),
      unknown_base_nm_(static_cast<double>(config.start_position_nm)),
      speed_nm_per_s_(0),
      acceleration_um_per_s2_(0)
{
    body_.set_travel(travel_min(), travel_max());
    body_.set_listener([this] { body_event_ = true; });
    reset();
}

Channel::~Channel()
{
    body_.set_listener(nullptr);   // the body stays in the world, which outlives the device
}

void Channel::reset()
{
    motion_ = Motion::Idle;
    pending_start_ = nullptr;
    body_.halt();
    body_event_ = false;
    blind_logical_.reset();
    known_ = false;
    unknown_base_nm_ = body_.position_nm();   // "It simply assumes its starting position as the zero position."
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
    body_.set_travel(travel_min(), travel_max());
    return std::nullopt;
}

void Channel::set_sensor_mode(SensorMode mode)
{
    stop();   // SSE: "all positioner channels of the system are implicitly stopped"
    sensor_mode_ = mode;
}

std::optional<ErrorCode> Channel::sensor_error() const
{
    if (!sensor_ || sensor_failed_)   // a failed sensor is not detected: as if none were attached
        return ErrorCode::NoSensorPresent;
    if (sensor_mode_ == SensorMode::Disabled)
        return ErrorCode::SensorDisabled;
    return std::nullopt;
}

std::optional<ErrorCode> Channel::check_linear_sensor() const
{
    if (auto err = sensor_error())
        return err;
    if (sensor_->kind != SensorKind::Linear)
        return ErrorCode::WrongSensorType;
    return std::nullopt;
}

void Channel::post_error(ErrorCode code)
{
    events_.push_back(ChannelEvent{ChannelEvent::Kind::Error, code});
    if (code == ErrorCode::RangeLimitReached)
        outcome_ = "range_limit";
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
    if (auto err = sensor_error())
        return err;
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
    if (!physical_position_known())
        return ErrorCode::PhysicalPositionUnknown;
    if (min == max)
        limit_.reset();   // "If both parameters have the same value then the ... limit is disabled."
    else
        limit_ = std::make_pair(min, max);
    return std::nullopt;
}

double Channel::logical_from_physical(double physical) const
{
    if (blind_stepped())   // the scale moves with the stage: see commit_blind()
        return physical - (body_.position_nm() - *blind_logical_);
    if (!known_)
        return physical - unknown_base_nm_;
    const double relative = physical - reference_nm_;
    return (scale_inverted_ ? -relative : relative) + scale_offset_;
}

double Channel::physical_from_logical(double logical) const
{
    if (blind_stepped())
        return logical + (body_.position_nm() - *blind_logical_);
    if (!known_)
        return logical + unknown_base_nm_;
    const double relative = logical - scale_offset_;
    return (scale_inverted_ ? -relative : relative) + reference_nm_;
}

std::int64_t Channel::position() const
{
    return std::llround(logical_from_physical(body_.position_nm()));
}

bool Channel::physical_position_known() const
{
    return known_ && !blind_stepped();
}

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
    // MPR/SARP: "If relative position commands are to be accumulated all new relative
    // position commands are added to the previous target position."
    const bool accumulate = accumulate_relative_ && motion_ == Motion::Targeting;
    const double base = accumulate ? target_physical_nm_ : body_.position_nm();
    const double delta = scale_inverted_ && physical_position_known() ? -static_cast<double>(distance)
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
    if (motion_ == Motion::Stepping) {   // a new movement ends the burst where it is
        commit_blind();
        blind_logical_.reset();
    }
    start(now);
}

void Channel::start_closed_loop(double target_physical, std::int32_t hold_ms, Ticks now)
{
    body_.halt();
    target_physical_nm_ = target_physical;
    hold_ms_ = hold_ms;
    const double here = body_.position_nm();
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
    // A stalled stage (control API) meets its obstacle like an end stop.
    const double clamped = std::clamp(reachable, std::max(travel_min(), body_.stop_min_nm()),
                                      std::min(travel_max(), body_.stop_max_nm()));
    end_stop_hit_ = clamped != reachable;
    if (end_stop_hit_)
        limit_hit_ = false;
    const double speed = speed_nm_per_s_ > 0 ? std::min<double>(speed_nm_per_s_, top_speed()) : top_speed();
    const double acceleration = acceleration_um_per_s2_ * 1000.0;   // µm/s² (m°/s²) -> nm/s² (µ°/s²)
    const Ticks end = body_.move_to(clamped, speed, acceleration);
    motion_ = Motion::Targeting;
    if (end <= now)
        arrive(now);
}



void Channel::on_body_event(Ticks now)
{
    using Outcome = models::StickSlipPositioner::Outcome;
    const Outcome outcome = body_.take_outcome();
    switch (motion_) {
    case Motion::Targeting:
        if (outcome == Outcome::Blocked) {   // stalled on the way: as at an end stop (142)
            end_stop_hit_ = true;
            limit_hit_ = false;
        }
        if (outcome == Outcome::Arrived || outcome == Outcome::Blocked)
            arrive(now);
        if (outcome == Outcome::Blocked)
            outcome_ = "stalled";
        return;
    case Motion::Referencing:
        if (outcome == Outcome::Blocked)
            reference_found_ = false;   // both ways blocked: "a second end stop" (2.3.3)
        if (outcome == Outcome::Arrived || outcome == Outcome::Blocked)
            finish_reference(now);
        return;
    case Motion::Stepping:
        if (outcome == Outcome::BurstDone || outcome == Outcome::LimitMet)
            end_burst(outcome == Outcome::LimitMet);
        return;
    case Motion::Scanning:
        if (outcome == Outcome::ScanDone) {
            motion_ = Motion::Idle;
            finish_movement();
        }
        return;
    case Motion::Idle:
    case Motion::MoveDelay:
    case Motion::Holding:
    case Motion::Calibrating:
        return;   // a stale event of a movement that was stopped or replaced
    }
}

void Channel::arrive(Ticks now)
{
    if (end_stop_hit_ || limit_hit_) {
        // 142: "generated in asynchronous mode if the target position of a closed-loop
        // command could not be reached, because a mechanical end stop was detected";
        // 147 likewise at a software range limit (2.3.4).
        motion_ = Motion::Idle;
        post_error(end_stop_hit_ ? ErrorCode::EndStopReached : ErrorCode::RangeLimitReached);
        outcome_ = end_stop_hit_ ? (body_.blocked() ? "stalled" : "end_stop") : "range_limit";
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
    body_.set_closed_loop_hold(true);   // a held position does not drift
    hold_until_ = hold_ms_ == kHoldForever_ms ? kNever : now + clock_.ticks_from_ms(hold_ms_);
}

void Channel::finish_movement()
{
    outcome_ = "completed";
    // SRC: the "completed" report (the controller words it: docs/protocol/mcs.md).
    if (report_on_complete_)
        events_.push_back(ChannelEvent{ChannelEvent::Kind::Completed});
}

std::optional<ErrorCode> Channel::find_reference(std::int32_t direction, std::int32_t hold_ms, std::int32_t auto_zero)
{
    if (auto err = sensor_error())
        return err;
    const auto search = frm_direction(firmware_, direction);
    if (!search || (auto_zero != 0 && auto_zero != 1))
        return ErrorCode::InvalidParameter;
    if (auto err = check_move(hold_ms))
        return err;
    if (sensor_->reference == ReferenceType::None)
        return ErrorCode::CouldNotFindReferenceMark;   // appendix 4.3: "cannot be referenced"
    begin_movement([this, search = *search, hold_ms, auto_zero](Ticks now) {
        body_.halt();
        hold_ms_ = hold_ms;
        auto_zero_ = auto_zero == 1;
        // Searching runs at the closed-loop speed if one is set, else at 1 mm/s (1°/s).
        search_speed_ = speed_nm_per_s_ > 0 ? std::min<double>(speed_nm_per_s_, top_speed())
                                            : std::min(1'000'000.0, top_speed());
        const double here = body_.position_nm();
        // End stops and range limits both turn the search around (2.3.4).
        const auto [lo, hi] = physical_limit();
        // End-stop types ignore the direction parameter and use the safe direction (SSD):
        // the end stop is their reference, so no direction aborts there.
        const bool end_stop_type = sensor_->reference == ReferenceType::EndStop;
        const double dir = end_stop_type ? (safe_direction_ == 0 ? 1.0 : -1.0) : (search.backward ? -1.0 : 1.0);
        plan_reference_search(here, dir, lo, hi, search.abort_on_end_stop && !end_stop_type);
        if (body_.blocked())
            reference_found_ = false;   // a stalled stage meets "end stops" both ways at once
        motion_ = Motion::Referencing;
        if (!body_.start_legs(std::move(reference_legs_), search_speed_))
            finish_reference(now);
        reference_legs_.clear();
    });
    return std::nullopt;
}

void Channel::plan_reference_search(double here, double dir, double lo, double hi, bool abort_at_end)
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
        } else if (mark >= lo && mark <= hi && (!abort_at_end || (mark - here) * dir >= 0)) {
            if ((mark - here) * dir < 0)
                reference_legs_.push_back(end_ahead);   // reverse at the end stop
            reference_legs_.push_back(mark);
            reference_point_ = mark;
            reference_found_ = true;
        } else if (abort_at_end) {
            reference_legs_ = {end_ahead};   // the mark lies behind or outside: 144 there
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
        } else if (abort_at_end) {
            reference_legs_ = {end_ahead};   // two marks do not fit before the end stop: 144
            break;
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

void Channel::finish_reference(Ticks now)
{
    if (!reference_found_) {
        // "If a second end stop is detected before the reference mark is found the search
        // will abort unsuccessfully" (2.3.3): 144 in async mode, status 0.
        motion_ = Motion::Idle;
        post_error(ErrorCode::CouldNotFindReferenceMark);
        outcome_ = "reference_not_found";
        return;
    }
    become_known(reference_point_, auto_zero_);
    end_stop_hit_ = false;
    limit_hit_ = false;
    arrive(now);
}

void Channel::become_known(double reference_physical, bool auto_zero)
{
    known_ = true;
    reference_nm_ = reference_physical;
    if (auto_zero) {   // "the current position resp. angle is set to zero"
        const double relative = body_.position_nm() - reference_nm_;
        scale_offset_ = static_cast<std::int32_t>(-std::llround(scale_inverted_ ? -relative : relative));
    }
}

models::StepLimit Channel::step_limit() const
{
    models::StepLimit l;
    l.active = limit_.has_value();
    if (!limit_ || limit_->first >= limit_->second)
        return l;   // end stops only
    if (blind_logical_) {   // the scale, and the limit on it, move with the stage (2.3.2)
        l.follows_stage = true;
        l.min_nm = static_cast<double>(limit_->first) - *blind_logical_;
        l.max_nm = static_cast<double>(limit_->second) - *blind_logical_;
        return l;
    }
    std::tie(l.min_nm, l.max_nm) = physical_limit();
    return l;
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



std::optional<ErrorCode> Channel::calibrate()
{
    if (locked_)
        return ErrorCode::MovementLocked;
    if (auto err = sensor_error())
        return err;
    begin_movement([this](Ticks now) {
        body_.halt();
        motion_ = Motion::Calibrating;
        calibrate_until_ = now + clock_.ticks_from_ms(config_.calibration_ms);
        if (calibrate_until_ <= now)
            tick(now);
    });
    return std::nullopt;
}

void Channel::stop()
{
    using Outcome = models::StickSlipPositioner::Outcome;
    const Outcome outcome = body_.take_outcome();   // an event of this very tick, not yet handled
    if (motion_ == Motion::Stepping) {
        // MST: "the current step is completed before the positioner is stopped".
        if (outcome == Outcome::BurstDone || outcome == Outcome::LimitMet)
            end_burst(outcome == Outcome::LimitMet);
        else if (body_.stop_burst())
            post_error(ErrorCode::RangeLimitReached);
        commit_blind();
    }
    if (motion_ == Motion::Scanning && outcome == Outcome::ScanDone)
        finish_movement();
    if (motion_ != Motion::Idle)
        outcome_ = "stopped";
    body_.halt();
    body_event_ = false;
    blind_logical_.reset();
    motion_ = Motion::Idle;
    pending_start_ = nullptr;
    reference_legs_.clear();
}

std::optional<ErrorCode> Channel::set_position(std::int64_t position)
{
    if (auto err = sensor_error())
        return err;
    // 3.2 SP: on a rotary positioner the angle is 0 .. 359,999,999 µ° (revolution 0).
    if (angular() && (position < 0 || position > 359'999'999))
        return ErrorCode::InvalidParameter;
    commit_blind();
    const double here = body_.position_nm();
    // 2.3.3: known physical position -> the offset is rewritten (non-volatile);
    // unknown -> only the current, volatile shift changes.
    if (physical_position_known()) {
        const double relative = here - reference_nm_;
        const double offset = static_cast<double>(position) - (scale_inverted_ ? -relative : relative);
        scale_offset_ = static_cast<std::int32_t>(std::clamp(std::llround(offset), -2'000'000'000LL, 2'000'000'000LL));
    } else {
        unknown_base_nm_ = here - static_cast<double>(position);
    }
    if (blind_logical_)
        blind_logical_ = static_cast<double>(position);   // blind steps go on from the new reading
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

Ticks Channel::next_change(Ticks now) const
{
    if (body_event_)
        return now + 1;
    switch (motion_) {
    case Motion::MoveDelay:
        return std::max(delay_until_, now + 1);
    case Motion::Holding:
        return hold_until_;
    case Motion::Calibrating:
        return std::max(calibrate_until_, now + 1);
    case Motion::Idle:
    case Motion::Targeting:
    case Motion::Referencing:
    case Motion::Stepping:
    case Motion::Scanning:
        return kNever;   // idle, or moving: the body wakes at the movement's events
    }
    return kNever;
}

void Channel::tick(Ticks now)
{
    if (body_event_) {
        body_event_ = false;
        on_body_event(now);
        return;
    }
    switch (motion_) {
    case Motion::MoveDelay:
        if (now >= delay_until_ && pending_start_) {
            auto start = std::move(pending_start_);
            pending_start_ = nullptr;
            motion_ = Motion::Idle;
            start(now);
        }
        return;
    case Motion::Holding:
        if (now >= hold_until_) {
            motion_ = Motion::Idle;
            body_.set_closed_loop_hold(false);
            finish_movement();
        }
        return;
    case Motion::Calibrating:
        if (now >= calibrate_until_) {
            // CS: end-stop types are moved to the end stop in the safe direction.
            if (sensor_ && sensor_->reference == ReferenceType::EndStop)
                body_.place(safe_direction_ == 0 ? travel_max() : travel_min());
            calibrated_ = true;
            motion_ = Motion::Idle;
            finish_movement();
        }
        return;
    case Motion::Idle:
    case Motion::Targeting:
    case Motion::Referencing:
    case Motion::Stepping:
    case Motion::Scanning:
        return;   // their events come from the body
    }
}

void Channel::place(double physical)
{
    body_.place(physical);
}

void Channel::set_referenced(bool known)
{
    if (known) {
        become_known(static_cast<double>(config_.reference_position), false);
        return;
    }
    if (!known_)
        return;
    unknown_base_nm_ = body_.position_nm() - static_cast<double>(position());   // the reading stays
    known_ = false;
}

void Channel::set_sensor_failed(bool failed)
{
    if (failed == sensor_failed_)
        return;
    if (failed) {
        // Without feedback no closed-loop movement can go on; open-loop steps can.
        if (motion_ != Motion::Idle && motion_ != Motion::Stepping && motion_ != Motion::Scanning) {
            stop();
            outcome_ = "sensor_failure";
        }
        known_ = false;
    } else {
        // "position calculation is done incrementally" (2.3.2): what moved meanwhile is lost.
        known_ = false;
        unknown_base_nm_ = body_.position_nm();
    }
    sensor_failed_ = failed;
}

void Channel::restore_defaults()
{
    sensor_ = config_.sensor_type == "none" ? nullptr : sensor_type_by_symbol(config_.sensor_type);
    sensor_mode_ = SensorMode::Enabled;
    scale_offset_ = 0;
    scale_inverted_ = false;
    safe_direction_ = 0;
    es_default_mode_ = 0;
    es_mode_ = 0;
    body_.set_travel(travel_min(), travel_max());
}

} // namespace rigsim::mcs
