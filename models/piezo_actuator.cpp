#include "models/piezo_actuator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rigsim::models {

namespace {

void require(bool ok, const char* what)
{
    if (!ok)
        throw std::invalid_argument(std::string("piezo actuator: ") + what);
}

} // namespace

PiezoActuator::PiezoActuator(const Clock& clock, const PiezoActuatorConfig& config)
    : clock_(clock), config_(config), tolerance_um_(1e-6 * config.travel_um)
{
    require(config.travel_um > 0, "travel_um must be > 0");
    require(config.max_voltage_v > 0, "max_voltage_v must be > 0");
    require(config.response_ms > 0, "response_ms must be > 0");
    require(config.hysteresis >= 0 && config.hysteresis <= 0.5, "hysteresis must be in 0..0.5");
    require(config.creep >= 0 && config.creep <= 0.5, "creep must be in 0..0.5");
    require(config.creep_t0_ms > 0, "creep_t0_ms must be > 0");
    // h' = h / (1 + h): after the normalisation of hysteretic_um() the loop is h * travel wide.
    const double h_v = config.hysteresis / (1 + config.hysteresis) * config.max_voltage_v;
    double sum_v = 0;
    for (int i = 0; i < kPlays; ++i) {
        threshold_v_[i] = (i + 0.5) / kPlays * h_v;
        state_.play_v[i] = threshold_v_[i];   // at 0 V, where the loop's branches meet
        sum_v += threshold_v_[i];
    }
    mean_threshold_v_ = sum_v / kPlays;
    for (int k = 0; k < kCreepElements; ++k)
        creep_tau_s_[k] = config.creep_t0_ms * 1e-3 * std::pow(10.0, k);
}

PiezoActuator::State PiezoActuator::advanced(const State& s, double dt_s) const
{
    State n = s;
    if (dt_s <= 0)
        return n;
    n.u_v += (voltage_v_ - s.u_v) * -std::expm1(-dt_s / (config_.response_ms * 1e-3));
    for (int i = 0; i < kPlays; ++i)
        n.play_v[i] = std::max(n.u_v - threshold_v_[i], std::min(n.u_v + threshold_v_[i], s.play_v[i]));
    const double target_um = config_.creep * hysteretic_um(n);
    for (int k = 0; k < kCreepElements; ++k)
        n.creep_um[k] += (target_um - s.creep_um[k]) * -std::expm1(-dt_s / creep_tau_s_[k]);
    return n;
}

PiezoActuator::State PiezoActuator::state_at(Ticks now) const
{
    return now > state_tick_ ? advanced(state_, clock_.seconds(now - state_tick_)) : state_;
}

double PiezoActuator::hysteretic_um(const State& s) const
{
    double sum_v = 0;
    for (double y : s.play_v)
        sum_v += y;
    return config_.travel_um * (sum_v / kPlays - mean_threshold_v_) / (config_.max_voltage_v - 2 * mean_threshold_v_);
}

double PiezoActuator::extension_of(const State& s) const
{
    double x = hysteretic_um(s);
    for (double c : s.creep_um)
        x += c;
    return x;
}

bool PiezoActuator::response_settled(const State& s) const
{
    return std::abs(voltage_v_ - s.u_v) * config_.travel_um / config_.max_voltage_v <= tolerance_um_;
}

double PiezoActuator::creep_settle_s(const State& s) const
{
    const double target_um = config_.creep * hysteretic_um(s);
    double t = 0;
    for (int k = 0; k < kCreepElements; ++k) {
        const double off = std::abs(target_um - s.creep_um[k]);
        if (off > tolerance_um_)
            t = std::max(t, creep_tau_s_[k] * std::log(off / tolerance_um_));
    }
    return t;
}

void PiezoActuator::set_voltage(double v)
{
    const Ticks now = clock_.now();
    state_ = state_at(now);
    state_tick_ = now;
    voltage_v_ = v;
    reschedule();
    for (const auto& listener : listeners_)
        listener();
}

double PiezoActuator::extension_um() const
{
    return extension_of(state_at(clock_.now()));
}

double PiezoActuator::si_velocity() const
{
    if (settled())
        return 0.0;
    // µm per ms is mm per s: * 1e-3 for m/s.
    return (config_.travel_um * voltage_v_ / config_.max_voltage_v - extension_um()) / config_.response_ms * 1e-3;
}

bool PiezoActuator::settled() const
{
    const State s = state_at(clock_.now());
    return response_settled(s) && creep_settle_s(s) == 0;
}

Ticks PiezoActuator::next_event(Ticks now) const
{
    const State s = state_at(now);
    if (!response_settled(s))
        return now + 1;
    const double creep_s = creep_settle_s(s);
    if (creep_s == 0)
        return kNever;
    // x_h no longer moves: the creep elements decay in closed form; one wake-up ends them.
    const double ticks = std::ceil(creep_s * clock_.tick_hz());
    return ticks >= 4e18 ? kNever : now + std::max<Ticks>(1, static_cast<Ticks>(ticks));
}

void PiezoActuator::on_event(Ticks now)
{
    state_ = state_at(now);
    state_tick_ = now;
}

} // namespace rigsim::models
