/*
 * rigsim_bench_lut_rig: what running piezo waveforms cost a whole rig, through the device layer.
 * In one process, on a stepped rigsim Clock at the rig's 1 kHz, real AptDevices (a BPC303
 * with 3 bays and a TPZ001, default actuators: hysteresis, creep, 1 ms response) are fed APT
 * frames through a session, as a client would send them: every bay gets the largest table its
 * model takes (catalogue lut_max_index + 1 samples: 8000 BPC, 513 TPZ; a sine) and
 * OUTPUTLUTPARAMS continuous, CycleLength = the table, DelayTime 1 (the shortest interval the
 * manual allows, p.109: one sample per base interval, 1 ms BPC, 250 us TPZ), no rests.
 * Variants, measured in the same run in alternating blocks:
 *   clock    the bare clock with one Tickable due every tick (the floor of a 1 kHz tick);
 *   idle     the same rig, tables and parameters loaded, never started, beside that Tickable
 *            (the clock then visits every tick, as it does while anything moves);
 *   running  the same, PZ_START_LUTOUTPUT sent to every channel;
 *   skip     the idle rig alone: the clock skips its idle stretches (the daemon's idle rig).
 * Then it checks the outputs (GET_OUTPUTVOLTS equals the table's sample of the tick instant)
 * and counts the samples a 1 kHz tick renders of a 250 us schedule (plan D-8).
 * A measurement, not a test: exit 0 whatever the figures, 1 if an output is wrong, 2 on bad
 * flags. See bench/README.md.
 */
#include "emulator/apt/apt_device.hpp"
#include "emulator/apt/catalogue.hpp"
#include "emulator/apt/config.hpp"
#include "models/clock.hpp"
#include "models/world.hpp"
#include "tick_bench.hpp"

#include <spdlog/logger.h>
#include <spdlog/sinks/null_sink.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace {

using rigsim::Clock;
using rigsim::Ticks;

struct Options {
    double seconds = 20;   ///< simulated seconds per block
    int blocks = 5;
    bool only = false;     ///< one variant alone (callgrind): no output report
};

enum class Variant { Clock, Idle, Running, Skip };
const std::vector<std::string> kVariantNames = {"clock", "idle", "running", "skip"};

const char* name(Variant v)
{
    return kVariantNames[static_cast<std::size_t>(v)].c_str();
}

/// Due every tick, does nothing: the bare clock, and what keeps the clock visiting every tick.
class EveryTick : public rigsim::Tickable {
public:
    Ticks next_change(Ticks now) const override { return now + 1; }
    void tick(Ticks) override { ++ticks_; }
    std::int64_t ticks() const { return ticks_; }

private:
    std::int64_t ticks_ = 0;
};

constexpr const char* kUsage =
    "usage: rigsim_bench_lut_rig [--seconds S] [--blocks N] [--only clock|idle|running|skip]\n"
    "  --seconds S   simulated seconds per block and variant (default 20)\n"
    "  --blocks N    alternating blocks per variant (default 5)\n"
    "  --only V      run one variant only (for callgrind)\n";

Options parse(int argc, char** argv, std::vector<Variant>& variants)
{
    Options o;
    for (std::size_t i : rigsim::bench::parse_command_line(
             argc, argv, "rigsim_bench_lut_rig", kUsage,
             {{"--seconds", 1, 100000, [&](long n) { o.seconds = static_cast<double>(n); }},
              {"--blocks", 1, 1000, [&](long n) { o.blocks = static_cast<int>(n); }}},
             kVariantNames))
        variants.push_back(static_cast<Variant>(i));
    o.only = variants.size() == 1;
    return o;
}

std::string le16(unsigned v)
{
    return {static_cast<char>(v & 0xFF), static_cast<char>((v >> 8) & 0xFF)};
}

std::string le32(std::uint32_t v)
{
    return le16(v & 0xFFFF) + le16(v >> 16);
}

/// A frame from the host (0x01) to `dest`: header-only, or with the data flag and `data`.
std::string frame(std::uint16_t id, std::uint8_t dest, const std::string& data, std::uint8_t p1 = 1)
{
    if (data.empty())
        return le16(id) + static_cast<char>(p1) + '\0' + static_cast<char>(dest) + '\x01';
    return le16(id) + le16(static_cast<unsigned>(data.size())) + static_cast<char>(dest | 0x80) + '\x01' + data;
}

/// The sine a channel of `samples` samples holds: 16384 + 16000 sin(2 pi k / samples).
std::int16_t sine(std::size_t k, std::size_t samples)
{
    return static_cast<std::int16_t>(std::lround(16384 + 16000 * std::sin(6.283185307179586 * k / samples)));
}

