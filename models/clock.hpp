#pragma once
// The one clock of a rig: integer ticks of a fixed physics period.
//
// Everything that changes with time (motion, hold times, later: status updates)
// is a Tickable registered here. In the daemon a Ticker (the one Asio timer) is the
// only caller of advance_to(); tests call advance() directly and never sleep.

#include <cstdint>
#include <limits>
#include <vector>

namespace rigsim {

using Ticks = std::int64_t;
inline constexpr Ticks kNever = std::numeric_limits<Ticks>::max();

/// Something whose state changes with clock time.
class Tickable {
public:
    virtual ~Tickable() = default;
    /// Earliest tick (> now) at which tick() must run, or kNever while nothing changes by itself.
    virtual Ticks next_change(Ticks now) const = 0;
    /// Bring the state up to tick `now` (called once per tick while next_change() is due).
    virtual void tick(Ticks now) = 0;
};

/// Integer tick counter; runs real time, scaled, or stepped by a test.
class Clock {
public:
    static constexpr std::uint32_t kDefaultTickHz = 1000;

    explicit Clock(std::uint32_t tick_hz = kDefaultTickHz);

    Ticks now() const { return now_; }
    std::uint32_t tick_hz() const { return tick_hz_; }
    double seconds(Ticks t) const { return static_cast<double>(t) / tick_hz_; }
    /// Ticks in `ms` milliseconds, rounded up so that a wait never ends early.
    Ticks ticks_from_ms(std::int64_t ms) const;

    void add(Tickable* t);
    void remove(Tickable* t);

    /// Earliest tick at which some Tickable needs to run, or kNever.
    Ticks next_wakeup() const;

    /// Advance to tick `target`, running every due tick in order; idle stretches are skipped.
    void advance_to(Ticks target);
    void advance(Ticks n) { advance_to(now_ + n); }
    /// Advance by a duration in milliseconds (tests).
    void advance_ms(std::int64_t ms) { advance(ticks_from_ms(ms)); }

private:
    std::uint32_t tick_hz_;
    Ticks now_ = 0;
    std::vector<Tickable*> tickables_;
};

} // namespace rigsim
