/*
 * rigsim_bench_axes: the daemon's CPU with many moving axes (issue 10). It generates a rig
 * of MCS devices (default 40 x 250 channels = 10,000 axes), starts rigsimd on it and
 * measures the daemon's CPU over three windows: idle (the baseline), every channel in a
 * long closed-loop move (SCLS 1 um/s, MPA 10 mm: hours), and every channel in an endless
 * open-loop burst (MST +-30000, 1 kHz). Several --daemon flags are measured one after the
 * other in the same run and printed side by side. A measurement, not a test: exit 0 whatever
 * the figures, 1 if something broke, 2 on bad flags. See bench/README.md.
 */
#include "daemon_process.hpp"
#include "proc_cpu.hpp"
#include "roundtrip.hpp"

#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#ifndef RIGSIMD_PATH
#define RIGSIMD_PATH "rigsimd"
#endif

namespace rigsim::bench {
namespace {

constexpr std::chrono::milliseconds kStartTimeout{30000};
constexpr std::chrono::milliseconds kStopTimeout{10000};
constexpr int kReplyTimeoutMs = 30000;
/// Wall time between starting the movements and measuring them (start-up transients).
constexpr double kSettleSeconds = 1.0;

struct Options {
    std::vector<std::string> daemons;
    int devices = 40;
    int channels = 250;
    double seconds = 5.0;
};

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

void print_usage(std::FILE* out)
{
    std::fprintf(out,
                 "usage: rigsim_bench_axes [--daemon PATH]... [--devices N] [--channels N]\n"
                 "                         [--seconds S]\n"
                 "  --daemon PATH   rigsimd to measure; repeat to compare (default %s)\n"
                 "  --devices N     MCS devices of the generated rig, 1..200 (default 40)\n"
                 "  --channels N    channels per device, 1..255 (default 250)\n"
                 "  --seconds S     length of each CPU window (default 5)\n",
                 RIGSIMD_PATH);
}

long parse_int(const std::string& flag, const std::string& value, long lo, long hi)
{
    char* end = nullptr;
    const long n = std::strtol(value.c_str(), &end, 10);
    if (value.empty() || *end != '\0' || n < lo || n > hi)
        throw UsageError(flag + " wants an integer in " + std::to_string(lo) + ".." + std::to_string(hi) +
                         ", not " + value);
    return n;
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
        if (flag == "--daemon") {
            options.daemons.push_back(value);
        } else if (flag == "--devices") {
            options.devices = static_cast<int>(parse_int(flag, value, 1, 200));
        } else if (flag == "--channels") {
            options.channels = static_cast<int>(parse_int(flag, value, 1, 255));
        } else if (flag == "--seconds") {
            char* end = nullptr;
            options.seconds = std::strtod(value.c_str(), &end);
            if (value.empty() || *end != '\0' || !(options.seconds > 0) || options.seconds > 3600)
                throw UsageError("--seconds wants a number in (0, 3600], not " + value);
        } else {
            throw UsageError("unknown flag: " + flag);
        }
    }
    if (options.daemons.empty())
        options.daemons.push_back(RIGSIMD_PATH);
    return options;
}

/// The rig: `devices` MCS devices named mcs000.. with `channels` default channels each
/// (linear S sensors, +-10.5 mm of travel, standing at 0).
std::string rig_json(int devices, int channels)
{
    std::string json = "{\"tick_hz\": 1000, \"devices\": [";
    for (int d = 0; d < devices; ++d) {
        char name[16];
        std::snprintf(name, sizeof name, "mcs%03d", d);
        json += d ? ",\n" : "\n";
        json += "{\"name\": \"" + std::string{name} + "\", \"protocol\": \"mcs\", \"mcs\": {\"system_id\": " +
                std::to_string(1000 + d) + ", \"channels\": [";
        for (int c = 0; c < channels; ++c)
            json += c ? ", {}" : "{}";
        json += "]}}";
    }
    return json + "\n]}\n";
}

/// A temporary file that holds `text` and is removed with the object.
class TempFile {
public:
    explicit TempFile(const std::string& text)
    {
        const char* tmp = std::getenv("TMPDIR");
        std::string pattern = std::string{tmp && *tmp ? tmp : "/tmp"} + "/rigsim_axes.XXXXXX";
        const int fd = ::mkstemp(pattern.data());
        if (fd < 0)
            throw std::runtime_error("mkstemp " + pattern + ": " + std::strerror(errno));
        ::close(fd);
        path_ = pattern;
        std::ofstream out(path_);
        out << text;
        if (!out.flush())
            throw std::runtime_error("cannot write " + path_);
    }
    ~TempFile() { ::unlink(path_.c_str()); }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

void write_all(int fd, const std::string& data)
{
    std::size_t done = 0;
    while (done < data.size()) {
        const auto n = ::write(fd, data.data() + done, data.size() - done);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            throw std::runtime_error(std::string{"write: "} + std::strerror(errno));
        done += static_cast<std::size_t>(n);
    }
}

/// Reads until `lines` '\n' have arrived; throws after kReplyTimeoutMs without progress.
std::string read_lines(int fd, std::size_t lines)
{
    std::string in;
    std::size_t seen = 0;
    char buf[65536];
    while (seen < lines) {
        pollfd p{fd, POLLIN, 0};
        const int r = ::poll(&p, 1, kReplyTimeoutMs);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            throw std::runtime_error("no reply within " + std::to_string(kReplyTimeoutMs) + " ms");
        const auto n = ::read(fd, buf, sizeof buf);
        if (n <= 0)
            throw std::runtime_error("connection closed while waiting for replies");
        for (ssize_t i = 0; i < n; ++i)
            seen += buf[i] == '\n';
        in.append(buf, static_cast<std::size_t>(n));
    }
    return in;
}

/// Sends `per_channel(c)` for every channel of every device, in one write per device,
/// and checks the answers against `answers(c)`.
template <class F, class G>
void command_all(const std::vector<UniqueFd>& fds, int channels, int commands_per_channel, F per_channel,
                 G answers)
{
    for (const auto& fd : fds) {
        std::string out;
        for (int c = 0; c < channels; ++c)
            out += per_channel(c);
        write_all(fd.get(), out);
    }
    for (const auto& fd : fds) {
        const std::string in = read_lines(fd.get(), static_cast<std::size_t>(channels * commands_per_channel));
        std::string expected;
        for (int c = 0; c < channels; ++c)
            expected += answers(c);
        if (in != expected)
            throw std::runtime_error("unexpected answers: \"" + printable(in.substr(0, 200), ReplyEnd::Newline) +
                                     "\"");
    }
}

/// Checks that the last channel of every device reports `status` (GS).
void expect_status(const std::vector<UniqueFd>& fds, int channels, int status)
{
    const std::string ch = std::to_string(channels - 1);
    const std::string expected = ":S" + ch + "," + std::to_string(status) + "\n";
    for (const auto& fd : fds) {
        write_all(fd.get(), ":GS" + ch + "\n");
        const auto in = read_lines(fd.get(), 1);
        if (in != expected)
            throw std::runtime_error("GS" + ch + ": expected \"" + printable(expected, ReplyEnd::Newline) +
                                     "\", got \"" + printable(in, ReplyEnd::Newline) + "\"");
    }
}

/// The daemon's CPU as % of one core over `seconds` of wall time.
double cpu_percent(pid_t pid, double seconds)
{
    const auto before = read_process_cpu(pid);
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    const auto after = read_process_cpu(pid);
    const double wall = std::chrono::duration<double>(after.wall - before.wall).count();
    if (before.schedstat_ns && after.schedstat_ns)
        return 100.0 * static_cast<double>(*after.schedstat_ns - *before.schedstat_ns) / 1e9 / wall;
    return 100.0 * (after.stat_s - before.stat_s) / wall;
}

struct Result {
    std::string daemon;
    double idle = 0;
    double closed_loop = 0;
    double open_loop = 0;
};

void progress(const std::string& what)
{
    std::fprintf(stderr, "rigsim_bench_axes: %s...\n", what.c_str());
}

Result measure(const std::string& path, const TempFile& rig, const Options& options)
{
    progress(path + ": start");
    DaemonProcess daemon{path, std::nullopt, kStartTimeout, {"--config", rig.path()}};
    std::vector<UniqueFd> fds;
    for (const auto& d : daemon.devices())
        if (d.protocol == "mcs")
            fds.push_back(connect_tcp(d.tcp_host, d.tcp_port));
    if (fds.size() != static_cast<std::size_t>(options.devices))
        throw std::runtime_error("the daemon lists " + std::to_string(fds.size()) + " MCS devices, not " +
                                 std::to_string(options.devices));
    Result r{path, 0, 0, 0};
    std::this_thread::sleep_for(std::chrono::duration<double>(kSettleSeconds));
    progress(path + ": idle window");
    r.idle = cpu_percent(daemon.pid(), options.seconds);

    // Closed loop: 10 mm at 1 um/s, hours away from the end.
    // SCLS acknowledges E-1,0 (its own description in the manual; docs/protocol/mcs.md).
    command_all(
        fds, options.channels, 2,
        [](int c) {
            const auto ch = std::to_string(c);
            return ":SCLS" + ch + ",1000\n:MPA" + ch + ",10000000,0\n";
        },
        [](int c) { return ":E-1,0\n:E" + std::to_string(c) + ",0\n"; });
    expect_status(fds, options.channels, 4);
    std::this_thread::sleep_for(std::chrono::duration<double>(kSettleSeconds));
    progress(path + ": closed-loop window");
    r.closed_loop = cpu_percent(daemon.pid(), options.seconds);
    expect_status(fds, options.channels, 4);

    // Open loop: endless bursts (+-30000 steps: until stopped) at 1 kHz.
    command_all(
        fds, options.channels, 1, [](int c) { return ":MST" + std::to_string(c) + ",30000,4095,1000\n"; },
        [](int c) { return ":E" + std::to_string(c) + ",0\n"; });
    expect_status(fds, options.channels, 1);
    std::this_thread::sleep_for(std::chrono::duration<double>(kSettleSeconds));
    progress(path + ": open-loop window");
    r.open_loop = cpu_percent(daemon.pid(), options.seconds);
    expect_status(fds, options.channels, 1);

    fds.clear();
    daemon.terminate(kStopTimeout);
    return r;
}

int run(const Options& options)
{
    ::signal(SIGPIPE, SIG_IGN);
    const int axes = options.devices * options.channels;
    const TempFile rig{rig_json(options.devices, options.channels)};
    std::vector<Result> results;
    for (const auto& path : options.daemons)
        results.push_back(measure(path, rig, options));

    std::printf("daemon CPU, %% of one core, %d MCS devices x %d channels = %d axes, tick 1 kHz,"
                " %.1f s windows\n",
                options.devices, options.channels, axes, options.seconds);
    std::printf("  %-8s %10s %12s %12s %14s %14s\n", "", "idle", "closed loop", "open loop", "closed/idle",
                "open/idle");
    for (std::size_t i = 0; i < results.size(); ++i) {
        const auto& r = results[i];
        const auto ratio = [&](double moving) { return r.idle > 0 ? moving / r.idle : 0.0; };
        std::printf("  daemon %zu %9.2f %% %10.2f %% %10.2f %% %13.1fx %13.1fx\n", i + 1, r.idle, r.closed_loop,
                    r.open_loop, ratio(r.closed_loop), ratio(r.open_loop));
    }
    for (std::size_t i = 0; i < results.size(); ++i)
        std::printf("  daemon %zu: %s\n", i + 1, results[i].daemon.c_str());
    std::printf("  (closed loop: SCLS 1 um/s + MPA 10 mm on every channel; open loop: MST +-30000 at 1 kHz)\n");
    std::fflush(stdout);
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
        std::fprintf(stderr, "rigsim_bench_axes: %s\n", e.what());
        print_usage(stderr);
        return 2;
    } catch (const std::exception& e) {
        std::fflush(stdout);
        std::fprintf(stderr, "rigsim_bench_axes: error: %s\n", e.what());
        return 1;
    }
}
