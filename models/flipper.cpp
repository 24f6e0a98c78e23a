#include "models/flipper.hpp"

#include <algorithm>

namespace rigsim::models {

void Flipper::move_to(Ticks now, int target, Ticks transit)
{
    target = target == 2 ? 2 : 1;
    on_event(now);   // an arrival due by now first
    if (target == target_)
        return;
    transit = std::max<Ticks>(1, transit);
    if (target_ != position_) {
        // Turning back on the way: as long as it has travelled.
        const Ticks travelled = std::max<Ticks>(1, now - start_);
        position_ = target_;
        target_ = target;
        start_ = now;
        arrive_ = now + travelled;
    } else {
        target_ = target;
        start_ = now;
        arrive_ = now + transit;
    }
    reschedule();
}

int Flipper::position_at(Ticks now) const
{
    if (target_ == position_)
        return position_;
    return now >= arrive_ ? target_ : 0;
}

void Flipper::place(int position)
{
    position_ = target_ = position == 2 ? 2 : 1;
    reschedule();
}

Ticks Flipper::next_event(Ticks now) const
{
    if (target_ == position_)
        return kNever;
    return std::max(arrive_, now);
}

void Flipper::on_event(Ticks now)
{
    if (target_ == position_ || now < arrive_)
        return;
    position_ = target_;
    reschedule();
    listener_(arrive_, position_);
}

} // namespace rigsim::models
