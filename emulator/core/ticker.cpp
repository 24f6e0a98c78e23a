#include "emulator/core/ticker.hpp"

#include <algorithm>
#include <cmath>

namespace rigsim {

Ticker::Ticker(boost::asio::io_context& io, Clock& clock, double time_scale,
               SteadyClock::duration min_period)
    : clock_(clock), time_scale_(time_scale), min_period_(min_period),
      start_(SteadyClock::now()), timer_(io), last_fire_(start_)
{
}

Ticker::SteadyClock::time_point Ticker::wall_of(Ticks t) const
{
    const long double ns = static_cast<long double>(t) * 1e9L
        / (static_cast<long double>(clock_.tick_hz()) * time_scale_);
    return start_ + std::chrono::nanoseconds(static_cast<std::int64_t>(std::ceil(ns)));
}

Ticks Ticker::due_at(SteadyClock::time_point wall) const
{
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(wall - start_).count();
    return static_cast<Ticks>(std::floor(static_cast<long double>(ns) * clock_.tick_hz()
                                         * time_scale_ / 1e9L));
}

void Ticker::sync()
{
    const Ticks due = due_at(SteadyClock::now());
    if (due > clock_.now())
        clock_.advance_to(due);
}

void Ticker::reschedule()
{
    if (stopped_)
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

} // namespace rigsim
