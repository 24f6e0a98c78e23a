// models::StrainGauge: reads a PiezoActuator of the world, sample-and-hold at 500 Hz, noise from a
// hash of (seed, sample index), an 8-sample mean, zeroing; no wake-ups while nothing moves.

#include "models/piezo_actuator.hpp"
#include "models/strain_gauge.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace test_strain_gauge {

using namespace rigsim;
using namespace rigsim::models;

namespace {

PiezoActuatorConfig lag_only()
{
    PiezoActuatorConfig c;
    c.hysteresis = 0;
    c.creep = 0;
    return c;
}

StrainGaugeConfig on(const std::string& key, double noise_um = 0, std::uint32_t seed = 1)
{
    StrainGaugeConfig g;
    g.actuator_key = key;
    g.noise_um = noise_um;
    g.seed = seed;
    return g;
}

/// A piezo and its gauge on a 1 kHz clock; the gauge's key sorts first (it is linked to a later body).
struct Stage {
    Clock clock;
    World world{clock};
    StrainGauge& gauge;   // added first
    PiezoActuator& piezo;
    explicit Stage(double noise_um = 0, std::uint32_t seed = 1, PiezoActuatorConfig c = lag_only())
        : gauge(world.emplace<StrainGauge>("a-tsg/0", clock, on("tpz/0", noise_um, seed))),
          piezo(world.emplace<PiezoActuator>("tpz/0", clock, c))
    {
        world.link_all();
    }
};

} // namespace

TEST_CASE("strain gauge: reads its actuator's extension, held at 500 Hz", "[unit][models][piezo]")
{
    Stage s;
    CHECK(s.gauge.actuator() == &s.piezo);
    s.piezo.set_voltage(60);
    double sampled = 0;
    for (Ticks t = 1; t <= 40; ++t) {
        s.clock.advance(1);
        if (t % 2 == 0)   // sample k at tick 2k on a 1 kHz clock
            sampled = s.piezo.extension_um();
        CHECK(s.gauge.sample_index(t) == t / 2);
        // Exact while the actuator moves; at rest (from ~15 ms) the gauge holds its last
        // sample, within the actuator's settling tolerance (1e-6 of the travel).
        REQUIRE(s.gauge.reading_um(t) == Approx(sampled).margin(2e-5));
        if (t <= 14)
            REQUIRE(s.gauge.reading_um(t) == sampled);
    }
    CHECK(s.gauge.reading_um(40) == Approx(16.0).epsilon(1e-6));
}

TEST_CASE("strain gauge: the same instant reads the same value whoever asks", "[unit][models][piezo]")
{
    auto run = [](bool read_often, std::uint32_t seed) {
        Stage s(0.01, seed, PiezoActuatorConfig{});
        std::vector<double> x;
        for (double v : {30.0, 75.0, 5.0}) {
            s.piezo.set_voltage(v);
            for (int i = 1; i <= 100; ++i) {
                s.clock.advance(1);
                if (read_often)
                    s.gauge.smoothed_um(s.clock.now());
            }
            x.push_back(s.gauge.reading_um(s.clock.now()));
            x.push_back(s.gauge.smoothed_um(s.clock.now()));
        }
        s.clock.advance(123'457);   // long after everything settled: no wake-ups, same samples
        x.push_back(s.gauge.reading_um(s.clock.now()));
        return x;
    };
    const auto once = run(false, 7);
    CHECK(run(true, 7) == once);
    CHECK(run(false, 8) != once);
}

TEST_CASE("strain gauge: the noise has the configured sigma, the smoothed reading is the mean "
          "of the last 8 samples",
          "[unit][models][piezo]")
{
    Stage s(0.01);
    s.piezo.set_voltage(37.5);
    s.clock.advance(100);
    REQUIRE(s.clock.next_wakeup() == kNever);   // at rest
    const int n = 20'000;
    double sum = 0, sum2 = 0, smooth2 = 0;
    for (int i = 0; i < n; ++i) {
        s.clock.advance(2);
        const Ticks now = s.clock.now();
        const double e = s.gauge.reading_um(now) - 10.0;
        sum += e;
        sum2 += e * e;
        const double sm = s.gauge.smoothed_um(now) - 10.0;
        smooth2 += sm * sm;
        if (i % 1000 == 0) {
            double mean = 0;
            for (int j = 0; j < 8; ++j)
                mean += s.gauge.reading_um(now - 2 * j) / 8;
            REQUIRE(s.gauge.smoothed_um(now) == Approx(mean).margin(1e-12));
        }
    }
    CHECK(sum / n == Approx(0).margin(3 * 0.01 / std::sqrt(n)));
    CHECK(std::sqrt(sum2 / n) == Approx(0.01).epsilon(0.03));
    CHECK(std::sqrt(smooth2 / n) == Approx(0.01 / std::sqrt(8.0)).epsilon(0.05));

    s.gauge.set_noise_um(0);
    CHECK(s.gauge.reading_um(s.clock.now()) == Approx(10.0).margin(1e-5));
    CHECK_THROWS_AS(s.gauge.set_noise_um(-1), std::invalid_argument);
}

TEST_CASE("strain gauge: zeroing makes the reading relative to where the actuator stands",
          "[unit][models][piezo]")
{
    Stage s;
    s.piezo.set_voltage(15);
    s.clock.advance(100);
    s.gauge.zero(s.clock.now());
    CHECK(s.gauge.zero_offset_um() == Approx(4.0).margin(1e-5));
    CHECK(s.gauge.reading_um(s.clock.now()) == Approx(0).margin(1e-12));
    CHECK(s.gauge.smoothed_um(s.clock.now()) == Approx(0).margin(1e-12));
    s.piezo.set_voltage(30);
    s.clock.advance(100);
    CHECK(s.gauge.reading_um(s.clock.now()) == Approx(4.0).margin(1e-5));
}

TEST_CASE("strain gauge: it is woken at its samples only while the actuator moves",
          "[unit][models][piezo]")
{
    Stage s;
    CHECK(s.clock.next_wakeup() == kNever);
    s.clock.advance(11);
    s.piezo.set_voltage(40);
    CHECK(s.world.next_change(s.clock.now()) == 12);   // the actuator; the gauge's next sample too
    s.clock.advance(40);
    CHECK(s.clock.next_wakeup() == kNever);
    const double held = s.gauge.reading_um(s.clock.now());
    CHECK(held == Approx(40.0 * 20 / 75).margin(1e-5));
    s.clock.advance(1'000'000);
    CHECK(s.gauge.reading_um(s.clock.now()) == held);
}

TEST_CASE("strain gauge: a missing or unfit actuator key is refused when linked",
          "[unit][models][piezo]")
{
    Clock clock;
    World world(clock);
    world.emplace<StrainGauge>("tsg/0", clock, on("tpz/9"));
    CHECK_THROWS_WITH(world.link_all(), "strain gauge \"tsg/0\": the world has no body \"tpz/9\" to be mounted on");

    World other(clock);
    other.emplace<StrainGauge>("tsg/0", clock, on("tsg/1"));
    other.emplace<StrainGauge>("tsg/1", clock, on("tsg/0"));
    CHECK_THROWS_WITH(other.link_all(), "strain gauge \"tsg/0\": \"tsg/1\" is not a piezo actuator");

    StrainGaugeConfig zero_rate = on("tpz/0");
    zero_rate.sample_hz = 0;
    CHECK_THROWS_AS(StrainGauge(clock, zero_rate), std::invalid_argument);
}

} // namespace test_strain_gauge
