// A TPZ001 piezo driver in closed loop on the TSG001 strain gauge reader mounted on its actuator
// (manual p.94, p.97, p.115, p.127-129): the loop reads the gauge through the world and holds the
// position against the actuator's creep, which an open-loop output does not; the gauge's noise
// repeats run after run. Wire-exact exchanges: transcripts/apt_strain_gauge.txt.
#include "apt_harness.hpp"

#include "models/piezo_actuator.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

namespace test_apt_closed_loop {

using namespace rigsim::test;

namespace {

constexpr double kTravelUm = 20;

/// A TPZ001 ("tpz", device 0) with a creeping 20 um, 75 V actuator; then a TSG001 ("tsg",
/// device 1) mounted on it (mounted_on "" fits none).
std::unique_ptr<AptHarness> tpz_with_gauge(double creep, double noise_um, std::uint32_t seed,
                                           const std::string& mounted_on = "tpz")
{
    rigsim::DeviceConfig tpz;
    tpz.name = "tpz";
    tpz.protocol = "apt";
    tpz.model = "TPZ001";
    auto& a = config_of(tpz).actuator;
    a.travel_um = kTravelUm;
    a.max_voltage_v = 75;
    a.creep = creep;
    a.hysteresis = 0.05;
    a.response_ms = 1;
    auto h = std::make_unique<AptHarness>(tpz);
    rigsim::DeviceConfig tsg;
    tsg.name = "tsg";
    tsg.protocol = "apt";
    tsg.model = "TSG001";
    auto& g = config_of(tsg).gauge;
    g.mounted_on = mounted_on;
    g.noise_um = noise_um;
    g.seed = seed;
    REQUIRE(h->add_device(tsg) == 1);
    return h;
}

double extension_um(AptHarness& h)
{
    auto* a = h.world().find_as<rigsim::models::PiezoActuator>("tpz/1");
    REQUIRE(a != nullptr);
    return a->extension_um();
}

/// TSG_READING's Reading word (p.129).
std::int16_t reading(AptHarness& h)
{
    const auto b = bytes(h.send("DD 07 01 00 50 01", 1));
    REQUIRE(b.size() == 12);
    return static_cast<std::int16_t>(get_u16(b, 8));
}

} // namespace

TEST_CASE("apt closed loop: a TPZ001 on its TSG001 holds OUTPUTPOS 50 % against creep for 60 s",
          "[device][apt][piezo][gauge]")
{
    auto h = tpz_with_gauge(0.02, 0.002, 1);
    h->send("40 06 01 02 50 01");   // closed loop (p.94): the gauge on hub A feeds input 1
    REQUIRE(h->send("41 06 01 00 50 01") == "42 06 01 02 01 50");
    h->send("46 06 04 00 D0 01 01 00 00 40");   // 16384 of 32767 (p.97)
    const double target_um = 16384.0 / 32767.0 * kTravelUm;
    h->advance_ms(500);
    double worst = 0;
    for (int s = 0; s < 60; ++s) {
        h->advance_ms(1000);
        worst = std::max(worst, std::abs(extension_um(*h) - target_um));
    }
    INFO("largest error " << worst << " um");
    CHECK(worst < 0.001 * kTravelUm);
}

TEST_CASE("apt closed loop: the same output in open loop creeps by more than 1 % of the travel in 60 s",
          "[device][apt][piezo][gauge]")
{
    auto h = tpz_with_gauge(0.02, 0.002, 1);
    h->send("43 06 04 00 D0 01 01 00 00 40");   // 50 % of 75 V (p.96), open loop
    h->advance_ms(500);
    const double start_um = extension_um(*h);
    h->advance_ms(60'000);
    const double drift = extension_um(*h) - start_um;
    INFO("drift " << drift << " um");
    CHECK(drift > 0.01 * kTravelUm);
}

TEST_CASE("apt closed loop: the gauge's noise repeats with its seed and changes with another",
          "[device][apt][gauge]")
{
    auto run = [](std::uint32_t seed) {
        auto h = tpz_with_gauge(0, 0.05, seed);
        h->send("43 06 04 00 D0 01 01 00 00 40");
        std::vector<std::int16_t> codes;
        for (int i = 0; i < 20; ++i) {
            h->advance_ms(7);
            codes.push_back(reading(*h));
        }
        return codes;
    };
    const auto first = run(7);
    CHECK(run(7) == first);
    CHECK(run(8) != first);
    // sigma 0.05 um of 20 um is about 82 codes: the samples differ.
    CHECK(*std::max_element(first.begin(), first.end()) != *std::min_element(first.begin(), first.end()));
}

TEST_CASE("apt closed loop: a TSG001 without a gauge fitted reads 0 with bit 0x1 clear and its TPZ001 stays open loop",
          "[device][apt][gauge]")
{
    auto h = tpz_with_gauge(0, 0, 1, "");
    h->send("43 06 04 00 D0 01 01 00 77 77");
    h->advance_ms(100);
    CHECK(h->send("DD 07 01 00 50 01", 1) == "DE 07 06 00 81 50 01 00 00 00 00 00");
    CHECK(h->send("50 06 01 00 50 01", 1) == "51 06 04 00 81 50 01 00 00 00");
    h->send("11 00 00 00 50 01", 1);
    h->advance_ms(100);
    CHECK(h->take(1) == "61 06 0A 00 81 50 01 00 00 00 00 00 00 00 00 00");
    h->send("40 06 01 02 50 01");   // D-19: no feedback
    CHECK(h->send("41 06 01 00 50 01") == "42 06 01 01 01 50");
}

} // namespace test_apt_closed_loop
