/*
 * rigsim_bench_soak: the daemon under many clients, event streams and a hostile control-API
 * client at once (issue 27). Three sections, each against a fresh rigsimd on the default rig:
 *   streams   - one MCS client's round trip with 0, 1 and 16 event streams reading (all events,
 *               or filtered to `status`), in alternating blocks;
 *   slowloris - 64 connections sending a request header a byte a second, and an honest client
 *               asking GET /api/clock every 100 ms: served or not, and when the slow ones go;
 *   soak      - 100 device clients (TCP and pty) x N commands, one in flight each, with random
 *               disconnects; alternating quiet blocks (the clients alone) and loaded ones (16
 *               streams reading, a quarter of them every event, the others filtered; the hostile
 *               API client, an honest one); then a churn block with
 *               clients and streams that never read; every answer checked (lost, misrouted:
 *               must be 0), the round trips of quiet and loaded blocks, and the daemon's RSS at
 *               start, its peak and after the churn.
 * A measurement, not a test: exit 0 whatever the figures, 1 if an answer was lost or misrouted
 * or something broke, 2 on bad flags. See bench/README.md "Soak".
 */
#include "daemon_process.hpp"
#include "roundtrip.hpp"
#include "soak_api.hpp"
#include "soak_devices.hpp"

#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#ifndef RIGSIMD_PATH
#define RIGSIMD_PATH "rigsimd"
#endif

