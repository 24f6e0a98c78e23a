// Ticker's queued jobs (POST /api/clock's step_ms and run_until_idle on the loop): a long step
// is done in slices with other handlers run between them, jobs run in order, and stop() or
// drop_jobs() end them without a call back. A slice of zero wall time makes every slice one
// piece of work, so the assertions are on ticks and on the order of handlers, never on wall time.
#include "emulator/daemon/ticker.hpp"

#include <catch2/catch.hpp>

#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>

#include <chrono>
#include <optional>
#include <stdexcept>
#include <vector>

namespace test_ticker_jobs {

using namespace rigsim;
using namespace std::chrono_literals;

namespace {

/// Wants a tick every tick from `from` until `until` (a LUT playing): every tick costs work.
class Busy : public Tickable {
public:
    Ticks next_change(Ticks now) const override
    {
        if (now < from)
            return from;
        return now < until ? now + 1 : kNever;
    }
    void tick(Ticks now) override
    {
        ++count;
        last = now;
    }

    Ticks from = 0;
    Ticks until = 0;
    std::int64_t count = 0;
    Ticks last = 0;
};

struct Fixture {
    Fixture() { clock.add(&busy); }
    ~Fixture() { clock.remove(&busy); }

    boost::asio::io_context io;
    Clock clock{1000};
    Busy busy;
    Ticker ticker{io, clock, 1.0, Ticker::Start::Paused, 1ms, std::chrono::steady_clock::duration::zero()};
};

} // namespace

TEST_CASE("ticker jobs: a long step runs in slices, other handlers run between them, done comes once at its end",
          "[unit][ticker]")
{
    Fixture f;
    f.busy.until = 1'000'000;
    std::vector<Ticks> done;
    f.ticker.queue_step(100'000, [&](Ticks reached) { done.push_back(reached); });
    CHECK(f.clock.now() == 0);   // nothing runs before the loop does
    CHECK(f.ticker.jobs() == 1);

    // A handler posted after the job (a device's bytes, another request) runs part-way.
    std::optional<Ticks> seen;
    boost::asio::post(f.io, [&] { seen = f.clock.now(); });
    f.io.run();
    REQUIRE(seen);
    CHECK(*seen > 0);
    CHECK(*seen < 100'000);
    CHECK(done == std::vector<Ticks>{100'000});
    CHECK(f.busy.count == 100'000);   // every tick ran, in order
    CHECK(f.busy.last == 100'000);
    CHECK(f.ticker.jobs() == 0);
    CHECK(f.ticker.paused());
    CHECK_THROWS_AS(f.ticker.queue_step(-1, [](Ticks) {}), std::invalid_argument);
}

TEST_CASE("ticker jobs: an idle stretch is one jump, jobs run in the order queued", "[unit][ticker]")
{
    Fixture f;
    std::vector<std::pair<int, Ticks>> done;
    f.ticker.queue_step(86'400'000, [&](Ticks t) { done.emplace_back(1, t); });   // a day, nothing due
    f.busy.from = 86'400'001;
    f.busy.until = 86'400'000 + 50;
    f.ticker.queue_run_until_idle(1'000'000, [&] { return f.busy.next_change(f.clock.now()) != kNever; },
                                  [&](Ticks t) { done.emplace_back(2, t); });
    f.ticker.queue_step(10, [&](Ticks t) { done.emplace_back(3, t); });
    f.io.run();
    CHECK(done == std::vector<std::pair<int, Ticks>>{{1, 86'400'000}, {2, 86'400'050}, {3, 86'400'060}});
    CHECK(f.busy.count == 50);
}

TEST_CASE("ticker jobs: run_until_idle stops at its limit while busy, and a job done may queue the next",
          "[unit][ticker]")
{
    Fixture f;
    f.busy.until = 5'000;
    const auto busy = [&] { return f.busy.next_change(f.clock.now()) != kNever; };
    std::vector<Ticks> done;
    f.ticker.queue_run_until_idle(1'000, busy, [&](Ticks t) {
        done.push_back(t);
        f.ticker.queue_run_until_idle(1'000'000, busy, [&](Ticks u) { done.push_back(u); });
    });
    f.io.run();
    CHECK(done == std::vector<Ticks>{1'000, 5'000});
    CHECK_FALSE(busy());
}

TEST_CASE("ticker jobs: while a job is queued sync() leaves the clock alone, and stop() and drop_jobs() end jobs unanswered",
          "[unit][ticker]")
{
    boost::asio::io_context io;
    Clock clock(1000);
    Busy busy;
    busy.until = 1'000'000;
    clock.add(&busy);
    {
        Ticker running(io, clock, 1.0, Ticker::Start::Running, 1ms, std::chrono::steady_clock::duration::zero());
        bool called = false;
        running.queue_step(500'000, [&](Ticks) { called = true; });
        const Ticks at = clock.now();
        running.sync();   // wall time passes, yet the job owns the clock
        CHECK(clock.now() == at);
        io.restart();
        io.run_one();     // one slice
        CHECK(clock.now() > at);
        CHECK(clock.now() < at + 500'000);
        running.drop_jobs();
        CHECK(running.jobs() == 0);
        io.restart();
        io.poll();
        CHECK_FALSE(called);

        running.queue_step(500'000, [&](Ticks) { called = true; });
        running.stop();
        CHECK(running.jobs() == 0);
        io.restart();
        io.run();
        CHECK_FALSE(called);
        running.queue_step(1, [&](Ticks) { called = true; });   // stopped: nothing is queued
        CHECK(running.jobs() == 0);
    }
    bool called = false;
    {
        Ticker gone(io, clock, 1.0, Ticker::Start::Paused, 1ms, std::chrono::steady_clock::duration::zero());
        gone.queue_step(10, [&](Ticks) { called = true; });   // its first slice is posted
    }
    const Ticks at = clock.now();
    io.restart();
    io.run();   // the slice posted before the ticker went does nothing
    CHECK_FALSE(called);
    CHECK(clock.now() == at);
    clock.remove(&busy);
}

} // namespace test_ticker_jobs
