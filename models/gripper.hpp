#pragma once
// A piezo gripper (the SmarAct MCS end effector, manual 3.2): jaws driven by a voltage that
// ramps at a set speed, closing on an object they hold. The jaws touch the object at
// `contact_cv`; beyond it the object pushes back with `stiffness_dun_per_cv` per 1/100 V, which
// a force sensor on the jaws reads.
//
// Units inside: the drive's 1/100 V (cV) and tenths of µN (dun), the resolution the controller
// drives and reads; the physical face adds the SI forms (voltage_v, force_n). A ramp is exact:
// the voltage is a function of clock time, sampled when read, and the world wakes the gripper
// only at the tick its ramp reaches the target. No protocol: what the voltage and the force mean
// to a client (opening, closed-loop force, zeroing, status codes) is the controller's.

#include "models/clock.hpp"
#include "models/world.hpp"

#include <cstdint>
#include <functional>

namespace rigsim::models {

/// The object between the jaws (config).
struct GripperConfig {
    std::int32_t contact_cv = 8'000;           ///< the jaws touch the object at this voltage
    std::int32_t stiffness_dun_per_cv = 5;     ///< the object pushes back beyond it
};

class Gripper : public Body {
public:
    /// std::invalid_argument for a stiffness <= 0 or a contact < 0.
    Gripper(const Clock& clock, GripperConfig config);

    /// Called at the tick a ramp reaches its target (and at once for a ramp with nowhere to go).
    void set_listener(std::function<void()> listener) { listener_ = std::move(listener); }
    const GripperConfig& config() const { return config_; }
    const Clock& clock() const { return clock_; }

    /// The drive voltage now (1/100 V).
    double voltage_cv() const;
    /// Ramp from the voltage now to `target_cv` at `speed_v_per_s` (> 0).
    void ramp_to(double target_cv, std::int32_t speed_v_per_s);
    /// The voltage stays where it is now; a ramp under way ends without reaching its target.
    void hold();
    /// Put the voltage at `cv`, at rest (power-up: 0, fully open).
    void set_voltage(double cv);
    bool ramping() const { return ramping_; }
    /// The force the jaws press on the object now (1/10 µN): 0 up to the contact.
    double force_dun() const;

    // The physical face in SI units.
    double voltage_v() const { return voltage_cv() / 100.0; }
    double force_n() const { return force_dun() * 1e-7; }

    BodyKind kind() const override { return BodyKind::Gripper; }
    bool settling() const override { return ramping_; }
    Ticks next_event(Ticks now) const override;
    void on_event(Ticks now) override;

private:
    const Clock& clock_;
    GripperConfig config_;
    std::function<void()> listener_;
    bool ramping_ = false;
    double voltage_cv_ = 0;            ///< at rest, or where the ramp started
    double ramp_to_cv_ = 0;
    double ramp_cv_per_tick_ = 0;
    Ticks ramp_start_ = 0;
    Ticks ramp_end_ = 0;               ///< tick at which the voltage reaches ramp_to_cv_
};

} // namespace rigsim::models
