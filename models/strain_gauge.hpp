#pragma once
// A strain gauge on a piezo actuator (TSG001/KSG101, a TPZ001's feedback, a BPC30x bay's
// sensor): it reads the actuator's physical extension, never a controller's protocol state.
//
// The gauge electronics sample at 500 Hz (APT manual p.129, PZ_GET_TSG_READING: "sampled at
// 500Hz") and hold each sample until the next: sample k is taken at the first tick at or after
// k/500 s. A sample's noise is a Gaussian drawn from a hash of (seed, k), not from a stream, so
// the same instant reads the same value whoever asks and however often, and a run repeats. The
// smoothed reading is the mean of the last 8 samples (plan D-16: the manual defines no filter).
//
// Cost: the gauge records samples (a wake-up every 2 ms) only while its actuator moves; the
// actuator calls it back on every new voltage. Once the actuator has settled every later
// sample holds the extension last recorded (the actuator moves by less than 1e-6 of its travel
// from then on), plus its own noise, with no wake-up at all.

#include "models/clock.hpp"
#include "models/world.hpp"

#include <array>
#include <cstdint>
#include <string>

namespace rigsim::models {

class PiezoActuator;

struct StrainGaugeConfig {
    std::string actuator_key;        ///< the world's key of the PiezoActuator the gauge is mounted on
    double noise_um = 0;             ///< sigma of the Gaussian noise of one sample
    std::uint32_t seed = 0;
    std::uint32_t sample_hz = 500;   ///< p.129
};

class StrainGauge : public Body {
public:
    static constexpr int kSmoothing = 8;

    /// std::invalid_argument for a sample rate of 0 or a negative noise.
    StrainGauge(const Clock& clock, StrainGaugeConfig config);

    /// Finds the actuator (std::invalid_argument if no body has the key or it is no piezo actuator).
    void link(World& world) override;
    /// The linked actuator, or nullptr before link().
    const PiezoActuator* actuator() const { return actuator_; }
    /// The configuration (with the noise last set).
    const StrainGaugeConfig& config() const { return config_; }

    /// Index of the sample held at tick `now`.
    std::int64_t sample_index(Ticks now) const;
    /// The sample held at `now` (the clock's now), less the zero offset (µm).
    double reading_um(Ticks now) const;
    /// Mean of the last 8 samples at `now`, less the zero offset (µm).
    double smoothed_um(Ticks now) const;
    /// Zero reference := the smoothed reading at `now` (so zeroing averages the noise out).
    void zero(Ticks now);
    /// Forget the zero reference (the reader's power-down): the raw extension reads again.
    void clear_zero() { offset_um_ = 0; }
    /// The extension that reads 0 (0 until zero()).
    double zero_offset_um() const { return offset_um_; }
    /// Sigma of the noise from now on, for every sample read (std::invalid_argument if < 0).
    void set_noise_um(double sigma_um);
    /// Sigma of the noise of one sample (µm).
    double noise_um() const { return config_.noise_um; }

    Ticks next_event(Ticks now) const override;
    void on_event(Ticks now) override;
    BodyKind kind() const override { return BodyKind::StrainGauge; }

private:
    struct Sample {
        std::int64_t index = -1;
        double extension_um = 0;
    };
    /// First tick of sample `k`.
    Ticks sample_tick(std::int64_t k) const;
    /// Records the samples due up to `now` while the actuator moves (reads call it too: the
    /// world may wake the gauge after a reader in the same tick).
    void catch_up(Ticks now) const;
    /// The physical extension of sample `k` (<= the newest index decided).
    double extension_of(std::int64_t k) const;
    /// Extension + noise of sample `k`, before the zero offset.
    double raw_um(std::int64_t k) const;
    double raw_smoothed_um(std::int64_t k) const;
    void on_actuator_changed();

    const Clock& clock_;
    StrainGaugeConfig config_;
    const PiezoActuator* actuator_ = nullptr;
    double offset_um_ = 0;
    bool recording_ = false;               ///< the actuator moves: samples are recorded
    mutable std::array<Sample, kSmoothing> ring_{};   ///< sample k at k % 8
    mutable std::int64_t newest_ = -1;     ///< highest sample index decided so far
    double held_um_ = 0;                   ///< extension of every sample after newest_ while at rest
};

} // namespace rigsim::models
