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

#include <spdlog/logger.h>
#include <spdlog/sinks/null_sink.h>

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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
    std::string only;      ///< run one variant alone (callgrind)
};

enum class Variant { Clock, Idle, Running, Skip };
constexpr Variant kVariants[] = {Variant::Clock, Variant::Idle, Variant::Running, Variant::Skip};

const char* name(Variant v)
{
    switch (v) {
    case Variant::Clock:
        return "clock";
    case Variant::Idle:
        return "idle";
    case Variant::Running:
        return "running";
    case Variant::Skip:
        return "skip";
    }
    return "?";
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

double thread_cpu_s()
{
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + ts.tv_nsec * 1e-9;
}

[[noreturn]] void usage(const char* why)
{
    if (why)
        std::fprintf(stderr, "rigsim_bench_lut_rig: %s\n", why);
    std::fprintf(why ? stderr : stdout,
                 "usage: rigsim_bench_lut_rig [--seconds S] [--blocks N] [--only clock|idle|running|skip]\n"
                 "  --seconds S   simulated seconds per block and variant (default 20)\n"
                 "  --blocks N    alternating blocks per variant (default 5)\n"
                 "  --only V      run one variant only (for callgrind)\n");
    std::exit(why ? 2 : 0);
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
        const std::string v = argv[++i];
        char* end = nullptr;
        const long n = std::strtol(v.c_str(), &end, 10);
        const bool number = !v.empty() && !*end;
        if (flag == "--seconds" && number && n >= 1 && n <= 100000)
            o.seconds = static_cast<double>(n);
        else if (flag == "--blocks" && number && n >= 1 && n <= 1000)
            o.blocks = static_cast<int>(n);
        else if (flag == "--only" && (v == "clock" || v == "idle" || v == "running" || v == "skip"))
            o.only = v;
        else
            usage(("unknown flag or value: " + flag + " " + v).c_str());
    }
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
    const Options o = parse(argc, argv);
    const Ticks ticks = static_cast<Ticks>(o.seconds * Clock::kDefaultTickHz);
    std::vector<Variant> variants;
    for (Variant v : kVariants)
        if (o.only.empty() || o.only == name(v))
            variants.push_back(v);

    std::vector<std::unique_ptr<Rig>> rigs;
    for (Variant v : variants)
        rigs.push_back(std::make_unique<Rig>(v));
    std::vector<std::vector<double>> cpu(variants.size());   // s per block
    for (int b = 0; b < o.blocks; ++b)
        for (std::size_t i = 0; i < variants.size(); ++i) {
            const double before = thread_cpu_s();
            rigs[i]->clock.advance(ticks);
            cpu[i].push_back(thread_cpu_s() - before);
        }

    bool ok = true;
    for (std::size_t i = 0; i < variants.size(); ++i)
        if (variants[i] == Variant::Running)
            ok = outputs_follow_tables(*rigs[i]) && ok;

    std::printf("piezo rig: BPC303 (3 bays, 8000-sample LUT at 1000 us) + TPZ001 (513-sample LUT at 250 us), "
                "continuous, DelayTime 1; tick 1000 Hz; %d blocks of %.0f simulated s per variant\n",
                o.blocks, o.seconds);
    std::printf("  %-8s %14s %14s %16s %12s %12s %10s\n", "variant", "ns/tick (med)", "ns/tick (min)",
                "us/simulated s", "- clock", "- idle", "% of core");
    double clock_med = -1, idle_med = -1;
    for (std::size_t i = 0; i < variants.size(); ++i) {
        std::vector<double> c = cpu[i];
        std::sort(c.begin(), c.end());
        const double med = c[c.size() / 2];
        if (variants[i] == Variant::Clock)
            clock_med = med;
        if (variants[i] == Variant::Idle)
            idle_med = med;
        const auto over = [&](double base) {
            return base < 0 ? std::string("-") : std::to_string(std::lround((med - base) / o.seconds * 1e6));
        };
        std::printf("  %-8s %14.1f %14.1f %16.1f %12s %12s %10.3f\n", name(variants[i]), med / ticks * 1e9,
                    c.front() / ticks * 1e9, med / o.seconds * 1e6,
                    variants[i] == Variant::Clock ? "-" : over(clock_med).c_str(),
                    variants[i] == Variant::Running ? over(idle_med).c_str() : "-", med / o.seconds * 100);
        if (variants[i] == Variant::Running && idle_med > 0 && clock_med >= 0)
            std::printf("  %-8s running/idle %.2fx, (running - clock)/(idle - clock) %.2fx\n", "", med / idle_med,
                        (med - clock_med) / std::max(idle_med - clock_med, 1e-12));
    }
    std::printf("  (CPU of this thread; '- clock', '- idle': us per simulated second above that baseline;\n"
                "   '%% of core': the variant's CPU per simulated second at time scale 1)\n");
    if (o.only.empty())
        ok = report_rendering() && ok;
    return ok ? 0 : 1;
}
