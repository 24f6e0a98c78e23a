#pragma once
// The arm of a motorised flip mount (MFF101/MFF102): at position 1 or position 2, or on its way
// from one to the other, which takes the transit time. A turn back on the way takes as long as
// the arm has travelled. Only the timing lives here; the flipper's protocol (positions by
// MOT_MOVE_JOG, its parameter block) is the module's (emulator/apt/flipper_module.*).
//
// The world wakes the body when the arm arrives (the listener hears it), and never while it rests.

#include "models/clock.hpp"
#include "models/owned_listener.hpp"
#include "models/world.hpp"

#include <functional>

namespace rigsim::models {

class Flipper : public Body {
public:
    /// Told when the arm arrives at `position` (1 or 2), at its tick.
    using Listener = std::function<void(Ticks at, int position)>;

    explicit Flipper(int position = 1) : position_(position == 2 ? 2 : 1) {}

    /// The listener of `owner` (a module: a power cycle's new one takes over before the old goes).
    void set_listener(const void* owner, Listener listener) { listener_.set(owner, std::move(listener)); }
    /// No listener any more, if `owner`'s is the one set.
    void clear_listener(const void* owner) { listener_.clear(owner); }

    /// From `now`, to `target` (1 or 2) in `transit` ticks (at least 1). Toward the position it
    /// is already at or travelling to: nothing changes. Back while travelling: it arrives after
    /// as long as it has travelled.
    void move_to(Ticks now, int target, Ticks transit);
    /// Where the arm rests (1 or 2), or 0 while it travels.
    int position_at(Ticks now) const;
    /// The position the arm travels to (or rests at).
    int target() const { return target_; }
    bool moving_at(Ticks now) const { return target_ != position_ && now < arrive_; }
    /// The tick the arm arrives (kNever while it rests).
    Ticks arrival() const { return target_ != position_ ? arrive_ : kNever; }
    /// Back where it started (a power cycle with the mechanics restored).
    void place(int position);

    Ticks next_event(Ticks now) const override;
    void on_event(Ticks now) override;
    BodyKind kind() const override { return BodyKind::Flipper; }

private:
    int position_;           ///< where it rests, or came from while travelling
    int target_ = position_;
    Ticks start_ = 0;
    Ticks arrive_ = 0;
    OwnedListener<Ticks, int> listener_;
};

} // namespace rigsim::models
