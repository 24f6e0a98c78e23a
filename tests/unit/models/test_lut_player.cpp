// models::LutPlayer: the piezo waveform generator (APT manual p.106-112) as a function of
// clock time: samples, rests, cycles, stop, sub-tick sample intervals, parameter checks.

#include "models/lut_player.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace test_lut_player {

using namespace rigsim;
using namespace rigsim::models;

namespace {

using Params = LutPlayer::Params;
constexpr double kPi = 3.14159265358979323846;

/// 16384 + 16000·sin(2πk/1000), k = 0..999 (plan §5.3).
LutPlayer::Table sine_table()
{
    LutPlayer::Table t(1000);
    for (int k = 0; k < 1000; ++k)
        t(k) = static_cast<std::int16_t>(std::lround(16384 + 16000 * std::sin(2 * kPi * k / 1000)));
    return t;
}

Params params(std::uint16_t mode, std::uint16_t length, std::int32_t delay = 1, std::int32_t pre = 0,
              std::int32_t post = 0, std::int32_t cycles = 1)
{
    Params p;
    p.mode = mode;
    p.cycle_length = length;
    p.delay_time = delay;
    p.pre_cycle_rest = pre;
    p.post_cycle_rest = post;
    p.num_cycles = cycles;
    return p;
}

/// 10, 20, 30, 40 at indices 0..3.
void load_ramp(LutPlayer& lut)
{
    for (std::size_t i = 0; i < 4; ++i)
        REQUIRE(lut.set_sample(i, static_cast<std::int16_t>(10 * (i + 1))));
}

std::vector<int> values(const LutPlayer& lut, Ticks from, Ticks to)
{
    std::vector<int> v;
    for (Ticks t = from; t < to; ++t)
        v.push_back(*lut.value_at(t));
    return v;
}

} // namespace

TEST_CASE("lut player: a 1000-sample sine at 1 ms per sample reads back the table at every tick",
          "[unit][models][lut]")
{
    Clock clock;   // 1 kHz
    LutPlayer lut(clock);
    const auto table = sine_table();
    lut.set_table(table);
    CHECK(lut.loaded() == 1000);
    lut.set_params(params(LutPlayer::kContinuous, 1000));
    CHECK_FALSE(lut.value_at(0).has_value());   // nothing output before a start
    REQUIRE_FALSE(lut.start(500, 1000));
    for (int k : {0, 1, 250, 500, 999})
        CHECK(*lut.value_at(500 + k) == table(k));
    for (int k = 0; k < 1000; ++k) {
        REQUIRE(*lut.value_at(500 + k) == table(k));
        REQUIRE(*lut.index_at(500 + k) == static_cast<std::size_t>(k));
    }
    CHECK(*lut.value_at(1500) == table(0));   // the next cycle
    CHECK(lut.cycle_at(1500) == 1);
    CHECK(lut.cycle_at(1499) == 0);
}

TEST_CASE("lut player: each cycle holds LUT[0] for PreCycleRest and LUT[L-1] for PostCycleRest",
          "[unit][models][lut]")
{
    Clock clock;
    LutPlayer lut(clock);
    load_ramp(lut);
    lut.set_params(params(LutPlayer::kContinuous, 4, /*delay*/ 2, /*pre*/ 3, /*post*/ 5));
    REQUIRE_FALSE(lut.start(100, 1000));
    // One cycle: 3 pre + 4 samples x 2 + 5 post = 16 intervals of 1 ms.
    const std::vector<int> cycle{10, 10, 10, 10, 10, 20, 20, 30, 30, 40, 40, 40, 40, 40, 40, 40};
    CHECK(values(lut, 100, 116) == cycle);
    CHECK(values(lut, 116, 132) == cycle);
    CHECK(*lut.index_at(101) == 0);   // pre-rest
    CHECK(*lut.index_at(113) == 3);   // post-rest
    CHECK(lut.cycle_at(131) == 1);
    CHECK(lut.cycle_at(132) == 2);
    // The module may sleep between changes of sample.
    CHECK(lut.next_change(100) == 103);
    CHECK(lut.next_change(105) == 107);
    CHECK(lut.next_change(109) == 116);   // L-1 then the post-rest: one stretch
}