/// One piezo channel of the rig: its device, its address and its LUT.
struct Channel {
    std::size_t device;
    std::uint8_t address;
    std::size_t samples;
    std::uint32_t base_us;
};

/// One variant's clock, world, devices and sessions.
struct Rig {
    Clock clock;
    rigsim::models::World world{clock};
    std::vector<std::unique_ptr<rigsim::apt::AptDevice>> devices;
    std::vector<std::unique_ptr<rigsim::Session>> sessions;
    std::vector<std::string> out;
    std::vector<Channel> channels;
    EveryTick every_tick;
    bool ticked;

    explicit Rig(Variant v) : out(2), ticked(v != Variant::Skip)
    {
        if (v != Variant::Clock)
            build(v == Variant::Running);
        if (ticked)
            clock.add(&every_tick);
    }
    ~Rig()
    {
        if (ticked)
            clock.remove(&every_tick);
        sessions.clear();
    }

    void add_device(const std::string& model, std::size_t bays)
    {
        rigsim::DeviceConfig c;
        c.name = model == "BPC303" ? "bpc303" : "tpz001";
        c.protocol = "apt";
        c.model = model;
        auto& apt = rigsim::apt::config_of(c);
        if (bays > 0) {
            rigsim::apt::PiezoBayConfig bay;
            bay.actuator.max_voltage_v = 150;
            apt.piezo_bays.assign(bays, bay);
        }
        auto log = std::make_shared<spdlog::logger>("apt", std::make_shared<spdlog::sinks::null_sink_st>());
        devices.push_back(std::make_unique<rigsim::apt::AptDevice>(c, world, log));
        std::string* sink = &out[devices.size() - 1];
        sessions.push_back(devices.back()->open_session([sink](std::string_view b) { sink->append(b); }, "bench"));
        const auto* model_info = rigsim::apt::find_controller(model);
        for (std::size_t b = 0; b < std::max<std::size_t>(bays, 1); ++b)
            channels.push_back({devices.size() - 1, static_cast<std::uint8_t>(bays ? 0x21 + b : 0x50),
                                model_info->lut_max_index + 1u, model_info->lut_base_interval_us});
    }

    void send(std::size_t d, const std::string& bytes) { sessions.at(d)->receive(bytes); }

    void build(bool start)
    {
        add_device("BPC303", 3);
        add_device("TPZ001", 0);
        world.link_all();
        for (const Channel& ch : channels) {
            for (std::size_t k = 0; k < ch.samples; ++k)
                send(ch.device, frame(0x0700, ch.address, le16(1) + le16(static_cast<unsigned>(k)) +
                                                              le16(static_cast<std::uint16_t>(sine(k, ch.samples)))));
            // OUTPUTLUTPARAMS (p.108): continuous, CycleLength = the table, NumCycles 1, DelayTime 1,
            // no rests, no triggers.
            send(ch.device, frame(0x0703, ch.address,
                                  le16(1) + le16(0x01) + le16(static_cast<unsigned>(ch.samples)) + le32(1) + le32(1) +
                                      le32(0) + le32(0) + le16(0) + le32(0) + le16(0)));
            if (start)
                send(ch.device, frame(0x0706, ch.address, {}));
        }
        for (auto& o : out)
            o.clear();
    }

    /// PZ_REQ_OUTPUTVOLTS of `ch`: the output code GET_OUTPUTVOLTS answers.
    int output_code(const Channel& ch)
    {
        out[ch.device].clear();
        send(ch.device, frame(0x0644, ch.address, {}));
        const std::string& r = out[ch.device];
        if (r.size() != 10)
            return -100000;
        return static_cast<std::int16_t>(static_cast<unsigned char>(r[8]) | static_cast<unsigned char>(r[9]) << 8);
    }
};

/// The sample the schedule gives `ch` at tick `t` of a run started at tick 0 (1 kHz).
std::int16_t expected(const Channel& ch, Ticks t)
{
    return sine(static_cast<std::size_t>(t * 1000 / ch.base_us % ch.samples), ch.samples);
}

/// Every channel's output equals its schedule's sample at the rig's current tick.
bool outputs_follow_tables(Rig& rig)
{
    bool ok = true;
    for (const Channel& ch : rig.channels) {
        const int got = rig.output_code(ch);
        if (got != expected(ch, rig.clock.now())) {
            std::fprintf(stderr, "rigsim_bench_lut_rig: channel 0x%02X of device %zu outputs %d at tick %lld, "
                         "the table says %d\n", ch.address, ch.device, got, static_cast<long long>(rig.clock.now()),
                         expected(ch, rig.clock.now()));
            ok = false;
        }
    }
    return ok;
}

