// rigsimd: emulated laboratory motion controllers on pseudo-terminals and TCP sockets.
// Flags, config, the rig, the loop; exceptions stop here.

#include "emulator/control/control_api.hpp"
#include "emulator/core/log_format.hpp"
#include "emulator/control/http_server.hpp"
#include "emulator/core/atomic_file.hpp"
#include "emulator/core/logging.hpp"
#include "emulator/daemon/rig.hpp"
#include "emulator/daemon/rig_families.hpp"
#include "emulator/transport/link_lock.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <grp.h>
#include <sys/stat.h>
#include <unistd.h>

namespace {

constexpr int kExitRuntimeError = 1;
constexpr int kExitUsage = 2;   // bad flag or bad config

/// Signals whose default action ends the process: each shuts the daemon down cleanly, so
/// that no pty symlink or endpoints file is left behind. SIGHUP has nothing to reload.
constexpr int kShutdownSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM};

/// A file the daemon wrote (--endpoints-json): removed at exit if it is still the one written
/// (through a symlink: the file the link points to, which is what was written).
class OwnedFile {
public:
    explicit OwnedFile(const std::string& path) : path_(rigsim::resolve_symlinks(path))
    {
        struct stat st {};
        if (::lstat(path_.c_str(), &st) == 0) {
            dev_ = st.st_dev;
            ino_ = st.st_ino;
        }
    }
    void remove() const
    {
        struct stat st {};
        if (ino_ != 0 && ::lstat(path_.c_str(), &st) == 0 && st.st_dev == dev_ && st.st_ino == ino_)
            ::unlink(path_.c_str());
    }

private:
    std::string path_;
    dev_t dev_ = 0;
    ino_t ino_ = 0;
};

