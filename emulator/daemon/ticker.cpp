#include "emulator/daemon/ticker.hpp"

#include <boost/asio/post.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rigsim {

Ticker::Ticker(boost::asio::io_context& io, Clock& clock, double time_scale, Start start,
               SteadyClock::duration min_period, SteadyClock::duration slice)
    : clock_(clock), time_scale_(time_scale), min_period_(min_period),
      start_(SteadyClock::now()), paused_(start == Start::Paused), timer_(io), last_fire_(start_),
      slice_(slice), io_(io)
{
}

Ticker::~Ticker() = default;

Ticker::SteadyClock::time_point Ticker::wall_of(Ticks t) const
{
    const long double ns = static_cast<long double>(t - anchor_) * 1e9L
        / (static_cast<long double>(clock_.tick_hz()) * time_scale_);
    return start_ + std::chrono::nanoseconds(static_cast<std::int64_t>(std::ceil(ns)));
}

Ticks Ticker::due_at(SteadyClock::time_point wall) const
{
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(wall - start_).count();
    return anchor_ + static_cast<Ticks>(std::floor(static_cast<long double>(ns) * clock_.tick_hz()
                                                   * time_scale_ / 1e9L));
}

void Ticker::sync()
{
    if (paused_ || !jobs_.empty())
        return;
    const Ticks due = due_at(SteadyClock::now());
    if (due > clock_.now())
        clock_.advance_to(due);
}

void Ticker::reschedule()
{
    clock_.changed_all();
    arm();
}

void Ticker::reschedule_announced()
{
    arm();
}

void Ticker::arm()
{
    if (stopped_ || paused_ || !jobs_.empty())
        return;
    const Ticks next = clock_.next_wakeup();
    if (next == kNever)
        return;   // an armed timer stays armed; it finds nothing to do and re-arms nothing
    const auto deadline = std::max(wall_of(next), last_fire_ + min_period_);
    if (deadline >= armed_for_)
        return;   // already armed for an earlier or equal deadline
    armed_for_ = deadline;
    timer_.expires_at(deadline);
    timer_.async_wait([this](const boost::system::error_code& ec) { on_timer(ec); });
}

void Ticker::on_timer(const boost::system::error_code& ec)
{
    if (ec == boost::asio::error::operation_aborted)
        return;   // re-armed earlier, or stopped: the new wait owns the schedule
    armed_for_ = SteadyClock::time_point::max();
    last_fire_ = timer_.expiry();
    sync();
    arm();   // the ticks asked every Tickable afresh
}

void Ticker::stop()
{
    stopped_ = true;
    timer_.cancel();
    jobs_.clear();
}

void Ticker::reanchor()
{
    start_ = SteadyClock::now();
    anchor_ = clock_.now();
}

void Ticker::disarm()
{
    timer_.cancel();
    armed_for_ = SteadyClock::time_point::max();
}

void Ticker::pause()
{
    if (paused_)
        return;
    sync();
    paused_ = true;
    disarm();
}

void Ticker::resume()
{
    if (!paused_)
        return;
    paused_ = false;
    reanchor();
    reschedule();
}

void Ticker::set_time_scale(double scale)
{
    if (!std::isfinite(scale) || scale <= 0)
        throw std::invalid_argument("the time scale must be a finite number above 0");
    sync();
    time_scale_ = scale;
    reanchor();
    disarm();
    reschedule();
}

void Ticker::step(Ticks n)
{
    if (n < 0)
        throw std::invalid_argument("a step must not be negative");
    sync();
    clock_.advance(n);
    if (!jobs_.empty())
        return;   // a queued job owns the clock; it re-anchors when it is done
    reanchor();
    disarm();
    reschedule();
}

Ticks Ticker::run_until_idle(Ticks max_ticks, const std::function<bool()>& busy)
{
    if (max_ticks < 0)
        throw std::invalid_argument("the limit must not be negative");
    sync();
    const Ticks limit = clock_.now() + max_ticks;
    while (clock_.now() < limit && busy()) {
        const Ticks next = clock_.next_wakeup();
        if (next == kNever)
            break;   // busy, yet nothing changes by itself any more: waiting cannot help
        clock_.advance_to(std::min(next, limit));
    }
    if (!jobs_.empty())
        return clock_.now();
    reanchor();
    disarm();
    reschedule();
    return clock_.now();
}

void Ticker::queue_step(Ticks n, JobDone done)
{
    if (n < 0)
        throw std::invalid_argument("a step must not be negative");
    queue(Job{n, {}, std::move(done)});
}

void Ticker::queue_run_until_idle(Ticks max_ticks, std::function<bool()> busy, JobDone done)
{
    if (max_ticks < 0)
        throw std::invalid_argument("the limit must not be negative");
    queue(Job{max_ticks, std::move(busy), std::move(done)});
}

void Ticker::drop_jobs()
{
    if (jobs_.empty())
        return;
    jobs_.clear();
    reanchor();
    reschedule();
}

void Ticker::queue(Job job)
{
    if (stopped_)
        return;
    if (jobs_.empty()) {
        sync();     // the job counts from the tick due now
        disarm();   // and owns the clock until it is done
    }
    jobs_.push_back(std::move(job));
    if (jobs_.size() == 1 && !in_slice_)
        post_slice();
}

void Ticker::post_slice()
{
    boost::asio::post(io_, [this, alive = std::weak_ptr<char>(alive_)] {
        if (alive.lock() && !stopped_)
            run_slice();
    });
}

void Ticker::run_slice()
{
    const auto end = SteadyClock::now() + slice_;
    in_slice_ = true;
    while (!jobs_.empty()) {
        Job& job = jobs_.front();
        if (job.limit < 0)
            job.limit = clock_.now() + job.ticks;
        if (!advance(job, end))
            break;
        auto done = std::move(job.done);
        jobs_.pop_front();
        if (jobs_.empty()) {
            reanchor();
            reschedule();
        }
        if (done)
            done(clock_.now());   // may queue the next job
        if (stopped_)
            break;
        if (SteadyClock::now() >= end)
            break;
    }
    in_slice_ = false;
    if (!jobs_.empty() && !stopped_)
        post_slice();
}

bool Ticker::advance(Job& job, SteadyClock::time_point end)
{
    if (job.busy) {
        while (clock_.now() < job.limit && job.busy()) {
            const Ticks next = clock_.next_wakeup();
            if (next == kNever)
                return true;   // busy, yet nothing changes by itself any more: waiting cannot help
            clock_.advance_to(std::min(next, job.limit));
            if (SteadyClock::now() >= end)
                return clock_.now() >= job.limit || !job.busy();
        }
        return true;
    }
    while (clock_.now() < job.limit) {
        if (clock_.next_wakeup() >= job.limit) {
            clock_.advance_to(job.limit);   // nothing due before the end: one jump
            return true;
        }
        const Ticks to = std::min(job.limit, clock_.now() + chunk_);
        const auto t0 = SteadyClock::now();
        clock_.advance_to(to);
        const auto t1 = SteadyClock::now();
        // Each call well under a slice, and few calls per slice: the chunk follows the cost of a tick.
        if (t1 - t0 < slice_ / 16)
            chunk_ = std::min<Ticks>(chunk_ * 2, Ticks{1} << 40);
        else if (t1 - t0 > slice_ / 4)
            chunk_ = std::max<Ticks>(chunk_ / 2, 1);
        if (t1 >= end)
            return clock_.now() >= job.limit;
    }
    return true;
}

} // namespace rigsim
