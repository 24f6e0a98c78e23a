#include "models/pi_loop.hpp"

#include <algorithm>
#include <stdexcept>

namespace rigsim::models {

PiLoop::PiLoop(std::uint32_t loop_rate_hz) : loop_rate_hz_(loop_rate_hz)
{
    if (loop_rate_hz == 0)
        throw std::invalid_argument("PI loop: the loop rate must be > 0 Hz");
}

void PiLoop::set_gains(int prop, int integral)
{
    prop_ = std::clamp(prop, 0, kMaxConst);
    integral_ = std::clamp(integral, 0, kMaxConst);
}

double PiLoop::step(double setpoint_frac, double measured_frac, double dt_s)
{
    const double error = setpoint_frac - measured_frac;
    const double wanted = kp() * error + integrator_;
    const bool pushes_further = (wanted >= 1 && error > 0) || (wanted <= 0 && error < 0);
    if (!pushes_further)
        integrator_ = std::clamp(integrator_ + ki_per_s() * error * dt_s, 0.0, 1.0);
    output_ = std::clamp(kp() * error + integrator_, 0.0, 1.0);
    return output_;
}

double PiLoop::run(double setpoint_frac, double measured_frac, Ticks elapsed, std::uint32_t tick_hz)
{
    if (elapsed <= 0 || tick_hz == 0)
        return output_;
    // Integer bookkeeping: `phase_` counts loop periods times tick_hz, so a 4 kHz loop on a 1 kHz
    // clock takes exactly 4 steps a tick and a 1 kHz loop on a 3 kHz clock one every 3 ticks.
    // Over a span longer than kMaxSpanS (a module that slept) the held measurement has long
    // settled the filter: only the last kMaxSpanS of steps are taken, so one call stays bounded.
    const auto max_elapsed = static_cast<Ticks>(kMaxSpanS * tick_hz);
    phase_ += static_cast<std::uint64_t>(std::min(elapsed, max_elapsed)) * loop_rate_hz_;
    const std::uint64_t steps = phase_ / tick_hz;
    phase_ %= tick_hz;
    const double dt_s = 1.0 / loop_rate_hz_;
    for (std::uint64_t i = 0; i < steps; ++i)
        step(setpoint_frac, measured_frac, dt_s);
    return output_;
}

void PiLoop::reset(double output_frac)
{
    output_ = std::clamp(output_frac, 0.0, 1.0);
    integrator_ = output_;
    phase_ = 0;
}

void PiLoop::reset(double output_frac, double setpoint_frac, double measured_frac)
{
    reset(output_frac);
    // The proportional term of the first step is already in the output: the integrator
    // takes the rest, so that step starts where the output is.
    integrator_ = std::clamp(output_ - kp() * (setpoint_frac - measured_frac), 0.0, 1.0);
}

} // namespace rigsim::models
