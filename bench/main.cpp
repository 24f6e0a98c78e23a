/*
 * rigsim_bench: round-trip latency of rigsimd against an echo floor on TCP and
 * pty, for an MCS and an APT request, the daemon's CPU time per command, and its
 * idle CPU. A measurement, not a test: it exits 0 whatever the figures, 1 if
 * something broke, 2 on bad flags. See bench/README.md.
 */
#include "cpu_placement.hpp"
#include "daemon_process.hpp"
#include "echo_servers.hpp"
#include "proc_cpu.hpp"
#include "roundtrip.hpp"

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
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

/// MCS GP (get position, MCS manual 3.3) of channel 0, which rests at 0.
const std::string kMcsRequest = ":GP0\n";
const std::string kMcsReply = ":P0,0\n";

/*
 * APT MGMSG_MOT_REQ_POSCOUNTER (0x0411) for channel 1: header only, to the
 * generic USB unit (0x50) from the host (0x01). The answer, MGMSG_MOT_GET_POSCOUNTER
 * (0x0412), carries 6 data bytes (0x81: to the host, data follows) from 0x50:
 * the channel (1, u16) and the position counter (i32), little-endian.
 */
const std::string kAptRequest{"\x11\x04\x01\x00\x50\x01", 6};
const std::string kAptReplyPrefix{"\x12\x04\x06\x00\x81\x50\x01\x00", 8};
constexpr std::size_t kAptReplySize = 12;

// Targets (see bench/README.md).
constexpr double kTargetMedianRatio = 1.5;
constexpr double kTargetCpuPerCommandUs = 5.0;
constexpr double kTargetIdlePercent = 1.0;

struct Options {
    int iterations = 20000;
    double idle_seconds = 5.0;
    std::string daemon = RIGSIMD_PATH;
    Pinning pinning = Pinning::Same;
    std::string protocol = "both";   ///< "mcs", "apt" or "both": the exchanges to time
};

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

