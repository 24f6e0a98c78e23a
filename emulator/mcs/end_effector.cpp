#include "emulator/mcs/end_effector.hpp"

#include "emulator/mcs/channel.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace rigsim::mcs {

namespace {

// SEET table (manual 3.2).
constexpr std::int32_t kMinVoltage_cv = 100;
constexpr std::int32_t kMaxVoltage_cv = 22'500;
constexpr std::int32_t kMinGain_dun_per_v = 1;
constexpr std::int32_t kMaxGain_dun_per_v = 10'000;
constexpr std::int32_t kMaxHold_ms = 60'000;   ///< MGFA holdTime: accepted, and ignored as the manual says the controller does

bool in_range(std::int32_t value, std::int32_t lo, std::int32_t hi)
{
    return value >= lo && value <= hi;
}

} // namespace

EndEffector::EndEffector(models::Gripper& gripper) : clock_(gripper.clock()), gripper_(gripper)
{
    gripper_.set_listener([this] { end_ramp(); });
}

EndEffector::~EndEffector()
{
    gripper_.set_listener({});   // the world outlives its devices
}

ChannelStatus EndEffector::status() const
{
    switch (activity_) {
    case Activity::Idle:
        return ChannelStatus::Stopped;
    case Activity::MovingOpening:
        return ChannelStatus::GripperMoving;   // code 8, missing from 4.1 (errata)
    case Activity::TargetingForce:
        return ChannelStatus::Targeting;
    case Activity::HoldingForce:
        return ChannelStatus::Holding;
    case Activity::ZeroingForce:
        return ChannelStatus::Calibrating;
    }
    return ChannelStatus::Stopped;
}

bool EndEffector::has_gripper() const
{
    switch (type_) {
    case EndEffectorType::Gripper:
    case EndEffectorType::ForceGripper:
        return true;
    case EndEffectorType::None:
    case EndEffectorType::ForceSensor:
        return false;
    }
    return false;
}

bool EndEffector::has_force_sensor() const
{
    switch (type_) {
    case EndEffectorType::ForceSensor:
    case EndEffectorType::ForceGripper:
        return true;
    case EndEffectorType::None:
    case EndEffectorType::Gripper:
        return false;
    }
    return false;
}

std::int32_t EndEffector::max_voltage_cv() const
{
    switch (type_) {
    case EndEffectorType::Gripper:
        return param1_;
    case EndEffectorType::ForceGripper:
        return param2_;
    case EndEffectorType::None:
    case EndEffectorType::ForceSensor:
        return 0;
    }
    return 0;
}

void EndEffector::reset()
{
    stop();
    gripper_.set_voltage(0);
    zero_offset_dun_ = 0;
    completed_ = false;
}

std::optional<ErrorCode> EndEffector::set_type(std::int32_t type, std::int32_t param1, std::int32_t param2)
{
    // SEET names types 1..3 only: None (0) cannot be set again.
    if (type < static_cast<int>(EndEffectorType::Gripper) || type > static_cast<int>(EndEffectorType::ForceGripper))
        return ErrorCode::InvalidParameter;
    const auto new_type = static_cast<EndEffectorType>(type);
    bool valid = false;
    switch (new_type) {
    case EndEffectorType::None:
        break;
    case EndEffectorType::Gripper:
        valid = in_range(param1, kMinVoltage_cv, kMaxVoltage_cv) && param2 == 0;
        break;
    case EndEffectorType::ForceSensor:
        valid = in_range(param1, kMinGain_dun_per_v, kMaxGain_dun_per_v) && param2 == 0;
        break;
    case EndEffectorType::ForceGripper:
        valid = in_range(param1, kMinGain_dun_per_v, kMaxGain_dun_per_v)
            && in_range(param2, kMinVoltage_cv, kMaxVoltage_cv);
        break;
    }
    if (!valid)
        return ErrorCode::InvalidParameter;
    // A new end effector: nothing moves, the gripper is fully open, the sensor uncalibrated.
    stop();
    type_ = new_type;
    param1_ = param1;
    param2_ = param2;
    gripper_.set_voltage(0);
    zero_offset_dun_ = 0;
    return std::nullopt;
}

std::optional<ErrorCode> EndEffector::move_opening_absolute(std::int32_t opening_cv, std::int32_t speed_v_per_s)
{
    if (!has_gripper())
        return ErrorCode::WrongEndEffectorType;
    if (!in_range(opening_cv, 0, kMaxOpening_cv) || !in_range(speed_v_per_s, 1, kMaxSpeed_v_per_s))
        return ErrorCode::InvalidParameter;
    // MGOA: "the channel will stop at the maximum voltage".
    const double target = std::min(opening_cv, max_voltage_cv());
    start_ramp(target, speed_v_per_s, Activity::MovingOpening);
    return std::nullopt;
}