TEST_CASE("lut player: a fixed run ends after NumCycles and holds its last value",
          "[unit][models][lut]")
{
    Clock clock;
    LutPlayer lut(clock);
    load_ramp(lut);
    REQUIRE(lut.set_sample(0, 99));   // LUT[0] differs from LUT[L-1]: the hold is the last
    lut.set_params(params(LutPlayer::kFixed, 4, 2, 3, 0, /*cycles*/ 3));
    REQUIRE_FALSE(lut.start(0, 1000));
    CHECK(lut.end_tick() == 33);   // 3 x (3 + 8)
    CHECK(lut.running_at(32));
    CHECK(*lut.value_at(32) == 40);
    CHECK_FALSE(lut.running_at(33));
    CHECK(*lut.value_at(33) == 40);
    CHECK(*lut.value_at(1'000'000) == 40);
    CHECK_FALSE(lut.index_at(33).has_value());
    CHECK(lut.cycle_at(32) == 2);
    CHECK(lut.cycle_at(33) == 3);
    CHECK(lut.cycle_at(1'000'000) == 3);
    CHECK(lut.next_change(31) == 33);
    CHECK(lut.next_change(33) == kNever);
    lut.stop(40);   // over already: nothing changes
    CHECK(*lut.value_at(40) == 40);
    CHECK(lut.end_tick() == 33);
    lut.reset();
    CHECK_FALSE(lut.value_at(40).has_value());
}

