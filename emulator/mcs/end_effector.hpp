#pragma once
// One MCS end effector channel (manual 3.2 SEET/GEET, 3.3 MGOA/MGOR/MGFA, 3.4 GGO/GF,
// 3.2 SZF): a gripper driven by a voltage, a force sensor, or a gripper with a force sensor.
// No I/O: the handler calls it, the Clock advances it.

#include "models/clock.hpp"
#include "models/gripper.hpp"
#include "emulator/mcs/errors.hpp"

#include <cstdint>
#include <optional>

namespace rigsim::mcs {

enum class ChannelStatus : int;

/// SEET types.
enum class EndEffectorType : int { None = 0, Gripper = 1, ForceSensor = 2, ForceGripper = 3 };

class EndEffector {
public:
    /// Limits of appendix/command descriptions.
    static constexpr std::int32_t kMaxOpening_cv = 22'500;     ///< MGOA range
    static constexpr std::int32_t kMaxSpeed_v_per_s = 225'000; ///< MGOA/MGOR/MGFA speed
    static constexpr std::int32_t kMaxForce_dun = 100'000;     ///< MGFA range
    static constexpr Ticks kZeroForce_ms = 1000;               ///< SZF "takes about one second"

    /// Power-up state: type None (SEET required), voltage 0, stopped. The jaws, their drive
    /// voltage and what they hold are `gripper`, a body of the world that outlives the channel.
    explicit EndEffector(models::Gripper& gripper);
    ~EndEffector();
    EndEffector(const EndEffector&) = delete;
    EndEffector& operator=(const EndEffector&) = delete;

    /// Status code of appendix 4.1: 0 stopped, 8 gripper moving (MGOA/MGOR),
    /// 4 targeting then 3 holding (MGFA), 6 calibrating (SZF).
    ChannelStatus status() const;

    /// SEET: validates type and parameters against the table of SEET (error 7 otherwise);
    /// stops any movement.
    std::optional<ErrorCode> set_type(std::int32_t type, std::int32_t param1, std::int32_t param2);
    EndEffectorType type() const { return type_; }
    std::int32_t param1() const { return param1_; }
    std::int32_t param2() const { return param2_; }

    /// MGOA/MGOR: ramp the gripper voltage at `speed` V/s; clipped to 0..max voltage of the
    /// configured gripper (SEET). 145 if the type has no gripper; 7 for out-of-range values.
    std::optional<ErrorCode> move_opening_absolute(std::int32_t opening_cv, std::int32_t speed_v_per_s);
    std::optional<ErrorCode> move_opening_relative(std::int32_t diff_cv, std::int32_t speed_v_per_s);
    /// MGFA: closed-loop force; 145 unless a force gripper (type 3).
    std::optional<ErrorCode> move_force_absolute(std::int32_t force_dun, std::int32_t speed_v_per_s,
                                                 std::int32_t hold_ms);
    /// GGO: gripper voltage in 1/100 V (145 without gripper).
    std::optional<ErrorCode> opening_cv(std::int32_t& out) const;
    /// GF: measured force in 1/10 µN relative to the last SZF (145 without force sensor).
    std::optional<ErrorCode> force_dun(std::int32_t& out) const;
    /// SZF: status 6 for about a second, then the current force reads zero (145 without sensor).
    std::optional<ErrorCode> zero_force();

    /// S: the voltage stays where it is; ends a ramp, an MGFA hold or an SZF (no completion).
    void stop();
    /// Power-up (R): stopped, gripper voltage 0 (fully open), force zero lost; the type
    /// configured with SEET is kept.
    void reset();
    /// The type back to None (SEET required), as a power cycle that erases saved settings leaves it.
    void restore_defaults()
    {
        type_ = EndEffectorType::None;
        param1_ = 0;
        param2_ = 0;
    }

    /// True once after a movement or SZF has completed (for SRC reports); clears the flag.
    bool take_completed();

    /// Tickable protocol (models/clock.hpp): the tick after the gripper's ramp ended (the world
    /// woke it; the controller reports it now), the end of SZF, else kNever (the gripper's ramp
    /// is the world's to wake).
    Ticks next_change(Ticks now) const;
    /// The SZF wait up to tick `now`; a ramp's end is taken.
    void tick(Ticks now);
    /// A ramp under way or SZF waiting: something changes by itself.
    bool busy() const { return gripper_.settling() || activity_ == Activity::ZeroingForce; }

private:
    /// What the channel is doing; each maps to one status code of appendix 4.1.
    enum class Activity { Idle, MovingOpening, TargetingForce, HoldingForce, ZeroingForce };

    bool has_gripper() const;
    bool has_force_sensor() const;
    std::int32_t max_voltage_cv() const;
    /// Force the sensor reads at the present voltage, before the SZF offset (1/10 µN).
    double raw_force_dun() const;
    /// Voltage at which MGFA's closed loop settles for `force_dun` (clipped to 0..max).
    double force_target_cv(std::int32_t force_dun) const;
    void start_ramp(double target_cv, std::int32_t speed_v_per_s, Activity activity);
    /// The gripper's ramp reached its target (its listener).
    void end_ramp();

    const Clock& clock_;
    models::Gripper& gripper_;
    EndEffectorType type_ = EndEffectorType::None;
    std::int32_t param1_ = 0;
    std::int32_t param2_ = 0;

    Activity activity_ = Activity::Idle;
    bool ramp_ended_ = false;          ///< the world woke the gripper at its ramp's end: tick now
    Ticks zeroing_end_ = 0;            ///< tick at which SZF takes the offset
    double zero_offset_dun_ = 0;       ///< raw force that reads 0 (SZF)
    bool completed_ = false;
};

} // namespace rigsim::mcs
