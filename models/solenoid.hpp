#pragma once
// The output of a solenoid driver (TSC001/KSC101, APT manual p.84-92): open, closed, or cycling
// OnTime open / OffTime closed for NumCycles cycles (0 = forever, p.87). Only the timing of the
// output lives here; modes, the interlock and triggers are the protocol module's.
//
// A cycle run is a function of clock time: started at s with on/off ticks, the output is
// open while (t - s) mod (on + off) < on, and the run ends at s + n·(on + off) with the output
// closed. The world wakes the body at each edge (the listener hears it) and at the end, and
// never while it is idle, open or closed.

#include "models/clock.hpp"
#include "models/world.hpp"

#include <cstdint>
#include <functional>

namespace rigsim::models {

class Solenoid : public Body {
public:
    /// Told at each edge of a cycle run (`active`: the output after the edge), at its tick.
    using Listener = std::function<void(Ticks at, bool active)>;

    void set_listener(Listener listener) { listener_ = std::move(listener); }

    /// Output on from `now` until close() (ends a cycle run).
    void open(Ticks now);
    /// Output off from `now` (ends a cycle run; its completed cycles stay counted).
    void close(Ticks now);
    /// From `now`: `on_ticks` open, `off_ticks` closed (each at least 1), `cycles` times,
    /// 0 = forever; restarts a run in progress.
    void start_cycles(Ticks now, Ticks on_ticks, Ticks off_ticks, std::int64_t cycles);

    /// The output at `now`.
    bool active_at(Ticks now) const;
    /// Whole cycles completed by `now` in the current or last run.
    std::int64_t cycles_done(Ticks now) const;
    /// A cycle run is in progress at `now`.
    bool running(Ticks now) const { return state_ == State::Cycling && now < end_; }
    /// Cycles of the current or last run (0 = forever).
    std::int64_t cycles_total() const { return cycles_; }
    /// First tick after the current run (kNever for a run without end, or none).
    Ticks end_tick() const { return state_ == State::Cycling ? end_ : kNever; }

    Ticks next_event(Ticks now) const override;
    void on_event(Ticks now) override;
    BodyKind kind() const override { return BodyKind::Solenoid; }

private:
    enum class State { Closed, Open, Cycling };
    Ticks period() const { return on_ + off_; }

    State state_ = State::Closed;
    Ticks start_ = 0;
    Ticks on_ = 1;
    Ticks off_ = 1;
    std::int64_t cycles_ = 0;
    Ticks end_ = kNever;
    std::int64_t done_ = 0;   ///< cycles completed, once a run is over
    Listener listener_;
};

} // namespace rigsim::models
