#include "models/strain_gauge.hpp"

#include "models/piezo_actuator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rigsim::models {

namespace {

constexpr double kTwoPi = 6.283185307179586;

std::uint64_t splitmix64(std::uint64_t x)
{
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
}

/// A standard normal variate that is a pure function of (seed, index): Box-Muller on two hashes.
double gaussian(std::uint32_t seed, std::int64_t index)
{
    const std::uint64_t h1 =
        splitmix64((static_cast<std::uint64_t>(seed) << 32) ^ splitmix64(static_cast<std::uint64_t>(index)));
    const std::uint64_t h2 = splitmix64(h1);
    const double u1 = (static_cast<double>(h1 >> 11) + 1.0) * 0x1.0p-53;   // (0, 1]
    const double u2 = static_cast<double>(h2 >> 11) * 0x1.0p-53;           // [0, 1)
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

} // namespace

StrainGauge::StrainGauge(const Clock& clock, StrainGaugeConfig config) : clock_(clock), config_(std::move(config))
{
    if (config_.sample_hz == 0)
        throw std::invalid_argument("strain gauge: the sample rate must be > 0 Hz");
    set_noise_um(config_.noise_um);
}

void StrainGauge::link(World& world)
{
    Body* body = world.find(config_.actuator_key);
    if (!body)
        throw std::invalid_argument("strain gauge \"" + key() + "\": the world has no body \""
                                    + config_.actuator_key + "\" to be mounted on");
    auto* actuator = dynamic_cast<PiezoActuator*>(body);
    if (!actuator)
        throw std::invalid_argument("strain gauge \"" + key() + "\": \"" + config_.actuator_key
                                    + "\" is not a piezo actuator");
    if (actuator_ == actuator)
        return;   // linked before (link_all() ran again)
    if (actuator_)
        throw std::invalid_argument("strain gauge \"" + key() + "\" is mounted on an actuator already");
    actuator_ = actuator;
    actuator->add_listener([this] { on_actuator_changed(); });
    held_um_ = actuator_->extension_um();
    if (!actuator_->settled())
        on_actuator_changed();
}

void StrainGauge::set_noise_um(double sigma_um)
{
    if (!(sigma_um >= 0))
        throw std::invalid_argument("strain gauge: the noise must be >= 0 µm");
    config_.noise_um = sigma_um;
}

std::int64_t StrainGauge::sample_index(Ticks now) const
{
    return std::max<Ticks>(now, 0) * config_.sample_hz / clock_.tick_hz();
}

Ticks StrainGauge::sample_tick(std::int64_t k) const
{
    const std::int64_t hz = clock_.tick_hz();
    return (k * hz + config_.sample_hz - 1) / config_.sample_hz;
}

void StrainGauge::catch_up(Ticks now) const
{
    const std::int64_t k_now = sample_index(now);
    if (!recording_ || k_now <= newest_)
        return;
    // Several samples due in one tick (a clock slower than 500 Hz) all see that tick's extension.
    const double x_um = actuator_->extension_um();
    for (std::int64_t k = std::max(newest_ + 1, k_now - kSmoothing + 1); k <= k_now; ++k)
        ring_[k % kSmoothing] = Sample{k, x_um};
    newest_ = k_now;
}

void StrainGauge::on_actuator_changed()
{
    const Ticks now = clock_.now();
    catch_up(now);
    if (!recording_) {
        // The samples up to now were taken at rest: they hold the extension last recorded.
        const std::int64_t k_now = sample_index(now);
        for (std::int64_t k = std::max(newest_ + 1, k_now - kSmoothing + 1); k <= k_now; ++k)
            ring_[k % kSmoothing] = Sample{k, held_um_};
        newest_ = std::max(newest_, k_now);
        recording_ = true;
    }
    reschedule();
}

double StrainGauge::extension_of(std::int64_t k) const
{
    if (k > newest_)
        return held_um_;
    const Sample& s = ring_[k % kSmoothing];
    return s.index == k ? s.extension_um : held_um_;
}

double StrainGauge::raw_um(std::int64_t k) const
{
    const double noise = config_.noise_um > 0 ? config_.noise_um * gaussian(config_.seed, k) : 0.0;
    return extension_of(k) + noise;
}

double StrainGauge::raw_smoothed_um(std::int64_t k) const
{
    const std::int64_t first = std::max<std::int64_t>(0, k - kSmoothing + 1);
    double sum = 0;
    for (std::int64_t i = first; i <= k; ++i)
        sum += raw_um(i);
    return sum / static_cast<double>(k - first + 1);
}

double StrainGauge::reading_um(Ticks now) const
{
    catch_up(now);
    return raw_um(sample_index(now)) - offset_um_;
}

double StrainGauge::smoothed_um(Ticks now) const
{
    catch_up(now);
    return raw_smoothed_um(sample_index(now)) - offset_um_;
}

void StrainGauge::zero(Ticks now)
{
    catch_up(now);
    offset_um_ = raw_smoothed_um(sample_index(now));
}

Ticks StrainGauge::next_event(Ticks now) const
{
    return recording_ ? sample_tick(sample_index(now) + 1) : kNever;
}

void StrainGauge::on_event(Ticks now)
{
    catch_up(now);
    if (recording_ && actuator_->settled()) {
        recording_ = false;
        held_um_ = extension_of(newest_);
    }
}

} // namespace rigsim::models
