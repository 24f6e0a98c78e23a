#pragma once
// A body of the world (models/world.hpp): a moving part under a stable key, woken only at its
// events, and its physical face.
//
// The physical face is what everything that is not a protocol talks to (kinematic chains,
// collisions, the control API's physical state): the body's kind, and its one degree of
// freedom in SI units with the unit in every name: metres for a body that travels along a
// line (a linear stage, a piezo actuator), radians for one that turns (a rotation stage, a
// goniometer). A body keeps its own resolution inside (an axis counts encoder counts or
// microsteps, a stick-slip positioner nm or µ°) and converts at the face; the protocol's scale
// (a controller's counts per mm) lives in the device that translates.

#include "models/clock.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rigsim::models {

class World;

/// What a body is.
enum class BodyKind {
    Linear,          ///< a carriage along a line (m)
    Rotary,          ///< a rotation stage: no end stops (rad)
    Goniometer,      ///< a cradle turning about a centre above it, between end stops (rad)
    PiezoActuator,   ///< a piezo stack that extends along a line (m); it pushes on: no obstacle stops it
    Gripper,         ///< jaws on a drive voltage closing on an object: no travel of its own (voltage, force)
    Solenoid,        ///< an output that opens and closes: no travel
    Flipper,         ///< a flip mount's arm between two positions: no travel of its own
    Paddle,          ///< a polarisation controller's fibre paddle: turns 0..170 degrees, not a joint
    StrainGauge,     ///< a sensor: no travel
    Watch,           ///< not a part: a watch over others (collisions)
};

/// The kind's name as the control API and the rig JSON spell it ("linear", "piezo_actuator", ...).
std::string_view body_kind_name(BodyKind kind);

/// How a body of a kind moves: along a line (its face in m), about an axis (rad), or not at all.
enum class Travel { None, Line, Angle };
Travel travel_of(BodyKind kind);

/// The physical faults a body may suffer (the control API's device faults that act on the stage
/// a channel drives: docs/control-api.md "Faults"). A lost reference, a power cycle and the
/// link's faults are the device's, not the body's.
enum class PhysicalFault {
    Stall,           ///< the body moves no further: a servo stalls, a stepper's carriage stays, a stick-slip stage is blocked
    Slip,            ///< part of each motion is lost (a stepper's microsteps, a stick-slip step's length)
    LimitSwitch,     ///< a limit switch reads pressed where the carriage stands
    SensorFailure,   ///< the position sensor (an encoder, an MCS sensor) reads nothing
};

/// One physical fault with its parameters, as the control API gives them.
struct BodyFault {
    PhysicalFault kind = PhysicalFault::Stall;
    std::optional<double> slip_steps;      ///< slip: the body's own steps lost per motion (a stepper's microsteps), >= 0
    std::optional<double> slip_fraction;   ///< slip: the part of each motion lost, 0..1
    int switch_side = 0;                   ///< limit_switch: +1 the forward switch, -1 the reverse one
};

/// Every physical fault active on a body, combined (World::add_fault).
struct PhysicalFaults {
    bool stalled = false;
    double slip_steps = 0;       ///< the sum of the slips' steps
    double slip_fraction = 0;    ///< each slip takes its part of what the others left: 1 - Π(1 - f)
    int switch_pressed = 0;      ///< the newest limit_switch fault's side; 0: none
    bool sensor_failed = false;
};

/// Where a body may stand: its end stops (±infinity where it has none).
struct TravelRange {
    double min = 0;
    double max = 0;
};

/// A moving part of the world.
class Body {
public:
    virtual ~Body() = default;
    /// Earliest tick (> now) at which on_event() must run, or kNever while only sampling
    /// changes the state (at rest, or in the middle of a planned profile).
    virtual Ticks next_event(Ticks now) const = 0;
    /// Handle what is due at `now` (an end of move, a limit met, ...).
    virtual void on_event(Ticks now) = 0;
    /// Resolve the keys of other bodies this one reads (World::link_all(), once every body
    /// exists, so a body may be added before the one it reads). std::invalid_argument for a
    /// missing or unfit body.
    virtual void link(World& world) { (void)world; }
    /// A body watching `body` (World::watch()) hears here that `body` was rescheduled: a
    /// motion of it started, changed or ended.
    virtual void on_watched(Body& body) { (void)body; }
    /// Bodies due at the same tick run in phase order: a body that reads the others at their
    /// state after the tick (a collision watch) has a later phase than the bodies it reads.
    virtual int phase() const { return 0; }

    const std::string& key() const { return key_; }

    // ---- The physical face ----
    virtual BodyKind kind() const = 0;
    Travel travel() const { return travel_of(kind()); }

    /// Position and velocity now. The _m forms for a body that travels along a line, the _rad
    /// forms for one that turns; the other forms, and any form on a body without travel, throw
    /// std::logic_error.
    double position_m() const;
    double angle_rad() const;
    double velocity_m_per_s() const;
    double angular_velocity_rad_per_s() const;
    /// The end stops.
    TravelRange travel_m() const;
    TravelRange travel_rad() const;
    /// Put the body at rest at a position (clamped to its end stops): a hand moved it, or a test
    /// sets it up.
    void place_m(double position);
    void place_rad(double angle);
    /// Whether an obstacle (a collision) stops the body; a piezo pushes on.
    bool stoppable() const { return si_stoppable(); }
    /// Obstacles met in a collision, each acting as the end stop on its side while set
    /// (std::nullopt clears that side); std::logic_error on a body that is not stoppable().
    void set_obstacles_m(std::optional<double> min, std::optional<double> max);
    void set_obstacles_rad(std::optional<double> min, std::optional<double> max);
    /// Something about the body still changes without a new command: a motion under way, a
    /// piezo settling or creeping, a solenoid cycling, a gauge sampling toward its reading.
    virtual bool settling() const { return false; }

    /// Why the body cannot take `fault` (a servo loses no steps, a stick-slip positioner has no
    /// limit switches, a piezo none of them), or std::nullopt; it may fill in a parameter's
    /// default (a stick-slip slip without a fraction loses half of each step). The message names
    /// the API's field ("kind", "counts", "fraction").
    virtual std::optional<std::string> refuses(BodyFault& fault) const;
    /// The physical faults acting on the body now (World::add_fault, World::remove_fault).
    const PhysicalFaults& faults() const { return faults_; }

protected:
    /// faults() changed: the body applies them to its physics (a jam, a slip, a switch).
    virtual void apply_faults() {}

    /// Tell the world that next_event() changed (call after every command that starts,
    /// changes or stops a motion). Harmless before the body joined a world.
    void reschedule();

    // The face's one implementation, in the unit of travel() (m or rad). A body without
    // travel keeps the defaults, which throw std::logic_error.
    virtual double si_position() const;
    virtual double si_velocity() const;
    virtual TravelRange si_travel() const;
    virtual void si_place(double position);
    virtual bool si_stoppable() const { return false; }
    virtual void si_set_obstacles(std::optional<double> min, std::optional<double> max);

private:
    friend class World;
    /// std::logic_error unless the body travels as `unit` says (`what` names the form called).
    void expect(Travel unit, const char* what) const;

    World* world_ = nullptr;
    std::string key_;
    PhysicalFaults faults_;
    std::uint64_t generation_ = 0;   ///< scheduled wake-ups of older generations are void
    std::vector<Body*> watchers_;    ///< told on every reschedule of this body
};

} // namespace rigsim::models
