/*
 * rigsim_bench_lut: what the piezo waveform generator (models/lut_player) costs per simulated
 * second. In one process, on a stepped rigsim Clock at --tick-hz, a Tickable reads
 * value_at() of --players LutPlayers every tick, each with a table of --samples samples
 * (a sine) clocked out continuously at --base-us per sample, as a piezo module does while a
 * LUT runs. Baselines, measured in the same run in alternating blocks: the same loop with the
 * players idle (never started), and the bare clock (a Tickable that reads nothing). A
 * measurement, not a test: exit 0 whatever the figures, 1 if a checksum is wrong, 2 on bad
 * flags. See bench/README.md.
 */
#include "models/clock.hpp"
#include "models/lut_player.hpp"
#include "tick_bench.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace {

using rigsim::Clock;
using rigsim::Ticks;
using rigsim::models::LutPlayer;

struct Options {
    double seconds = 100;   ///< simulated seconds per block
    int blocks = 10;
    int players = 5;
    int samples = 8000;
    std::uint32_t base_us = 1000;
    std::uint32_t tick_hz = 1000;
};

enum class Variant { Clock, Idle, Running };
const std::vector<std::string> kVariantNames = {"clock", "idle", "running"};

const char* name(Variant v)
{
    return kVariantNames[static_cast<std::size_t>(v)].c_str();
}

/// Reads every player each tick, as a piezo module's tick() does while a LUT runs.
class Reader : public rigsim::Tickable {
public:
    explicit Reader(std::vector<LutPlayer*> players) : players_(std::move(players)) {}
    Ticks next_change(Ticks now) const override { return now + 1; }
    void tick(Ticks now) override
    {
        for (const LutPlayer* p : players_)
            if (const auto v = p->value_at(now))
                sum_ += *v;
    }
    std::int64_t sum() const { return sum_; }

private:
    std::vector<LutPlayer*> players_;
    std::int64_t sum_ = 0;
};

constexpr const char* kUsage =
    "usage: rigsim_bench_lut [--seconds S] [--blocks N] [--players N] [--samples N]\n"
    "                        [--base-us B] [--tick-hz HZ] [--only clock|idle|running]\n"
    "  --seconds S   simulated seconds per block and variant (default 100)\n"
    "  --blocks N    alternating blocks per variant (default 10)\n"
    "  --players N   LUT players read every tick (default 5)\n"
    "  --samples N   table length and CycleLength, 1..8000 (default 8000)\n"
    "  --base-us B   base sample interval in us, DelayTime 1 (default 1000: BPC; TPZ 250)\n"
    "  --tick-hz HZ  clock rate (default 1000)\n"
    "  --only V      run one variant only (for callgrind)\n";

Options parse(int argc, char** argv, std::vector<Variant>& variants)
{
    Options o;
    for (std::size_t i : rigsim::bench::parse_command_line(
             argc, argv, "rigsim_bench_lut", kUsage,
             {{"--seconds", 1, 100000, [&](long n) { o.seconds = static_cast<double>(n); }},
              {"--blocks", 1, 1000, [&](long n) { o.blocks = static_cast<int>(n); }},
              {"--players", 1, 1000, [&](long n) { o.players = static_cast<int>(n); }},
              {"--samples", 1, 8000, [&](long n) { o.samples = static_cast<int>(n); }},
              {"--base-us", 1, 1000000, [&](long n) { o.base_us = static_cast<std::uint32_t>(n); }},
              {"--tick-hz", 1, 1000000, [&](long n) { o.tick_hz = static_cast<std::uint32_t>(n); }}},
             kVariantNames))
        variants.push_back(static_cast<Variant>(i));
    return o;
}

/// One variant's clock, players and reader.
struct Setup {
    Clock clock;
    std::vector<std::unique_ptr<LutPlayer>> players;
    std::unique_ptr<Reader> reader;

