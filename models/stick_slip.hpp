#pragma once
// A stick-slip piezo positioner (SmarAct MCS, manual 2.3.1): one axis driven by open-loop
// steps, by closed-loop moves, and by the scanning piezo that shares the axis.
//
// Units: positions in nm (µ° on a rotary stage: the same numbers, the protocol chooses),
// speeds in nm/s, step frequency in Hz, scan levels 0..4095.
//
// State is a function of clock time, so the world wakes the body only at its events:
// - a closed-loop move is an exact MotionProfile: one event, the tick it ends;
// - a step burst at f Hz has made floor(t·f) steps t seconds after it started; the steps are
//   replayed lazily, in order, whenever the position is read, each with the next draw of
//   the seeded jitter generator (a stick-slip step is never exactly the same twice), so the
//   sequence of widths does not depend on when anyone looks. Events: the tick of the last
//   step, and the tick of the step that meets the software range limit (found by replaying
//   ahead, at most kLookAheadSteps steps per wake-up); a mechanical end stop does not end a
//   burst, the steps go on without moving;
// - a scan (models/piezo_scanner.hpp) ends at one tick; end stops clamp it;
// - at rest and not holding a closed-loop position, the stage creeps at drift_nm_per_s
//   (rest + drift · elapsed, clamped at the end stops); that is no event: it just stops
//   at an end stop, and nobody is told.
// Once an event has been handled, outcome() says what happened, and the listener is called.
//
// Faults (the control API's "stall" and "slip"): a blocked stage moves no further than where
// it stood when it was blocked (end stops at that point: steps go on without moving, a
// closed-loop move or search in progress ends at once, outcome Blocked); a slipping stage makes
// every step shorter by a fraction and drives closed-loop moves slower by it (from the next
// movement on).
//
// Obstacles (a collision, models/collision_watch.hpp) narrow the travel on one side like the
// mechanical end stops: a closed-loop move or a search that meets one ends there (outcome
// Blocked, as the stall's), steps against one go on without moving, a scan or the drift stops
// at it. Motion away is free.

