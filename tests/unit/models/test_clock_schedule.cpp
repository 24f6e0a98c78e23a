// The clock's schedule (models/clock.hpp, "The schedule"): the answers of Announced tickables
// are kept between their announcements, and every change the rules promise to see is seen.
#include "models/clock.hpp"

#include <catch2/catch.hpp>

#include <functional>
#include <vector>

namespace test_clock_schedule {

using namespace rigsim;

namespace {

/// Due at `due` (kNever: idle); counts how often it is asked, records when it ran. Its tick
/// runs `on_tick`, which may set any timer (its own: `due`; another's).
struct Timer : Tickable {
    Ticks next_change(Ticks now) const override
    {
        ++asked;
        return due > now ? due : (due == kNever ? kNever : now + 1);
    }
    void tick(Ticks now) override
    {
        ran.push_back(now);
        due = kNever;
        if (on_tick)
            on_tick(now);
    }
    Ticks due = kNever;
    mutable int asked = 0;
    std::vector<Ticks> ran;
    std::function<void(Ticks)> on_tick;
};

/// A clock that keeps its schedule, with `a` and `b` Announced (in that order).
struct Kept {
    Kept()
    {
        clock.add(&a, Clock::Schedule::Announced);
        clock.add(&b, Clock::Schedule::Announced);
        clock.keep_schedule();
    }
    Clock clock{1000};
    Timer a, b;
};

} // namespace

TEST_CASE("a kept schedule asks an Announced tickable again only when it is announced", "[unit][clock]")
{
    // A build without NDEBUG asks every kept answer again at each next_wakeup() to check it: the
    // counts hold where the schedule is not checked.
    Kept k;
    CHECK(k.clock.next_wakeup() == kNever);
    const int asked_a = k.a.asked, asked_b = k.b.asked;
    for (int i = 0; i < 10; ++i)
        CHECK(k.clock.next_wakeup() == kNever);
    k.clock.advance(1000);   // nothing due: one jump
#ifdef NDEBUG
    CHECK(k.a.asked == asked_a);
    CHECK(k.b.asked == asked_b);
#endif

    k.b.due = 1500;
    k.clock.changed(k.b);
    CHECK(k.clock.next_wakeup() == 1500);
    CHECK(k.clock.next_wakeup() == 1500);
#ifdef NDEBUG
    CHECK(k.a.asked == asked_a);       // a not at all
    CHECK(k.b.asked == asked_b + 1);   // b once
#endif
    (void)asked_a;
    (void)asked_b;
    k.clock.advance(1000);
    CHECK(k.b.ran == std::vector<Ticks>{1500});
    CHECK(k.clock.next_wakeup() == kNever);
}

TEST_CASE("a kept schedule sees the timer a tickable sets in its own tick", "[unit][clock]")
{
    Kept k;
    k.a.due = 10;
    k.a.on_tick = [&](Ticks now) {
        if (now < 40)
            k.a.due = now + 10;   // periodic, re-armed in its tick, never announced
    };
    k.clock.changed(k.a);
    k.clock.advance(100);
    CHECK(k.a.ran == std::vector<Ticks>{10, 20, 30, 40});
}

TEST_CASE("a kept schedule sees the timers one tickable's tick starts in another, the same tick and later",
          "[unit][clock]")
{
    // As a body's event in the world (registered first) starts its device's timer.
    Kept k;
    k.a.due = 5;
    k.a.on_tick = [&](Ticks now) {
        if (now == 5) {
            k.b.due = now;   // due at once: runs in the same tick, after a
            k.a.due = 7;
        } else {
            k.b.due = now + 3;   // later: seen without an announcement
        }
    };
    k.clock.changed(k.a);
    k.clock.advance(100);
    CHECK(k.a.ran == std::vector<Ticks>{5, 7});
    CHECK(k.b.ran == std::vector<Ticks>{5, 10});
}

TEST_CASE("a kept schedule: the earliest answer moving later leaves the next earliest", "[unit][clock]")
{
    Kept k;
    k.a.due = 10;
    k.b.due = 20;
    k.clock.changed_all();
    CHECK(k.clock.next_wakeup() == 10);
    k.a.due = 30;   // later than announced: announce it (a later answer kept too early only costs a wake-up)
    k.clock.changed(k.a);
    CHECK(k.clock.next_wakeup() == 20);
    k.b.due = kNever;
    k.clock.changed(k.b);
    CHECK(k.clock.next_wakeup() == 30);
    k.clock.advance(100);
    CHECK(k.a.ran == std::vector<Ticks>{30});
    CHECK(k.b.ran.empty());
}

TEST_CASE("a kept answer earlier than the truth wakes the clock but runs nothing early", "[unit][clock]")
{
    Kept k;
    k.a.due = 10;
    k.clock.changed(k.a);
    CHECK(k.clock.next_wakeup() == 10);
    k.a.due = 20;   // moved later and not announced: allowed, the clock asks before it ticks
    k.clock.advance(15);
    CHECK(k.a.ran.empty());
    CHECK(k.clock.next_wakeup() == 20);
    k.clock.advance(10);
    CHECK(k.a.ran == std::vector<Ticks>{20});
}

TEST_CASE("an Asked tickable is asked at every wake-up, announced or not", "[unit][clock]")
{
    Kept k;
    Timer asked;
    k.clock.add(&asked);
    CHECK(k.clock.next_wakeup() == kNever);
    asked.due = 50;   // never announced
    CHECK(k.clock.next_wakeup() == 50);
    k.clock.advance(100);
    CHECK(asked.ran == std::vector<Ticks>{50});
    k.clock.remove(&asked);
}

TEST_CASE("a clock that keeps no schedule asks every tickable afresh at every call", "[unit][clock]")
{
    // A test stepping the clock by hand and changing devices directly (the default).
    Clock clock(1000);
    Timer t;
    clock.add(&t, Clock::Schedule::Announced);
    CHECK_FALSE(clock.keeps_schedule());
    CHECK(clock.next_wakeup() == kNever);
    t.due = 5;   // never announced
    CHECK(clock.next_wakeup() == 5);
    clock.advance(10);
    CHECK(t.ran == std::vector<Ticks>{5});
}

TEST_CASE("changed_all() asks every Announced tickable again, and remove() keeps the others' answers", "[unit][clock]")
{
    Kept k;
    Timer c;
    k.clock.add(&c, Clock::Schedule::Announced);
    CHECK(k.clock.next_wakeup() == kNever);
    k.a.due = 30;
    k.b.due = 20;
    c.due = 10;
    k.clock.changed_all();
    CHECK(k.clock.next_wakeup() == 10);
    k.clock.remove(&c);
    CHECK(k.clock.next_wakeup() == 20);
    k.clock.changed(c);   // no longer registered: nothing
    k.clock.advance(100);
    CHECK(k.b.ran == std::vector<Ticks>{20});
    CHECK(k.a.ran == std::vector<Ticks>{30});
    CHECK(c.ran.empty());
}

} // namespace test_clock_schedule