namespace rigsim::bench {
namespace {

using SteadyClock = std::chrono::steady_clock;
constexpr std::chrono::milliseconds kStartTimeout{30000};
constexpr std::chrono::milliseconds kStopTimeout{20000};

struct Options {
    std::string daemon = RIGSIMD_PATH;
    std::string only;            ///< "": every section
    int clients = 100;
    int commands = 10000;        ///< per client, over the timed blocks
    int blocks = 4;              ///< alternating quiet and loaded
    int streams = 16;
    int disconnect_every = 500;
    int probe_round_trips = 20000;
    int slow = 64;
    int slow_seconds = 15;
    unsigned seed = 27;
};

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

void print_usage(std::FILE* out)
{
    std::fprintf(out,
                 "usage: rigsim_bench_soak [--daemon PATH] [--only streams|slowloris|soak] [--clients N]\n"
                 "                         [--commands N] [--blocks N] [--disconnect-every N]\n"
                 "                         [--round-trips N] [--slow N] [--slow-seconds S] [--seed N]\n"
                 "  --commands N          commands per client over the soak's timed blocks (default 10000)\n"
                 "  --clients N           device clients, 15..200 (default 100)\n"
                 "  --blocks N            timed blocks, alternating quiet and loaded, even (default 4)\n"
                 "  --disconnect-every N  mean commands between a client's disconnects, 0: never (default 500)\n"
                 "  --round-trips N       round trips per condition of the streams section (default 20000)\n"
                 "  --slow N              slowloris connections (default 64)\n"
                 "  --slow-seconds S      length of the slowloris section (default 15)\n"
                 "  --daemon PATH         rigsimd to measure (default %s)\n",
                 RIGSIMD_PATH);
}

long parse_int(const std::string& flag, const std::string& value, long lo, long hi)
{
    char* end = nullptr;
    const long n = std::strtol(value.c_str(), &end, 10);
    if (value.empty() || *end != '\0' || n < lo || n > hi)
        throw UsageError(flag + " wants an integer in " + std::to_string(lo) + ".." + std::to_string(hi) + ", not " +
                         value);
    return n;
}

Options parse_options(int argc, char** argv)
{
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string flag = argv[i];
        if (flag == "-h" || flag == "--help") {
            print_usage(stdout);
            std::exit(0);
        }
        if (i + 1 >= argc)
            throw UsageError("unknown flag or missing value: " + flag);
        const std::string v = argv[++i];
        if (flag == "--daemon")
            o.daemon = v;
        else if (flag == "--only" && (v == "streams" || v == "slowloris" || v == "soak"))
            o.only = v;
        else if (flag == "--clients")
            o.clients = static_cast<int>(parse_int(flag, v, 15, 200));
        else if (flag == "--commands")
            o.commands = static_cast<int>(parse_int(flag, v, 1, 10'000'000));
        else if (flag == "--blocks")
            o.blocks = static_cast<int>(parse_int(flag, v, 2, 100)) / 2 * 2;
        else if (flag == "--disconnect-every")
            o.disconnect_every = static_cast<int>(parse_int(flag, v, 0, 10'000'000));
        else if (flag == "--round-trips")
            o.probe_round_trips = static_cast<int>(parse_int(flag, v, 10, 10'000'000));
        else if (flag == "--slow")
            o.slow = static_cast<int>(parse_int(flag, v, 0, 1000));
        else if (flag == "--slow-seconds")
            o.slow_seconds = static_cast<int>(parse_int(flag, v, 1, 3600));
        else if (flag == "--seed")
            o.seed = static_cast<unsigned>(parse_int(flag, v, 0, 1'000'000'000));
        else
            throw UsageError("unknown flag or value: " + flag + " " + v);
    }
    return o;
}

/// The daemon's resident set and its peak, in KiB (/proc/PID/status VmRSS, VmHWM), and the
/// resident set's parts: anonymous (heap, stacks, mappings of its own) and file-backed (the
/// program's and libraries' pages it has run or read, RssFile).
struct Rss {
    long now_kb = 0;
    long peak_kb = 0;
    long anon_kb = 0;
    long file_kb = 0;
};

Rss rss_of(pid_t pid)
{
    std::ifstream in("/proc/" + std::to_string(pid) + "/status");
    Rss r;
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("VmRSS:", 0) == 0)
            r.now_kb = std::atol(line.c_str() + 6);
        else if (line.rfind("VmHWM:", 0) == 0)
            r.peak_kb = std::atol(line.c_str() + 6);
        else if (line.rfind("RssAnon:", 0) == 0)
            r.anon_kb = std::atol(line.c_str() + 8);
        else if (line.rfind("RssFile:", 0) == 0)
            r.file_kb = std::atol(line.c_str() + 8);
    }
    return r;
}

double mb(long kb)
{
    return static_cast<double>(kb) / 1024.0;
}

double percentile(std::vector<double> v, double p)
{
    if (v.empty())
        return 0;
    std::sort(v.begin(), v.end());
    const auto r = static_cast<std::size_t>(p * static_cast<double>(v.size()));
    return v[std::min(r, v.size() - 1)];
}

/// `n` event stream paths: `filtered` ones keep `status` events only.
std::vector<std::string> stream_paths(int n, bool filtered)
{
    return std::vector<std::string>(static_cast<std::size_t>(n), filtered ? "/api/events?type=status" : "/api/events");
}

/// The soak's `n` streams, as a lab's tools follow a rig: a quarter take every event (every
/// command's wire entries: they fall behind the soak's clients), a quarter the moves and status,
/// a quarter one device's events, a quarter one device's wire log.
std::vector<std::string> soak_stream_paths(int n)
{
    const char* kinds[] = {"/api/events", "/api/events?type=status,move_started,move_ended",
                           "/api/events?device=mcs0", "/api/events?device=tdc001&type=wire"};
    std::vector<std::string> paths;
    for (int i = 0; i < n; ++i)
        paths.emplace_back(kinds[i % 4]);
    return paths;
}

// ---- Section 1: what event streams cost a device round trip

void streams_section(const Options& o)
{
    DaemonProcess daemon(o.daemon, std::nullopt, kStartTimeout);
    const auto api = parse_control(daemon.endpoints_json());
    const auto& mcs = daemon.device("mcs0", "mcs");
    auto fd = connect_tcp(mcs.tcp_host, mcs.tcp_port);
    const Exchange gp{":GP0\n", ":P0,0\n", ReplyEnd::Newline};
    round_trips(fd.get(), gp, 1000);   // warm-up
    struct Condition {
        const char* name;
        int streams;
        bool filtered;
        std::vector<std::int64_t> samples;
    };
    std::vector<Condition> conditions{{"0", 0, false, {}}, {"1 (all events)", 1, false, {}},
                                      {"16 (all events)", o.streams, false, {}},
                                      {"16 (?type=status)", o.streams, true, {}}};
    constexpr int kBlocks = 10;
    for (int b = 0; b < kBlocks; ++b)
        for (auto& c : conditions) {
            std::unique_ptr<EventStreams> streams;
            if (c.streams > 0)
                streams = std::make_unique<EventStreams>(api, stream_paths(c.streams, c.filtered), true);
            auto s = round_trips(fd.get(), gp, std::max(1, o.probe_round_trips / kBlocks));
            c.samples.insert(c.samples.end(), s.begin(), s.end());
        }
    std::printf("\nstream cost: mcs0 \":GP0\" over TCP, one in flight, %d round trips per condition in %d "
                "alternating blocks, us\n",
                o.probe_round_trips, kBlocks);
    std::printf("  %-20s %9s %9s %10s %10s\n", "streams reading", "median", "p99", "median/0", "p99/0");
    LatencyStats base{};
    for (auto& c : conditions) {
        const auto st = latency_stats(c.samples);
        if (c.streams == 0)
            base = st;
        std::printf("  %-20s %9.2f %9.2f %10.2f %10.2f\n", c.name, st.median_us, st.p99_us,
                    st.median_us / base.median_us, st.p99_us / base.p99_us);
    }
    daemon.terminate(kStopTimeout);
}

// ---- Section 2: slowloris on a quiet daemon

void slowloris_section(const Options& o)
{
    DaemonProcess daemon(o.daemon, std::nullopt, kStartTimeout);
    const auto api = parse_control(daemon.endpoints_json());
    HostileApiClient::Settings s;
    s.slow = o.slow;
    s.bodies = false;
    s.honest_interval_ms = 100;
    HostileApiClient hostile(api, s);
    std::this_thread::sleep_for(std::chrono::seconds(o.slow_seconds));
    const auto r = hostile.stop();
    std::printf("\nslowloris: %d connections sending a request header a byte a second for %d s; an honest "
                "GET /api/clock every 100 ms\n",
                o.slow, o.slow_seconds);
    std::printf("  honest requests served %llu of %llu (p50 %.2f ms, p99 %.2f ms)\n",
                static_cast<unsigned long long>(r.honest_ok),
                static_cast<unsigned long long>(r.honest_ok + r.honest_failed), percentile(r.honest_ms, 0.5),
                percentile(r.honest_ms, 0.99));
    std::printf("  slow connections opened %llu, closed by the daemon %zu, after median %.1f s (max %.1f s)\n",
                static_cast<unsigned long long>(r.slow_opened), r.slow_closed_after_s.size(),
                percentile(r.slow_closed_after_s, 0.5), percentile(r.slow_closed_after_s, 1.0));
    daemon.terminate(kStopTimeout);
}

// ---- Section 3: the soak

/// The device clients: one on each device's pty, the rest over TCP, spread over the devices.
std::vector<DeviceClients::Spec> client_specs(const std::vector<SoakDevice>& devices, int clients)
{
    std::vector<DeviceClients::Spec> specs;
    for (const auto& d : devices)
        specs.push_back({&d, true});
    for (std::size_t i = 0; specs.size() < static_cast<std::size_t>(clients); ++i)
        specs.push_back({&devices[i % devices.size()], false});
    return specs;
}

/// Clients that never read: two on each APT device over TCP, flooding position requests.
std::vector<NonReadingClients::Target> hog_targets(const std::vector<SoakDevice>& devices)
{
    std::vector<NonReadingClients::Target> t;
    for (const auto& d : devices)
        for (int k = 0; k < 2; ++k)
            t.push_back({d.endpoints.tcp_host, d.endpoints.tcp_port, d.commands[0].request});
    return t;
}

void print_round_trips(const char* name, std::vector<std::int64_t>& quiet, std::vector<std::int64_t>& loaded)
{
    const auto q = latency_stats(quiet);
    const auto l = latency_stats(loaded);
    std::printf("  %-5s %9zu %9.2f %9.2f %9zu %9.2f %9.2f %9.2f %9.2f\n", name, quiet.size(), q.median_us, q.p99_us,
                loaded.size(), l.median_us, l.p99_us, l.median_us / q.median_us, l.p99_us / q.p99_us);
}

bool soak_section(const Options& o)
{
    DaemonProcess daemon(o.daemon, std::nullopt, kStartTimeout);
    const auto api = parse_control(daemon.endpoints_json());
    const auto devices = soak_devices(daemon.devices());
    const auto pid = daemon.pid();
    long peak_kb = 0;
    const auto sample = [&] { peak_kb = std::max(peak_kb, rss_of(pid).now_kb); };
    DeviceClients clients(client_specs(devices, o.clients), o.seed, o.disconnect_every);
    // Warm-up: every device's wire log fills its ring (1000 entries); then every client goes.
    RoundTrips warm;
    clients.run_block(std::max(1, std::min(o.commands, 1000)), warm, sample);
    clients.close_all();
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));   // what the daemon frees, freed
    const auto start = rss_of(pid);
    const long start_kb = start.now_kb;

    RoundTrips quiet, loaded;
    HostileReport hostile_report;
    std::uint64_t stream_bytes = 0;
    std::size_t streams_closed = 0;
    const int per_block = std::max(1, o.commands / o.blocks);
    for (int b = 0; b < o.blocks; ++b) {
        if (b % 2 == 0) {
            clients.run_block(per_block, quiet, sample);
            continue;
        }
        EventStreams streams(api, soak_stream_paths(o.streams), true);
        HostileApiClient hostile(api, HostileApiClient::Settings{});
        clients.run_block(per_block, loaded, sample);
        auto r = hostile.stop();
        hostile_report.honest_ok += r.honest_ok;
        hostile_report.honest_failed += r.honest_failed;
        hostile_report.honest_ms.insert(hostile_report.honest_ms.end(), r.honest_ms.begin(), r.honest_ms.end());
        hostile_report.slow_opened += r.slow_opened;
        hostile_report.slow_closed_after_s.insert(hostile_report.slow_closed_after_s.end(),
                                                  r.slow_closed_after_s.begin(), r.slow_closed_after_s.end());
        hostile_report.big_bodies += r.big_bodies;
        hostile_report.big_refused += r.big_refused;
        hostile_report.slow_bodies_closed += r.slow_bodies_closed;
        stream_bytes += streams.bytes();
        streams_closed += streams.closed_by_daemon();
    }
    // The churn: streams and device clients that never read, beside the clients, until the
    // daemon has dropped them; then everyone goes.
    std::size_t streams_dropped = 0, hogs_dropped = 0, hogs = 0;
    {
        EventStreams deaf(api, stream_paths(o.streams, false), false);
        NonReadingClients hog(hog_targets(devices));
        RoundTrips churn;
        clients.run_block(per_block, churn, sample);
        launch::wait_until([&] { return deaf.closed_by_daemon() == static_cast<std::size_t>(o.streams) &&
                                        hog.dropped() == hog.count(); },
                           std::chrono::milliseconds(10000));
        sample();
        streams_dropped = deaf.closed_by_daemon();
        hogs_dropped = hog.dropped();
        hogs = hog.count();
    }
    clients.close_all();
    const auto went = SteadyClock::now();
    long after_kb = rss_of(pid).now_kb;
    launch::wait_until([&] { return (after_kb = rss_of(pid).now_kb) <= start_kb * 11 / 10; },
                       std::chrono::milliseconds(10000));
    const double after_s = std::chrono::duration<double>(SteadyClock::now() - went).count();
    const auto after = rss_of(pid);
    peak_kb = std::max(peak_kb, after.peak_kb);

    const auto& t = clients.totals();
    std::printf("\nsoak: %d device clients (%zu on ptys, the rest TCP) x %d commands in %d blocks alternating quiet "
                "and loaded, a disconnect every ~%d commands\n",
                o.clients, devices.size(), per_block * o.blocks, o.blocks, o.disconnect_every);
    std::printf("  answers checked %llu: lost %llu, misrouted %llu; abandoned by disconnects %llu, reconnects %llu, "
                "closed by the daemon %llu\n",
                static_cast<unsigned long long>(t.answered), static_cast<unsigned long long>(t.lost),
                static_cast<unsigned long long>(t.misrouted), static_cast<unsigned long long>(t.abandoned),
                static_cast<unsigned long long>(t.reconnects), static_cast<unsigned long long>(t.refused));
    std::printf("  round trip, us   quiet: n    p50       p99   loaded: n    p50       p99  p50 ratio p99 ratio\n");
    print_round_trips("tcp", quiet.tcp, loaded.tcp);
    print_round_trips("pty", quiet.pty, loaded.pty);
    std::printf("  loaded blocks: %d streams read %.1f MB (%zu closed by the daemon, behind); honest API requests served %llu of %llu (p50 %.2f ms, "
                "p99 %.2f ms); slowloris connections %llu, closed by the daemon %zu (median after %.1f s); "
                "1 MiB bodies %llu, refused 413 %llu; slow bodies closed %llu\n",
                o.streams, static_cast<double>(stream_bytes) / 1e6, streams_closed,
                static_cast<unsigned long long>(hostile_report.honest_ok),
                static_cast<unsigned long long>(hostile_report.honest_ok + hostile_report.honest_failed),
                percentile(hostile_report.honest_ms, 0.5), percentile(hostile_report.honest_ms, 0.99),
                static_cast<unsigned long long>(hostile_report.slow_opened), hostile_report.slow_closed_after_s.size(),
                percentile(hostile_report.slow_closed_after_s, 0.5),
                static_cast<unsigned long long>(hostile_report.big_bodies),
                static_cast<unsigned long long>(hostile_report.big_refused),
                static_cast<unsigned long long>(hostile_report.slow_bodies_closed));
    std::printf("  churn: %d streams that never read, dropped %zu; %zu device clients that never read, dropped %zu\n",
                o.streams, streams_dropped, hogs, hogs_dropped);
    std::printf("  rss: start %.1f MB, peak %.1f MB, after the churn %.1f MB (%.2f x start, %.1f s after the last "
                "client went)\n",
                mb(start_kb), mb(peak_kb), mb(after_kb), static_cast<double>(after_kb) / static_cast<double>(start_kb),
                after_s);
    std::printf("       anonymous (heap and the daemon's own mappings) %.1f MB -> %.1f MB (%.2f x); file-backed (code "
                "and data of the program and libraries) %.1f MB -> %.1f MB\n",
                mb(start.anon_kb), mb(after.anon_kb),
                static_cast<double>(after.anon_kb) / static_cast<double>(std::max(1L, start.anon_kb)), mb(start.file_kb),
                mb(after.file_kb));
    daemon.terminate(kStopTimeout);
    return t.lost == 0 && t.misrouted == 0;
}

} // namespace
} // namespace rigsim::bench

int main(int argc, char** argv)
{
    using namespace rigsim::bench;
    ::signal(SIGPIPE, SIG_IGN);
    Options o;
    try {
        o = parse_options(argc, argv);
    } catch (const UsageError& e) {
        std::fprintf(stderr, "rigsim_bench_soak: %s\n", e.what());
        print_usage(stderr);
        return 2;
    }
    try {
        std::printf("rigsim_bench_soak: %s\n", o.daemon.c_str());
        bool ok = true;
        if (o.only.empty() || o.only == "streams")
            streams_section(o);
        if (o.only.empty() || o.only == "slowloris")
            slowloris_section(o);
        if (o.only.empty() || o.only == "soak")
            ok = soak_section(o);
        std::fflush(stdout);
        if (!ok) {
            std::fprintf(stderr, "rigsim_bench_soak: answers were lost or misrouted\n");
            return 1;
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rigsim_bench_soak: %s\n", e.what());
        return 1;
    }
}