constexpr std::string_view kUsage = R"(Usage: rigsimd [OPTION]...
Emulate SmarAct MCS and MCS2 and Thorlabs APT motion controllers on pseudo-terminals and
TCP sockets. Without --config, runs the built-in default rig (config/default.json), with
its control API on 127.0.0.1:40200 (where rigsimctl looks by default).

  --config FILE          run the rig described in FILE (JSON, see docs/config.md)
  --check-config FILE    validate FILE and exit: 0 if valid, 2 with a message naming the
                         JSON pointer if not
  --endpoints-json FILE  once every endpoint listens, write FILE (atomically) with
                         {"devices":[{"name","protocol","model","tcp","pty"}]} ("rfc2217"
                         too for a device that has one), and "control":
                         "http://HOST:PORT" when the control API is on
  --pty-dir DIR          put each device's pty symlink at DIR/<name> unless the config
                         names a path (default /tmp/rigsim; created if missing); a
                         link's directory must be this user's or root's, writable by
                         no one else unless sticky (exit 2 otherwise)
  --pty-group GROUP      give each device's pty to GROUP (a name or number), mode 0660,
                         so that its members open it as they open a serial port (e.g.
                         dialout); this user must be root or a member of GROUP
  --replace-links        take over pty symlinks that a running rigsimd holds (it runs on
                         without them); without it such a link stops start-up (exit 2).
                         Links left by a daemon that died are replaced either way
  --ephemeral-ports      give every TCP endpoint an ephemeral port (ignore tcp_port and
                         rfc2217_port)
  --rfc2217              give every device an RFC 2217 endpoint (a serial port over TCP,
                         pyserial's rfc2217://HOST:PORT), on its rfc2217_port or an
                         ephemeral one; listed in --endpoints-json as "rfc2217"
  --bind ADDR            listen for TCP on ADDR (default 127.0.0.1)
  --control ADDR:PORT    serve the HTTP control API (docs/control-api.md) on ADDR:PORT;
                         ADDR an IP address ([::1] for IPv6), PORT 0 picks a free port;
                         wins over the config's "control" (default: off unless the
                         config has "control", then on 127.0.0.1; the default rig's
                         is port 40200); a device's tcp_port is refused (exit 2)
  --control-token TOKEN  the control API takes only requests carrying the header
                         "Authorization: Bearer TOKEN" (401 otherwise); TOKEN printable
                         ASCII without spaces, at most 1024 characters
  --control-token-file FILE
                         the same, the token being FILE's first line (FILE at most 4 KiB;
                         keeps the token out of the process list)
  --control-allow-host NAME
                         a Host header the control API accepts besides IP addresses and
                         localhost (may be repeated); any other name is refused (403),
                         as are cross-origin requests and bodies that are not JSON
  --max-connections N    TCP connections open at once, all devices together; more are
                         accepted and closed at once (1..65536; default 256)
  --max-connections-per-device N
                         TCP connections open at once on one device (1..65536;
                         default 32)
  --time-scale X         run the physics X times faster than wall time (0.001..1000;
                         default: the config's clock.time_scale, else 1)
  --paused               start with the clock paused (also the config's clock.paused):
                         devices answer, nothing moves until the control API resumes or
                         steps the clock
  --tick-hz N            physics tick rate in Hz, overriding the config's tick_hz
                         (1..100000; default 1000)
  --state-file FILE      keep what devices save in non-volatile memory (APT
                         MOT_SET_EEPROMPARAMS) in FILE across restarts; without it, saves
                         last until the daemon exits. A FILE that cannot be read stops
                         start-up; a symlink is written through; a FILE with damaged
                         entries is kept as FILE.damaged at the next save. Saves are
                         written behind: kill -9 may lose the last milliseconds' saves
  --state-sync           with --state-file: a save is on disk (fsync) before the device
                         goes on, so no save a client made is lost, even to kill -9
  --log-level LEVEL      trace, debug, info, warn, error, critical or off (default info);
  --log-level NAME=LEVEL   the level of one logger: a device name, or rigsimd
                         (may be repeated)
  --help                 show this help and exit
  --version              show the version and exit

Logs go to standard error (repeated warnings about one connection are rate-limited:
at most 10 per second, then a count); the endpoint list goes to standard output.
SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2 and SIGALRM shut down cleanly: the
pty symlinks and the --endpoints-json file are removed (SIGHUP reloads nothing).
Exit status: 0 on success or after a signal, 1 on a run-time failure (e.g. a port in
use), 2 on a bad flag or config, or on a pty link that a running rigsimd holds.
)";

/// Where the control API listens.
struct ControlListen {
    boost::asio::ip::address address = boost::asio::ip::make_address("127.0.0.1");
    std::uint16_t port = 0;
};

struct Options {
    std::optional<ControlListen> control;   ///< --control
    rigsim::control::HttpAccess control_access;   ///< --control-token(-file), --control-allow-host
    std::optional<std::string> config;
    std::optional<std::string> check_config;
    std::optional<std::string> endpoints_json;
    std::optional<std::uint32_t> tick_hz;
    std::optional<double> time_scale;   ///< --time-scale
    bool replace_links = false;         ///< --replace-links
    rigsim::RigOptions rig;
};

struct UsageError {
    std::string message;
};

/// A user's value in a message: quoted, and cut to a sane length.
std::string echo(std::string_view value)
{
    constexpr std::size_t kMax = 64;
    if (value.size() <= kMax)
        return "\"" + std::string(value) + "\"";
    return "\"" + std::string(value.substr(0, kMax)) + "\"... (" + std::to_string(value.size()) + " characters)";
}

/// A bound as the help text writes it (0.001, 1000).
std::string number_text(double v)
{
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", v);
    return buffer;
}

double parse_double(std::string_view flag, const std::string& value, double lo, double hi)
{
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi)
        throw UsageError{std::string(flag) + ": expected a number " + number_text(lo) + ".." + number_text(hi)
                         + ", got " + echo(value)};
    return v;
}

