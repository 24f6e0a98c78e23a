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

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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
    std::string only;       ///< run one variant alone (callgrind)
};

enum class Variant { Clock, Idle, Running };
constexpr Variant kVariants[] = {Variant::Clock, Variant::Idle, Variant::Running};

const char* name(Variant v)
{
    switch (v) {
    case Variant::Clock:
        return "clock";
    case Variant::Idle:
        return "idle";
    case Variant::Running:
        return "running";
    }
    return "?";
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

double thread_cpu_s()
{
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + ts.tv_nsec * 1e-9;
}

[[noreturn]] void usage(const char* why)
{
    if (why)
        std::fprintf(stderr, "rigsim_bench_lut: %s\n", why);
    std::fprintf(why ? stderr : stdout,
                 "usage: rigsim_bench_lut [--seconds S] [--blocks N] [--players N] [--samples N]\n"
                 "                        [--base-us B] [--tick-hz HZ] [--only clock|idle|running]\n"
                 "  --seconds S   simulated seconds per block and variant (default 100)\n"
                 "  --blocks N    alternating blocks per variant (default 10)\n"
                 "  --players N   LUT players read every tick (default 5)\n"
                 "  --samples N   table length and CycleLength, 1..8000 (default 8000)\n"
                 "  --base-us B   base sample interval in us, DelayTime 1 (default 1000: BPC; TPZ 250)\n"
                 "  --tick-hz HZ  clock rate (default 1000)\n"
                 "  --only V      run one variant only (for callgrind)\n");
    std::exit(why ? 2 : 0);
}

long number(const char* flag, const char* value, long lo, long hi)
{
    char* end = nullptr;
    const long n = std::strtol(value, &end, 10);
    if (!*value || *end || n < lo || n > hi)
        usage((std::string(flag) + " wants an integer in " + std::to_string(lo) + ".." + std::to_string(hi)).c_str());
    return n;
}

Options parse(int argc, char** argv)
{
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string flag = argv[i];
        if (flag == "-h" || flag == "--help")
            usage(nullptr);
        if (i + 1 >= argc)
            usage(("missing value or unknown flag: " + flag).c_str());
        const char* v = argv[++i];
        if (flag == "--seconds")
            o.seconds = static_cast<double>(number("--seconds", v, 1, 100000));
        else if (flag == "--blocks")
            o.blocks = static_cast<int>(number("--blocks", v, 1, 1000));
        else if (flag == "--players")
            o.players = static_cast<int>(number("--players", v, 1, 1000));
        else if (flag == "--samples")
            o.samples = static_cast<int>(number("--samples", v, 1, 8000));
        else if (flag == "--base-us")
            o.base_us = static_cast<std::uint32_t>(number("--base-us", v, 1, 1000000));
        else if (flag == "--tick-hz")
            o.tick_hz = static_cast<std::uint32_t>(number("--tick-hz", v, 1, 1000000));
        else if (flag == "--only" && (!std::strcmp(v, "clock") || !std::strcmp(v, "idle") || !std::strcmp(v, "running")))
            o.only = v;
        else
            usage(("unknown flag or value: " + flag + " " + v).c_str());
    }
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
    const Options o = parse(argc, argv);
    const Ticks ticks = static_cast<Ticks>(o.seconds * o.tick_hz);
    std::vector<Variant> variants;
    for (Variant v : kVariants)
        if (o.only.empty() || o.only == name(v))
            variants.push_back(v);

    std::vector<std::unique_ptr<Setup>> setups;
    for (Variant v : variants)
        setups.push_back(std::make_unique<Setup>(o, v));
    std::vector<std::vector<double>> cpu(variants.size());   // s per block
    for (int b = 0; b < o.blocks; ++b)
        for (std::size_t i = 0; i < variants.size(); ++i) {
            const double before = thread_cpu_s();
            setups[i]->clock.advance(ticks);
            cpu[i].push_back(thread_cpu_s() - before);
        }

    for (std::size_t i = 0; i < variants.size(); ++i)
        if (variants[i] == Variant::Running &&
            setups[i]->reader->sum() != expected_sum(o, *setups[i], ticks * o.blocks)) {
            std::fprintf(stderr, "rigsim_bench_lut: the players did not output the table\n");
            return 1;
        }

    std::printf("LUT players: %d x %d samples, %u us per sample, tick %u Hz; %d blocks of %.0f simulated s "
                "per variant\n",
                o.players, o.samples, o.base_us, o.tick_hz, o.blocks, o.seconds);
    std::printf("  %-9s %14s %14s %16s %12s %12s\n", "variant", "ns/tick (med)", "ns/tick (min)", "us/simulated s",
                "- clock", "- idle");
    std::vector<double> med(variants.size());
    double clock_med = -1, idle_med = -1;
    for (std::size_t i = 0; i < variants.size(); ++i) {
        std::vector<double> c = cpu[i];
        std::sort(c.begin(), c.end());
        med[i] = c[c.size() / 2];
        if (variants[i] == Variant::Clock)
            clock_med = med[i];
        if (variants[i] == Variant::Idle)
            idle_med = med[i];
        const auto over = [&](double base) {
            return base < 0 ? std::string("-") : std::to_string(std::lround((med[i] - base) / o.seconds * 1e6));
        };
        std::printf("  %-9s %14.1f %14.1f %16.1f %12s %12s\n", name(variants[i]), med[i] / ticks * 1e9,
                    c.front() / ticks * 1e9, med[i] / o.seconds * 1e6, over(clock_med).c_str(),
                    variants[i] == Variant::Running ? over(idle_med).c_str() : "-");
    }
    std::printf("  (CPU of this thread; the last two columns: us per simulated second above each baseline)\n");
    return 0;
}