TEST_CASE("lut player: a continuous run goes on until stop, which holds the value of that instant",
          "[unit][models][lut]")
{
    Clock clock;
    LutPlayer lut(clock);
    load_ramp(lut);
    lut.set_params(params(LutPlayer::kContinuous, 4, 1, 0, 0, /*ignored*/ 0));
    REQUIRE_FALSE(lut.start(0, 1000));
    CHECK(lut.end_tick() == kNever);
    const Ticks late = 3'600'000'001;   // an hour on, sample 1 of its cycle
    CHECK(lut.running_at(late));
    CHECK(*lut.value_at(late) == 20);
    // A SET during the run changes the next run, not this one (the run is a function of time).
    REQUIRE(lut.set_sample(2, -5));
    lut.set_params(params(LutPlayer::kFixed, 2));
    CHECK(*lut.value_at(late + 1) == 30);
    lut.stop(late + 1);
    CHECK(lut.end_tick() == late + 1);
    CHECK_FALSE(lut.running_at(late + 1));
    CHECK(*lut.value_at(late + 1) == 30);
    CHECK(*lut.value_at(late + 10'000) == 30);
    CHECK(lut.cycle_at(late + 10'000) == late / 4);
    // The next start takes the new table and parameters.
    REQUIRE_FALSE(lut.start(late + 20, 1000));
    CHECK(values(lut, late + 20, late + 23) == std::vector<int>{10, 20, 20});
}

TEST_CASE("lut player: sample intervals shorter than a tick give the exact schedule's sample at each tick",
          "[unit][models][lut]")
{
    LutPlayer::Table ramp(13);
    for (int i = 0; i < 13; ++i)
        ramp(i) = static_cast<std::int16_t>(100 * i);

    SECTION("0.25 ms samples (TPZ base) on a 1 ms tick: every fourth sample")
    {
        Clock clock;
        LutPlayer lut(clock, 513);
        lut.set_table(ramp);
        lut.set_params(params(LutPlayer::kContinuous, 13));
        REQUIRE_FALSE(lut.start(0, 250));
        for (Ticks k = 0; k < 40; ++k)
            REQUIRE(*lut.index_at(k) == static_cast<std::size_t>(4 * k % 13));
    }
    SECTION("DelayTime 3 of 0.25 ms: a sample every 0.75 ms")
    {
        Clock clock;
        LutPlayer lut(clock, 513);
        lut.set_table(ramp);
        lut.set_params(params(LutPlayer::kContinuous, 13, 3));
        REQUIRE_FALSE(lut.start(7, 250));
        for (Ticks k = 0; k < 9; ++k)
            REQUIRE(*lut.value_at(7 + k) == 100 * (4 * k / 3));
        CHECK(lut.next_change(7) == 8);
    }
    SECTION("a fixed run of 1.25 ms is over at the first tick past it")
    {
        Clock clock;
        LutPlayer lut(clock, 513);
        lut.set_table(ramp);
        lut.set_params(params(LutPlayer::kFixed, 5, 1, 0, 0, 1));
        REQUIRE_FALSE(lut.start(0, 250));
        CHECK(lut.end_tick() == 2);
        CHECK(*lut.value_at(1) == 400);
        CHECK(*lut.value_at(2) == 400);
    }
    SECTION("a tick of 1/3 ms that does not divide the sample interval")
    {
        Clock clock(3000);
        LutPlayer lut(clock);
        lut.set_table(ramp);
        lut.set_params(params(LutPlayer::kFixed, 2, 1, 0, 0, 1));
        REQUIRE_FALSE(lut.start(0, 1000));
        CHECK(values(lut, 0, 6) == std::vector<int>{0, 0, 0, 100, 100, 100});
        CHECK(lut.end_tick() == 6);
    }
}

TEST_CASE("lut player: the largest parameters neither overflow nor end", "[unit][models][lut]")
{
    Clock clock;
    LutPlayer lut(clock);
    lut.set_table(sine_table());
    constexpr std::int32_t kMax = std::numeric_limits<std::int32_t>::max();
    lut.set_params(params(LutPlayer::kFixed, 1000, kMax, kMax, kMax, kMax));
    REQUIRE_FALSE(lut.start(0, 1000));
    CHECK(lut.end_tick() == kNever);
    CHECK(*lut.value_at(2'000'000'000) == lut.sample(0));   // still in the first pre-rest
    CHECK(*lut.value_at(kMax) == lut.sample(0));             // sample 0 itself, for DelayTime intervals
    CHECK(lut.next_change(0) == kMax);
}

TEST_CASE("lut player: parameters the unit ignores come with a reason", "[unit][models][lut]")
{
    using Catch::Matchers::Contains;
    const auto check = [](const Params& p, std::size_t capacity = 8000, bool triggers = true) {
        return LutPlayer::check_params(p, capacity, triggers);
    };
    CHECK_FALSE(check(params(LutPlayer::kContinuous, 8000)));
    CHECK_FALSE(check(params(LutPlayer::kFixed, 513, 0, 0, 0, 1), 513));   // DelayTime 0 taken as 1
    CHECK_FALSE(check(params(LutPlayer::kFixed | LutPlayer::kInputTrig, 10)));

    CHECK_THAT(*check(params(0, 10)), Contains("neither"));
    CHECK_THAT(*check(params(LutPlayer::kGated, 10)), Contains("neither"));
    CHECK_THAT(*check(params(LutPlayer::kContinuous | LutPlayer::kFixed, 10)), Contains("both"));
    CHECK_THAT(*check(params(0x0101, 10)), Contains("above 0x80"));
    CHECK_THAT(*check(params(LutPlayer::kFixed | LutPlayer::kInputTrig, 10), 513, false), Contains("trigger"));
    CHECK_THAT(*check(params(LutPlayer::kContinuous, 0)), Contains("CycleLength 0"));
    CHECK_THAT(*check(params(LutPlayer::kContinuous, 514), 513), Contains("CycleLength 514"));
    CHECK_THAT(*check(params(LutPlayer::kContinuous, 8001)), Contains("CycleLength 8001"));
    CHECK_THAT(*check(params(LutPlayer::kFixed, 10, 1, 0, 0, 0)), Contains("NumCycles 0"));
    CHECK_FALSE(check(params(LutPlayer::kContinuous, 10, 1, 0, 0, 0)));   // ignored when continuous
    CHECK_THAT(*check(params(LutPlayer::kContinuous, 10, -1)), Contains("DelayTime"));
    CHECK_THAT(*check(params(LutPlayer::kContinuous, 10, 1, -1)), Contains("PreCycleRest"));
    CHECK_THAT(*check(params(LutPlayer::kContinuous, 10, 1, 0, -1)), Contains("PostCycleRest"));
    Params trig = params(LutPlayer::kContinuous | LutPlayer::kOutputTrig, 10);
    trig.op_trig_start = 10;
    CHECK_THAT(*check(trig), Contains("OPTrigStart 10"));
    trig.op_trig_start = 9;
    CHECK_FALSE(check(trig));

    CHECK_THAT(*LutPlayer::check_index(513, 513), Contains("Index 513"));
    CHECK_FALSE(LutPlayer::check_index(512, 513));
    CHECK_THAT(*LutPlayer::check_start(params(LutPlayer::kContinuous, 40), 39, 1000), Contains("39 samples loaded"));
    CHECK_THAT(*LutPlayer::check_start(params(LutPlayer::kContinuous, 40), 40, 0), Contains("interval"));
    CHECK_FALSE(LutPlayer::check_start(params(LutPlayer::kContinuous, 40), 40, 250));
}

TEST_CASE("lut player: a start the unit ignores leaves the output as it was", "[unit][models][lut]")
{
    Clock clock;
    LutPlayer lut(clock, 513);
    load_ramp(lut);
    CHECK_FALSE(lut.set_sample(513, 1));
    CHECK(lut.loaded() == 4);
    lut.set_params(params(LutPlayer::kContinuous, 5));   // one more than loaded
    CHECK(lut.start(0, 250));
    CHECK_FALSE(lut.started());
    CHECK_FALSE(lut.value_at(0).has_value());
    lut.set_params(params(LutPlayer::kFixed, 4, 1, 0, 0, 1));
    REQUIRE_FALSE(lut.start(0, 1000));
    lut.set_params(params(0, 4));
    CHECK(lut.start(10, 1000));   // ignored: the held value of the run before stays
    CHECK(*lut.value_at(10) == 40);
    CHECK(lut.end_tick() == 4);
}

} // namespace test_lut_player