std::optional<ErrorCode> EndEffector::move_opening_relative(std::int32_t diff_cv, std::int32_t speed_v_per_s)
{
    if (!has_gripper())
        return ErrorCode::WrongEndEffectorType;
    if (!in_range(diff_cv, -kMaxOpening_cv, kMaxOpening_cv) || !in_range(speed_v_per_s, 1, kMaxSpeed_v_per_s))
        return ErrorCode::InvalidParameter;
    // MGOR is relative to the voltage applied now, not to a running ramp's target; beyond
    // 0 or the maximum voltage "the channel will stop at the boundary".
    const double target = std::clamp(gripper_.voltage_cv() + diff_cv, 0.0, static_cast<double>(max_voltage_cv()));
    start_ramp(target, speed_v_per_s, Activity::MovingOpening);
    return std::nullopt;
}

std::optional<ErrorCode> EndEffector::move_force_absolute(std::int32_t force_dun, std::int32_t speed_v_per_s,
                                                          std::int32_t hold_ms)
{
    if (type_ != EndEffectorType::ForceGripper)
        return ErrorCode::WrongEndEffectorType;
    if (!in_range(force_dun, -kMaxForce_dun, kMaxForce_dun) || !in_range(speed_v_per_s, 1, kMaxSpeed_v_per_s)
        || !in_range(hold_ms, 0, kMaxHold_ms))
        return ErrorCode::InvalidParameter;
    // holdTime "has not been implemented yet" (MGFA): accepted and ignored; the force is
    // held until S.
    start_ramp(force_target_cv(force_dun), speed_v_per_s, Activity::TargetingForce);
    return std::nullopt;
}

double EndEffector::raw_force_dun() const
{
    // Only a force gripper presses on something; a bare force sensor sees no load.
    if (type_ != EndEffectorType::ForceGripper)
        return 0;
    return gripper_.force_dun();
}

double EndEffector::force_target_cv(std::int32_t force_dun) const
{
    const double raw = force_dun + zero_offset_dun_;
    const double max_cv = max_voltage_cv();
    const auto& held = gripper_.config();   // the closed loop meets the object's stiffness
    if (raw > 0)
        return std::min(held.contact_cv + raw / held.stiffness_dun_per_cv, max_cv);
    // Below the contact the sensor reads a constant: a zero raw force is met anywhere up
    // to the contact, so the loop stops at the first such voltage; a negative raw force is
    // never met, so the loop winds the voltage down to 0 (fully open).
    if (raw == 0)
        return std::min(gripper_.voltage_cv(), static_cast<double>(held.contact_cv));
    return 0;
}

std::optional<ErrorCode> EndEffector::opening_cv(std::int32_t& out) const
{
    if (!has_gripper())
        return ErrorCode::WrongEndEffectorType;
    out = static_cast<std::int32_t>(std::lround(gripper_.voltage_cv()));
    return std::nullopt;
}

std::optional<ErrorCode> EndEffector::force_dun(std::int32_t& out) const
{
    if (!has_force_sensor())
        return ErrorCode::WrongEndEffectorType;
    out = static_cast<std::int32_t>(std::lround(raw_force_dun() - zero_offset_dun_));
    return std::nullopt;
}

std::optional<ErrorCode> EndEffector::zero_force()
{
    if (!has_force_sensor())
        return ErrorCode::WrongEndEffectorType;
    // One thing at a time: SZF ends a running ramp or hold where it is.
    stop();
    activity_ = Activity::ZeroingForce;
    zeroing_end_ = clock_.now() + clock_.ticks_from_ms(kZeroForce_ms);
    return std::nullopt;
}

void EndEffector::start_ramp(double target_cv, std::int32_t speed_v_per_s, Activity activity)
{
    activity_ = activity;   // before the ramp: one with nowhere to go ends at once (end_ramp)
    gripper_.ramp_to(target_cv, speed_v_per_s);
    ramp_ended_ = false;    // ended at once: within the command, not a wake-up of the world
}

void EndEffector::end_ramp()
{
    ramp_ended_ = true;
    switch (activity_) {
    case Activity::MovingOpening:
        activity_ = Activity::Idle;
        completed_ = true;
        return;
    case Activity::TargetingForce:
        // MGFA: "it will try to hold the given force and have a status of 3 until the
        // channel is explicitly stopped" -- it never completes by itself.
        activity_ = Activity::HoldingForce;
        return;
    case Activity::Idle:
    case Activity::HoldingForce:
    case Activity::ZeroingForce:
        return;
    }
}

void EndEffector::stop()
{
    gripper_.hold();
    activity_ = Activity::Idle;
}

bool EndEffector::take_completed()
{
    return std::exchange(completed_, false);
}

Ticks EndEffector::next_change(Ticks now) const
{
    if (ramp_ended_)
        return now + 1;
    return activity_ == Activity::ZeroingForce ? std::max(zeroing_end_, now + 1) : kNever;
}

void EndEffector::tick(Ticks now)
{
    ramp_ended_ = false;
    switch (activity_) {
    case Activity::Idle:
    case Activity::HoldingForce:
    case Activity::MovingOpening:
    case Activity::TargetingForce:
        return;
    case Activity::ZeroingForce:
        if (now >= zeroing_end_) {
            zero_offset_dun_ = raw_force_dun();
            activity_ = Activity::Idle;
            completed_ = true;
        }
        return;
    }
}

} // namespace rigsim::mcs
