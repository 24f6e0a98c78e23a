// Clock: integer ticks, due tickables run in order, idle stretches skipped.
#include "models/clock.hpp"

#include <catch2/catch.hpp>

#include <vector>

namespace test_clock {

using namespace rigsim;

namespace {

/// Wants a tick at every multiple of `period`, records when it ran.
struct Periodic : Tickable {
    explicit Periodic(Ticks p) : period(p) {}
    Ticks next_change(Ticks now) const override { return (now / period + 1) * period; }
    void tick(Ticks now) override { ran.push_back(now); }
    Ticks period;
    std::vector<Ticks> ran;
};

struct Idle : Tickable {
    Ticks next_change(Ticks) const override { return kNever; }
    void tick(Ticks) override { ++ticks; }
    int ticks = 0;
};

} // namespace

TEST_CASE("clock runs tickables exactly at their due ticks", "[unit][clock]")
{
    Clock clock(1000);
    Periodic p(250);
    Idle idle;
    clock.add(&p);
    clock.add(&idle);
    clock.advance(1000);
    CHECK(clock.now() == 1000);
    CHECK(p.ran == std::vector<Ticks>{250, 500, 750, 1000});
    CHECK(idle.ticks == 0);
    clock.remove(&p);
    clock.advance(1'000'000'000);   // idle: skipped in one step
    CHECK(clock.now() == 1'000'001'000);
    CHECK(p.ran.size() == 4);
}

TEST_CASE("clock converts milliseconds to ticks rounding up", "[unit][clock]")
{
    CHECK(Clock(1000).ticks_from_ms(1500) == 1500);
    CHECK(Clock(300).ticks_from_ms(10) == 3);
    CHECK(Clock(100).ticks_from_ms(1) == 1);
    CHECK(Clock(1000).seconds(250) == Approx(0.25));
    CHECK_THROWS(Clock(0));
}

} // namespace test_clock