std::uint32_t parse_uint(std::string_view flag, const std::string& value, std::uint32_t lo, std::uint32_t hi)
{
    char* end = nullptr;
    const unsigned long long v = std::strtoull(value.c_str(), &end, 10);
    if (value.empty() || value[0] == '-' || *end != '\0' || v < lo || v > hi)
        throw UsageError{std::string(flag) + ": expected an integer " + std::to_string(lo) + ".."
                         + std::to_string(hi) + ", got " + echo(value)};
    return static_cast<std::uint32_t>(v);
}

/// "ADDR:PORT" (IPv6: "[ADDR]:PORT"): an IP literal, no host name, and a port 0..65535.
ControlListen parse_control(const std::string& value)
{
    const UsageError bad{"--control: expected ADDR:PORT with an IP address (e.g. 127.0.0.1:0), got " + echo(value)};
    const auto colon = value.rfind(':');
    if (colon == std::string::npos)
        throw bad;
    std::string host = value.substr(0, colon);
    if (host.size() >= 2 && host.front() == '[' && host.back() == ']')
        host = host.substr(1, host.size() - 2);
    else if (host.find(':') != std::string::npos)
        throw bad;   // an IPv6 address needs brackets, or its last group reads as the port
    boost::system::error_code ec;
    ControlListen listen;
    listen.address = boost::asio::ip::make_address(host, ec);
    if (ec)
        throw bad;
    listen.port = static_cast<std::uint16_t>(parse_uint("--control", value.substr(colon + 1), 0, 65535));
    return listen;
}

/// --control-token TOKEN or --control-token-file FILE: one of them, once.
void set_control_token(const std::string& flag, const std::string& value, rigsim::control::HttpAccess& access)
{
    if (!access.token.empty())
        throw UsageError{flag + ": the control token is already given (--control-token or --control-token-file, once)"};
    if (flag == "--control-token-file") {
        try {
            access.token = rigsim::control::read_token_file(value);
        } catch (const std::runtime_error& e) {
            throw UsageError{e.what()};
        }
        return;
    }
    if (auto why = rigsim::control::bad_token(value))
        throw UsageError{flag + ": " + *why};
    access.token = value;
}

/// --pty-group GROUP: a group name or number that this process may give its ptys to (root, or a
/// member of it: fchown allows no other).
long parse_pty_group(const std::string& v)
{
    const std::string flag = "--pty-group";
    if (v.empty())
        throw UsageError{flag + ": expected a group name or number, got \"\""};
    gid_t gid = 0;
    std::string shown = v;
    if (v.find_first_not_of("0123456789") == std::string::npos) {
        if (v.size() > 9)
            throw UsageError{flag + ": expected a group name or number, got " + echo(v)};
        gid = static_cast<gid_t>(std::stoul(v));
    } else {
        // A group with many members (a directory service's) needs a larger buffer: ERANGE, retried
        // up to 16 MiB.
        std::vector<char> buffer(16384);
        struct group entry {};
        struct group* found = nullptr;
        int err = 0;
        while ((err = ::getgrnam_r(v.c_str(), &entry, buffer.data(), buffer.size(), &found)) == ERANGE
               && buffer.size() < (std::size_t{16} << 20))
            buffer.resize(buffer.size() * 4);
        if (err != 0)
            throw UsageError{flag + ": cannot look up group " + echo(v) + ": " + std::strerror(err)};
        if (found == nullptr)
            throw UsageError{flag + ": no group " + echo(v) + " on this system"};
        gid = found->gr_gid;
        shown = v + " (" + std::to_string(gid) + ")";
    }
    if (::geteuid() != 0 && ::getegid() != gid) {
        std::vector<gid_t> groups(static_cast<std::size_t>(std::max(::getgroups(0, nullptr), 0)) + 1);
        const int n = ::getgroups(static_cast<int>(groups.size()), groups.data());
        if (std::find(groups.begin(), groups.begin() + std::max(n, 0), gid) == groups.begin() + std::max(n, 0))
            throw UsageError{flag + ": this user is not a member of group " + shown
                             + ", so it cannot give its ptys to it (add it to the group, or run as a member)"};
    }
    return static_cast<long>(gid);
}

