#include "emulator/apt/output_trace.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

namespace rigsim::apt {

namespace {

/// Position changes below this (µm) do not make a new sample on their own: the actuator's
/// settling tail and creep would otherwise fill the ring with no visible change.
constexpr double kPositionResolution_um = 1e-4;

} // namespace

void OutputTrace::record(const Sample& s, bool always)
{
    if (size_ > 0) {
        Sample& last = ring_[(head_ + kTraceSamples - 1) % kTraceSamples];
        if (last.tick == s.tick) {
            last = s;
            return;
        }
        const bool same = last.output_code == s.output_code && last.output_v == s.output_v
                          && last.lut_index == s.lut_index
                          && std::abs(last.position_um - s.position_um) < kPositionResolution_um;
        if (same && !always)
            return;
    }
    if (ring_.empty())
        ring_.resize(kTraceSamples);
    ring_[head_] = s;
    head_ = (head_ + 1) % kTraceSamples;
    if (size_ < kTraceSamples)
        ++size_;
}

void OutputTrace::to_json(Ticks from, std::size_t max, nlohmann::json& out) const
{
    // Ticks rise through the ring: the first sample at or after `from` by bisection.
    std::size_t lo = 0;
    std::size_t hi = size_;
    while (lo < hi) {
        const std::size_t mid = (lo + hi) / 2;
        if (at(mid).tick < from)
            lo = mid + 1;
        else
            hi = mid;
    }
    auto samples = nlohmann::json::array();
    std::size_t i = lo;
    for (; i < size_ && i - lo < max; ++i) {
        const Sample& s = at(i);
        samples.push_back({s.tick, s.output_code, s.output_v, s.position_um,
                           s.lut_index < 0 ? nlohmann::json(nullptr) : nlohmann::json(s.lut_index)});
    }
    out["capacity"] = kTraceSamples;
    out["kept"] = size_;
    out["oldest_tick"] = size_ > 0 ? nlohmann::json(at(0).tick) : nlohmann::json(nullptr);
    out["next_from"] = i > lo ? at(i - 1).tick + 1 : from;
    out["samples"] = std::move(samples);
}

} // namespace rigsim::apt
