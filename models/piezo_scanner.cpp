#include "models/piezo_scanner.hpp"

#include <algorithm>
#include <cmath>

namespace rigsim::models {

PiezoScanner::PiezoScanner(const Clock& clock, double range_nm) : clock_(clock), range_nm_(range_nm) {}

void PiezoScanner::start(Ticks now, double target_levels, double speed_levels_per_s)
{
    settle(now);
    scanning_ = true;
    target_levels_ = target_levels;
    speed_levels_per_s_ = speed_levels_per_s;
    start_ = now;
    // The first tick whose elapsed time covers the span; the estimate is corrected with the
    // very expression level_at() uses, so the end tick and the level agree to the bit.
    const double span = std::abs(target_levels_ - level_);
    const double estimate = span / speed_levels_per_s_ * clock_.tick_hz();
    end_ = now + std::max<Ticks>(0, static_cast<Ticks>(std::min(estimate, 4e18)) - 2);
    while (clock_.seconds(end_ - start_) * speed_levels_per_s_ < span)
        ++end_;
}

double PiezoScanner::level_at(Ticks now) const
{
    if (!scanning_)
        return level_;
    const double t = clock_.seconds(now - start_);
    const double span = target_levels_ - level_;
    const double done = std::min(std::abs(span), t * speed_levels_per_s_);
    return level_ + std::copysign(done, span);
}

double PiezoScanner::displacement_nm(Ticks now) const
{
    return scanning_ ? (level_at(now) - level_) * range_nm_ / kMaxLevel : 0.0;
}

void PiezoScanner::settle(Ticks now)
{
    level_ = level_at(now);
    scanning_ = false;
}

} // namespace rigsim::models
