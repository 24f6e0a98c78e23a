#pragma once
// A piezo stack actuator driven by an amplifier (TPZ001, KPZ101, a BPC30x bay): its extension
// follows the drive voltage with a first-order lag, open-loop hysteresis and creep. No
// protocol: the piezo module clips and slews the voltage before set_voltage() and turns the
// extension into codes; a strain gauge (models/strain_gauge.hpp) reads the extension.
//
// Model, per step of dt seconds (one tick, or any span a read extrapolates over):
//   u   += (v - u)(1 - e^{-dt/tau})            the stack's charge lags the amplifier's voltage v:
//                                               exact for any dt while v is constant, so ticks
//                                               and reads agree and a skipped tick changes nothing
//   y_i  = max(u - r_i, min(u + r_i, y_i))      Prandtl-Ishlinskii hysteresis: 8 play operators of
//                                               thresholds r_i = (i + 1/2)/8 * h' * Vmax, equal
//                                               weights, h' = h / (1 + h); a play output depends
//                                               only on u's path, and u between two steps is
//                                               monotone, so dt does not change it either. At
//                                               power-up y_i = r_i: the state at 0 V after a cycle
//   x_h  = travel * (mean(y_i) - m) / (Vmax - 2m)  m = mean(r_i): both branches of the loop meet
//                                               at 0 V (x_h = 0) and at Vmax (x_h = travel), so
//                                               the actuator reaches its travel at its rating; in
//                                               between the rising branch sits below and the
//                                               falling branch above the line, h * travel apart
//                                               at mid-range (exact while r_7 <= Vmax/4, i.e.
//                                               h <= 0.36; the config allows 0..0.3)
//   c_k += (g * x_h - c_k)(1 - e^{-dt/tau_k})   creep: 4 Kelvin-Voigt elements, tau_k = t0 * 10^k
//                                               (t0 = 100 ms: 0.1, 1, 10, 100 s), so a step of x_h
//   x    = x_h + sum(c_k)                       creeps g * step per decade of time from t0 to 100 t0
//                                               (0.999, 0.990 g), 0.905 g in the next decade, then
//                                               stops at 4 g * step: the logarithmic creep of piezo
//                                               stacks over the seconds to minutes a scan lasts
// h = 0 makes every play the identity and g = 0 keeps c_k at 0: x = travel/Vmax * u, an exact
// first-order lag (golden transcripts rely on it).
//
// Cost: the world wakes the actuator every tick only while u has not reached v (to within
// 1e-6 of the travel); creep alone needs no steps (x_h is then constant, its elements decay in
// closed form), so one wake-up ends it, at the tick it is within 1e-6 of the travel too. At
// rest next_event() is kNever. Reads between wake-ups extrapolate without changing the state.

#include "models/clock.hpp"
#include "models/world.hpp"

#include <array>
#include <functional>
#include <vector>

namespace rigsim::models {

struct PiezoActuatorConfig {
    double travel_um = 20;        ///< extension at max_voltage_v (without creep)
    double max_voltage_v = 75;    ///< the actuator's rating (75, 100 or 150 V)
    double response_ms = 1.0;     ///< first-order time constant tau
    double hysteresis = 0.05;     ///< major-loop width / travel (0..0.3)
    double creep = 0.01;          ///< creep per decade of time / step (0..0.05)
    double creep_t0_ms = 100;     ///< the shortest creep time constant
};

class PiezoActuator : public Body {
public:
    static constexpr int kPlays = 8;
    static constexpr int kCreepElements = 4;
    /// Called after every set_voltage() (a strain gauge starts sampling again).
    using Listener = std::function<void()>;

    /// std::invalid_argument for a travel, voltage, time constant or creep t0 <= 0, or a
    /// hysteresis or creep outside 0..0.5.
    PiezoActuator(const Clock& clock, const PiezoActuatorConfig& config);

    /// Drive voltage from now on (V; the amplifier's output after its clip and slew limit).
    void set_voltage(double v);
    /// The drive voltage last set (V).
    double voltage() const { return voltage_v_; }
    /// Physical extension at the clock's now (µm).
    double extension_um() const;
    /// True once the extension moves by less than 1e-6 of the travel from now on.
    bool settled() const;
    /// The configuration as built.
    const PiezoActuatorConfig& config() const { return config_; }
    /// Call `listener` after every set_voltage().
    void add_listener(Listener listener) { listeners_.push_back(std::move(listener)); }

    Ticks next_event(Ticks now) const override;
    void on_event(Ticks now) override;

    BodyKind kind() const override { return BodyKind::PiezoActuator; }
    bool settling() const override { return !settled(); }

protected:
    /// The extension (m); its rate as the first-order lag makes it (toward the extension the
    /// voltage asks for, over the response time; hysteresis and creep aside), 0 once settled;
    /// the travel 0 to the rated extension. A piezo is not placed (its voltage sets it) and
    /// pushes on against an obstacle.
    double si_position() const override { return extension_um() * 1e-6; }
    double si_velocity() const override;
    TravelRange si_travel() const override { return {0.0, config_.travel_um * 1e-6}; }

private:
    struct State {
        double u_v = 0;                               ///< lagged (charge) voltage
        std::array<double, kPlays> play_v{};          ///< play operator outputs
        std::array<double, kCreepElements> creep_um{};
    };
    /// `s` after dt seconds at the drive voltage.
    State advanced(const State& s, double dt_s) const;
    State state_at(Ticks now) const;
    double hysteretic_um(const State& s) const;
    double extension_of(const State& s) const;
    bool response_settled(const State& s) const;
    /// Seconds until every creep element is within tolerance of its target (0 if already).
    double creep_settle_s(const State& s) const;

    const Clock& clock_;
    PiezoActuatorConfig config_;
    std::array<double, kPlays> threshold_v_{};
    std::array<double, kCreepElements> creep_tau_s_{};
    double tolerance_um_;
    double voltage_v_ = 0;
    State state_;
    double mean_threshold_v_ = 0;   ///< m of the hysteresis normalisation
    Ticks state_tick_ = 0;   ///< the tick state_ describes
    std::vector<Listener> listeners_;
};

} // namespace rigsim::models
