#include "models/paddle.hpp"

#include <algorithm>
#include <cmath>

namespace rigsim::models {

void Paddle::move_to(Ticks now, double target_deg, double deg_per_tick)
{
    const double at = angle_at(now);
    target_deg = std::clamp(target_deg, 0.0, max_deg_);
    from_ = at;
    target_ = target_deg;
    start_ = now;
    rate_ = deg_per_tick > 0 ? deg_per_tick : 1e-9;
    end_ = now + std::max<Ticks>(1, static_cast<Ticks>(std::ceil(std::abs(target_deg - at) / rate_)));
    moving_ = true;
    reschedule();
}

void Paddle::stop(Ticks now)
{
    from_ = target_ = angle_at(now);
    moving_ = false;
    reschedule();
}

void Paddle::place(double deg)
{
    from_ = target_ = std::clamp(deg, 0.0, max_deg_);
    moving_ = false;
    reschedule();
}

double Paddle::angle_at(Ticks now) const
{
    if (!moving_ || now >= end_)
        return target_;
    if (now <= start_)
        return from_;
    const double travelled = rate_ * static_cast<double>(now - start_);
    return target_ >= from_ ? std::min(target_, from_ + travelled) : std::max(target_, from_ - travelled);
}

int Paddle::direction_at(Ticks now) const
{
    if (!moving_at(now) || target_ == from_)
        return 0;
    return target_ > from_ ? 1 : -1;
}

Ticks Paddle::next_event(Ticks now) const
{
    return moving_ ? std::max(end_, now) : kNever;
}

void Paddle::on_event(Ticks now)
{
    if (!moving_ || now < end_)
        return;
    moving_ = false;
    from_ = target_;
    reschedule();
    listener_(end_);
}

} // namespace rigsim::models
