// Ticker: the one Asio timer pacing the Clock. A real io_context, run for short bounded
// stretches; the assertions are on clock ticks and on whether the timer is armed, and where
// time has to pass, on relations to wall time measured around the call (a tick k is never
// run before start + k / (tick_hz * time_scale), and never later than the tick due at the
// last measurement), which scheduling noise cannot break.
#include "emulator/daemon/ticker.hpp"

#include <catch2/catch.hpp>

#include <boost/asio/io_context.hpp>

#include <chrono>
#include <cmath>
#include <functional>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace test_ticker {

using namespace rigsim;
using namespace std::chrono_literals;

namespace {

using SteadyClock = std::chrono::steady_clock;

/// Wants to run at the ticks in `due`; records the ticks it ran at and the wall time of each.
class Wakeups : public Tickable {
public:
    explicit Wakeups(std::set<Ticks> due = {}) : due(std::move(due)) {}

    Ticks next_change(Ticks now) const override
    {
        const auto it = due.upper_bound(now);
        return it == due.end() ? kNever : *it;
    }
    void tick(Ticks now) override
    {
        ran.push_back(now);
        ran_at.push_back(SteadyClock::now());
    }

    std::set<Ticks> due;
    std::vector<Ticks> ran;
    std::vector<SteadyClock::time_point> ran_at;
};

/// Wants to run at every multiple of `period`; counts its ticks (cheap for long runs).
class Every : public Tickable {
public:
    explicit Every(Ticks period) : period_(period) {}
    Ticks next_change(Ticks now) const override { return (now / period_ + 1) * period_; }
    void tick(Ticks now) override
    {
        ++count;
        last = now;
    }

    std::int64_t count = 0;
    Ticks last = 0;

private:
    Ticks period_;
};

/// The tick due `elapsed` after the ticker's start, computed as the ticker does.
Ticks due_after(SteadyClock::duration elapsed, std::uint32_t tick_hz, double time_scale)
{
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(elapsed).count();
    return static_cast<Ticks>(
        std::floor(static_cast<long double>(ns) * tick_hz * time_scale / 1e9L));
}

/// The earliest wall time tick k may run, given that the ticker started at or after `t0`.
SteadyClock::time_point earliest_wall_of(Ticks k, SteadyClock::time_point t0, std::uint32_t tick_hz,
                                         double time_scale)
{
    const long double ns = static_cast<long double>(k) * 1e9L / (static_cast<long double>(tick_hz) * time_scale);
    return t0 + std::chrono::nanoseconds(static_cast<std::int64_t>(std::floor(ns)));
}

/// Whether anything (the ticker's timer) is pending on `io`: runs what is ready without
/// blocking; an io_context without pending work stops.
bool armed(boost::asio::io_context& io)
{
    io.restart();
    io.poll();
    return !io.stopped();
}

/// Runs handlers one by one until `done()` or the polling deadline; the handlers run.
std::size_t run_until(boost::asio::io_context& io, const std::function<bool()>& done,
                      SteadyClock::duration budget = 5s)
{
    const auto deadline = SteadyClock::now() + budget;
    std::size_t handlers = 0;
    while (!done() && SteadyClock::now() < deadline) {
        io.restart();
        handlers += io.run_one_until(deadline);
    }
    return handlers;
}

} // namespace

TEST_CASE("ticker: nothing due, nothing armed: an idle rig costs no wake-ups", "[unit][ticker]")
{
    boost::asio::io_context io;
    Clock clock(1000);
    Wakeups idle;
    clock.add(&idle);
    Ticker ticker(io, clock, 1.0);
    CHECK_FALSE(armed(io));   // constructing arms nothing
    ticker.reschedule();
    CHECK_FALSE(armed(io));   // nothing due: reschedule() arms nothing
    io.restart();
    CHECK(io.run_for(100ms) == 0);   // returns at once: no work
    CHECK(io.stopped());
    CHECK(clock.now() == 0);
    CHECK(idle.ran.empty());
}

TEST_CASE("ticker: started paused, no wall time passes into the clock before resume", "[unit][ticker]")
{
    // Pausing after construction counted the time in between as ticks: a daemon started with
    // --paused, or a test fixture under load, did not start at tick 0.
    boost::asio::io_context io;
    Clock clock(1000);
    Ticker ticker(io, clock, 1.0, Ticker::Start::Paused);
    CHECK(ticker.paused());
    std::this_thread::sleep_for(20ms);
    ticker.pause();
    ticker.sync();
    CHECK(clock.now() == 0);
    ticker.resume();
    CHECK_FALSE(ticker.paused());
    CHECK(clock.now() == 0);   // resume anchors the wall time at the paused tick
}