    Setup(const Options& o, Variant v) : clock(o.tick_hz)
    {
        LutPlayer::Table table(o.samples);
        for (int k = 0; k < o.samples; ++k)
            table(k) = static_cast<std::int16_t>(std::lround(16384 + 16000 * std::sin(6.283185307179586 * k / o.samples)));
        std::vector<LutPlayer*> read;
        for (int i = 0; i < o.players; ++i) {
            players.push_back(std::make_unique<LutPlayer>(clock));
            LutPlayer& p = *players.back();
            p.set_table(table);
            LutPlayer::Params params;
            params.mode = LutPlayer::kContinuous;
            params.cycle_length = static_cast<std::uint16_t>(o.samples);
            p.set_params(params);
            if (v == Variant::Running && p.start(0, o.base_us))
                std::exit(1);
            if (v != Variant::Clock)
                read.push_back(&p);
        }
        reader = std::make_unique<Reader>(std::move(read));
        clock.add(reader.get());
    }
    ~Setup() { clock.remove(reader.get()); }
};

/// The sum of every value the players output at ticks 1 to `ticks` (the clock ticks a
/// Tickable at 1, 2, ... after a start at 0), computed from the table alone: the bench's check
/// that the loop read what the schedule says.
std::int64_t expected_sum(const Options& o, const Setup& s, Ticks ticks)
{
    const LutPlayer& p = *s.players.front();
    std::int64_t sum = 0;
    for (Ticks t = 1; t <= ticks; ++t) {
        const std::int64_t us = t * 1'000'000 / o.tick_hz;
        sum += p.sample(static_cast<std::size_t>(us / o.base_us % o.samples));
    }
    return sum * o.players;
}

} // namespace

int main(int argc, char** argv)
{
    using rigsim::bench::BlockTimes;
    std::vector<Variant> variants;
    const Options o = parse(argc, argv, variants);
    const Ticks ticks = static_cast<Ticks>(o.seconds * o.tick_hz);

    std::vector<std::unique_ptr<Setup>> setups;
    std::vector<std::function<void()>> blocks;
    for (Variant v : variants) {
        setups.push_back(std::make_unique<Setup>(o, v));
        blocks.push_back([s = setups.back().get(), ticks] { s->clock.advance(ticks); });
    }
    const std::vector<BlockTimes> cpu = rigsim::bench::run_alternating(o.blocks, blocks);

    for (std::size_t i = 0; i < variants.size(); ++i)
        if (variants[i] == Variant::Running &&
            setups[i]->reader->sum() != expected_sum(o, *setups[i], ticks * o.blocks)) {
            std::fprintf(stderr, "rigsim_bench_lut: the players did not output the table\n");
            return 1;
        }

    std::printf("LUT players: %d x %d samples, %u us per sample, tick %u Hz; %d blocks of %.0f simulated s "
                "per variant\n",
                o.players, o.samples, o.base_us, o.tick_hz, o.blocks, o.seconds);
    const rigsim::bench::Table table({{"variant", 9}, {"ns/tick (med)", 14}, {"ns/tick (min)", 14},
                                      {"us/simulated s", 16}, {"- clock", 12}, {"- idle", 12}});
    table.header();
    double clock_med = -1, idle_med = -1;
    for (std::size_t i = 0; i < variants.size(); ++i) {
        const double med = cpu[i].median();
        if (variants[i] == Variant::Clock)
            clock_med = med;
        if (variants[i] == Variant::Idle)
            idle_med = med;
        const auto over = [&](double base) {
            return base < 0 ? std::string("-") : std::to_string(std::lround((med - base) / o.seconds * 1e6));
        };
        table.row({name(variants[i]), rigsim::bench::fixed(med / ticks * 1e9, 1),
                   rigsim::bench::fixed(cpu[i].min() / ticks * 1e9, 1), rigsim::bench::fixed(med / o.seconds * 1e6, 1),
                   over(clock_med), variants[i] == Variant::Running ? over(idle_med) : "-"});
    }
    std::printf("  (CPU of this thread; the last two columns: us per simulated second above each baseline)\n");
    return 0;
}
