// A moving MCS positioner costs no clock wake-ups between the events of its movement
// (issue 10: state is a function of clock time, the world wakes a body only when due).
#include "mcs_harness.hpp"

#include <catch2/catch.hpp>

namespace test_mcs_wakeups {

using rigsim::Ticks;
using rigsim::test::McsHarness;
using rigsim::test::mcs_device_config;

namespace {

/// Advance `ms` milliseconds one wake-up at a time; returns how many ticks ran.
int wakeups_over(McsHarness& h, std::int64_t ms)
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

} // namespace

TEST_CASE("MCS: moving channels wake the clock at their events only, not once per tick",
          "[device][mcs][wakeups]")
{
    McsHarness h(mcs_device_config(3));
    CHECK(h.send(":SCM1\n:SRC0,1\n:SRC1,1\n:SRC2,1\n") == "");
    // A 10 mm move at 10 mm/s (1 s), an endless step burst, a 2 s scan.
    CHECK(h.send(":MPA0,10000000,0\n:MST1,30000,4095,1000\n:MSCA2,4095,2047\n") == "");
    CHECK(wakeups_over(h, 900) == 0);
    CHECK(h.send(":GS0\n:GS1\n:GS2\n") == ":S0,4\n:S1,1\n:S2,2\n");
    CHECK(wakeups_over(h, 200) == 1);   // the move's end
    CHECK(h.send("") == ":C0\n");
    CHECK(wakeups_over(h, 1000) == 1);  // the scan's end
    CHECK(h.send("") == ":C2\n");
    CHECK(wakeups_over(h, 60'000) == 0);   // a minute of open-loop steps
    CHECK(h.send(":GS1\n:S1\n:GS1\n") == ":S1,1\n:S1,0\n");
}

TEST_CASE("MCS: busy() while a channel calibrates, waits out a power-save move delay or holds for a time, not for the keep-alive",
          "[device][mcs][wakeups]")
{
    McsHarness h(mcs_device_config(1));
    CHECK_FALSE(h.device().busy());
    CHECK(h.send(":CS0\n") == ":E0,0\n");   // calibrating (status 6): no body moves, the device waits
    CHECK(h.send(":GS0\n") == ":S0,6\n");
    CHECK(h.device().busy());
    while (h.device().busy())
        h.clock().advance_to(h.clock().next_wakeup());
    CHECK(h.send(":GS0\n") == ":S0,0\n");

    CHECK(h.send(":SSE2\n:MPA0,1000,0\n") == ":E-1,0\n:E0,0\n");   // power save: the move waits (status 5)
    CHECK(h.send(":GS0\n") == ":S0,5\n");
    CHECK(h.device().busy());
    h.advance_ms(1000);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,1000\n");
    CHECK_FALSE(h.device().busy());

    CHECK(h.send(":SSE1\n:MPA0,2000,500\n") == ":E-1,0\n:E0,0\n");   // then holds 500 ms
    h.advance_ms(100);
    CHECK(h.send(":GS0\n") == ":S0,3\n");
    CHECK(h.device().busy());   // the hold ends by itself
    h.advance_ms(500);
    CHECK(h.send(":GS0\n") == ":S0,0\n");
    CHECK_FALSE(h.device().busy());

    CHECK(h.send(":K5000\n") == ":E-1,0\n");   // a keep-alive deadline is not work a test waits for
    CHECK(h.clock().next_wakeup() != rigsim::kNever);
    CHECK_FALSE(h.device().busy());
}

} // namespace test_mcs_wakeups