/// D-8: tick by tick over the first cycle of every channel (8000 ticks: the BPC's 8000 x 1 ms),
/// reading PZ_REQ_OUTPUTVOLTS each tick: which table indices reach the output in that cycle and
/// how far the index moves from one tick to the next.
bool report_rendering()
{
    Rig rig(Variant::Running);
    const std::size_t n = rig.channels.size();
    std::vector<std::set<std::size_t>> seen(n);
    std::vector<std::int64_t> max_step(n, 0);
    std::vector<Ticks> cycle_ticks(n);
    Ticks longest = 0;
    for (std::size_t i = 0; i < n; ++i) {
        cycle_ticks[i] = static_cast<Ticks>(rig.channels[i].samples * rig.channels[i].base_us / 1000);
        longest = std::max(longest, cycle_ticks[i]);
        seen[i].insert(0);   // the start instant outputs sample 0
    }
    bool ok = true;
    for (Ticks t = 1; t <= longest; ++t) {
        rig.clock.advance(1);
        for (std::size_t i = 0; i < n; ++i) {
            const Channel& ch = rig.channels[i];
            ok = rig.output_code(ch) == expected(ch, t) && ok;
            if (t >= cycle_ticks[i])
                continue;
            const auto index = static_cast<std::int64_t>(t * 1000 / ch.base_us);
            const auto before = static_cast<std::int64_t>((t - 1) * 1000 / ch.base_us);
            seen[i].insert(static_cast<std::size_t>(index));
            max_step[i] = std::max(max_step[i], index - before);
        }
    }
    std::printf("\noutput over each channel's first cycle, PZ_REQ_OUTPUTVOLTS read every tick (%s)\n",
                ok ? "every reading = the schedule's sample at the tick instant" : "MISMATCH");
    for (std::size_t i = 0; i < n; ++i) {
        const Channel& ch = rig.channels[i];
        std::printf("  %s 0x%02X: %zu samples x %u us = %lld ticks a cycle, %.2f samples per tick: %zu of %zu samples "
                    "reach the output (%.0f %%), the index advances by up to %lld a tick\n",
                    ch.device == 0 ? "BPC303" : "TPZ001", ch.address, ch.samples, ch.base_us,
                    static_cast<long long>(cycle_ticks[i]), 1000.0 / ch.base_us, seen[i].size(), ch.samples,
                    100.0 * seen[i].size() / ch.samples, static_cast<long long>(max_step[i]));
    }
    return ok;
}

} // namespace

int main(int argc, char** argv)
{
    using rigsim::bench::fixed;
    std::vector<Variant> variants;
    const Options o = parse(argc, argv, variants);
    const Ticks ticks = static_cast<Ticks>(o.seconds * Clock::kDefaultTickHz);

    std::vector<std::unique_ptr<Rig>> rigs;
    std::vector<std::function<void()>> blocks;
    for (Variant v : variants) {
        rigs.push_back(std::make_unique<Rig>(v));
        blocks.push_back([r = rigs.back().get(), ticks] { r->clock.advance(ticks); });
    }
    const std::vector<rigsim::bench::BlockTimes> cpu = rigsim::bench::run_alternating(o.blocks, blocks);

    bool ok = true;
    for (std::size_t i = 0; i < variants.size(); ++i)
        if (variants[i] == Variant::Running)
            ok = outputs_follow_tables(*rigs[i]) && ok;

    std::printf("piezo rig: BPC303 (3 bays, 8000-sample LUT at 1000 us) + TPZ001 (513-sample LUT at 250 us), "
                "continuous, DelayTime 1; tick 1000 Hz; %d blocks of %.0f simulated s per variant\n",
                o.blocks, o.seconds);
    const rigsim::bench::Table table({{"variant", 8}, {"ns/tick (med)", 14}, {"ns/tick (min)", 14},
                                      {"us/simulated s", 16}, {"- clock", 12}, {"- idle", 12}, {"% of core", 10}});
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
        table.row({name(variants[i]), fixed(med / ticks * 1e9, 1), fixed(cpu[i].min() / ticks * 1e9, 1),
                   fixed(med / o.seconds * 1e6, 1), variants[i] == Variant::Clock ? "-" : over(clock_med),
                   variants[i] == Variant::Running ? over(idle_med) : "-", fixed(med / o.seconds * 100, 3)});
        if (variants[i] == Variant::Running && idle_med > 0 && clock_med >= 0)
            std::printf("  %-8s running/idle %.2fx, (running - clock)/(idle - clock) %.2fx\n", "", med / idle_med,
                        (med - clock_med) / std::max(idle_med - clock_med, 1e-12));
    }
    std::printf("  (CPU of this thread; '- clock', '- idle': us per simulated second above that baseline;\n"
                "   '%% of core': the variant's CPU per simulated second at time scale 1)\n");
    if (!o.only)
        ok = report_rendering() && ok;
    return ok ? 0 : 1;
}
