// An MCS controller on a clock that keeps its schedule, as the daemon's does (models/clock.hpp,
// "The schedule"): the clock asks the device for its next change only after its tick, any tick,
// or its announcement that a session's commands were handled. Every step goes to two harnesses,
// one on such a clock, and both must answer the same and wake at the same ticks: a timer a
// command starts and nobody announces (a calibration, a power-save move delay, a hold, the
// keep-alive) would be missed by the one that keeps its schedule.
#include "mcs_harness.hpp"

#include <catch2/catch.hpp>

#include <string>

namespace test_mcs_schedule {

using rigsim::Ticks;
using rigsim::test::McsHarness;
using rigsim::test::mcs_device_config;

namespace {

/// The same controller twice: `asked` on the tests' clock, `kept` on one that keeps its schedule.
class Twin {
public:
    explicit Twin(std::size_t channels) : asked_(mcs_device_config(channels)), kept_(mcs_device_config(channels))
    {
        kept_.keep_schedule();
    }
    /// Bytes to both; their answers (the same, checked), and both due next at the same tick.
    std::string send(const std::string& bytes)
    {
        const auto a = asked_.send(bytes);
        const auto k = kept_.send(bytes);
        INFO("sent " << bytes);
        CHECK(k == a);
        CHECK(kept_.clock().next_wakeup() == asked_.clock().next_wakeup());
        return k;
    }
    /// Both clocks `ms` on, one wake-up at a time; the number of wake-ups (the same, checked).
    int advance_ms(std::int64_t ms)
    {
        const int a = wakeups_over(asked_, ms);
        const int k = wakeups_over(kept_, ms);
        CHECK(k == a);
        return k;
    }

private:
    static int wakeups_over(McsHarness& h, std::int64_t ms)
    {
        const Ticks end = h.clock().now() + h.clock().ticks_from_ms(ms);
        int wakeups = 0;
        for (Ticks next = h.clock().next_wakeup(); next <= end; next = h.clock().next_wakeup()) {
            h.clock().advance_to(next);
            ++wakeups;
        }
        h.clock().advance_to(end);
        return wakeups;
    }

    McsHarness asked_;
    McsHarness kept_;
};

} // namespace

TEST_CASE("mcs schedule: the timers commands start, on a kept schedule", "[device][mcs][clock]")
{
    Twin t(2);
    CHECK(t.send(":CS0\n") == ":E0,0\n");   // calibrating: the device's own timer
    CHECK(t.advance_ms(10'000) >= 1);
    CHECK(t.send(":GS0\n") == ":S0,0\n");
    CHECK(t.send(":SSE2\n:MPA0,1000,0\n") == ":E-1,0\n:E0,0\n");   // power save: a move delay
    CHECK(t.send(":GS0\n") == ":S0,5\n");
    CHECK(t.advance_ms(1000) >= 1);
    CHECK(t.send(":GS0\n:GP0\n") == ":S0,0\n:P0,1000\n");
    CHECK(t.send(":SSE1\n:MPA0,2000,500\n") == ":E-1,0\n:E0,0\n");   // then a hold of 500 ms
    t.advance_ms(100);
    CHECK(t.send(":GS0\n") == ":S0,3\n");
    t.advance_ms(500);
    CHECK(t.send(":GS0\n") == ":S0,0\n");
    CHECK(t.send(":K500\n") == ":E-1,0\n");   // the keep-alive: every command counts
    CHECK(t.send(":SCM1\n:MPA1,5000000,0\n") == "");   // asynchronous: its end comes by itself
    t.advance_ms(400);
    CHECK(t.send(":GS1\n") == ":S1,4\n");
    t.advance_ms(501);                      // no command for 500 ms: every positioner stops
    CHECK(t.send(":GS1\n") == ":S1,0\n");
    CHECK(t.send(":SCM0\n:K0\n") == ":E-1,0\n:E-1,0\n");
    CHECK(t.send(":MPA1,0,0\n") == ":E1,0\n");
    t.advance_ms(2000);
    CHECK(t.send(":GP1\n") == ":P1,0\n");
}

} // namespace test_mcs_schedule