#include "models/clock.hpp"
#include "models/motion_profile.hpp"
#include "models/piezo_scanner.hpp"
#include "models/world.hpp"

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace rigsim::models {

/// The positioner as built (config).
struct StickSlipConfig {
    double start_position_nm = 0;
    double travel_min_nm = -std::numeric_limits<double>::infinity();   ///< mechanical end stop
    double travel_max_nm = std::numeric_limits<double>::infinity();    ///< mechanical end stop
    double step_width_nm = 1000;        ///< one step at full amplitude (4095)
    double step_jitter_fraction = 0;    ///< each step is width · (1 ± this), uniformly
    std::uint32_t jitter_seed = 0;
    double scan_range_nm = 1500;        ///< a full 0..4095 scan
    double drift_nm_per_s = 0;          ///< open-loop creep at rest, signed; 0: none
    /// Linear (positions in nm, the face in m), rotary or goniometer (positions in µ°, the face
    /// in rad).
    BodyKind kind = BodyKind::Linear;
};

/// A software range limit an open-loop burst stops at (MCS 2.3.4).
struct StepLimit {
    /// A limit is set: a step that is cut short anywhere but at a mechanical end stop ends
    /// the burst. Without one, bursts only ever stop at the end stops (and go on stepping).
    bool active = false;
    double min_nm = -std::numeric_limits<double>::infinity();
    double max_nm = std::numeric_limits<double>::infinity();
    /// The window is relative to the position before each step (a limit on a scale that
    /// moves with the stage: MCS with its sensor disabled, 2.3.2).
    bool follows_stage = false;
};

/// One burst of open-loop steps.
struct StepBurst {
    std::int64_t steps = 0;         ///< > 0; 0: until stopped
    double direction = 1;           ///< +1 or -1
    std::int32_t amplitude_levels = 4095;   ///< 0..4095: the step width scales with it
    double frequency_hz = 1;
    StepLimit limit;
};

class StickSlipPositioner : public Body {
public:
    enum class Motion { Rest, Profile, Burst, Scan };
    /// What the last event did.
    enum class Outcome { None, Arrived, BurstDone, LimitMet, ScanDone, Blocked };
    /// Steps replayed ahead per wake-up while looking for the one that meets a range limit.
    static constexpr std::int64_t kLookAheadSteps = 1 << 16;

    StickSlipPositioner(const Clock& clock, const StickSlipConfig& config);

    /// Called after every event that changed outcome().
    void set_listener(std::function<void()> listener) { listener_ = std::move(listener); }
    /// Mechanical end stops (±infinity: none, an endless rotary stage). At rest only.
    void set_travel(double min_nm, double max_nm);
    /// What the stage is from now on (linear, rotary, goniometer: the controller was told another
    /// positioner type, MCS SST); the positions keep their numbers (nm become µ°).
    void set_kind(BodyKind kind);
    double travel_min_nm() const { return config_.travel_min_nm; }
    double travel_max_nm() const { return config_.travel_max_nm; }
    /// The end stops the stage meets now: the mechanical ones, or the obstacle of a stall,
    /// narrowed by the obstacles of a collision.
    double stop_min_nm() const;
    double stop_max_nm() const;

    /// Obstacles met in a collision (nm; std::nullopt: none on that side), each acting as the
    /// end stop on its side while set. A stage already past one is held where it stands (the
    /// obstacle is taken to be there). A closed-loop move or search in progress that meets one
    /// ends there, outcome Blocked.
    void set_obstacles(std::optional<double> min_nm, std::optional<double> max_nm);
    const std::optional<double>& obstacle_min_nm() const { return obstacle_min_nm_; }
    const std::optional<double>& obstacle_max_nm() const { return obstacle_max_nm_; }

    /// Stall: the stage moves no further than where it is now; a closed-loop move in progress
    /// ends there (outcome Blocked). `false`: free again, at rest where it stands.
    void set_blocked(bool blocked);
    bool blocked() const { return blocked_; }
    /// Slip: steps shorter and closed-loop moves slower by `fraction` (0 <= fraction < 1),
    /// from the next movement on.
    void set_slip(double fraction) { slip_ = fraction; }
    double slip() const { return slip_; }
    /// Velocity at the clock's now (nm/s): a profile's, a burst's mean, a scan's, the drift.
    double velocity_nm_per_s() const;

    /// The stage is held at its closed-loop target (no drift) until any motion command
    /// (halt included) or `false` releases it.
    void set_closed_loop_hold(bool hold);
    bool closed_loop_hold() const { return hold_; }

    /// Position at the clock's now (nm).
    double position_nm() const;
    Motion motion() const { return motion_; }
    /// The outcome of the last event, and forget it.
    Outcome take_outcome();

    /// Stop where the stage is now (a burst stops after its steps due so far).
    void halt();
    /// Put the stage at `position_nm`, at rest (a calibration run to an end stop).
    void place(double position_nm);
    /// Closed-loop move from rest at the position now to `target_nm`; `acceleration_nm_per_s2`
    /// 0 means unlimited. Returns the end tick; a move that ends now is done at return.
    Ticks move_to(double target_nm, double speed_nm_per_s, double acceleration_nm_per_s2);
    /// A closed-loop move under way brakes at `acceleration_nm_per_s2` (> 0) from the speed it has
    /// now and comes to rest where that takes it, never past the move's own target or an end stop
    /// (it brakes harder where it must): one event, outcome Arrived. Returns the end tick and, in
    /// `rest_nm`, where it will rest; anything but a closed-loop move halts at once (returns now).
    Ticks decelerate(double acceleration_nm_per_s2, double* rest_nm = nullptr);
    /// Drive through `legs_nm` in order at `speed_nm_per_s` without acceleration limit, each
    /// leg from rest where the last one ended (a reference search turning at end stops);
    /// one event per leg end, outcome Arrived after the last. Returns false if all legs
    /// are done at once (no distance).
    bool start_legs(std::vector<double> legs_nm, double speed_nm_per_s);

    /// Start a burst of open-loop steps now.
    void start_burst(const StepBurst& burst);
    /// Steps made by the current (or last) burst up to now.
    std::int64_t steps_done() const;
    /// Stop a burst; "the current step is completed" (MCS MST): a step begun but not yet
    /// due is made, without jitter. Returns true if that step met the range limit.
    bool stop_burst();

    /// Scan the piezo to `target_levels` at `speed_levels_per_s`; returns true if the scan
    /// is over at once (no span).
    bool start_scan(double target_levels, double speed_levels_per_s);
    /// The piezo level at now, 0..4095.
    double scan_level() const;

    Ticks next_event(Ticks now) const override;
    void on_event(Ticks now) override;

    BodyKind kind() const override { return config_.kind; }
    /// No limit switches (the end stops are mechanical); a slip is a fraction of each step
    /// (below 1; half if none is given), never a count of steps.
    std::optional<std::string> refuses(BodyFault& fault) const override;
    /// A motion under way (the drift at rest is no settling: it has no end).
    bool settling() const override { return motion_ != Motion::Rest; }

protected:
    double si_position() const override;
    double si_velocity() const override;
    TravelRange si_travel() const override;
    void si_place(double position) override;
    bool si_stoppable() const override { return true; }
    void si_set_obstacles(std::optional<double> min, std::optional<double> max) override;
    /// A stall blocks it, a slip shortens its steps; a failed sensor is the device's to read.
    void apply_faults() override;

private:
    /// m (rad) per nm (µ°).
    double si_per_nm() const;
    /// A burst replayed up to some step.
    struct Replay {
        double position_nm = 0;
        std::int64_t done = 0;
        std::uint32_t jitter_state = 0;
        bool limit_met = false;
    };
    /// Steps due `elapsed` ticks into the burst, capped at its length.
    std::int64_t steps_due(Ticks elapsed) const;
    /// The first tick at which step `n` (1-based) is due.
    Ticks tick_of_step(std::int64_t n) const;
    /// Make steps until `r.done == target` or the range limit is met.
    void replay(Replay& r, std::int64_t target) const;
    /// One step of `delta_nm` from `position_nm` within end stops and limit; false if the
    /// range limit cut it short.
    bool step(double& position_nm, double delta_nm) const;
    /// The end stops without the obstacles: mechanical, or the stall's.
    double end_min_nm() const { return blocked_ ? block_nm_ : config_.travel_min_nm; }
    double end_max_nm() const { return blocked_ ? block_nm_ : config_.travel_max_nm; }
    /// `x` within the obstacles, as seen from `from` (a stage past one stays where it is).
    double within_obstacles(double x, double from) const;
    /// The tick at which the closed-loop profile under way meets an obstacle, or kNever.
    Ticks obstacle_tick() const;
    /// Position at rest at `now`, drift included.
    double rest_position(Ticks now) const;
    /// Replay the burst up to now.
    void catch_up() const;
    void settle();
    void end_motion(Outcome outcome);
    /// Plan the next leg that has a distance at `now`; false if none is left.
    bool next_leg(Ticks now);

    const Clock& clock_;
    StickSlipConfig config_;
    std::function<void()> listener_;
    Motion motion_ = Motion::Rest;
    Outcome outcome_ = Outcome::None;
    double rest_nm_;                  ///< position at rest, or where a motion started
    Ticks rest_since_ = 0;            ///< when the stage came to rest at rest_nm_ (drift base)
    bool hold_ = false;               ///< holding a closed-loop target: no drift
    // Closed-loop move.
    MotionProfile profile_;
    Ticks profile_start_ = 0;
    Ticks profile_end_ = 0;
    std::vector<double> legs_nm_;     ///< legs still to drive after the current one
    std::size_t next_leg_ = 0;
    double leg_speed_nm_per_s_ = 0;
    // Open-loop burst; the replay is a cache of a function of time.
    StepBurst burst_;
    double step_width_nm_ = 0;
    Ticks burst_start_ = 0;
    mutable Replay replay_;
    std::uint32_t jitter_state_;      ///< at rest: the generator's state for the next burst
    // Scan.
    PiezoScanner scanner_;
    // Faults.
    bool blocked_ = false;
    double block_nm_ = 0;             ///< where a stalled stage is held
    double slip_ = 0;                 ///< fraction lost per step / of the closed-loop speed
    std::optional<double> obstacle_min_nm_;
    std::optional<double> obstacle_max_nm_;
};

} // namespace rigsim::models
