#include "emulator/core/ticker.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rigsim {

Ticker::Ticker(boost::asio::io_context& io, Clock& clock, double time_scale, Start start,
               SteadyClock::duration min_period)
    : clock_(clock), time_scale_(time_scale), min_period_(min_period),
      start_(SteadyClock::now()), paused_(start == Start::Paused), timer_(io), last_fire_(start_)
{
}

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
    if (paused_)
        return;
    const Ticks due = due_at(SteadyClock::now());
    if (due > clock_.now())
        clock_.advance_to(due);
}

void Ticker::reschedule()
{
    if (stopped_ || paused_)
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
    reschedule();
}

void Ticker::stop()
{
    stopped_ = true;
    timer_.cancel();
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
    reanchor();
    disarm();
    reschedule();
    return clock_.now();
}

} // namespace rigsim
