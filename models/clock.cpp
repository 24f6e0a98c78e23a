#include "models/clock.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <typeinfo>

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

void Clock::add(Tickable* t, Schedule schedule)
{
    t->slot_ = entries_.size();
    entries_.push_back(Entry{t, schedule});
    if (schedule == Schedule::Asked)
        asked_.push_back(t->slot_);
    all_stale_ = true;
}

void Clock::remove(Tickable* t)
{
    if (t->slot_ >= entries_.size() || entries_[t->slot_].tickable != t)
        return;
    entries_.erase(entries_.begin() + static_cast<std::ptrdiff_t>(t->slot_));
    t->slot_ = Tickable::kNoSlot;
    asked_.clear();
    for (std::size_t slot = 0; slot < entries_.size(); ++slot) {
        entries_[slot].tickable->slot_ = slot;
        if (entries_[slot].schedule == Schedule::Asked)
            asked_.push_back(slot);
    }
    stale_.clear();
    all_stale_ = true;
}

void Clock::changed(const Tickable& t)
{
    if (all_stale_ || t.slot_ >= entries_.size())
        return;
    auto& e = entries_[t.slot_];
    if (e.tickable != &t || e.schedule != Schedule::Announced || e.stale)
        return;
    e.stale = true;
    stale_.push_back(t.slot_);
}

void Clock::changed_all()
{
    all_stale_ = true;
}

void Clock::refresh(Entry& e) const
{
    const Ticks old = e.next;
    e.next = e.tickable->next_change(now_);
    e.stale = false;
    if (e.next <= kept_min_)
        kept_min_ = e.next;
    else if (old == kept_min_)
        kept_min_valid_ = false;   // the earliest answer moved later: another may be the earliest now
}

Ticks Clock::next_wakeup() const
{
    if (!keep_ || all_stale_) {
        kept_min_ = kNever;
        for (auto& e : entries_)
            if (e.schedule == Schedule::Announced) {
                e.next = e.tickable->next_change(now_);
                e.stale = false;
                kept_min_ = std::min(kept_min_, e.next);
            }
        kept_min_valid_ = true;
        stale_.clear();
        all_stale_ = false;
    } else {
        for (const auto slot : stale_)
            refresh(entries_[slot]);
        stale_.clear();
        if (!kept_min_valid_) {
            kept_min_ = kNever;
            for (const auto& e : entries_)
                if (e.schedule == Schedule::Announced)
                    kept_min_ = std::min(kept_min_, e.next);
            kept_min_valid_ = true;
        }
    }
    Ticks next = kept_min_;
    for (const auto slot : asked_)
        next = std::min(next, entries_[slot].tickable->next_change(now_));
#ifndef NDEBUG
    if (keep_)
        check_kept();
#endif
    return next;
}

void Clock::check_kept() const
{
    for (const auto& e : entries_) {
        if (e.schedule != Schedule::Announced || e.stale)
            continue;
        const Ticks fresh = e.tickable->next_change(now_);
        if (fresh < e.next) {
            std::fprintf(stderr,
                         "rigsim: Clock: the Tickable %s (slot %zu) is due at tick %lld, but the clock kept %lld "
                         "(now %lld): a change of its next_change() was not announced (Clock::changed)\n",
                         typeid(*e.tickable).name(), static_cast<std::size_t>(&e - entries_.data()),
                         static_cast<long long>(fresh), static_cast<long long>(e.next), static_cast<long long>(now_));
            std::abort();
        }
    }
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
        // Each asked afresh, in order: a tick may make a later Tickable due at the same tick (a
        // body's event starts its device's timer).
        for (std::size_t slot = 0; slot < entries_.size(); ++slot) {
            Tickable* t = entries_[slot].tickable;
            if (t->next_change(now_ - 1) <= now_)
                t->tick(now_);
        }
        all_stale_ = true;   // and any tick may have moved any Tickable's next change
    }
}

} // namespace rigsim