TEST_CASE("ticker: sync() brings the clock to the tick due at the wall time of the call", "[unit][ticker]")
{
    const double time_scale = GENERATE(1.0, 10.0, 1000.0);
    INFO("time scale " << time_scale);
    constexpr std::uint32_t kTickHz = 1000;
    boost::asio::io_context io;
    Clock clock(kTickHz);
    Wakeups w({1, 2, 3, 4, 5});
    clock.add(&w);

    const auto t0 = SteadyClock::now();
    Ticker ticker(io, clock, time_scale);
    const auto t1 = SteadyClock::now();
    CHECK(ticker.time_scale() == time_scale);
    std::this_thread::sleep_for(5ms);   // at least 5 ms of wall time pass: at least 5 ticks

    const auto w0 = SteadyClock::now();
    ticker.sync();
    const auto w1 = SteadyClock::now();
    INFO("clock at " << clock.now());
    CHECK(clock.now() >= due_after(w0 - t1, kTickHz, time_scale));
    CHECK(clock.now() <= due_after(w1 - t0, kTickHz, time_scale));
    CHECK(clock.now() >= static_cast<Ticks>(5 * time_scale));
    // Every due tick ran, in order, and none before its wall time.
    CHECK(w.ran == std::vector<Ticks>{1, 2, 3, 4, 5});
    for (std::size_t i = 0; i < w.ran.size(); ++i)
        CHECK(w.ran_at[i] >= earliest_wall_of(w.ran[i], t0, kTickHz, time_scale));

    // A second sync() never moves the clock back, nor past the tick due now.
    const Ticks first = clock.now();
    ticker.sync();
    const auto w2 = SteadyClock::now();
    CHECK(clock.now() >= first);
    CHECK(clock.now() <= due_after(w2 - t0, kTickHz, time_scale));
    CHECK_FALSE(armed(io));   // sync() alone arms nothing
}

TEST_CASE("ticker: the timer wakes for each due tick, never before start + k / (tick_hz * time_scale)",
          "[unit][ticker]")
{
    // 10,000 ticks per second of wall time: the wake-ups at 200, 400 and 600 ticks are
    // 20, 40 and 60 ms after the start.
    constexpr std::uint32_t kTickHz = 1000;
    constexpr double kTimeScale = 10.0;
    boost::asio::io_context io;
    Clock clock(kTickHz);
    Wakeups w({200, 400, 600});
    clock.add(&w);

    const auto t0 = SteadyClock::now();
    Ticker ticker(io, clock, kTimeScale);
    ticker.reschedule();
    CHECK(armed(io));
    const auto handlers = run_until(io, [&] { return w.ran.size() == 3; });
    const auto t_end = SteadyClock::now();

    REQUIRE(w.ran == std::vector<Ticks>{200, 400, 600});
    CHECK(handlers >= 1);
    CHECK(handlers <= 3);   // one wake-up per due tick at most (a late one catches up several)
    for (std::size_t i = 0; i < w.ran.size(); ++i) {
        INFO("tick " << w.ran[i]);
        CHECK(w.ran_at[i] >= earliest_wall_of(w.ran[i], t0, kTickHz, kTimeScale));
    }
    CHECK(clock.now() >= 600);
    CHECK(clock.now() <= due_after(t_end - t0, kTickHz, kTimeScale));
    // Nothing is due any more: the last wake-up armed nothing.
    CHECK_FALSE(armed(io));
}

TEST_CASE("ticker: a late wake-up runs every tick due by then at once: the schedule does not drift",
          "[unit][ticker]")
{
    constexpr std::uint32_t kTickHz = 1000;
    boost::asio::io_context io;
    Clock clock(kTickHz);
    // Due every 10 ms for 50 ms, then not for 1000 s.
    Wakeups w({10, 20, 30, 40, 50, 1'000'000});
    clock.add(&w);

    const auto t0 = SteadyClock::now();
    Ticker ticker(io, clock, 1.0);
    ticker.reschedule();   // armed for tick 10
    // The process is held up past tick 50 before the loop runs (a busy machine).
    std::this_thread::sleep_for(50ms);
    io.restart();
    CHECK(io.run_one_for(5s) == 1);
    const auto t_end = SteadyClock::now();

    // One wake-up brought the clock to the tick due then, not one tick per firing.
    CHECK(w.ran == std::vector<Ticks>{10, 20, 30, 40, 50});
    CHECK(clock.now() >= 50);
    CHECK(clock.now() < 1'000'000);
    CHECK(clock.now() <= due_after(t_end - t0, kTickHz, 1.0));
    CHECK(armed(io));   // for tick 1,000,000
    ticker.stop();
}

