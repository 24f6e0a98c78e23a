#pragma once
// A fibre paddle of a motorised polarisation controller (MPC320/MPC220): it turns between 0 and
// its end (170 degrees) at a set speed, from where it stands to a target, and stops where it is
// told to. Its angle is a function of clock time along the current move; only the timing and the
// angle live here, the protocol (counts, jog steps, home) is the module's
// (emulator/apt/polariser_module.*).
//
// The world wakes the body when a move ends (the listener hears it), and never while it rests.

#include "models/clock.hpp"
#include "models/owned_listener.hpp"
#include "models/world.hpp"

#include <functional>

namespace rigsim::models {

class Paddle : public Body {
public:
    /// Told when a move ends (the paddle at its target), at its tick.
    using Listener = std::function<void(Ticks at)>;

    explicit Paddle(double max_deg) : max_deg_(max_deg) {}

    /// The listener of `owner` (a module: a power cycle's new one takes over before the old goes).
    void set_listener(const void* owner, Listener listener) { listener_.set(owner, std::move(listener)); }
    /// No listener any more, if `owner`'s is the one set.
    void clear_listener(const void* owner) { listener_.clear(owner); }

    /// From `now`, toward `target_deg` (clamped to 0..max) at `deg_per_tick` (> 0); replaces a move
    /// under way from where the paddle is.
    void move_to(Ticks now, double target_deg, double deg_per_tick);
    /// Stop where it is at `now` (no event).
    void stop(Ticks now);
    /// Put it at `deg` without a move (a power cycle restoring the mechanics).
    void place(double deg);

    double angle_at(Ticks now) const;
    bool moving_at(Ticks now) const { return moving_ && now < end_; }
    /// +1 turning up, -1 down, 0 at rest.
    int direction_at(Ticks now) const;
    double target() const { return target_; }
    double max_deg() const { return max_deg_; }

    Ticks next_event(Ticks now) const override;
    void on_event(Ticks now) override;
    BodyKind kind() const override { return BodyKind::Paddle; }

private:
    double max_deg_;
    double from_ = 0;
    double target_ = 0;
    double rate_ = 0;   ///< degrees per tick along the move
    Ticks start_ = 0;
    Ticks end_ = 0;
    bool moving_ = false;
    OwnedListener<Ticks> listener_;
};

} // namespace rigsim::models
