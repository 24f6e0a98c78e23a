// models::PiLoop: PICONSTS gains (plan D-12), clamped output with anti-windup, bumpless reset,
// sub-stepped at the loop rate; closed on a PiezoActuator it holds a set point against creep.

#include "models/pi_loop.hpp"
#include "models/piezo_actuator.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

namespace test_pi_loop {

using namespace rigsim;
using namespace rigsim::models;

namespace {

struct Response {
    double peak_frac = 0;    ///< highest position reached (fraction of the travel)
    double final_frac = 0;   ///< position at the end
    double worst_hold_frac = 0;   ///< largest |position - set point| over the hold window
};

/// Closes `pi` on an actuator: every tick, measure the extension, run the filter, set the voltage.
/// The hold window is the last `hold_ticks` of `ticks`.
Response closed_loop(PiLoop& pi, const PiezoActuatorConfig& config, double setpoint_frac, Ticks ticks,
                     Ticks hold_ticks = 0)
{
    Clock clock;
    World world(clock);
    auto& p = world.emplace<PiezoActuator>("tpz/0", clock, config);
    Response r;
    for (Ticks t = 0; t < ticks; ++t) {
        const double measured = p.extension_um() / config.travel_um;
        p.set_voltage(pi.run(setpoint_frac, measured, 1, clock.tick_hz()) * config.max_voltage_v);
        clock.advance(1);
        const double x = p.extension_um() / config.travel_um;
        r.peak_frac = std::max(r.peak_frac, x);
        if (t >= ticks - hold_ticks)
            r.worst_hold_frac = std::max(r.worst_hold_frac, std::abs(x - setpoint_frac));
    }
    r.final_frac = p.extension_um() / config.travel_um;
    return r;
}

} // namespace

TEST_CASE("PI loop: PropConst and IntConst map to Kp = Prop/255 and Ki = 4 Int per second",
          "[unit][models][piezo]")
{
    PiLoop pi(4000);
    pi.set_gains(100, 15);   // the manual's example (p.99)
    CHECK(pi.prop() == 100);
    CHECK(pi.integral() == 15);
    CHECK(pi.kp() == Approx(100.0 / 255));
    CHECK(pi.ki_per_s() == 60.0);
    pi.set_gains(300, -1);   // the protocol layer refuses these; the model clamps
    CHECK(pi.prop() == 255);
    CHECK(pi.integral() == 0);
    CHECK_THROWS_AS(PiLoop(0), std::invalid_argument);

    pi.set_gains(51, 0);     // proportional only: 0.2 per unit of error
    CHECK(pi.step(0.5, 0.25, 1e-3) == Approx(0.05));
}

TEST_CASE("PI loop: the output is clamped to 0..1 and the integrator does not wind up",
          "[unit][models][piezo]")
{
    PiLoop pi(1000);
    pi.set_gains(0, 255);
    for (int i = 0; i < 10'000; ++i)   // 10 s against an unreachable set point
        pi.step(1.5, 0.2, 1e-3);
    CHECK(pi.output() == 1.0);
    pi.step(0.5, 1.0, 1e-3);          // the error reverses: the output leaves the clamp at once
    CHECK(pi.output() == Approx(1.0 - 1020 * 0.5 * 1e-3));
    for (int i = 0; i < 10'000; ++i)
        pi.step(-0.5, 0.3, 1e-3);
    CHECK(pi.output() == 0.0);
    pi.step(0.5, 0.0, 1e-3);
    CHECK(pi.output() == Approx(1020 * 0.5 * 1e-3));
}

TEST_CASE("PI loop: reset is bumpless", "[unit][models][piezo]")
{
    PiLoop pi(4000);
    pi.set_gains(100, 15);
    pi.reset(0.4);
    CHECK(pi.output() == 0.4);
    CHECK(pi.step(0.3, 0.3, 2.5e-4) == 0.4);   // no error: the output stays where it was
    pi.reset(1.7);
    CHECK(pi.output() == 1.0);
    // With an error in force, the proportional term must not jump the first step: it moves
    // only by the integral of one step, Ki * error * dt.
    const double error = 0.2;
    pi.reset(0.4, 0.5, 0.5 - error);
    CHECK(pi.step(0.5, 0.5 - error, 2.5e-4) == Approx(0.4 + pi.ki_per_s() * error * 2.5e-4).epsilon(1e-12));
}

TEST_CASE("PI loop: run() takes the steps of the loop rate inside the ticks", "[unit][models][piezo]")
{
    PiLoop stepped(4000);
    PiLoop manual(4000);
    stepped.set_gains(20, 200);
    manual.set_gains(20, 200);
    stepped.run(0.6, 0.1, 1, 1000);    // one 1 kHz tick: four 250 µs steps
    for (int i = 0; i < 4; ++i)
        manual.step(0.6, 0.1, 1.0 / 4000);
    CHECK(stepped.output() == manual.output());

    PiLoop slow(1000);                 // a 1 kHz loop on a 3 kHz clock: a step every third tick
    slow.set_gains(0, 100);
    CHECK(slow.run(0.5, 0.0, 1, 3000) == 0.0);
    CHECK(slow.run(0.5, 0.0, 1, 3000) == 0.0);
    CHECK(slow.run(0.5, 0.0, 1, 3000) == Approx(400 * 0.5 * 1e-3));
    CHECK(slow.run(0.5, 0.0, 6, 3000) == Approx(3 * 400 * 0.5 * 1e-3));

    // After a long sleep (a simulated day at 4 kHz would be 3.5e8 steps) one call takes at
    // most kMaxSpanS of steps: the same output as a call over exactly that span. A module in
    // closed loop therefore runs the loop every tick (it never sleeps through one).
    PiLoop slept(4000);
    PiLoop capped(4000);
    slept.set_gains(10, 1);
    capped.set_gains(10, 1);
    slept.run(0.01, 0.0, 86'400'000, 1000);
    capped.run(0.01, 0.0, static_cast<Ticks>(PiLoop::kMaxSpanS * 1000), 1000);
    CHECK(slept.output() == capped.output());
    CHECK(capped.output() < 0.1);   // not saturated: a day of steps would have integrated to 1
}

TEST_CASE("PI loop: on a creeping actuator it holds the set point within 0.1 % of the travel",
          "[unit][models][piezo]")
{
    PiezoActuatorConfig c;   // 20 µm, 75 V, tau 1 ms, hysteresis 0.05
    c.creep = 0.05;          // the most the config allows
    PiLoop pi(4000);
    pi.set_gains(100, 15);
    const Response held = closed_loop(pi, c, 0.5, 61'000, 60'000);   // 1 s to settle, then 60 s
    CHECK(held.worst_hold_frac < 1e-3);

    // The same actuator in open loop at the voltage the loop settled to drifts by creep.
    Clock clock;
    World world(clock);
    auto& open = world.emplace<PiezoActuator>("tpz/0", clock, c);
    open.set_voltage(pi.output() * c.max_voltage_v);
    clock.advance(1000);
    const double at_1s = open.extension_um();
    clock.advance(60'000);
    CHECK((open.extension_um() - at_1s) / c.travel_um > 0.01);
}

TEST_CASE("PI loop: a step response overshoots by less than 5 % over a grid of gains",
          "[unit][models][piezo]")
{
    PiezoActuatorConfig c;   // defaults (tau 1 ms, hysteresis 0.05) without creep: a slow loop
    c.creep = 0;             // (Int 1: Ki = 4/s) lags creep by ~0.1 %, which is not overshoot
    for (int prop : {0, 100, 255}) {
        for (int integral : {1, 15, 100}) {
            CAPTURE(prop, integral);
            PiLoop pi(4000);
            pi.set_gains(prop, integral);
            const Response r = closed_loop(pi, c, 0.5, 5000);
            CHECK(r.peak_frac < 0.5 * 1.05);
            CHECK(r.final_frac == Approx(0.5).margin(1e-3));
        }
    }
}

} // namespace test_pi_loop
