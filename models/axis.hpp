#pragma once
// One motor-driven axis: a carriage between two end stops (a rotation stage has none),
// moved along exact motion profiles by a servo or a stepper. Stage units: counts (encoder
// counts or microsteps), counts/s, counts/s^2, counts/s^3. No protocol: the controller channel
// that owns the axis says which limit switches stop it and where its soft stops are, and turns
// the axis's events into its own messages, counters and status bits.
//
// The state is a function of clock time: a read samples the profile at the clock's now, and
// the world wakes the axis only at the tick at which its motion ends, a limit is met or a soft
// stop is crossed: the same tick at which sampling every tick would first see it. Between
// these events nothing runs.

#include "models/clock.hpp"
#include "models/motion_profile.hpp"
#include "models/world.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rigsim::models {

/// What the motor does when the carriage meets an end stop whose limit switch is ignored.
enum class Drive {
    Servo,     ///< DC servo or brushless: the motor stalls against the stop (a fault); the motion ends
    Stepper,   ///< open loop: the motor keeps stepping and loses the microsteps; the motion runs on
};

/// What an axis reports to its owner, at the tick it happens.
enum class AxisEvent {
    Arrived,          ///< the profile reached its end
    StoppedAtLimit,   ///< a limit switch that stops the axis, or a travel limit, ended the motion there
    SoftStopped,      ///< the motor crossed a soft stop and stopped dead on it
    Stalled,          ///< a servo met an end stop: the motion ended there, with a fault
    LostSteps,        ///< a stepper met an end stop and runs on against it (the motion goes on)
};

struct AxisConfig {
    Drive drive = Drive::Servo;
    bool rotary = false;                ///< no end stops; a home switch once per turn
    double travel_min_counts = 0;       ///< the end stops (a rotation stage: the span it may run)
    double travel_max_counts = 0;
    double counts_per_turn = 0;         ///< rotary: the home switch sits at every multiple
    double start_position_counts = 0;   ///< where the carriage stands at power-up
    /// What the carriage is (linear, rotary, goniometer: the physical face's metres or radians).
    BodyKind kind = BodyKind::Linear;
    /// Metres (radians for a rotary stage or a goniometer) per count: the stage's resolution, for
    /// the physical face (Body::position_m(), ...). 0: the axis has no face (a test's bare axis).
    double si_per_count = 0;
};

class Axis : public Body {
public:
    using Listener = std::function<void(AxisEvent)>;

    Axis(const Clock& clock, const AxisConfig& config);

    /// Where events go (from on_event(), or from a command whose motion ends at once).
    void set_listener(Listener listener) { listener_ = std::move(listener); }

    /// Carriage position at the clock's now.
    double position_counts() const;
    double velocity_counts_per_s() const;
    /// Microsteps a stepper made against an end stop that the carriage did not follow (signed,
    /// since power-up): its counters count them.
    double lost_counts() const;
    /// Where the motor stands: position_counts() + lost_counts().
    double motor_position_counts() const;
    /// Where the current (or last) profile ends.
    double target_counts() const { return profile_.target(); }
    bool moving() const { return moving_; }

    bool rotary() const { return config_.rotary; }
    double travel_min_counts() const { return config_.travel_min_counts; }
    double travel_max_counts() const { return config_.travel_max_counts; }
    /// The travel the controller allows (the end stops unless narrowed): the axis stops there.
    double limit_min_counts() const { return limit_min_counts_; }
    double limit_max_counts() const { return limit_max_counts_; }
    void set_limits(double min_counts, double max_counts);
    /// Whether the limit switch at each end stops the axis (else the carriage meets the end stop).
    void set_limit_switches(bool forward_stops, bool reverse_stops);
    /// Obstacles met in a collision (carriage counts; std::nullopt: none on that side). Each acts
    /// as the end stop on its side while set, a rotation stage's too: a servo meeting it stalls
    /// there (Stalled), a stepper presses on and loses microsteps (LostSteps); no limit switch is
    /// pressed. A carriage already past one is held where it stands (the obstacle is taken to be
    /// there). Setting or clearing one mid-motion re-plans the motion from now.
    void set_obstacles(std::optional<double> min_counts, std::optional<double> max_counts);
    const std::optional<double>& obstacle_min_counts() const { return obstacle_min_counts_; }
    const std::optional<double>& obstacle_max_counts() const { return obstacle_max_counts_; }
    /// Soft stops in motor position (motor_position_counts()): a crossing stops the axis dead.
    void set_soft_stops(double min_motor_counts, double max_motor_counts);
    void clear_soft_stops();

    /// Where a run toward one end is planned to: past the end stop (a linear axis), where the
    /// limits above end it.
    double run_target_counts(bool forward) const;
    /// The next home switch of a rotation stage ahead of the carriage (once per turn).
    double next_home_switch_counts(bool forward) const;

    /// Move to `target_counts` (a trapezoid; an S-curve if `jerk_counts_per_s3` > 0). A target
    /// past a limit that stops the axis is planned to stop there. Velocity must be > 0.
    void move_to(double target_counts, double velocity_counts_per_s, double acceleration_counts_per_s2,
                 double jerk_counts_per_s3 = 0);
    /// Stop where the carriage is now, without an event.
    void stop_immediately();
    /// Decelerate to rest at `acceleration_counts_per_s2`; Arrived where it comes to rest.
    void stop_profiled(double acceleration_counts_per_s2);

