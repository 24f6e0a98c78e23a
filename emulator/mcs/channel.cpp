#include "emulator/mcs/channel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rigsim::mcs {

namespace {

/// What a positioner with sensor `sensor` is (one without is taken as linear).
models::BodyKind kind_of(const SensorType* sensor)
{
    switch (sensor ? sensor->kind : SensorKind::Linear) {
    case SensorKind::Linear:
        return models::BodyKind::Linear;
    case SensorKind::Rotary:
        return models::BodyKind::Rotary;
    case SensorKind::Goniometer:
        return models::BodyKind::Goniometer;
    }
    return models::BodyKind::Linear;
}

models::StickSlipConfig stick_slip_config(int index, const McsChannelConfig& c)
{
    models::StickSlipConfig s;
    s.start_position_nm = static_cast<double>(c.start_position_nm);
    s.step_width_nm = static_cast<double>(c.step_width_nm);
    s.step_jitter_fraction = static_cast<double>(c.step_jitter_percent) / 100.0;
    s.jitter_seed = 0x9e3779b9u ^ static_cast<std::uint32_t>(index);
    s.scan_range_nm = static_cast<double>(c.scan_range_nm);
    s.drift_nm_per_s = static_cast<double>(c.drift_nm_per_s);
    // The stage is what the configured sensor says it came with (a positioner without one is
    // taken as linear); an SST says another positioner is attached (set_sensor_type).
    s.kind = kind_of(c.sensor_type == "none" ? nullptr : sensor_type_by_symbol(c.sensor_type));
    return s;
}

} // namespace

Channel::Channel(int index, const McsChannelConfig& config, Firmware firmware, models::World& world,
                 const std::string& key)
    : firmware_(firmware), clock_(world.clock()),
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
    outcome_ = "";   // a reset (R, POST /api/reset, a power cycle) forgets the last motion's end
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
    body_.set_kind(kind_of(sensor_));
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
    if (code == ErrorCode::CouldNotFindReferenceMark)
        outcome_ = "reference_not_found";
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
    if (stop_at_empty_limit(ErrorCode::RangeLimitReached))
        return;
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
    body_.set_kind(kind_of(sensor_));
    body_.set_travel(travel_min(), travel_max());
}

} // namespace rigsim::mcs
