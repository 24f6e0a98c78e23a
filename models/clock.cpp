#include "models/clock.hpp"

#include <algorithm>
#include <stdexcept>

namespace rigsim {

Clock::Clock(std::uint32_t tick_hz) : tick_hz_(tick_hz)
{
    if (tick_hz_ == 0)
        throw std::invalid_argument("tick rate must be positive");
}

Ticks Clock::ticks_from_ms(std::int64_t ms) const
{
    return (ms * static_cast<std::int64_t>(tick_hz_) + 999) / 1000;
}

void Clock::add(Tickable* t)
{
    tickables_.push_back(t);
}

void Clock::remove(Tickable* t)
{
    tickables_.erase(std::remove(tickables_.begin(), tickables_.end(), t), tickables_.end());
}

Ticks Clock::next_wakeup() const
{
    Ticks next = kNever;
    for (const auto* t : tickables_)
        next = std::min(next, t->next_change(now_));
    return next;
}

void Clock::advance_to(Ticks target)
{
    while (now_ < target) {
        const Ticks due = std::max(next_wakeup(), now_ + 1);
        if (due > target) {
            now_ = target;   // nothing changes before target: skip the idle stretch
            return;
        }
        now_ = due;
        for (auto* t : tickables_)
            if (t->next_change(now_ - 1) <= now_)
                t->tick(now_);
    }
}

} // namespace rigsim