/// One option of the command line other than --help and --version; `value` takes its value,
/// `no_value` refuses one.
template <class Value, class NoValue>
void parse_option(const std::string& arg, Value& value, NoValue& no_value, Options& o)
{
    if (arg == "--config")
        o.config = value();
    else if (arg == "--check-config")
        o.check_config = value();
    else if (arg == "--endpoints-json")
        o.endpoints_json = value();
    else if (arg == "--pty-dir") {
        o.rig.pty_dir = value();
        if (o.rig.pty_dir.empty())
            throw UsageError{"--pty-dir: expected a directory, got \"\""};
        while (o.rig.pty_dir.size() > 1 && o.rig.pty_dir.back() == '/')
            o.rig.pty_dir.pop_back();
    } else if (arg == "--pty-group") {
        o.rig.pty_group = parse_pty_group(value());
    } else if (arg == "--replace-links") {
        no_value();
        o.replace_links = true;
    } else if (arg == "--ephemeral-ports") {
        no_value();
        o.rig.ephemeral_ports = true;
    } else if (arg == "--rfc2217") {
        no_value();
        o.rig.rfc2217 = true;
    } else if (arg == "--bind") {
        const auto v = value();
        boost::system::error_code ec;
        o.rig.bind = boost::asio::ip::make_address(v, ec);
        if (ec)
            throw UsageError{"--bind: expected an IP address, got " + echo(v)};
    } else if (arg == "--control")
        o.control = parse_control(value());
    else if (arg == "--control-token" || arg == "--control-token-file")
        set_control_token(arg, value(), o.control_access);
    else if (arg == "--control-allow-host") {
        const auto v = value();
        const auto name = rigsim::control::host_name_of(v);
        if (!name || v.find(':') != std::string::npos)
            throw UsageError{"--control-allow-host: expected a host name without a port, got " + echo(v)};
        o.control_access.allowed_hosts.push_back(*name);
    }
    else if (arg == "--max-connections")
        o.rig.max_connections = parse_uint(arg, value(), 1, 65536);
    else if (arg == "--max-connections-per-device")
        o.rig.max_connections_per_device = parse_uint(arg, value(), 1, 65536);
    else if (arg == "--time-scale")
        o.time_scale = parse_double(arg, value(), 0.001, 1000);
    else if (arg == "--paused") {
        no_value();
        o.rig.paused = true;
    }
    else if (arg == "--state-sync") {
        no_value();
        o.rig.state_sync = true;
    } else if (arg == "--state-file") {
        o.rig.state_file = value();
        if (o.rig.state_file.empty())
            throw UsageError{"--state-file: expected a file name, got \"\""};
    } else if (arg == "--tick-hz")
        o.tick_hz = parse_uint(arg, value(), 1, 100000);
    else if (arg == "--log-level") {
        if (auto err = rigsim::apply_log_level(value(), o.rig.log_levels))
            throw UsageError{*err};
    } else
        throw UsageError{"unknown option " + echo(arg) + " (see --help)"};
}

