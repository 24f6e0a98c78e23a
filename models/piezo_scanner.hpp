#pragma once
// The scanning piezo of a stick-slip positioner: a 12-bit level (0..4095) that sweeps the
// stage over its scan range without steps (MCS manual 2.3.1 "scanning"). A scan runs at a
// constant speed in levels per second from the level reached so far to a target level, so
// the level is a function of clock time and a scan has one event: the tick it ends.
//
// The piezo shares its axis with the stick-slip drive, so it is a part of
// StickSlipPositioner (models/stick_slip.hpp), not a body of its own: the positioner folds
// the scan's displacement into its one position.

#include "models/clock.hpp"

namespace rigsim::models {

class PiezoScanner {
public:
    static constexpr double kMaxLevel = 4095.0;   ///< 12 bits

    /// `range_nm`: displacement of a full 0..4095 sweep (nm, or µ° on a rotary stage).
    PiezoScanner(const Clock& clock, double range_nm);

    /// Scan from the level reached at `now` to `target_levels` at `speed_levels_per_s` (> 0).
    void start(Ticks now, double target_levels, double speed_levels_per_s);
    /// The level at `now` (the target from the end tick on).
    double level_at(Ticks now) const;
    /// Displacement since the scan started (nm), at `now`.
    double displacement_nm(Ticks now) const;
    /// First tick at which the level has reached the target (the start tick for no span).
    Ticks end_tick() const { return end_; }
    bool scanning() const { return scanning_; }
    /// End the scan where it is at `now` (or at its target after its end tick).
    void settle(Ticks now);
    /// The level at rest.
    double level() const { return level_; }

private:
    const Clock& clock_;
    double range_nm_;
    bool scanning_ = false;
    double level_ = 0;          ///< levels, at rest or at the start of a scan
    double target_levels_ = 0;
    double speed_levels_per_s_ = 1;
    Ticks start_ = 0;
    Ticks end_ = 0;
};

} // namespace rigsim::models