TEST_CASE("ticker: reschedule() re-arms for an earlier wake-up, keeps an earlier one armed", "[unit][ticker]")
{
    boost::asio::io_context io;
    Clock clock(1000);
    Wakeups w;
    clock.add(&w);
    Ticker ticker(io, clock, 1.0);

    SECTION("an earlier wake-up replaces a later one")
    {
        w.due = {1'000'000};   // 1000 s away
        ticker.reschedule();
        CHECK(armed(io));
        w.due.insert(20);      // a command starts something due in 20 ms
        ticker.reschedule();
    }
    SECTION("a later wake-up leaves the earlier one armed")
    {
        w.due = {20};
        ticker.reschedule();
        w.due.insert(1'000'000);
        ticker.reschedule();
    }
    // Tick 20 runs long before tick 1,000,000 is due: the timer was armed for it.
    REQUIRE(run_until(io, [&] { return !w.ran.empty(); }) >= 1);
    CHECK(w.ran.front() == 20);
    CHECK(clock.now() >= 20);
    CHECK(clock.now() < 1'000'000);
    CHECK(armed(io));   // re-armed for tick 1,000,000 after the wake-up
    ticker.stop();
}

TEST_CASE("ticker: stop() cancels the armed wake-up and nothing is armed after it", "[unit][ticker]")
{
    boost::asio::io_context io;
    Clock clock(1000);
    Wakeups w({1'000'000});
    clock.add(&w);
    Ticker ticker(io, clock, 1.0);
    ticker.reschedule();
    CHECK(armed(io));

    ticker.stop();
    io.restart();
    CHECK(io.run_for(5s) == 1);   // only the cancelled wait completes, at once
    CHECK(io.stopped());
    w.due.insert(5);
    ticker.reschedule();
    CHECK_FALSE(armed(io));
    CHECK(clock.now() == 0);
    CHECK(w.ran.empty());
}

TEST_CASE("ticker: scaled beyond one tick per min_period, it wakes at most once per min_period",
          "[unit][ticker]")
{
    // 1,000,000 ticks per second of wall time (1 tick per microsecond), something due every
    // 100 ticks, wake-ups at most every 5 ms.
    constexpr std::uint32_t kTickHz = 1000;
    constexpr double kTimeScale = 1000.0;
    constexpr auto kMinPeriod = 5ms;
    boost::asio::io_context io;
    Clock clock(kTickHz);
    Every every(100);
    clock.add(&every);

    const auto t0 = SteadyClock::now();
    Ticker ticker(io, clock, kTimeScale, Ticker::Start::Running, kMinPeriod);
    ticker.reschedule();
    const auto wakeups = io.run_for(50ms);
    const auto t_end = SteadyClock::now();
    ticker.stop();

    INFO(wakeups << " wake-ups, clock at " << clock.now());
    // The k-th wake-up is due no earlier than start + k x min_period.
    CHECK(wakeups >= 1);
    CHECK(static_cast<std::int64_t>(wakeups) <= (t_end - t0) / kMinPeriod);
    // Each wake-up brings the clock to the due tick: at least 5,000 ticks per wake-up, and
    // every tick due on the way ran.
    CHECK(clock.now() >= static_cast<Ticks>(wakeups) * 5000);
    CHECK(clock.now() <= due_after(t_end - t0, kTickHz, kTimeScale));
    CHECK(every.count == clock.now() / 100);
}

// ---- Time under test control ----

TEST_CASE("ticker: paused, the clock stays at its tick and the timer is disarmed, and step() runs the due ticks",
          "[unit][ticker]")
{
    constexpr std::uint32_t kTickHz = 1000;
    boost::asio::io_context io;
    Clock clock(kTickHz);
    Wakeups w({5, 100, 250});
    clock.add(&w);
    Ticker ticker(io, clock, 1.0);
    ticker.reschedule();
    REQUIRE(armed(io));

    ticker.pause();
    CHECK(ticker.paused());
    const Ticks at_pause = clock.now();
    CHECK_FALSE(armed(io));   // the timer's wait was cancelled
    std::this_thread::sleep_for(20ms);   // 20 ticks of wall time pass: none runs
    ticker.sync();
    ticker.reschedule();
    CHECK(clock.now() == at_pause);
    CHECK_FALSE(armed(io));

    // step(): exactly n ticks, each due tick on the way runs once, in order.
    ticker.step(100 - at_pause);
    CHECK(clock.now() == 100);
    CHECK(w.ran == std::vector<Ticks>{5, 100});
    CHECK_FALSE(armed(io));   // still paused
    ticker.step(0);
    CHECK(clock.now() == 100);
    CHECK_THROWS_AS(ticker.step(-1), std::invalid_argument);
}

