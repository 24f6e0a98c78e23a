#pragma once
// The digital PI filter of a piezo controller's closed loop (PZ_SET_PICONSTS, APT manual
// p.99: "the required position is compared with the actual position ... passed through a
// digital PI-type filter ... to develop an output voltage"). Fractions throughout: set point
// and measurement as fractions of the travel, output as a fraction of the maximum voltage.
//
// Gain mapping (a rigsim choice, plan D-12: the manual gives the 0..255 ranges, no units):
//   Kp = PropConst / 255          (255: full output for an error of the whole travel)
//   Ki = 4 * IntConst per second  (IntConst 15, the manual's example: the error integrates to
//                                  the output in 1/60 s)
// The plant (actuator + strain gauge) has a gain of about 1, so the loop's bandwidth is about
// Ki. Measured (default actuator, tau = 1 ms, 1 kHz ticks, 4 kHz loop, a step to mid-travel):
// the overshoot stays under 5 % at every PropConst for IntConst up to 120 with the extension
// fed back every tick, up to 35 through a 500 Hz strain gauge (its hold adds delay); at
// 255/255 it is 21 % and 73 %. So high IntConst overshoots, as a real loop with too much gain
// does; the manual's example (100, 15) does not.
//
// Output clamped to 0..1 with anti-windup: the integrator does not integrate an error that
// pushes a clamped output further, and stays within 0..1 itself. reset() is bumpless: the
// integrator takes the output in force, so switching from open to closed loop does not jump.
// The filter runs at the unit's loop rate (TPZ001/KPZ101 4 kHz, BPC30x 1 kHz: p.109's base
// sample intervals), sub-stepped inside a tick by run(); the measurement is held over a tick.

#include "models/clock.hpp"

#include <cstdint>

namespace rigsim::models {

class PiLoop {
public:
    static constexpr int kMaxConst = 255;

    /// `loop_rate_hz` > 0 (std::invalid_argument otherwise).
    explicit PiLoop(std::uint32_t loop_rate_hz);

    /// PropConst and IntConst, each clamped to 0..255 (the protocol layer refuses the rest).
    void set_gains(int prop, int integral);
    /// PropConst as set (0..255).
    int prop() const { return prop_; }
    /// IntConst as set (0..255).
    int integral() const { return integral_; }
    /// Proportional gain (output fraction per travel fraction).
    double kp() const { return prop_ / 255.0; }
    /// Integral gain (per second).
    double ki_per_s() const { return 4.0 * integral_; }
    /// Filter steps per second.
    std::uint32_t loop_rate_hz() const { return loop_rate_hz_; }

    /// One filter step of `dt_s`: the new output (0..1 of the maximum voltage).
    double step(double setpoint_frac, double measured_frac, double dt_s);
    /// The filter steps due in `elapsed` ticks of a `tick_hz` clock, at the loop rate, with the
    /// measurement held; the output of the last (unchanged if no step is due).
    double run(double setpoint_frac, double measured_frac, Ticks elapsed, std::uint32_t tick_hz);
    /// Bumpless restart: the output (and the integrator) becomes `output_frac` (clamped to 0..1).
    void reset(double output_frac);
    /// Bumpless with an error: the first step after it (same set point and measurement)
    /// outputs `output_frac` (as far as the integrator's 0..1 range allows).
    void reset(double output_frac, double setpoint_frac, double measured_frac);
    /// The longest span run() steps through in one call (s).
    static constexpr double kMaxSpanS = 1.0;
    /// The output of the last step (0..1).
    double output() const { return output_; }

private:
    std::uint32_t loop_rate_hz_;
    int prop_ = 0;
    int integral_ = 0;
    double integrator_ = 0;
    double output_ = 0;
    std::uint64_t phase_ = 0;   ///< loop steps due, in 1/tick_hz units (an exact integer count)
};

} // namespace rigsim::models
