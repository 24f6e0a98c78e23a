#pragma once
// The one Asio timer that paces the Clock against wall time (simavr's avr->sleep hook:
// the daemon sleeps, tests bypass it and step the clock).
//
// Drift-free: the wall time of tick k is start + k / (tick_hz * time_scale); the clock is
// brought to the tick that is due now (never by counting timer firings). While nothing
// moves, the timer is not armed at all, so an idle rig costs no CPU; I/O calls sync()
// before it hands bytes to a device, so a command always sees the current tick.

#include "models/clock.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include <chrono>
#include <deque>
#include <functional>
#include <memory>

namespace rigsim {

class Ticker {
public:
    enum class Start { Running, Paused };
    /// `min_period` bounds the wake-up rate when the clock is scaled beyond 1 tick per period.
    /// A ticker that starts Paused lets no wall time pass into the clock before resume(): a
    /// daemon started with --paused, or a test, sits at the clock's tick until it is stepped
    /// (pausing after construction would count the time spent in between).
    Ticker(boost::asio::io_context& io, Clock& clock, double time_scale, Start start = Start::Running,
           std::chrono::steady_clock::duration min_period = std::chrono::milliseconds(1),
           std::chrono::steady_clock::duration slice = kDefaultSlice);
    ~Ticker();
    Ticker(const Ticker&) = delete;
    Ticker& operator=(const Ticker&) = delete;

    /// Wall time one slice of a queued step or run-until-idle takes at most (beyond one wake-up's
    /// work, which is never split) before the loop serves device and API traffic again.
    static constexpr std::chrono::steady_clock::duration kDefaultSlice = std::chrono::milliseconds(2);

    /// Advance the clock to the tick that is due at the current wall time.
    void sync();
    /// Arm the timer for the clock's next wake-up (call after anything that may start motion),
    /// every Tickable asked afresh (Clock::changed_all()): after a control request, whose changes
    /// nobody announced one by one.
    void reschedule();
    /// The same when every change since the last wake-up was announced (Clock::changed()): after
    /// a batch of client bytes, whose device announced what it handled. Asks only the announced
    /// Tickables and the Asked ones (models/clock.hpp, "The schedule").
    void reschedule_announced();
    void stop();

    double time_scale() const { return time_scale_; }
    bool paused() const { return paused_; }

    // ---- Time under test control (the control API's POST /api/clock) ----
    // Each change of mode re-anchors the wall-time mapping at the current tick, so the clock
    // continues from where it is and never jumps to catch up.

    /// Stop the clock at the current tick; devices still answer from the paused state.
    void pause();
    /// Run again from the current tick.
    void resume();
    /// Clock ticks per wall tick from now on; throws std::invalid_argument unless finite and > 0.
    void set_time_scale(double scale);
    /// Advance the clock `n` ticks now, running every due tick (paused or running).
    void step(Ticks n);
    /// Advance the clock as fast as the CPU allows, from wake-up to wake-up, while `busy()` and
    /// for at most `max_ticks`; returns the tick reached.
    Ticks run_until_idle(Ticks max_ticks, const std::function<bool()>& busy);

    // ---- The same, on the loop: long clock work that does not stop the daemon ----
    // A queued job runs in slices of at most `slice` wall time each, posted to the io_context,
    // so that devices and the control API are served between slices (they see the clock where
    // the job has brought it). Jobs run one after the other in the order they were queued; while
    // one is queued the clock does not follow wall time (sync() does nothing), and when the last
    // is done the wall-time mapping is re-anchored at the tick reached. stop() drops queued jobs
    // without calling them back.

    /// Called once when a job is done, with the tick reached.
    using JobDone = std::function<void(Ticks reached)>;
    /// step(n), sliced; throws std::invalid_argument for n < 0 (before queuing anything).
    void queue_step(Ticks n, JobDone done);
    /// run_until_idle(), sliced; `busy` is called between wake-ups, on the loop.
    void queue_run_until_idle(Ticks max_ticks, std::function<bool()> busy, JobDone done);
    /// Jobs queued and not yet done (the one running included).
    std::size_t jobs() const { return jobs_.size(); }
    /// Drop the queued jobs without calling them back (their owner goes); the clock follows
    /// wall time again from the tick reached.
    void drop_jobs();

private:
    using SteadyClock = std::chrono::steady_clock;
    SteadyClock::time_point wall_of(Ticks t) const;
    Ticks due_at(SteadyClock::time_point wall) const;
    void on_timer(const boost::system::error_code& ec);
    /// reschedule() without asking anything afresh.
    void arm();
    /// The wall time of the current tick is now (after a change of mode or a jump).
    void reanchor();
    void disarm();

    struct Job {
        Ticks ticks = 0;                ///< the step, or run-until-idle's limit
        std::function<bool()> busy;     ///< set: run until idle
        JobDone done;
        Ticks limit = -1;               ///< the tick the job ends at, fixed when it starts
    };
    void queue(Job job);
    void post_slice();
    void run_slice();
    /// Work on `job` until it is done (true) or the slice ends at `end` (false).
    bool advance(Job& job, SteadyClock::time_point end);

    Clock& clock_;
    double time_scale_;
    SteadyClock::duration min_period_;
    SteadyClock::time_point start_;   ///< the wall time of tick anchor_
    Ticks anchor_ = 0;
    bool paused_ = false;
    boost::asio::steady_timer timer_;
    SteadyClock::time_point armed_for_ = SteadyClock::time_point::max();
    SteadyClock::time_point last_fire_;
    bool stopped_ = false;
    SteadyClock::duration slice_;
    std::deque<Job> jobs_;
    bool in_slice_ = false;
    Ticks chunk_ = 1024;   ///< ticks per Clock::advance_to() call of a step, adapted to the slice
    boost::asio::io_context& io_;
    /// Posted slices hold a weak reference: one that runs after the ticker is gone does nothing.
    std::shared_ptr<char> alive_ = std::make_shared<char>();
};

} // namespace rigsim
