// models::PiezoActuator: first-order response, Prandtl-Ishlinskii hysteresis, logarithmic creep,
// and wake-ups only while it moves.

#include "models/piezo_actuator.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace test_piezo_actuator {

using namespace rigsim;
using namespace rigsim::models;

namespace {

PiezoActuatorConfig linear(double response_ms)
{
    PiezoActuatorConfig c;
    c.travel_um = 20;
    c.max_voltage_v = 75;
    c.response_ms = response_ms;
    c.hysteresis = 0;
    c.creep = 0;
    return c;
}

/// Extension after each voltage of `volts`, each held for `hold` ticks.
std::vector<double> drive(Clock& clock, PiezoActuator& p, const std::vector<double>& volts, Ticks hold)
{
    std::vector<double> x;
    for (double v : volts) {
        p.set_voltage(v);
        clock.advance(hold);
        x.push_back(p.extension_um());
    }
    return x;
}

std::vector<double> ramp(double from, double to, double step)
{
    std::vector<double> v;
    const int n = static_cast<int>(std::lround(std::abs(to - from) / step));
    for (int i = 1; i <= n; ++i)
        v.push_back(from + (to - from) * i / n);
    return v;
}

} // namespace

TEST_CASE("piezo actuator: without hysteresis and creep a step is the exact first-order lag",
          "[unit][models][piezo]")
{
    for (std::uint32_t hz : {1000u, 10'000u}) {
        Clock clock(hz);
        World world(clock);
        auto& p = world.emplace<PiezoActuator>("tpz/0", clock, linear(1.0));
        const double k = 20.0 / 75.0;
        p.set_voltage(70);
        CHECK(p.voltage() == 70);
        for (Ticks t = 1; t <= 20 * static_cast<Ticks>(hz) / 1000; ++t) {
            clock.advance(1);
            const double s = clock.seconds(t);
            REQUIRE(p.extension_um() == Approx(k * 70 * (1 - std::exp(-s / 1e-3))).margin(1e-9));
        }
        // A second step from where the first one stands: the lag starts again from there.
        const double x0 = p.extension_um();
        const Ticks t0 = clock.now();
        p.set_voltage(20);
        for (int i = 0; i < 7; ++i) {
            clock.advance(3);
            const double s = clock.seconds(clock.now() - t0);
            REQUIRE(p.extension_um() == Approx(k * 20 + (x0 - k * 20) * std::exp(-s / 1e-3)).margin(1e-9));
        }
    }
}

TEST_CASE("piezo actuator: a voltage cycle opens a hysteresis loop of the configured width, "
          "the same on every run",
          "[unit][models][piezo]")
{
    auto cycle = [](double hysteresis) {
        Clock clock;
        World world(clock);
        PiezoActuatorConfig c = linear(0.1);
        c.hysteresis = hysteresis;
        auto& p = world.emplace<PiezoActuator>("tpz/0", clock, c);
        std::vector<double> x = drive(clock, p, ramp(0, 75, 0.5), 2);     // 150 points up
        const auto down = drive(clock, p, ramp(75, 0, 0.5), 2);           // 150 points down
        x.insert(x.end(), down.begin(), down.end());
        return x;
    };
    const auto x = cycle(0.05);
    // Mid-range (37.5 V): rising point 74, falling point 150 + 74 (both at 37.5 V).
    const double width_um = x[150 + 74] - x[74];
    CHECK(width_um == Approx(0.05 * 20).epsilon(1e-3));
    CHECK(x[74] == Approx(20.0 * 37.5 / 75 - 0.025 * 20).epsilon(1e-3));   // rising branch below
    CHECK(x.back() == Approx(0).margin(1e-6));                              // the branches meet at 0 V
    CHECK(x[149] == Approx(20.0).epsilon(1e-3));                            // and at the rating: full travel
    CHECK(cycle(0.05) == x);                                                // deterministic to the bit
    CHECK(cycle(0.2)[150 + 74] - cycle(0.2)[74] == Approx(0.2 * 20).epsilon(1e-3));
    const auto none = cycle(0);
    CHECK(none[150 + 74] - none[74] == Approx(0).margin(1e-9));
}

TEST_CASE("piezo actuator: a step creeps by the configured fraction per decade of time",
          "[unit][models][piezo]")
{
    Clock clock;
    World world(clock);
    PiezoActuatorConfig c = linear(1.0);
    c.creep = 0.01;
    auto& p = world.emplace<PiezoActuator>("tpz/0", clock, c);
    p.set_voltage(75);
    std::vector<double> at;   // extension at 0.1, 1, 10, 100 s
    for (Ticks t : {100, 1000, 10'000, 100'000}) {
        clock.advance_to(t);
        at.push_back(p.extension_um());
    }
    // Elements of 0.1, 1, 10 and 100 s: 0.999, 0.990 and 0.905 times the creep in the three
    // decades (the slowest element is 63 % through at 100 s).
    CHECK((at[1] - at[0]) / 20.0 == Approx(0.01 * 0.999).epsilon(1e-2));
    CHECK((at[2] - at[1]) / 20.0 == Approx(0.01 * 0.990).epsilon(1e-2));
    CHECK((at[3] - at[2]) / 20.0 == Approx(0.01 * 0.905).epsilon(1e-2));
}

TEST_CASE("piezo actuator: woken every tick while it responds, once for creep, never at rest",
          "[unit][models][piezo]")
{
    Clock clock;
    World world(clock);
    auto& lag = world.emplace<PiezoActuator>("tpz/0", clock, linear(1.0));
    CHECK(lag.settled());
    CHECK(world.next_change(0) == kNever);
    lag.set_voltage(50);
    CHECK_FALSE(lag.settled());
    CHECK(world.next_change(0) == 1);
    clock.advance(5);
    CHECK(world.next_change(clock.now()) == clock.now() + 1);
    clock.advance(30);   // 1e-6 of the travel after ln(50/75e-6)*tau = 13.4 ms
    CHECK(lag.settled());
    CHECK(world.next_change(clock.now()) == kNever);
    CHECK(lag.extension_um() == Approx(20.0 * 50 / 75).margin(1e-9));

    PiezoActuatorConfig c = linear(1.0);
    c.creep = 0.01;
    auto& creeping = world.emplace<PiezoActuator>("tpz/1", clock, c);
    creeping.set_voltage(75);
    clock.advance(30);
    CHECK_FALSE(creeping.settled());
    const Ticks end = world.next_change(clock.now());
    CHECK(end > clock.now() + 100'000);   // one wake-up, minutes away (the 100 s element)
    CHECK(end < kNever);
    clock.advance_to(end);
    CHECK(creeping.settled());
    CHECK(world.next_change(clock.now()) == kNever);
}

TEST_CASE("piezo actuator: reads do not change what it does", "[unit][models][piezo]")
{
    auto run = [](bool read_often) {
        Clock clock;
        World world(clock);
        PiezoActuatorConfig c;   // defaults: hysteresis and creep on
        auto& p = world.emplace<PiezoActuator>("tpz/0", clock, c);
        std::vector<double> x;
        for (double v : {30.0, 75.0, 10.0, 40.0}) {
            p.set_voltage(v);
            for (int i = 0; i < 40; ++i) {
                clock.advance(7);
                if (read_often || i == 39)
                    x.push_back(p.extension_um());
            }
        }
        return read_often ? std::vector<double>{x[39], x[79], x[119], x[159]} : x;
    };
    CHECK(run(true) == run(false));
}

TEST_CASE("piezo actuator: a configuration out of range is refused", "[unit][models][piezo]")
{
    Clock clock;
    auto bad = [&](auto change) {
        PiezoActuatorConfig c;
        change(c);
        return [&clock, c] { PiezoActuator p(clock, c); };
    };
    CHECK_THROWS_AS(bad([](auto& c) { c.travel_um = 0; })(), std::invalid_argument);
    CHECK_THROWS_AS(bad([](auto& c) { c.max_voltage_v = -75; })(), std::invalid_argument);
    CHECK_THROWS_AS(bad([](auto& c) { c.response_ms = 0; })(), std::invalid_argument);
    CHECK_THROWS_AS(bad([](auto& c) { c.hysteresis = 0.6; })(), std::invalid_argument);
    CHECK_THROWS_AS(bad([](auto& c) { c.creep = -0.01; })(), std::invalid_argument);
    CHECK_THROWS_AS(bad([](auto& c) { c.creep_t0_ms = 0; })(), std::invalid_argument);
    CHECK_NOTHROW(bad([](auto&) {})());
}

} // namespace test_piezo_actuator
