// MCS channel: the reference search (FRM, 2.3.3), sensor calibration (CS) and the software
// range limit (SPL/SAL, 2.3.4). The rest of the channel is in channel.cpp.
#include "emulator/mcs/channel.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace rigsim::mcs {

bool Channel::empty_limit() const
{
    return limit_ && limit_->first > limit_->second;
}

bool Channel::stop_at_empty_limit(ErrorCode code)
{
    if (!empty_limit())
        return false;
    body_.halt();
    motion_ = Motion::Idle;
    post_error(code);
    return true;
}

std::pair<double, double> Channel::physical_limit() const
{
    if (empty_limit()) {   // no position is inside it: the stage may not leave where it stands
        const double here = body_.position_nm();
        return {here, here};
    }
    double lo = travel_min();
    double hi = travel_max();
    if (limit_) {
        double a = physical_from_logical(static_cast<double>(limit_->first));
        double b = physical_from_logical(static_cast<double>(limit_->second));
        if (a > b)
            std::swap(a, b);   // an inverted scale turns the limit around
        lo = std::max(lo, a);
        hi = std::min(hi, b);
    }
    return {lo, hi};
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
        // 2.3.4: the limit's boundaries act as end stops for FRM, and "if the reference mark is
        // located outside the range limit then it will not be found". An empty limit has every
        // mark outside it, so the search fails where it starts: 144 (4.2), not 147.
        if (stop_at_empty_limit(ErrorCode::CouldNotFindReferenceMark))
            return;
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
    if (!limit_)
        return l;   // end stops only
    if (blind_logical_ && !empty_limit()) {   // the scale, and the limit on it, move with the stage (2.3.2)
        l.follows_stage = true;
        l.min_nm = static_cast<double>(limit_->first) - *blind_logical_;
        l.max_nm = static_cast<double>(limit_->second) - *blind_logical_;
        return l;
    }
    std::tie(l.min_nm, l.max_nm) = physical_limit();
    return l;
}

std::optional<ErrorCode> Channel::calibrate()
{
    if (locked_)
        return ErrorCode::MovementLocked;
    if (auto err = sensor_error())
        return err;
    begin_movement([this](Ticks now) {
        // CS moves the positioner "up to several mm", and 2.3.4 warns that near a range limit
        // boundary "the calibration will be aborted": under an empty limit it stops where it
        // starts, with the limit's 147 (the manual names no code of its own for it).
        if (stop_at_empty_limit(ErrorCode::RangeLimitReached))
            return;
        body_.halt();
        motion_ = Motion::Calibrating;
        calibrate_until_ = now + clock_.ticks_from_ms(config_.calibration_ms);
        if (calibrate_until_ <= now)
            tick(now);
    });
    return std::nullopt;
}

} // namespace rigsim::mcs