void print_usage(std::FILE* out)
{
    std::fprintf(out,
                 "usage: rigsim_bench [--iterations N] [--idle-seconds S] [--pin MODE]\n"
                 "                    [--protocol mcs|apt|both] [--daemon PATH]\n"
                 "  --iterations N    timed round trips per protocol, transport and server\n"
                 "                    (default 20000), after %d warm-up round trips\n"
                 "  --idle-seconds S  length of each idle CPU window, 0 to skip (default 5)\n"
                 "  --pin MODE        same: client and servers (rigsimd and the floor) on one\n"
                 "                    CPU (default); split: client on one CPU, servers on\n"
                 "                    another; none: left to the scheduler\n"
                 "  --protocol P      mcs, apt or both (default): the exchanges to time; one\n"
                 "                    alone gives callgrind a count per protocol\n"
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
        } else if (flag == "--protocol") {
            if (value != "mcs" && value != "apt" && value != "both")
                throw UsageError("--protocol wants mcs, apt or both, not " + value);
            options.protocol = value;
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

/// One server under measurement: the client's fd, the exchange it must give, its CPU clock.
struct Server {
    int fd;
    Exchange exchange;
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
    round_trips(rigsim.fd, rigsim.exchange, kWarmupIterations);
    round_trips(floor.fd, floor.exchange, kWarmupIterations);
    const auto run_block = [](Server& server, int iterations) {
        const auto before = server.read_cpu();
        auto samples = round_trips(server.fd, server.exchange, iterations);
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

/// One protocol's round trip: the device that answers it and how its reply is checked.
struct Protocol {
    /// "mcs" or "apt", as in the endpoints file; also the report's label.
    const char* name;
    /// The device of the default rig that answers.
    const char* device;
    /// The heading of its round-trip table.
    const char* title;
    std::string request;
    ReplyEnd end;
    /// What the floor answers to `request`: as many bytes as a real reply, except
    /// for MCS, where a repeated request would put a '\n' inside the reply, so the
    /// floor echoes the 5 bytes of ":GP0\n" for the 6 of ":P0,0\n".
    std::size_t floor_reply_bytes;
    /// rigsimd's reply to one request on `fd`, checked; every timed reply must equal it.
    std::function<std::string(int fd)> first_reply;
};

/// The APT reply, whose position bytes are learnt from the first one: the header
/// and channel are checked here, and the whole reply (so the position, which
/// nothing moves) on every round trip after it.
std::string first_apt_reply(int fd)
{
    const auto reply = request_fixed_length(fd, kAptRequest, kAptReplySize);
    if (reply.compare(0, kAptReplyPrefix.size(), kAptReplyPrefix) != 0)
        throw std::runtime_error(
            "sent \"" + printable(kAptRequest, ReplyEnd::Length) + "\", expected \"" +
            printable(kAptReplyPrefix, ReplyEnd::Length) + " + 4 position bytes\", got \"" +
            printable(reply, ReplyEnd::Length) + "\"");
    return reply;
}

const Protocol kMcs{"mcs",
                    "mcs0",
                    "round trip \":GP0\\n\" -> \":P0,0\\n\" (mcs0; floor echoes 5 bytes), us",
                    kMcsRequest,
                    ReplyEnd::Newline,
                    kMcsRequest.size(),
                    [](int) { return kMcsReply; }};

const Protocol kApt{"apt",
                    "tdc001",
                    "round trip MGMSG_MOT_REQ_POSCOUNTER -> MGMSG_MOT_GET_POSCOUNTER "
                    "(tdc001; 6 -> 12 bytes, the floor alike), us",
                    kAptRequest,
                    ReplyEnd::Length,
                    kAptReplySize,
                    first_apt_reply};

struct TransportResult {
    /// "mcs tcp", "apt pty", ...
    std::string name;
    LatencyStats rigsim;
    LatencyStats floor;
    CpuDelta rigsim_cpu;
    CpuDelta floor_cpu;
};

double median_ratio(const TransportResult& r)
{
    return r.rigsim.median_us / r.floor.median_us;
}

double p99_ratio(const TransportResult& r)
{
    return r.rigsim.p99_us / r.floor.p99_us;
}

/// Times `protocol` against rigsimd on `rigsim_fd` and the floor on `floor_fd`.
TransportResult measure_pair(const Protocol& protocol, const char* transport, int rigsim_fd,
                             int floor_fd, pid_t daemon_pid, pid_t echo_tid,
                             const Options& options)
{
    Server rigsim{rigsim_fd,
                  {protocol.request, protocol.first_reply(rigsim_fd), protocol.end},
                  [daemon_pid] { return read_process_cpu(daemon_pid); },
                  {},
                  {}};
    Server floor{floor_fd,
                 {protocol.request, echo_reply(protocol.request, protocol.floor_reply_bytes),
                  protocol.end},
                 [echo_tid] { return read_thread_cpu(echo_tid); },
                 {},
                 {}};
    measure_interleaved(rigsim, floor, options);
    return {std::string{protocol.name} + " " + transport, latency_stats(rigsim.samples_ns),
            latency_stats(floor.samples_ns), rigsim.cpu, floor.cpu};
}

EchoShape floor_shape(const Protocol& protocol)
{
    return {protocol.request.size(), protocol.floor_reply_bytes};
}

TransportResult measure_tcp(const Protocol& protocol, const DaemonProcess& daemon,
                            const Placement& placement, const Options& options)
{
    const auto& device = daemon.device(protocol.device, protocol.name);
    TcpEchoServer echo{floor_shape(protocol), placement.server_cpu};
    auto rigsim_fd = connect_tcp(device.tcp_host, device.tcp_port);
    auto floor_fd = connect_tcp("127.0.0.1", echo.port());
    return measure_pair(protocol, "tcp", rigsim_fd.get(), floor_fd.get(), daemon.pid(),
                        echo.thread_id(), options);
}

TransportResult measure_pty(const Protocol& protocol, const DaemonProcess& daemon,
                            const Placement& placement, const Options& options)
{
    const auto& device = daemon.device(protocol.device, protocol.name);
    PtyEchoServer echo{floor_shape(protocol), placement.server_cpu};
    auto rigsim_fd = open_pty(device.pty_path);
    auto floor_fd = open_pty(echo.slave_path());
    return measure_pair(protocol, "pty", rigsim_fd.get(), floor_fd.get(), daemon.pid(),
                        echo.thread_id(), options);
}

/// One protocol's figures on both transports.
struct ProtocolResult {
    const Protocol* protocol;
    TransportResult tcp;
    TransportResult pty;
};

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
    const char* name = r.name.c_str();
    std::printf("  %s  %-19s %10.2f %10.2f\n", name, "rigsimd", r.rigsim.median_us,
                r.rigsim.p99_us);
    std::printf("  %s  %-19s %10.2f %10.2f\n", name, "floor (echo)", r.floor.median_us,
                r.floor.p99_us);
    std::printf("  %s  %-19s %10.2f %10.2f\n", name, "ratio rigsimd/floor", median_ratio(r),
                p99_ratio(r));
}

void print_cpu_per_command(const std::string& transport, const char* server, const CpuDelta& d,
                           int iterations)
{
    std::printf("  %s  %-19s %10.2f %10.2f", transport.c_str(), server, d.stat_s * 1e6 / iterations,
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

/// The exchanges --protocol asks for, MCS first.
std::vector<const Protocol*> protocols_of(const Options& options)
{
    std::vector<const Protocol*> out;
    for (const Protocol* p : {&kMcs, &kApt})
        if (options.protocol == "both" || options.protocol == p->name)
            out.push_back(p);
    return out;
}

int run(const Options& options)
{
    // A peer closing mid-write must be an error return, not a fatal signal.
    ::signal(SIGPIPE, SIG_IGN);

    const auto placement = choose_placement(options.pinning);
    DaemonProcess daemon{options.daemon, placement.server_cpu, kStartTimeout};
    if (placement.client_cpu)
        pin_this_thread(*placement.client_cpu);
    std::printf("rigsim_bench: %s (pid %d)\n", options.daemon.c_str(),
                static_cast<int>(daemon.pid()));
    for (const Protocol* protocol : protocols_of(options)) {
        const auto& d = daemon.device(protocol->device, protocol->name);
        std::printf("  %s (%s %s): tcp %s:%u, pty %s\n", d.name.c_str(), d.protocol.c_str(),
                    d.model.c_str(), d.tcp_host.c_str(), static_cast<unsigned>(d.tcp_port),
                    d.pty_path.c_str());
    }
    std::printf("  %d timed round trips per protocol, transport and server after %d warm-up,"
                " in %d alternating blocks\n",
                options.iterations, kWarmupIterations, kBlocks);
    std::printf("  %s; idle windows %.1f s\n\n", describe(placement).c_str(),
                options.idle_seconds);
    std::fflush(stdout);

    progress("idle window, fresh daemon");
    const auto idle_fresh = measure_idle(daemon.pid(), options.idle_seconds);
    std::vector<ProtocolResult> results;
    for (const Protocol* protocol : protocols_of(options)) {
        progress((std::string{protocol->name} + " tcp round trips").c_str());
        auto tcp = measure_tcp(*protocol, daemon, placement, options);
        progress((std::string{protocol->name} + " pty round trips").c_str());
        auto pty = measure_pty(*protocol, daemon, placement, options);
        results.push_back({protocol, std::move(tcp), std::move(pty)});
    }
    // After clients have come and gone: a transport that spins on a closed peer shows here.
    progress("idle window, after clients closed");
    const auto idle_after = measure_idle(daemon.pid(), options.idle_seconds);

    for (const auto& r : results) {
        std::printf("%s\n", r.protocol->title);
        std::printf("  %-28s %10s %10s\n", "", "median", "p99");
        print_latency(r.tcp);
        print_latency(r.pty);
        std::printf("\n");
    }
    std::printf("server CPU per command over the timed round trips, us"
                " (/proc stat resolution %.2f us)\n",
                stat_tick_s() * 1e6 / options.iterations);
    std::printf("  %-28s %10s %10s %10s\n", "", "stat", "of it sys", "schedstat");
    for (const auto& r : results) {
        print_cpu_per_command(r.tcp, options.iterations);
        print_cpu_per_command(r.pty, options.iterations);
    }
    std::printf("\nidle CPU (default rig, no traffic)\n");
    print_idle("fresh daemon", idle_fresh);
    print_idle("after clients closed", idle_after);

    std::printf("\n== summary (%s) ==\n", describe(placement).c_str());
    for (const auto& r : results) {
        for (const TransportResult* t : {&r.tcp, &r.pty}) {
            const std::string label = t->name + " ratio rigsimd/floor at median";
            std::printf("  %-38s %8.2f     <= %.1f    %s\n", label.c_str(), median_ratio(*t),
                        kTargetMedianRatio, verdict(median_ratio(*t) <= kTargetMedianRatio));
        }
    }
    for (const auto& r : results) {
        const double cpu_us = r.tcp.rigsim_cpu.stat_s * 1e6 / options.iterations;
        const std::string label = "daemon CPU per command (" + r.tcp.name + ")";
        const double floor_us = r.tcp.floor_cpu.stat_s * 1e6 / options.iterations;
        std::printf("  %-38s %8.2f us  <= %.0f us   %s   (floor echo thread: %.2f us, ratio %.2f)\n",
                    label.c_str(), cpu_us, kTargetCpuPerCommandUs,
                    verdict(cpu_us <= kTargetCpuPerCommandUs), floor_us,
                    floor_us > 0 ? cpu_us / floor_us : 0.0);
    }
    if (idle_fresh && idle_after) {
        const double idle = std::max(idle_percent(*idle_fresh), idle_percent(*idle_after));
        std::printf("  %-38s %8.2f %%   <= %.0f %%    %s\n", "idle CPU (worse window)", idle,
                    kTargetIdlePercent, verdict(idle <= kTargetIdlePercent));
    } else {
        std::printf("  %-38s skipped\n", "idle CPU");
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