TEST_CASE("ticker: resume() continues from the paused tick, without catching up the paused wall time",
          "[unit][ticker]")
{
    constexpr std::uint32_t kTickHz = 1000;
    boost::asio::io_context io;
    Clock clock(kTickHz);
    Wakeups w({1'000'000});
    clock.add(&w);
    Ticker ticker(io, clock, 1.0);
    ticker.pause();
    ticker.step(40);
    std::this_thread::sleep_for(200ms);   // 200 ticks' worth of wall time while paused

    const auto r0 = SteadyClock::now();
    ticker.resume();
    CHECK_FALSE(ticker.paused());
    ticker.sync();
    const auto r1 = SteadyClock::now();
    // From tick 40 on, at most the ticks due in the wall time since resume() (not the 200 ms).
    CHECK(clock.now() >= 40);
    CHECK(clock.now() <= 40 + due_after(r1 - r0, kTickHz, 1.0));
    ticker.reschedule();
    CHECK(armed(io));   // running again: the far wake-up is armed
}

TEST_CASE("ticker: set_time_scale() changes the pace from the current tick and refuses what is not a scale",
          "[unit][ticker]")
{
    constexpr std::uint32_t kTickHz = 1000;
    boost::asio::io_context io;
    Clock clock(kTickHz);
    Ticker ticker(io, clock, 1.0);
    ticker.pause();
    ticker.step(500);
    const auto r0 = SteadyClock::now();   // the clock runs from resume() on: bound it from here
    ticker.resume();

    const auto t0 = SteadyClock::now();
    ticker.set_time_scale(100.0);
    const auto t1 = SteadyClock::now();
    CHECK(ticker.time_scale() == 100.0);
    const Ticks at_change = clock.now();
    CHECK(at_change >= 500);
    CHECK(at_change <= 500 + due_after(t1 - r0 + 1ms, kTickHz, 1.0));   // no jump at the change
    std::this_thread::sleep_for(5ms);
    const auto w0 = SteadyClock::now();
    ticker.sync();
    const auto w1 = SteadyClock::now();
    CHECK(clock.now() >= at_change + due_after(w0 - t1, kTickHz, 100.0));
    CHECK(clock.now() <= at_change + due_after(w1 - t0, kTickHz, 100.0));

    for (double bad : {0.0, -1.0, std::nan(""), HUGE_VAL})
        CHECK_THROWS_AS(ticker.set_time_scale(bad), std::invalid_argument);
    CHECK(ticker.time_scale() == 100.0);
}

TEST_CASE("ticker: run_until_idle() runs wake-up to wake-up until not busy, or until its limit", "[unit][ticker]")
{
    constexpr std::uint32_t kTickHz = 1000;
    boost::asio::io_context io;
    Clock clock(kTickHz);
    // Busy until its last wake-up at tick 30,000 (a 30 s homing), with a 100 ms update beside it.
    Wakeups move({10'000, 20'000, 30'000});
    Every updates(100);
    clock.add(&move);
    clock.add(&updates);
    // Paused from the start: no wall time passes into the clock before the run (a loaded machine
    // took 4 ms between construction and pause()).
    Ticker ticker(io, clock, 1.0, Ticker::Start::Paused);
    const auto busy = [&] { return move.next_change(clock.now()) != kNever; };

    CHECK(ticker.run_until_idle(5'000, busy) == 5'000);   // the limit comes first
    CHECK(move.ran.empty());
    CHECK(updates.count == 50);
    // Returns with the move done, without running the io_context: nothing waited for wall time.
    CHECK(ticker.run_until_idle(1'000'000, busy) == 30'000);
    CHECK(move.ran == std::vector<Ticks>{10'000, 20'000, 30'000});
    CHECK(updates.count == 300);   // every update on the way ran
    CHECK(ticker.run_until_idle(1'000, busy) == 30'000);   // not busy: nothing to run
    CHECK(ticker.paused());
    CHECK_THROWS_AS(ticker.run_until_idle(-1, busy), std::invalid_argument);
}

} // namespace test_ticker