/// Parses argv; returns nullopt when --help or --version has been answered.
std::optional<Options> parse_args(int argc, char** argv)
{
    Options o;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        std::optional<std::string> inline_value;
        if (arg.rfind("--", 0) == 0) {
            if (const auto eq = arg.find('='); eq != std::string::npos) {
                inline_value = arg.substr(eq + 1);
                arg.resize(eq);
            }
        }
        auto value = [&]() -> std::string {
            if (inline_value)
                return *inline_value;
            if (i + 1 >= argc)
                throw UsageError{arg + ": missing value"};
            return argv[++i];
        };
        auto no_value = [&] {
            if (inline_value)
                throw UsageError{arg + ": takes no value"};
        };
        if (arg == "--help" || arg == "-h") {
            no_value();
            std::cout << kUsage;
            return std::nullopt;
        }
        if (arg == "--version") {
            no_value();
            std::cout << "rigsimd " RIGSIM_VERSION "\n";
            return std::nullopt;
        }
        parse_option(arg, value, no_value, o);
    }
    if (o.config && o.check_config)
        throw UsageError{"--config and --check-config exclude each other"};
    if (o.rig.state_sync && o.rig.state_file.empty())
        throw UsageError{"--state-sync: needs --state-file (without a file, saves last until the daemon exits)"};
    return o;
}

/// Locks every device's pty link for the daemon's life (emulator/transport/link_lock.hpp),
/// before anything is built; the exit status if one is a running daemon's (2) or cannot be
/// locked (1).
std::optional<int> lock_pty_links(const rigsim::RigConfig& config, const Options& opts,
                                  std::vector<rigsim::LinkLock>& links)
{
    try {
        for (const auto& d : config.devices) {
            links.emplace_back(d.pty, opts.replace_links);
            if (const auto pid = links.back().replaced_pid())
                rigsim::make_logger("rigsimd", opts.rig.log_levels)
                    ->warn("pty link {} taken over from the running rigsimd pid {} (--replace-links): it runs on "
                           "without it", d.pty, *pid);
        }
    } catch (const rigsim::LinkInUse& e) {
        std::cerr << "rigsimd: " << e.what() << "\n";
        return kExitUsage;
    } catch (const rigsim::UnsafeLinkDir& e) {
        std::cerr << "rigsimd: " << e.what() << "\n";
        return kExitUsage;
    } catch (const std::exception& e) {
        std::cerr << "rigsimd: " << e.what() << "\n";
        return kExitRuntimeError;
    }
    return std::nullopt;
}

/// Where the control API listens, if it is on: --control, else the config's "control" on
/// 127.0.0.1 (port 0 under --ephemeral-ports).
std::optional<ControlListen> control_listen(const rigsim::RigConfig& config, const Options& opts)
{
    if (opts.control)
        return opts.control;
    if (!config.control)
        return std::nullopt;
    ControlListen listen;
    listen.port = opts.rig.ephemeral_ports ? 0 : config.control->port;
    return listen;
}

/// Why --control's port cannot be used: a device of the rig listens on it too (the run would
/// fail to bind one of them).
std::optional<std::string> control_port_clash(const rigsim::RigConfig& config, const Options& opts)
{
    if (!opts.control || opts.control->port == 0 || opts.rig.ephemeral_ports)
        return std::nullopt;
    for (std::size_t i = 0; i < config.devices.size(); ++i) {
        const auto& d = config.devices[i];
        const char* key = d.tcp_port == opts.control->port                ? "tcp_port"
                          : d.rfc2217_port == std::optional<std::uint16_t>(opts.control->port) ? "rfc2217_port"
                                                                                                : nullptr;
        if (key)
            return "--control: port " + std::to_string(opts.control->port) + " is device \"" + d.name + "\"'s " + key
                   + " (/devices/" + std::to_string(i) + "/" + key + "); choose another, or add --ephemeral-ports";
    }
    return std::nullopt;
}

