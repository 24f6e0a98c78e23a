#include "models/lut_player.hpp"

#include <algorithm>
#include <limits>

namespace rigsim::models {

namespace {

constexpr std::int64_t kUsPerS = 1'000'000;

std::string hex16(std::uint16_t v)
{
    static const char digits[] = "0123456789ABCDEF";
    std::string s = "0x";
    for (int shift = 12; shift >= 0; shift -= 4)
        s += digits[(v >> shift) & 0xF];
    return s;
}

/// a * b + c, or nullopt on overflow (all operands >= 0).
std::optional<std::int64_t> mul_add(std::int64_t a, std::int64_t b, std::int64_t c)
{
    std::int64_t r = 0;
    if (__builtin_mul_overflow(a, b, &r) || __builtin_add_overflow(r, c, &r))
        return std::nullopt;
    return r;
}

} // namespace

bool LutPlayer::Params::operator==(const Params& o) const
{
    return mode == o.mode && cycle_length == o.cycle_length && num_cycles == o.num_cycles &&
           delay_time == o.delay_time && pre_cycle_rest == o.pre_cycle_rest &&
           post_cycle_rest == o.post_cycle_rest && op_trig_start == o.op_trig_start &&
           op_trig_width == o.op_trig_width && trig_repeat_cycle == o.trig_repeat_cycle;
}

LutPlayer::LutPlayer(const Clock& clock, std::size_t capacity)
    : clock_(clock), table_(Table::Zero(static_cast<Eigen::Index>(std::min(capacity, kMaxSamples))))
{
}

std::optional<std::string> LutPlayer::check_index(std::size_t index, std::size_t capacity)
{
    if (index >= capacity)
        return "Index " + std::to_string(index) + " is past the table (0.." + std::to_string(capacity - 1) +
               ", p.106)";
    return std::nullopt;
}

std::optional<std::string> LutPlayer::check_params(const Params& p, std::size_t capacity, bool has_triggers)
{
    const bool continuous = p.mode & kContinuous;
    const bool fixed = p.mode & kFixed;
    if (!continuous && !fixed)
        return "Mode " + hex16(p.mode) + " is neither OUTPUTLUT_CONTINUOUS (0x01) nor OUTPUTLUT_FIXED (0x02) (p.108)";
    if (continuous && fixed)
        return "Mode " + hex16(p.mode) + " is both OUTPUTLUT_CONTINUOUS and OUTPUTLUT_FIXED (p.108)";
    if (p.mode & 0xFF00)
        return "Mode " + hex16(p.mode) + " has bits above 0x80, which the manual does not define (p.108-109)";
    if (!has_triggers && (p.mode & kTriggerBits))
        return "Mode " + hex16(p.mode) + ": trigger bits 0x04-0x80 are not applicable to this unit (p.108)";
    if (p.cycle_length == 0)
        return "CycleLength 0 outputs no sample";
    if (p.cycle_length > capacity)
        return "CycleLength " + std::to_string(p.cycle_length) + " is more than the table's " +
               std::to_string(capacity) + " samples (p.106, p.109)";
    if (fixed && p.num_cycles < 1)
        return "NumCycles " + std::to_string(p.num_cycles) + ": fixed mode outputs 1.. cycles (p.109)";
    if (p.delay_time < 0 || p.pre_cycle_rest < 0 || p.post_cycle_rest < 0)
        return "DelayTime, PreCycleRest and PostCycleRest are 0.. sample intervals (p.109-110)";
    if ((p.mode & kOutputTrig) && (p.op_trig_start < 1 || p.op_trig_start >= p.cycle_length))
        return "OPTrigStart " + std::to_string(p.op_trig_start) + " is not in 1..CycleLength-1 (p.110)";
    if ((p.mode & kOutputTrig) && p.op_trig_width < 0)
        return "OPTrigWidth " + std::to_string(p.op_trig_width) + " is negative (p.110)";
    if ((p.mode & kOutputTrigRepeat) && p.trig_repeat_cycle >= capacity)
        return "TrigRepeatCycle " + std::to_string(p.trig_repeat_cycle) + " is past the table (p.110)";
    return std::nullopt;
}

std::optional<std::string> LutPlayer::check_start(const Params& p, std::size_t loaded,
                                                  std::uint32_t base_interval_us)
{
    if (base_interval_us == 0)
        return std::string("a base sample interval of 0 us");
    if (p.cycle_length > loaded)
        return "CycleLength " + std::to_string(p.cycle_length) + " is more than the " + std::to_string(loaded) +
               " samples loaded (p.109)";
    return std::nullopt;
}

bool LutPlayer::set_sample(std::size_t index, std::int16_t value)
{
    if (index >= capacity())
        return false;
    table_(static_cast<Eigen::Index>(index)) = value;
    loaded_ = std::max(loaded_, index + 1);
    return true;
}

std::int16_t LutPlayer::sample(std::size_t index) const
{
    return index < capacity() ? table_(static_cast<Eigen::Index>(index)) : std::int16_t{0};
}

void LutPlayer::set_table(const Table& table)
{
    const Eigen::Index n = std::min(table.size(), table_.size());
    table_.head(n) = table.head(n);
    loaded_ = std::max(loaded_, static_cast<std::size_t>(n));
}

std::optional<std::string> LutPlayer::start(Ticks now, std::uint32_t base_interval_us)
{
    if (auto why = check_params(params_, capacity(), true))
        return why;
    if (auto why = check_start(params_, loaded_, base_interval_us))
        return why;
    started_ = true;
    run_ = params_;
    run_table_ = table_.head(run_.cycle_length);
    base_interval_us_ = base_interval_us;
    start_ = now;
    cycle_intervals_ = std::int64_t{run_.pre_cycle_rest} + std::int64_t{run_.cycle_length} * delay_intervals() +
                       run_.post_cycle_rest;
    held_ = run_table_(run_.cycle_length - 1);
    end_ = kNever;
    if (run_.mode & kFixed) {
        const auto total = mul_add(run_.num_cycles, cycle_intervals_, 0);
        end_ = total ? tick_of_interval(*total) : kNever;
    }
    return std::nullopt;
}

void LutPlayer::stop(Ticks now)
{
    if (!running_at(now))
        return;
    held_ = run_table_(static_cast<Eigen::Index>(where(intervals_at(now)).index));
    end_ = now;
}

void LutPlayer::reset()
{
    started_ = false;
    start_ = 0;
    end_ = 0;
    held_ = 0;
}

std::optional<std::int16_t> LutPlayer::value_at(Ticks t) const
{
    if (!started_)
        return std::nullopt;
    if (t >= end_)
        return held_;
    const Ticks at = std::max(t, start_);
    return run_table_(static_cast<Eigen::Index>(where(intervals_at(at)).index));
}

std::optional<std::size_t> LutPlayer::index_at(Ticks t) const
{
    if (!running_at(t))
        return std::nullopt;
    return where(intervals_at(t)).index;
}

std::int64_t LutPlayer::cycle_at(Ticks t) const
{
    if (!started_ || t < start_)
        return 0;
    const std::int64_t cycles = intervals_at(std::min(t, end_)) / cycle_intervals_;
    return (run_.mode & kFixed) ? std::min<std::int64_t>(cycles, run_.num_cycles) : cycles;
}

Ticks LutPlayer::next_change(Ticks now) const
{
    if (!running_at(now))
        return kNever;
    const std::int64_t n = intervals_at(now);
    const std::int64_t within = n % cycle_intervals_;
    const std::int64_t cycle_start = n - within;
    const std::int64_t pre = run_.pre_cycle_rest;
    std::int64_t next = cycle_start + cycle_intervals_;   // the post-rest holds LUT[L-1] to here
    if (within < pre) {
        next = cycle_start + pre;
    } else {
        const std::int64_t k = (within - pre) / delay_intervals();
        if (k + 1 < run_.cycle_length)
            next = cycle_start + pre + (k + 1) * delay_intervals();
    }
    return std::min(tick_of_interval(next), end_);
}

std::int64_t LutPlayer::delay_intervals() const
{
    return std::max<std::int64_t>(1, run_.delay_time);
}

std::int64_t LutPlayer::intervals_at(Ticks t) const
{
    // floor((t - start) s · 1e6 / (hz · b)) in integers: the whole seconds and the rest apart,
    // so that nothing overflows before 9e12 s; floor(floor(x) / b) = floor(x / b).
    const std::int64_t hz = clock_.tick_hz();
    const Ticks dt = t - start_;
    const std::int64_t us = (dt / hz) * kUsPerS + (dt % hz) * kUsPerS / hz;
    return us / base_interval_us_;
}

Ticks LutPlayer::tick_of_interval(std::int64_t n) const
{
    // intervals_at(t) >= n  <=>  (t - start) · 1e6 >= n · b · hz.
    const std::int64_t hz = clock_.tick_hz();
    const auto us = mul_add(n, base_interval_us_, 0);
    if (!us)
        return kNever;
    const auto whole = mul_add(*us / kUsPerS, hz, (*us % kUsPerS * hz + kUsPerS - 1) / kUsPerS);
    if (!whole)
        return kNever;
    const auto t = mul_add(1, start_, *whole);
    return t ? *t : kNever;
}

LutPlayer::Where LutPlayer::where(std::int64_t n) const
{
    const std::int64_t within = n % cycle_intervals_;
    const std::int64_t pre = run_.pre_cycle_rest;
    if (within < pre)
        return {n / cycle_intervals_, 0};
    const std::int64_t k = (within - pre) / delay_intervals();
    const std::int64_t last = run_.cycle_length - 1;
    return {n / cycle_intervals_, static_cast<std::size_t>(std::min(k, last))};
}

} // namespace rigsim::models
