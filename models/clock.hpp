#pragma once
// The one clock of a rig: integer ticks of a fixed physics period.
//
// Everything that changes with time (motion, hold times, status updates, answers held on a
// wire) is a Tickable registered here. In the daemon a Ticker (the one Asio timer) is the
// only caller of advance_to(); tests call advance() directly and never sleep.
//
// The schedule. To find its next wake-up the clock needs every Tickable's next_change(). The
// daemon asks after every command, and asking each of a rig's devices every time cost more
// than the command (bench/README.md). So the clock keeps each Tickable's last answer, and asks
// again only when that answer may have moved:
//   - after every tick in which anything ran, every Tickable (a body's event starts a device's
//     timer; a device's answer is held on its wire);
//   - a Tickable registered Schedule::Asked (the default): at every next_wakeup(), as its next
//     change may follow anything (the World, whose bodies any command may start; a test's
//     Tickable);
//   - a Tickable registered Schedule::Announced: when it is announced, changed(t) (after
//     anything outside its tick() that may move its next change: a command it handled, a
//     session opened or closed, another device's command it follows), or changed_all() (a
//     control request, a power-up).
// A clock keeps the Announced answers only once its owner promises those announcements,
// keep_schedule() (the daemon's rig, whose devices announce their commands and whose control
// API announces its requests through Ticker::reschedule()). Until then (a test that steps the
// clock and calls into devices by hand) every call asks every Tickable afresh, as a clock
// without a schedule would. A build without NDEBUG (the sanitizer pass of scripts/test.sh)
// checks every kept answer against a fresh one at every next_wakeup() and aborts, naming the
// Tickable, on one that came too late: a change nobody announced.

#include <cstddef>
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

private:
    friend class Clock;
    static constexpr std::size_t kNoSlot = std::numeric_limits<std::size_t>::max();
    std::size_t slot_ = kNoSlot;   ///< its entry in its clock (Clock::add)
};

/// Integer tick counter; runs real time, scaled, or stepped by a test.
class Clock {
public:
    static constexpr std::uint32_t kDefaultTickHz = 1000;

    /// How the clock learns when a Tickable is next due (see "The schedule" above).
    enum class Schedule {
        Asked,       ///< asked at every next_wakeup()
        Announced,   ///< its last answer stands until it is announced (changed()) or anything ticks
    };

    explicit Clock(std::uint32_t tick_hz = kDefaultTickHz);

    Ticks now() const { return now_; }
    std::uint32_t tick_hz() const { return tick_hz_; }
    double seconds(Ticks t) const { return static_cast<double>(t) / tick_hz_; }
    /// Ticks in `ms` milliseconds, rounded up so that a wait never ends early.
    Ticks ticks_from_ms(std::int64_t ms) const;

    /// Registers `t` (on one clock at a time); ticks run in the order of registration.
    void add(Tickable* t, Schedule schedule = Schedule::Asked);
    void remove(Tickable* t);

    /// `t`'s next_change() may have moved: asked again before the next wake-up is found. For an
    /// Announced Tickable; nothing for an Asked or unregistered one.
    void changed(const Tickable& t);
    /// Every Tickable's next_change() may have moved.
    void changed_all();
    /// From now on every change of an Announced Tickable's next change outside the clock's ticks
    /// is announced (changed(), changed_all()): keep their answers between announcements.
    void keep_schedule() { keep_ = true; }
    bool keeps_schedule() const { return keep_; }

    /// Earliest tick at which some Tickable needs to run, or kNever.
    Ticks next_wakeup() const;

    /// Advance to tick `target`, running every due tick in order; idle stretches are skipped.
    void advance_to(Ticks target);
    void advance(Ticks n) { advance_to(now_ + n); }
    /// Advance by a duration in milliseconds (tests).
    void advance_ms(std::int64_t ms) { advance(ticks_from_ms(ms)); }

private:
    struct Entry {
        Tickable* tickable;
        Schedule schedule;
        Ticks next = kNever;   ///< Announced: its last answer (valid unless `stale`)
        bool stale = true;
    };
    /// Ask Announced entry `e` again; keeps the minimum of the answers.
    void refresh(Entry& e) const;
    /// Every kept answer no later than a fresh one (builds without NDEBUG; aborts otherwise).
    void check_kept() const;

    std::uint32_t tick_hz_;
    Ticks now_ = 0;
    bool keep_ = false;
    mutable std::vector<Entry> entries_;              ///< in registration order
    std::vector<std::size_t> asked_;                  ///< slots of the Asked entries
    mutable std::vector<std::size_t> stale_;          ///< slots of Announced entries to ask again
    mutable bool all_stale_ = true;                   ///< every Announced entry is to be asked again
    mutable Ticks kept_min_ = kNever;                 ///< the earliest kept answer
    mutable bool kept_min_valid_ = true;
};

} // namespace rigsim