/// The control API on `listen`, started; throws if it cannot listen.
std::unique_ptr<rigsim::control::HttpServer> start_control(boost::asio::io_context& io, rigsim::Rig& rig,
                                                           const ControlListen& listen,
                                                           const rigsim::control::HttpAccess& access,
                                                           std::shared_ptr<spdlog::logger> log)
{
    if (!listen.address.is_loopback())
        log->warn("control API listens on {}, beyond loopback: anyone who reaches it steers the rig{}",
                  rigsim::tcp_address_text(listen.address, listen.port),
                  access.token.empty() ? " (no --control-token is set)" : "");
    auto api = std::make_shared<rigsim::control::ControlApi>(rig);
    auto router = [api](std::string_view method, std::string_view target, std::string_view body) {
        return api->handle(method, target, body);
    };
    std::unique_ptr<rigsim::control::HttpServer> server;
    try {
        server = std::make_unique<rigsim::control::HttpServer>(io, listen.address, listen.port, router, log,
                                                               rigsim::control::HttpServerLimits{}, access);
    } catch (const std::exception& e) {
        throw std::runtime_error("control API: cannot listen on tcp "
                                 + rigsim::tcp_address_text(listen.address, listen.port) + ": " + e.what());
    }
    // A control connection's buffers (a stream's queue) are given back to the system after it goes.
    server->on_connection_closed([&rig] { rig.memory_trim().request(); });
    server->start();
    return server;
}

/// "http://127.0.0.1:PORT": where a client on this machine reaches `server`.
std::string control_url(const rigsim::control::HttpServer& server)
{
    const auto ep = server.local_endpoint();
    return "http://" + rigsim::tcp_address_text(rigsim::client_address(ep.address()), ep.port());
}

/// Runs the rig until a shutdown signal; the exit status.
/// Tell the user where everything listens: one line per device and the control URL on stdout, and
/// the endpoints JSON file (--endpoints-json), which `endpoints_file` then owns (removed at exit).
void announce_endpoints(const rigsim::Rig& rig, const std::string& url, const Options& opts, spdlog::logger& log,
                        std::optional<OwnedFile>& endpoints_file)
{
    for (const auto& e : rig.endpoints())
        std::cout << e.name << " (" << e.protocol << " " << e.model << "): tcp " << e.tcp << " pty " << e.pty << "\n";
    if (!url.empty())
        std::cout << "control: " << url << "\n";
    std::cout.flush();
    if (opts.endpoints_json) {
        for (const auto& stale : rigsim::remove_stale_temporaries(*opts.endpoints_json))
            log.info("removed {}, left by a daemon that was killed while writing it", stale);
        rigsim::write_file_atomically(*opts.endpoints_json, rigsim::endpoints_json(rig.endpoints(), url));
        endpoints_file.emplace(*opts.endpoints_json);
    }
}

/// Runs `io` until it is stopped. A handler that throws costs only the operation it served (its
/// connection, which the unwinding closes): the daemon logs it and goes on serving the others.
void run_loop(boost::asio::io_context& io, spdlog::logger& log)
{
    for (;;) {
        try {
            io.run();
            return;
        } catch (const std::exception& e) {
            log.error("a handler failed and its connection was dropped: {}; serving the others", e.what());
        }
    }
}

