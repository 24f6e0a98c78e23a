/*
 * rigsim_bench: round-trip latency of rigsimd against an echo floor on TCP and
 * pty, the daemon's CPU time per command, and its idle CPU. A measurement, not
 * a test: it exits 0 whatever the figures, 1 if something broke, 2 on bad flags.
 * See bench/README.md.
 */
#include "cpu_placement.hpp"
#include "daemon_process.hpp"
#include "echo_servers.hpp"
#include "proc_cpu.hpp"
#include "roundtrip.hpp"

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#ifndef RIGSIMD_PATH
#define RIGSIMD_PATH "rigsimd"
#endif

namespace rigsim::bench {
namespace {

constexpr int kWarmupIterations = 1000;
/// rigsimd and the floor alternate in this many blocks of round trips.
constexpr int kBlocks = 10;
constexpr std::chrono::milliseconds kStartTimeout{10000};
constexpr std::chrono::milliseconds kStopTimeout{5000};

const std::string kRequest = ":GP0\n";
const std::string kReply = ":P0,0\n";

// Targets (see bench/README.md).
constexpr double kTargetMedianRatio = 1.5;
constexpr double kTargetCpuPerCommandUs = 5.0;
constexpr double kTargetIdlePercent = 1.0;

struct Options {
    int iterations = 20000;
    double idle_seconds = 5.0;
    std::string daemon = RIGSIMD_PATH;
    Pinning pinning = Pinning::Same;
};

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

void print_usage(std::FILE* out)
{
    std::fprintf(out,
                 "usage: rigsim_bench [--iterations N] [--idle-seconds S] [--pin MODE]\n"
                 "                    [--daemon PATH]\n"
                 "  --iterations N    timed round trips per transport and server (default "
                 "20000),\n"
                 "                    after %d warm-up round trips\n"
                 "  --idle-seconds S  length of each idle CPU window, 0 to skip (default 5)\n"
                 "  --pin MODE        same: client and servers (rigsimd and the floor) on one\n"
                 "                    CPU (default); split: client on one CPU, servers on\n"
                 "                    another; none: left to the scheduler\n"
                 "  --daemon PATH     rigsimd to start (default %s)\n",
                 kWarmupIterations, RIGSIMD_PATH);
}

Options parse_options(int argc, char** argv)
{
    Options options;
    for (int i = 1; i < argc; ++i) {
        const std::string flag = argv[i];
        if (flag == "-h" || flag == "--help") {
            print_usage(stdout);
            std::exit(0);
        }
        if (i + 1 >= argc)
            throw UsageError("unknown flag or missing value: " + flag);
        const std::string value = argv[++i];
        char* end = nullptr;
        if (flag == "--iterations") {
            const long n = std::strtol(value.c_str(), &end, 10);
            if (value.empty() || *end != '\0' || n < 1 || n > 100000000)
                throw UsageError("--iterations wants an integer in 1..100000000, not " + value);
            options.iterations = static_cast<int>(n);
        } else if (flag == "--idle-seconds") {
            const double s = std::strtod(value.c_str(), &end);
            if (value.empty() || *end != '\0' || !(s >= 0) || s > 3600)
                throw UsageError("--idle-seconds wants a number in 0..3600, not " + value);
            options.idle_seconds = s;
        } else if (flag == "--pin") {
            const auto pinning = parse_pinning(value);
            if (!pinning)
                throw UsageError("--pin wants same, split or none, not " + value);
            options.pinning = *pinning;
        } else if (flag == "--daemon") {
            options.daemon = value;
        } else {
            throw UsageError("unknown flag: " + flag);
        }
    }
    return options;
}

/// A server's CPU time over an interval of wall time.
struct CpuDelta {
    double stat_s = 0;
    double system_s = 0;
    std::optional<double> schedstat_s;
    double wall_s = 0;
};

CpuDelta cpu_delta(const CpuSample& before, const CpuSample& after)
{
    CpuDelta d;
    d.stat_s = after.stat_s - before.stat_s;
    d.system_s = after.system_s - before.system_s;
    if (before.schedstat_ns && after.schedstat_ns)
        d.schedstat_s = static_cast<double>(*after.schedstat_ns - *before.schedstat_ns) / 1e9;
    d.wall_s = std::chrono::duration<double>(after.wall - before.wall).count();
    return d;
}

/// Adds `d` to `total`; schedstat only while both have it.
void accumulate(CpuDelta& total, const CpuDelta& d, bool first)
{
    total.stat_s += d.stat_s;
    total.system_s += d.system_s;
    total.wall_s += d.wall_s;
    if (first)
        total.schedstat_s = d.schedstat_s;
    else if (total.schedstat_s && d.schedstat_s)
        *total.schedstat_s += *d.schedstat_s;
    else
        total.schedstat_s.reset();
}

/// One server under measurement: the client's fd, the reply it must give, its CPU clock.
struct Server {
    int fd;
    std::string expected;
    std::function<CpuSample()> read_cpu;
    std::vector<std::int64_t> samples_ns;
    /// CPU of the server (daemon process or echo thread) over the timed round trips.
    CpuDelta cpu;
};

/*
 * rigsimd and the floor take turns in blocks, so that a change of machine state
 * during the run (another load, frequency, where the scheduler puts the threads)
 * shifts both and leaves the ratio alone. Each server is idle while the other
 * runs, so its CPU deltas add up to its CPU over its own round trips.
 */
void measure_interleaved(Server& rigsim, Server& floor, const Options& options)
{
    round_trips(rigsim.fd, kRequest, rigsim.expected, kWarmupIterations);
    round_trips(floor.fd, kRequest, floor.expected, kWarmupIterations);
    const auto run_block = [](Server& server, int iterations) {
        const auto before = server.read_cpu();
        auto samples = round_trips(server.fd, kRequest, server.expected, iterations);
        accumulate(server.cpu, cpu_delta(before, server.read_cpu()), server.samples_ns.empty());
        server.samples_ns.insert(server.samples_ns.end(), samples.begin(), samples.end());
    };
    const long long total = options.iterations;
    for (int block = 0; block < kBlocks; ++block) {
        const int n = static_cast<int>(total * (block + 1) / kBlocks - total * block / kBlocks);
        // Alternate who goes first, so that neither always follows the other.
        Server& one = block % 2 == 0 ? rigsim : floor;
        Server& other = block % 2 == 0 ? floor : rigsim;
        run_block(one, n);
        run_block(other, n);
    }
}

struct TransportResult {
    const char* name;
    LatencyStats rigsim;
    LatencyStats floor;
    CpuDelta rigsim_cpu;
    CpuDelta floor_cpu;
};

TransportResult result_of(const char* name, Server& rigsim, Server& floor)
{
    return {name, latency_stats(rigsim.samples_ns), latency_stats(floor.samples_ns), rigsim.cpu,
            floor.cpu};
}

double median_ratio(const TransportResult& r)
{
    return r.rigsim.median_us / r.floor.median_us;
}

double p99_ratio(const TransportResult& r)
{
    return r.rigsim.p99_us / r.floor.p99_us;
}

TransportResult measure_tcp(const DaemonProcess& daemon, const Placement& placement,
                            const Options& options)
{
    const auto& ep = daemon.endpoints();
    TcpEchoServer echo{placement.server_cpu};
    auto rigsim_fd = connect_tcp(ep.tcp_host, ep.tcp_port);
    auto floor_fd = connect_tcp("127.0.0.1", echo.port());
    Server rigsim{rigsim_fd.get(), kReply, [&] { return read_process_cpu(daemon.pid()); }, {}, {}};
    Server floor{floor_fd.get(), kRequest, [&] { return read_thread_cpu(echo.thread_id()); }, {},
                 {}};
    measure_interleaved(rigsim, floor, options);
    return result_of("tcp", rigsim, floor);
}

TransportResult measure_pty(const DaemonProcess& daemon, const Placement& placement,
                            const Options& options)
{
    PtyEchoServer echo{placement.server_cpu};
    auto rigsim_fd = open_pty(daemon.endpoints().pty_path);
    auto floor_fd = open_pty(echo.slave_path());
    Server rigsim{rigsim_fd.get(), kReply, [&] { return read_process_cpu(daemon.pid()); }, {}, {}};
    Server floor{floor_fd.get(), kRequest, [&] { return read_thread_cpu(echo.thread_id()); }, {},
                 {}};
    measure_interleaved(rigsim, floor, options);
    return result_of("pty", rigsim, floor);
}

/// Samples the daemon's CPU over a window of wall time in which nothing talks to it.
std::optional<CpuDelta> measure_idle(pid_t pid, double seconds)
{
    if (seconds <= 0)
        return std::nullopt;
    const auto before = read_process_cpu(pid);
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    return cpu_delta(before, read_process_cpu(pid));
}

double idle_percent(const CpuDelta& d)
{
    return 100.0 * d.stat_s / d.wall_s;
}

void print_latency(const TransportResult& r)
{
    std::printf("  %s  %-19s %10.2f %10.2f\n", r.name, "rigsimd", r.rigsim.median_us,
                r.rigsim.p99_us);
    std::printf("  %s  %-19s %10.2f %10.2f\n", r.name, "floor (echo)", r.floor.median_us,
                r.floor.p99_us);
    std::printf("  %s  %-19s %10.2f %10.2f\n", r.name, "ratio rigsimd/floor", median_ratio(r),
                p99_ratio(r));
}

void print_cpu_per_command(const char* transport, const char* server, const CpuDelta& d,
                           int iterations)
{
    std::printf("  %s  %-19s %10.2f %10.2f", transport, server, d.stat_s * 1e6 / iterations,
                d.system_s * 1e6 / iterations);
    if (d.schedstat_s)
        std::printf(" %10.2f", *d.schedstat_s * 1e6 / iterations);
    else
        std::printf(" %10s", "-");
    std::printf("\n");
}

void print_cpu_per_command(const TransportResult& r, int iterations)
{
    print_cpu_per_command(r.name, "rigsimd", r.rigsim_cpu, iterations);
    print_cpu_per_command(r.name, "floor (echo)", r.floor_cpu, iterations);
}

void print_idle(const char* label, const std::optional<CpuDelta>& d)
{
    if (!d) {
        std::printf("  %-28s skipped (--idle-seconds 0)\n", label);
        return;
    }
    std::printf("  %-28s %6.2f %% of one core over %.1f s  (/proc stat, resolution %.2f %%)",
                label, idle_percent(*d), d->wall_s, 100.0 * stat_tick_s() / d->wall_s);
    if (d->schedstat_s)
        std::printf("  %6.3f %% (schedstat)", 100.0 * *d->schedstat_s / d->wall_s);
    std::printf("\n");
}

/// A line on stderr, so that stdout holds only the figures.
void progress(const char* phase)
{
    std::fprintf(stderr, "rigsim_bench: %s...\n", phase);
}

const char* verdict(bool pass)
{
    return pass ? "PASS" : "FAIL";
}

int run(const Options& options)
{
    // A peer closing mid-write must be an error return, not a fatal signal.
    ::signal(SIGPIPE, SIG_IGN);

    const auto placement = choose_placement(options.pinning);
    DaemonProcess daemon{options.daemon, placement.server_cpu, kStartTimeout};
    if (placement.client_cpu)
        pin_this_thread(*placement.client_cpu);
    const auto& ep = daemon.endpoints();
    std::printf("rigsim_bench: %s (pid %d)\n", options.daemon.c_str(),
                static_cast<int>(daemon.pid()));
    std::printf("  tcp %s:%u, pty %s\n", ep.tcp_host.c_str(), static_cast<unsigned>(ep.tcp_port),
                ep.pty_path.c_str());
    std::printf("  %d timed round trips per server after %d warm-up, in %d alternating blocks\n",
                options.iterations, kWarmupIterations, kBlocks);
    std::printf("  %s; idle windows %.1f s\n\n", describe(placement).c_str(),
                options.idle_seconds);
    std::fflush(stdout);

    progress("idle window, fresh daemon");
    const auto idle_fresh = measure_idle(daemon.pid(), options.idle_seconds);
    progress("tcp round trips");
    const auto tcp = measure_tcp(daemon, placement, options);
    progress("pty round trips");
    const auto pty = measure_pty(daemon, placement, options);
    // After clients have come and gone: a transport that spins on a closed peer shows here.
    progress("idle window, after clients closed");
    const auto idle_after = measure_idle(daemon.pid(), options.idle_seconds);

    std::printf("round trip \":GP0\\n\" -> \":P0,0\\n\", us\n");
    std::printf("  %-24s %10s %10s\n", "", "median", "p99");
    print_latency(tcp);
    print_latency(pty);
    std::printf("\nserver CPU per command over the timed round trips, us"
                " (/proc stat resolution %.2f us)\n",
                stat_tick_s() * 1e6 / options.iterations);
    std::printf("  %-24s %10s %10s %10s\n", "", "stat", "of it sys", "schedstat");
    print_cpu_per_command(tcp, options.iterations);
    print_cpu_per_command(pty, options.iterations);
    std::printf("\nidle CPU (default rig, no traffic)\n");
    print_idle("fresh daemon", idle_fresh);
    print_idle("after clients closed", idle_after);

    const double tcp_cpu_us = tcp.rigsim_cpu.stat_s * 1e6 / options.iterations;
    std::printf("\n== summary (%s) ==\n", describe(placement).c_str());
    std::printf("  tcp ratio rigsimd/floor at median  %8.2f     <= %.1f    %s\n",
                median_ratio(tcp), kTargetMedianRatio,
                verdict(median_ratio(tcp) <= kTargetMedianRatio));
    std::printf("  pty ratio rigsimd/floor at median  %8.2f     <= %.1f    %s\n",
                median_ratio(pty), kTargetMedianRatio,
                verdict(median_ratio(pty) <= kTargetMedianRatio));
    std::printf("  daemon CPU per command (tcp)       %8.2f us  <= %.0f us   %s"
                "   (floor echo thread: %.2f us)\n",
                tcp_cpu_us, kTargetCpuPerCommandUs, verdict(tcp_cpu_us <= kTargetCpuPerCommandUs),
                tcp.floor_cpu.stat_s * 1e6 / options.iterations);
    if (idle_fresh && idle_after) {
        const double idle = std::max(idle_percent(*idle_fresh), idle_percent(*idle_after));
        std::printf("  idle CPU (worse window)            %8.2f %%   <= %.0f %%    %s\n", idle,
                    kTargetIdlePercent, verdict(idle <= kTargetIdlePercent));
    } else {
        std::printf("  idle CPU                           skipped\n");
    }
    std::printf("  (for reference: a Python test double spends ~28 us/command)\n");
    std::fflush(stdout);

    daemon.terminate(kStopTimeout);
    return 0;
}

}  // namespace
}  // namespace rigsim::bench

int main(int argc, char** argv)
{
    using namespace rigsim::bench;
    try {
        return run(parse_options(argc, argv));
    } catch (const UsageError& e) {
        std::fprintf(stderr, "rigsim_bench: %s\n", e.what());
        print_usage(stderr);
        return 2;
    } catch (const std::exception& e) {
        std::fflush(stdout);
        std::fprintf(stderr, "rigsim_bench: error: %s\n", e.what());
        return 1;
    }
}
