#pragma once
// A piezo inertia actuator (Thorlabs PIA series) driven open loop by a KIM101/TIM101 piezo motor
// controller: each drive pulse (a "step": the voltage ramps up slowly and drops at once) moves the
// screw by one step length, a longer one forward than in reverse (issue 37 p. 396: "the inherent
// nature of the PIA actuators going further in one direction as compared with another"). A step's
// length scales with the drive voltage, as a stick-slip step's does with its amplitude. Against an
// end stop (or an obstacle, or while stalled) the pulses go on and the screw stays.
//
// A run of pulses is planned once, as an exact trapezoid in pulses (MotionProfile: the step rate
// ramps up at the step acceleration); its state is a function of clock time, so the world wakes
// the body only when a run ends. The body counts the pulses it was driven (signed: forward
// positive); a controller's position counter is an offset of that count (open loop: it counts
// pulses, not distance). Only the timing, the pulses and the distance live here; the protocol
// (channels, jog sizes, the counter's zero) is the module's (emulator/apt/pzmot_module.*).
//
// Units: nm inside, metres at the face (a linear body).

#include "models/clock.hpp"
#include "models/motion_profile.hpp"
#include "models/owned_listener.hpp"
#include "models/world.hpp"

#include <cstdint>
#include <optional>

namespace rigsim::models {

/// The actuator as built (config).
struct InertialDriveConfig {
    double travel_min_nm = 0;           ///< the reverse end stop
    double travel_max_nm = 13e6;        ///< the forward end stop (a PIA13: 13 mm)
    double start_nm = 6.5e6;
    double step_forward_nm = 20;        ///< one forward pulse at the reference voltage
    double step_reverse_nm = 18;        ///< one reverse pulse at the reference voltage
    double reference_voltage_v = 110;   ///< the drive voltage the step lengths are given at
};

class InertialDrive : public Body {
public:
    /// Told when a run of pulses ends by itself (all pulses made), at its tick.
    using Listener = std::function<void(Ticks at)>;

    InertialDrive(const Clock& clock, const InertialDriveConfig& config);

    void set_listener(const void* owner, Listener listener) { listener_.set(owner, std::move(listener)); }
    void clear_listener(const void* owner) { listener_.clear(owner); }

    /// From now, `pulses` pulses (> 0) in `direction` (+1 forward, -1 reverse) at up to
    /// `rate_per_s` pulses a second, the rate ramping up at `accel_per_s2` (0: at once), with
    /// `voltage_v` drive. A run under way stops first where it is (a pulse has no momentum).
    /// std::nullopt pulses: until stopped.
    void run(int direction, std::optional<std::int64_t> pulses, double rate_per_s, double accel_per_s2,
             double voltage_v);
    /// Stop now, after the pulses made so far (no event; a run already at its end ends as it would).
    void stop();
    /// Put the screw at `nm` (clamped to the end stops), at rest.
    void place(double nm);

    /// Pulses driven since the body was made, forward positive, whole pulses only.
    std::int64_t pulses() const;
    double position_nm() const;
    bool running() const;
    /// +1 forward, -1 reverse, 0 at rest.
    int direction() const { return running() ? direction_ : 0; }
    /// Whether the run under way was asked for without an end.
    bool endless() const { return running() && endless_; }
    /// Pulses a second now (0 at rest).
    double rate_per_s() const;
    double stop_min_nm() const;
    double stop_max_nm() const;
    const InertialDriveConfig& config() const { return config_; }

    Ticks next_event(Ticks now) const override;
    void on_event(Ticks now) override;
    BodyKind kind() const override { return BodyKind::Linear; }
    std::optional<std::string> refuses(BodyFault& fault) const override;
    bool settling() const override { return running(); }

protected:
    double si_position() const override { return position_nm() * 1e-9; }
    double si_velocity() const override;
    TravelRange si_travel() const override { return {config_.travel_min_nm * 1e-9, config_.travel_max_nm * 1e-9}; }
    void si_place(double position) override { place(position * 1e9); }
    bool si_stoppable() const override { return true; }
    void si_set_obstacles(std::optional<double> min, std::optional<double> max) override;
    void apply_faults() override;

private:
    /// Pulses made in the run under way at `now` (whole pulses).
    std::int64_t run_pulses_at(Ticks now) const;
    /// The length of one pulse of the run under way (nm, >= 0), the slip taken off.
    double pulse_nm() const;
    /// Start the distance over from where the screw is now (the stops, the slip or a stall changed).
    void rebase();
    /// End a run whose end tick has come before anything replaces or stops it.
    void finish_due();

    const Clock& clock_;
    InertialDriveConfig config_;
    double base_nm_;                    ///< where the screw was at base_pulses_ of the run
    std::int64_t base_pulses_ = 0;
    std::int64_t pulses_before_ = 0;    ///< pulses of the runs before this one
    MotionProfile profile_;
    Ticks start_ = 0;
    Ticks end_ = 0;
    bool running_ = false;
    bool endless_ = false;
    int direction_ = 1;
    double voltage_v_ = 110;
    std::optional<double> obstacle_min_nm_;
    std::optional<double> obstacle_max_nm_;
    std::optional<double> stalled_at_nm_;
    double slip_ = 0;
    OwnedListener<Ticks> listener_;
};

} // namespace rigsim::models