int run(const rigsim::RigConfig& config, const Options& opts)
{
    auto log = rigsim::make_logger("rigsimd", opts.rig.log_levels);
    // Summaries of rate-limited warnings appear within a second of their window's end.
    spdlog::flush_every(std::chrono::seconds(1));
    // Ownership order: the io_context outlives the rig, and its pending handlers (which hold
    // connections, which hold sessions on devices) are run to completion before the rig is
    // destroyed, so no session outlives its device. One thread runs it and no other thread hands
    // it work (the state file's writer and spdlog's flusher never touch it): its scheduler and
    // reactor need no locks: 535 fewer instructions per command (bench/README.md, "A repeatable
    // instruction count").
    boost::asio::io_context io(BOOST_ASIO_CONCURRENCY_HINT_UNSAFE);
    boost::asio::signal_set signals(io);
    for (const int signo : kShutdownSignals)
        signals.add(signo);
    std::signal(SIGPIPE, SIG_IGN);
    std::optional<rigsim::Rig> rig;
    std::unique_ptr<rigsim::control::HttpServer> control;
    std::optional<OwnedFile> endpoints_file;
    auto shut_down = [&] {
        if (control)
            control->stop();
        if (rig)
            rig->stop();
        boost::system::error_code ignored;
        signals.cancel(ignored);
        io.restart();
        io.run();   // every operation is cancelled: this runs their handlers, then returns
        control.reset();
        rig.reset();
        if (endpoints_file)
            endpoints_file->remove();
    };
    int status = 0;
    try {
        rig.emplace(io, config, opts.rig);
        signals.async_wait([&](const boost::system::error_code& ec, int signo) {
            if (ec)
                return;
            log->info("signal {} ({}): shutting down", signo, ::strsignal(signo));
            io.stop();
        });

        rig->start();
        std::string url;
        if (const auto listen = control_listen(config, opts)) {
            control = start_control(io, *rig, *listen, opts.control_access, log);
            url = control_url(*control);
            log->info("control API on {}", url);
        }
        announce_endpoints(*rig, url, opts, *log, endpoints_file);
        log->info("rig running: {} device(s), tick {} Hz, time scale {}{}", rig->endpoints().size(),
                  config.tick_hz, opts.rig.time_scale, opts.rig.paused ? ", clock paused" : "");
        run_loop(io, *log);
    } catch (const rigsim::ConfigError& e) {
        // Found once the devices exist (a frame's joint on a channel that cannot drive it).
        log->critical("{}", e.what());
        std::cerr << e.what() << "\n";
        status = kExitUsage;
    } catch (const std::exception& e) {
        log->critical("{}", e.what());
        std::cerr << "rigsimd: " << e.what() << "\n";
        status = kExitRuntimeError;
    }
    try {
        shut_down();
    } catch (const std::exception& e) {
        log->critical("while shutting down: {}", e.what());
        status = kExitRuntimeError;
    }
    rigsim::flush_log_summaries();
    if (status != 0)
        return status;
    log->info("stopped");
    return 0;
}

} // namespace

int main(int argc, char** argv)
{
    std::optional<Options> parsed;
    try {
        parsed = parse_args(argc, argv);
    } catch (const UsageError& e) {
        std::cerr << "rigsimd: " << e.message << "\n";
        return kExitUsage;
    }
    if (!parsed)
        return 0;
    auto& opts = *parsed;

    rigsim::RigConfig config;
    try {
        if (opts.check_config) {
            config = rigsim::load_rig_config(*opts.check_config);
            rigsim::resolve_pty_paths(config, opts.rig.pty_dir, *opts.check_config);
            rigsim::check_rig_devices(config);
            std::cout << *opts.check_config << ": valid\n";
            return 0;
        }
        config = opts.config ? rigsim::load_rig_config(*opts.config) : rigsim::default_rig_config();
        rigsim::resolve_pty_paths(config, opts.rig.pty_dir, opts.config ? *opts.config : "built-in default rig");
    } catch (const rigsim::ConfigError& e) {
        std::cerr << e.what() << "\n";
        return kExitUsage;
    } catch (const std::exception& e) {
        // A check the loader missed, refused deeper down (a model's precondition): still the
        // config's fault, reported as one rather than as a crash.
        const auto& source = opts.check_config ? *opts.check_config : opts.config ? *opts.config : std::string("rig");
        std::cerr << source << ": invalid rig: " << e.what() << "\n";
        return kExitUsage;
    }
    if (const auto clash = control_port_clash(config, opts)) {
        std::cerr << "rigsimd: " << *clash << "\n";
        return kExitUsage;
    }
    if (opts.tick_hz)
        config.tick_hz = *opts.tick_hz;
    opts.rig.time_scale = opts.time_scale.value_or(config.clock.time_scale);
    opts.rig.paused = opts.rig.paused || config.clock.paused;
    std::vector<rigsim::LinkLock> links;   // released after run() has removed the links
    if (const auto status = lock_pty_links(config, opts, links))
        return *status;
    return run(config, opts);
}
