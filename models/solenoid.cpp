#include "models/solenoid.hpp"

#include <algorithm>

namespace rigsim::models {

void Solenoid::open(Ticks now)
{
    done_ = cycles_done(now);
    state_ = State::Open;
    reschedule();
}

void Solenoid::close(Ticks now)
{
    done_ = cycles_done(now);
    state_ = State::Closed;
    reschedule();
}

void Solenoid::start_cycles(Ticks now, Ticks on_ticks, Ticks off_ticks, std::int64_t cycles)
{
    state_ = State::Cycling;
    start_ = now;
    on_ = std::max<Ticks>(1, on_ticks);
    off_ = std::max<Ticks>(1, off_ticks);
    cycles_ = std::max<std::int64_t>(0, cycles);
    done_ = 0;
    Ticks span = 0;
    end_ = kNever;
    if (cycles_ > 0 && !__builtin_mul_overflow(cycles_, period(), &span) && !__builtin_add_overflow(now, span, &span))
        end_ = span;
    reschedule();
}

bool Solenoid::active_at(Ticks now) const
{
    switch (state_) {
    case State::Closed:
        return false;
    case State::Open:
        return true;
    case State::Cycling:
        return now >= start_ && now < end_ && (now - start_) % period() < on_;
    }
    return false;
}

std::int64_t Solenoid::cycles_done(Ticks now) const
{
    if (state_ != State::Cycling)
        return done_;
    if (now < start_)
        return 0;
    const std::int64_t done = (now - start_) / period();
    return cycles_ > 0 ? std::min(done, cycles_) : done;
}

Ticks Solenoid::next_event(Ticks now) const
{
    if (state_ != State::Cycling)
        return kNever;
    if (now < start_)
        return start_ + on_;
    const Ticks cycle_start = now - (now - start_) % period();
    const Ticks edge = now < cycle_start + on_ ? cycle_start + on_ : cycle_start + period();
    return std::min(edge, end_);
}

void Solenoid::on_event(Ticks now)
{
    if (state_ != State::Cycling)
        return;
    if (now >= end_) {
        done_ = cycles_;
        state_ = State::Closed;
        return;   // the output closed at the last cycle's off edge: no edge here
    }
    if (listener_)
        listener_(now, active_at(now));
}

} // namespace rigsim::models
