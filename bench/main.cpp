/*
 * rigsim_bench: round-trip latency of rigsimd against an echo floor on TCP and
 * pty, the daemon's CPU time per command, and its idle CPU. A measurement, not
 * a test: it exits 0 whatever the figures, 1 if something broke, 2 on bad flags.
 * See bench/README.md.
 */
#include "daemon_process.hpp"
#include "echo_servers.hpp"
#include "roundtrip.hpp"

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#ifndef RIGSIMD_PATH
#define RIGSIMD_PATH "rigsimd"
#endif

namespace rigsim::bench {
namespace {

constexpr int kWarmupIterations = 1000;
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
};

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

void print_usage(std::FILE* out)
{
    std::fprintf(out,
                 "usage: rigsim_bench [--iterations N] [--idle-seconds S] [--daemon PATH]\n"
                 "  --iterations N    timed round trips per transport and server (default "
                 "20000),\n"
                 "                    after %d warm-up round trips\n"
                 "  --idle-seconds S  length of each idle CPU window, 0 to skip (default 5)\n"
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
        } else if (flag == "--daemon") {
            options.daemon = value;
        } else {
            throw UsageError("unknown flag: " + flag);
        }
    }
    return options;
}

/// Daemon CPU over an interval: per command (µs) or as a share of one core (%).
struct CpuDelta {
    double stat_s = 0;
    std::optional<double> schedstat_s;
    double wall_s = 0;
};

CpuDelta cpu_delta(const CpuSample& before, const CpuSample& after)
{
    CpuDelta d;
    d.stat_s = after.stat_s - before.stat_s;
    if (before.schedstat_ns && after.schedstat_ns)
        d.schedstat_s = static_cast<double>(*after.schedstat_ns - *before.schedstat_ns) / 1e9;
    d.wall_s = std::chrono::duration<double>(after.wall - before.wall).count();
    return d;
}

struct Run {
    LatencyStats latency;
    std::optional<CpuDelta> daemon_cpu;
};

/// Warm-up, then the timed round trips; samples `daemon_pid`'s CPU around the timed part.
Run measure(int fd, const std::string& expected, const Options& options,
            std::optional<pid_t> daemon_pid)
{
    round_trips(fd, kRequest, expected, kWarmupIterations);
    Run run;
    std::optional<CpuSample> before;
    if (daemon_pid)
        before = read_cpu(*daemon_pid);
    auto samples = round_trips(fd, kRequest, expected, options.iterations);
    if (daemon_pid)
        run.daemon_cpu = cpu_delta(*before, read_cpu(*daemon_pid));
    run.latency = latency_stats(samples);
    return run;
}

struct TransportResult {
    const char* name;
    Run rigsim;
    Run floor;
};

double median_ratio(const TransportResult& r)
{
    return r.rigsim.latency.median_us / r.floor.latency.median_us;
}

double p99_ratio(const TransportResult& r)
{
    return r.rigsim.latency.p99_us / r.floor.latency.p99_us;
}

TransportResult measure_tcp(const DaemonProcess& daemon, const Options& options)
{
    TransportResult result{"tcp", {}, {}};
    {
        const auto& ep = daemon.endpoints();
        auto fd = connect_tcp(ep.tcp_host, ep.tcp_port);
        result.rigsim = measure(fd.get(), kReply, options, daemon.pid());
    }
    TcpEchoServer echo;
    auto fd = connect_tcp("127.0.0.1", echo.port());
    result.floor = measure(fd.get(), kRequest, options, std::nullopt);
    fd.reset();  // the echo thread sees end of file and returns before the join
    return result;
}

TransportResult measure_pty(const DaemonProcess& daemon, const Options& options)
{
    TransportResult result{"pty", {}, {}};
    {
        auto fd = open_pty(daemon.endpoints().pty_path);
        result.rigsim = measure(fd.get(), kReply, options, daemon.pid());
    }
    PtyEchoServer echo;
    auto fd = open_pty(echo.slave_path());
    result.floor = measure(fd.get(), kRequest, options, std::nullopt);
    fd.reset();
    return result;
}