    /// Put the carriage at `counts` (clamped to the end stops), at rest: a hand moved it, or a
    /// test sets it up. The motor's lost steps stay, so the counters follow the carriage.
    void place(double counts);
    /// A jammed axis does not follow its motor: a servo stalls on the tick after a motion
    /// starts (Stalled, where it stands); a stepper's motor runs its profile while the carriage
    /// stays (the microsteps are lost, the motion ends Arrived when the profile does).
    void set_jammed(bool jammed);
    bool jammed() const { return jammed_; }
    /// A stepper loses microsteps in every motion that arrives: `counts` plus `fraction` of the
    /// motion's length (at most all of it). The carriage stops that much short of the target
    /// while the motor, and so the counters, reach it. Servos close the loop and lose nothing.
    void set_slip(double counts, double fraction);
    /// A limit switch reads pressed where the carriage stands (+1 forward, -1 reverse, 0 none):
    /// a motion toward it ends at once as at that limit (if the switch stops the axis).
    void set_switch_pressed(int side);
    int switch_pressed() const { return switch_pressed_; }

    /// The drive cannot move the carriage (a servo whose encoder failed has no position loop):
    /// the axis is jammed while this or a stall fault (faults()) lasts.
    void set_loop_open(bool open);
    /// A limit switch held pressed by hand (a test's set-up: +1, -1, 0): it reads pressed unless a
    /// limit_switch fault (faults()) says otherwise.
    void set_switch_held(int side);
    int switch_held() const { return switch_held_; }
    /// A servo loses no steps (slip); a stepper slips by steps or a fraction, at least one.
    std::optional<std::string> refuses(BodyFault& fault) const override;

    Ticks next_event(Ticks now) const override;
    void on_event(Ticks now) override;

    BodyKind kind() const override { return config_.kind; }
    bool settling() const override { return moving_; }

protected:
    double si_position() const override;
    double si_velocity() const override;
    TravelRange si_travel() const override;
    void si_place(double position) override;
    bool si_stoppable() const override { return true; }
    void si_set_obstacles(std::optional<double> min, std::optional<double> max) override;
    /// A stall jams it, a slip loses steps, a limit_switch fault presses a switch.
    void apply_faults() override;

private:
    /// The axis at one tick of a motion.
    struct Track {
        Ticks tick = 0;
        double position_counts = 0;   ///< carriage
        double lost_counts = 0;       ///< since power-up
        int contact = 0;              ///< +1 / -1: a stepper pressing on the forward / reverse end stop
    };
    /// What happens at a tick, and the axis right after it.
    struct Hit {
        AxisEvent event;
        Track after;
    };
    struct Scan {
        Track track;              ///< at the end of the scan, or just before the hit
        std::optional<Hit> hit;
    };

    /// The first stop ahead in a direction: an obstacle, else (a linear axis) the travel limit;
    /// `stops` if a limit switch or a narrowed travel ends the motion there (else the carriage
    /// meets it: a servo stalls, a stepper presses on).
    struct Stop {
        double at_counts;
        bool stops;
    };
    std::optional<Stop> stop_ahead(bool forward) const;
    /// Profile position at tick `k` (the target from the end of the profile on).
    double profile_at(Ticks k) const;
    bool stops_at(bool forward) const;
    /// A stepper pressing on the end stop ahead (direction `dir`) that does not stop it runs on.
    bool slips(int dir) const;
    /// The per-tick rule at tick `k`: soft stop, limit or end stop, end of profile.
    std::optional<Hit> classify(Ticks k, double profile_before, double profile, double lost_before) const;
    /// Walk the motion from `from` to `until` (at most the end of the profile), piece by monotone
    /// piece; with `find_hits`, stop at the first hit.
    Scan scan(const Track& from, Ticks until, bool find_hits) const;
    /// One monotone piece (s.tick, b]: advances `s`, or returns the first hit in it.
    std::optional<Hit> scan_piece(Track& s, Ticks b, bool find_hits) const;
    /// Ticks at which the motion may turn round (the last tick before each reversal, and the next).
    std::vector<Ticks> piece_ends(Ticks after, Ticks until) const;
    Track now_track() const;
    void start(MotionProfile profile, double from_velocity_counts_per_s);
    /// Anchor the motion at now, under the rules it ran by so far (before they change).
    void settle();
    void replan();
    void apply(Hit hit);
    /// The event a jam or a pressed switch forces on the current motion, if any.
    std::optional<Hit> forced_hit() const;
    /// The direction of the current motion (+1, -1, 0).
    int motion_direction() const;

    const Clock& clock_;
    AxisConfig config_;
    double limit_min_counts_;
    double limit_max_counts_;
    bool forward_switch_stops_ = true;
    bool reverse_switch_stops_ = true;
    bool soft_stops_ = false;
    double soft_min_motor_counts_ = 0;
    double soft_max_motor_counts_ = 0;
    std::optional<double> obstacle_min_counts_;
    std::optional<double> obstacle_max_counts_;

    MotionProfile profile_;
    bool moving_ = false;
    Ticks start_ = 0;            ///< tick the profile was planned at
    Ticks end_ = 0;              ///< tick at which it ends
    double start_velocity_counts_per_s_ = 0;
    double motor_offset_ = 0;    ///< lost steps at the start of the motion
    std::vector<Ticks> turns_;   ///< last tick before each reversal of the profile
    Track anchor_;               ///< last tick the state was settled at (rest: the state)
    std::optional<Hit> pending_;
    Listener listener_;
    bool jammed_ = false;
    double jam_position_counts_ = 0;   ///< where a jammed stepper's carriage stays
    double slip_counts_ = 0;
    double slip_fraction_ = 0;
    double motion_from_counts_ = 0;    ///< where the current motion started (the carriage)
    int switch_pressed_ = 0;
    bool loop_open_ = false;
    int switch_held_ = 0;
};

} // namespace rigsim::models
