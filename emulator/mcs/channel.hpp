#pragma once
// One MCS positioner channel: sensor, closed-loop settings and motion state.
// No I/O: the handler calls it, the Clock advances it.

#include "emulator/core/clock.hpp"
#include "emulator/core/rig_config.hpp"
#include "emulator/mcs/codec.hpp"
#include "emulator/mcs/sensor_types.hpp"
#include "models/trapezoid.hpp"

#include <cstdint>
#include <optional>

namespace rigsim::mcs {

/// Channel status codes of appendix 4.1 (8: gripper moving, per the errata).
enum class ChannelStatus : int {
    Stopped = 0,
    Stepping = 1,
    Scanning = 2,
    Holding = 3,
    Targeting = 4,
    MoveDelay = 5,
    Calibrating = 6,
    FindingReferenceMark = 7,
    GripperMoving = 8,
    Locked = 9,
};

/// GCT channel types.
enum class ChannelType : int { Positioner = 0, EndEffector = 1 };

class Channel {
public:
    /// The hold time that means "hold until stopped" (MPA/MPR, manual 3.3).
    static constexpr std::int32_t kHoldForever_ms = 60'000;
    static constexpr std::int32_t kMaxClosedLoopSpeed = 100'000'000;       ///< SCLS range
    static constexpr std::int32_t kMaxClosedLoopAcceleration = 10'000'000; ///< SCLA range

    Channel(const McsChannelConfig& config, const Clock& clock);

    ChannelType type() const { return ChannelType::Positioner; }
    ChannelStatus status() const;
    /// Appendix 4.3 entry, or nullptr for a positioner without sensor.
    const SensorType* sensor() const { return sensor_; }

    /// SST: implicitly stops the positioner.
    std::optional<ErrorCode> set_sensor_type(std::int32_t code);
    /// GP: the position in nm (errors 129, 143).
    std::optional<ErrorCode> check_linear_sensor() const;
    std::int64_t position_nm() const;

    std::optional<ErrorCode> move_absolute(std::int64_t position_nm, std::int32_t hold_ms);
    std::optional<ErrorCode> move_relative(std::int64_t distance_nm, std::int32_t hold_ms);
    void stop();

    std::optional<ErrorCode> set_closed_loop_speed(std::int32_t speed_nm_per_s);
    std::optional<ErrorCode> set_closed_loop_acceleration(std::int32_t acceleration_um_per_s2);
    std::int32_t closed_loop_speed() const { return speed_nm_per_s_; }
    std::int32_t closed_loop_acceleration() const { return acceleration_um_per_s2_; }

    Ticks next_change(Ticks now) const;
    void tick(Ticks now);

private:
    enum class Motion { Idle, Targeting, Holding };

    std::optional<ErrorCode> start_move(double target_physical_nm, std::int32_t hold_ms);
    void sample(Ticks now);
    void arrive(Ticks now);

    const Clock& clock_;
    const SensorType* sensor_;
    double travel_min_nm_;
    double travel_max_nm_;
    double zero_offset_nm_;          ///< physical position that reads 0
    double max_speed_nm_per_s_;
    std::int32_t speed_nm_per_s_;
    std::int32_t acceleration_um_per_s2_;

    Motion motion_ = Motion::Idle;
    models::AxisState state_;        ///< physical position (nm), velocity (nm/s)
    models::TrapezoidProfile profile_;
    Ticks move_start_ = 0;
    Ticks move_end_ = 0;             ///< tick at which the profile is done
    Ticks hold_until_ = 0;           ///< kNever: hold until stopped
    std::int32_t hold_ms_ = 0;
    bool end_stop_hit_ = false;      ///< the target lay beyond a mechanical end stop
    double target_physical_nm_ = 0;  ///< MPR accumulates onto this while targeting
};

} // namespace rigsim::mcs
