#pragma once
// The sampled output trace of a piezo channel for the control API (docs/control-api.md
// "Traces"): a fixed ring of the newest kTraceSamples samples, allocated once at the first
// sample, so recording costs a comparison and, when the output changed, one copy: no allocation
// per tick. The module records at each tick it runs; a sample equal to the last one is not kept
// unless a LUT runs, and a second sample of the same tick replaces the first.

#include "emulator/core/control_surface.hpp"
#include "models/clock.hpp"

#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rigsim::apt {

class OutputTrace {
public:
    /// One sample: [tick, output_code, output_v, position_um, lut_index|null] in JSON.
    struct Sample {
        Ticks tick = 0;
        double output_v = 0;       ///< the amplifier's output
        double position_um = 0;    ///< the actuator's physical extension (the world)
        std::int16_t output_code = 0;
        std::int16_t lut_index = -1;   ///< the LUT sample being output, -1: no LUT runs
    };

    /// Keep `s` if it differs from the last sample kept, or `always` (a LUT runs).
    void record(const Sample& s, bool always);
    /// Samples with tick >= `from`, oldest first, at most `max`, into `out`'s "samples", with
    /// "capacity", "kept" (samples in the ring), "oldest_tick" and "next_from" (the tick to ask
    /// from for the samples after these).
    void to_json(Ticks from, std::size_t max, nlohmann::json& out) const;
    std::size_t size() const { return size_; }
    void clear() { size_ = 0; head_ = 0; }

private:
    /// The i-th oldest sample kept.
    const Sample& at(std::size_t i) const { return ring_[(head_ + kTraceSamples - size_ + i) % kTraceSamples]; }

    std::vector<Sample> ring_;   ///< kTraceSamples once the first sample came
    std::size_t head_ = 0;       ///< where the next sample goes
    std::size_t size_ = 0;
};

} // namespace rigsim::apt