/// Samples the daemon's CPU over a window of wall time in which nothing talks to it.
std::optional<CpuDelta> measure_idle(pid_t pid, double seconds)
{
    if (seconds <= 0)
        return std::nullopt;
    const auto before = read_cpu(pid);
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    return cpu_delta(before, read_cpu(pid));
}

double idle_percent(const CpuDelta& d)
{
    return 100.0 * d.stat_s / d.wall_s;
}

void print_latency(const TransportResult& r)
{
    std::printf("  %s  rigsimd             %10.2f %10.2f\n", r.name, r.rigsim.latency.median_us,
                r.rigsim.latency.p99_us);
    std::printf("  %s  floor (echo)        %10.2f %10.2f\n", r.name, r.floor.latency.median_us,
                r.floor.latency.p99_us);
    std::printf("  %s  ratio rigsimd/floor %10.2f %10.2f\n", r.name, median_ratio(r),
                p99_ratio(r));
}

void print_cpu_per_command(const TransportResult& r, int iterations)
{
    const auto& d = *r.rigsim.daemon_cpu;
    std::printf("  %s  %7.2f us/command  (/proc stat, resolution %.2f us)", r.name,
                d.stat_s * 1e6 / iterations, stat_tick_s() * 1e6 / iterations);
    if (d.schedstat_s)
        std::printf("  %7.2f us/command (schedstat)", *d.schedstat_s * 1e6 / iterations);
    std::printf("\n");
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

    DaemonProcess daemon{options.daemon, kStartTimeout};
    const auto& ep = daemon.endpoints();
    std::printf("rigsim_bench: %s (pid %d)\n", options.daemon.c_str(), static_cast<int>(daemon.pid()));
    std::printf("  tcp %s:%u, pty %s\n", ep.tcp_host.c_str(), static_cast<unsigned>(ep.tcp_port),
                ep.pty_path.c_str());
    std::printf("  %d timed round trips per run after %d warm-up; idle windows %.1f s\n\n",
                options.iterations, kWarmupIterations, options.idle_seconds);
    std::fflush(stdout);

    progress("idle window, fresh daemon");
    const auto idle_fresh = measure_idle(daemon.pid(), options.idle_seconds);
    progress("tcp round trips");
    const auto tcp = measure_tcp(daemon, options);
    progress("pty round trips");
    const auto pty = measure_pty(daemon, options);
    // After clients have come and gone: a transport that spins on a closed peer shows here.
    progress("idle window, after clients closed");
    const auto idle_after = measure_idle(daemon.pid(), options.idle_seconds);

    std::printf("round trip \":GP0\\n\" -> \":P0,0\\n\"    median us     p99 us\n");
    print_latency(tcp);
    print_latency(pty);
    std::printf("\ndaemon CPU per command (over the timed round trips)\n");
    print_cpu_per_command(tcp, options.iterations);
    print_cpu_per_command(pty, options.iterations);
    std::printf("\nidle CPU (default rig, no traffic)\n");
    print_idle("fresh daemon", idle_fresh);
    print_idle("after clients closed", idle_after);

    const double tcp_cpu_us = tcp.rigsim.daemon_cpu->stat_s * 1e6 / options.iterations;
    std::printf("\n== summary ==================================================\n");
    std::printf("  tcp ratio rigsimd/floor at median  %8.2f     <= %.1f    %s\n",
                median_ratio(tcp), kTargetMedianRatio,
                verdict(median_ratio(tcp) <= kTargetMedianRatio));
    std::printf("  pty ratio rigsimd/floor at median  %8.2f     <= %.1f    %s\n",
                median_ratio(pty), kTargetMedianRatio,
                verdict(median_ratio(pty) <= kTargetMedianRatio));
    std::printf("  daemon CPU per command (tcp)       %8.2f us  <= %.0f us   %s\n", tcp_cpu_us,
                kTargetCpuPerCommandUs, verdict(tcp_cpu_us <= kTargetCpuPerCommandUs));
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
