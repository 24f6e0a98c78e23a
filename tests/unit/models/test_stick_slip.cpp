// models::StickSlipPositioner: open-loop bursts, closed-loop profiles and scans as functions
// of clock time, woken by the world only at their events.

#include "models/stick_slip.hpp"
#include "models/world.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

namespace test_stick_slip {

using namespace rigsim;
using namespace rigsim::models;

namespace {

/// A positioner that counts its wake-ups.
class Counted : public StickSlipPositioner {
public:
    using StickSlipPositioner::StickSlipPositioner;
    void on_event(Ticks now) override
    {
        woken.push_back(now);
        StickSlipPositioner::on_event(now);
    }
    std::vector<Ticks> woken;
};

StickSlipConfig plain(double jitter = 0.0, std::uint32_t seed = 1)
{
    StickSlipConfig c;
    c.start_position_nm = 0;
    c.travel_min_nm = -1e9;
    c.travel_max_nm = 1e9;
    c.step_width_nm = 1000;
    c.step_jitter_fraction = jitter;
    c.jitter_seed = seed;
    c.scan_range_nm = 1500;
    return c;
}

StepBurst burst(std::int64_t steps, double frequency_hz, double direction = 1)
{
    StepBurst b;
    b.steps = steps;
    b.direction = direction;
    b.amplitude_levels = 4095;
    b.frequency_hz = frequency_hz;
    return b;
}

/// The positions after each step, drawn the way the positioner draws its jitter.
std::vector<double> reference_steps(std::uint32_t seed, double jitter, int n)
{
    std::vector<double> at;
    double p = 0;
    std::uint32_t state = seed;
    for (int i = 0; i < n; ++i) {
        state = state * 1664525u + 1013904223u;
        const double u = static_cast<double>(state >> 8) / static_cast<double>(1u << 24) * 2.0 - 1.0;
        p += 1000.0 * (1.0 + jitter * u);
        at.push_back(p);
    }
    return at;
}

} // namespace

TEST_CASE("stick-slip: a burst has made floor(t*f) steps at t and ends at its last step's tick",
          "[unit][models][stick_slip]")
{
    Clock clock;
    World world(clock);
    auto& p = world.emplace<Counted>("mcs/0", clock, plain());
    p.start_burst(burst(100, 300));
    CHECK(p.next_event(clock.now()) == 334);   // step 100 is due at 100/300 s = 333.3 ms
    clock.advance(10);
    CHECK(p.steps_done() == 3);
    CHECK(p.position_nm() == 3000.0);
    clock.advance(323);
    CHECK(p.steps_done() == 99);
    CHECK(p.motion() == StickSlipPositioner::Motion::Burst);
    clock.advance(1);
    CHECK(p.motion() == StickSlipPositioner::Motion::Rest);
    CHECK(p.take_outcome() == StickSlipPositioner::Outcome::BurstDone);
    CHECK(p.position_nm() == 100'000.0);
    clock.advance(10'000);
    CHECK(p.woken == std::vector<Ticks>{334});   // one wake-up, at the end, none per step or tick
}

TEST_CASE("stick-slip: the jitter sequence depends on the seed only, not on when anyone looks",
          "[unit][models][stick_slip]")
{
    const auto expected = reference_steps(42, 0.03, 500);
    Clock clock_a, clock_b;
    World world_a(clock_a), world_b(clock_b);
    auto& a = world_a.emplace<Counted>("a/0", clock_a, plain(0.03, 42));
    auto& b = world_b.emplace<Counted>("b/0", clock_b, plain(0.03, 42));
    a.start_burst(burst(500, 1000));
    b.start_burst(burst(500, 1000));
    for (int t = 1; t <= 500; ++t) {   // a is read every tick, b only at the end
        clock_a.advance(1);
        REQUIRE(a.position_nm() == expected[static_cast<std::size_t>(t - 1)]);
    }
    clock_b.advance(500);
    CHECK(b.position_nm() == expected.back());
    CHECK(a.woken == b.woken);

    // The generator goes on from where the last burst left it.
    const auto longer = reference_steps(42, 0.03, 510);
    b.start_burst(burst(10, 1000));
    clock_b.advance(10);
    CHECK(b.position_nm() == longer.back());

    Clock clock_c;
    World world_c(clock_c);
    auto& c = world_c.emplace<Counted>("c/0", clock_c, plain(0.03, 43));
    c.start_burst(burst(500, 1000));
    clock_c.advance(500);
    CHECK(c.position_nm() != expected.back());
}

TEST_CASE("stick-slip: an end stop holds a burst that goes on stepping, a range limit ends it at its tick",
          "[unit][models][stick_slip]")
{
    Clock clock;
    World world(clock);
    auto config = plain();
    config.travel_max_nm = 5500;
    auto& p = world.emplace<Counted>("mcs/0", clock, config);
    p.start_burst(burst(10, 100));
    clock.advance(70);
    CHECK(p.position_nm() == 5500.0);   // held at the end stop since step 6
    CHECK(p.motion() == StickSlipPositioner::Motion::Burst);
    clock.advance(100);
    CHECK(p.take_outcome() == StickSlipPositioner::Outcome::BurstDone);
    CHECK(p.woken == std::vector<Ticks>{100});

    Clock clock2;
    World world2(clock2);
    auto& q = world2.emplace<Counted>("mcs/1", clock2, plain());
    auto limited = burst(0, 100);   // until stopped
    limited.limit.active = true;
    limited.limit.max_nm = 5500;
    q.start_burst(limited);
    CHECK(q.next_event(clock2.now()) == 60);   // step 6 would pass 5500 nm
    clock2.advance(1000);
    CHECK(q.woken == std::vector<Ticks>{60});
    CHECK(q.take_outcome() == StickSlipPositioner::Outcome::LimitMet);
    CHECK(q.position_nm() == 5500.0);
    CHECK(q.steps_done() == 6);
}

TEST_CASE("stick-slip: an endless burst without a limit never wakes the world", "[unit][models][stick_slip]")
{
    Clock clock;
    World world(clock);
    auto& p = world.emplace<Counted>("mcs/0", clock, plain());
    p.start_burst(burst(0, 2000));
    CHECK(p.next_event(clock.now()) == kNever);
    clock.advance(1'000'000);   // 1000 s
    CHECK(p.woken.empty());
    CHECK(p.steps_done() == 2'000'000);
    // Stopping completes the step begun (MST): 5 ms into a 300 Hz burst, step 2 has begun.
    p.start_burst(burst(0, 300));
    clock.advance(5);
    CHECK(p.steps_done() == 1);
    CHECK_FALSE(p.stop_burst());
    CHECK(p.steps_done() == 2);
    CHECK(p.motion() == StickSlipPositioner::Motion::Rest);
    CHECK(p.woken.empty());
}

TEST_CASE("stick-slip: a closed-loop move is sampled exactly and wakes once, at its end tick",
          "[unit][models][stick_slip]")
{
    Clock clock;
    World world(clock);
    auto& p = world.emplace<Counted>("mcs/0", clock, plain());
    const Ticks end = p.move_to(1'000'000, 1'000'000, 0);   // 1 mm at 1 mm/s
    CHECK(end == 1000);
    CHECK(p.next_event(clock.now()) == 1000);
    clock.advance(250);
    CHECK(p.position_nm() == Approx(250'000.0));
    clock.advance(1000);
    CHECK(p.woken == std::vector<Ticks>{1000});
    CHECK(p.take_outcome() == StickSlipPositioner::Outcome::Arrived);
    CHECK(p.position_nm() == 1'000'000.0);
    CHECK(p.move_to(1'000'000, 1'000'000, 0) == clock.now());   // no distance: done at once
    CHECK(p.motion() == StickSlipPositioner::Motion::Rest);
}

TEST_CASE("stick-slip: a scan moves the axis by the scan range per 4095 levels and ends at its tick",
          "[unit][models][stick_slip][piezo]")
{
    Clock clock;
    World world(clock);
    auto& p = world.emplace<Counted>("mcs/0", clock, plain());
    CHECK_FALSE(p.start_scan(4095, 4095));   // a full sweep in one second
    CHECK(p.next_event(clock.now()) == 1000);
    clock.advance(500);
    CHECK(p.scan_level() == Approx(2047.5));
    CHECK(p.position_nm() == Approx(750.0));
    clock.advance(600);
    CHECK(p.woken == std::vector<Ticks>{1000});
    CHECK(p.take_outcome() == StickSlipPositioner::Outcome::ScanDone);
    CHECK(p.scan_level() == 4095.0);
    CHECK(p.position_nm() == Approx(1500.0));
    CHECK(p.start_scan(4095, 10));   // already there: over at once
}

TEST_CASE("stick-slip: an open-loop positioner at rest drifts at drift_nm_per_s and stops at its end stop, "
          "a closed-loop hold does not drift",
          "[unit][models]")
{
    Clock clock;
    World world(clock);
    StickSlipConfig c = plain();
    c.travel_max_nm = 5000;
    c.drift_nm_per_s = 1000;
    auto& p = world.emplace<Counted>("mcs/0", clock, c);
    CHECK(p.next_event(clock.now()) == kNever);
    clock.advance(2000);   // 2 s at 1000 nm/s
    CHECK(p.position_nm() == Approx(2000.0));
    clock.advance(10'000);   // at the end stop after 3 s more: it stays there, without an event
    CHECK(p.position_nm() == 5000.0);
    CHECK(p.woken.empty());
    CHECK(p.next_event(clock.now()) == kNever);

    // A closed-loop move to 1000 nm, then held there: no drift while the hold lasts.
    const Ticks end = p.move_to(1000, 1'000'000, 0);
    clock.advance(end - clock.now());
    CHECK(p.take_outcome() == StickSlipPositioner::Outcome::Arrived);
    p.set_closed_loop_hold(true);
    clock.advance(3000);
    CHECK(p.position_nm() == 1000.0);
    // The hold ends: the drift starts from there, then.
    p.set_closed_loop_hold(false);
    clock.advance(500);
    CHECK(p.position_nm() == Approx(1500.0));
    CHECK(p.woken == std::vector<Ticks>{end});
}

TEST_CASE("stick-slip: a negative drift stops at the minimum end stop, and a drift of 0 never moves",
          "[unit][models]")
{
    Clock clock;
    World world(clock);
    StickSlipConfig c = plain();
    c.travel_min_nm = -300;
    c.drift_nm_per_s = -200;
    auto& p = world.emplace<Counted>("mcs/0", clock, c);
    clock.advance(1000);
    CHECK(p.position_nm() == Approx(-200.0));
    p.set_closed_loop_hold(true);
    p.halt();   // releases the hold
    CHECK_FALSE(p.closed_loop_hold());
    clock.advance(5000);
    CHECK(p.position_nm() == -300.0);
    auto& still = world.emplace<Counted>("mcs/1", clock, plain());
    clock.advance(5000);
    CHECK(still.position_nm() == 0.0);
    CHECK(p.woken.empty());
}

} // namespace test_stick_slip
