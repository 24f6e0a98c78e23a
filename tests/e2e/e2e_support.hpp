#pragma once
// Helpers for the end-to-end tests: start the real rigsimd in a fresh temp dir (through the
// launcher the benches share, tests/support/rigsimd_process.hpp), find its endpoints, talk MCS
// to it over TCP and over its pty. Standard library and POSIX only, so these tests see the
// daemon exactly as a user does. Nothing here sleeps for a fixed time: every wait polls with a
// deadline.

#include "tests/support/rigsimd_process.hpp"

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <termios.h>

namespace rigsim::e2e {

using launch::Millis;
using launch::SteadyClock;

/// How long a test waits for an answer it expects before calling it lost.
inline constexpr Millis kAnswerTimeout{3000};
/// How long the daemon may take to write its endpoints file (generous for sanitizer builds).
inline constexpr Millis kStartTimeout{15000};
/// How long the daemon may take to exit after SIGTERM/SIGINT.
inline constexpr Millis kShutdownTimeout{5000};

/// Polls `pred` every few ms until it holds (true) or `timeout` passes (false).
using launch::wait_until;

/// Milliseconds elapsed since `start`, as a double for messages and comparisons.
double elapsed_ms(SteadyClock::time_point start);

/// A fresh directory from mkdtemp, removed with its contents on destruction (kept if the
/// environment variable RIGSIM_E2E_KEEP_TMP is set, for post-mortems).
class TempDir : public launch::TempDir {
public:
    TempDir() : launch::TempDir("rigsim-e2e", "RIGSIM_E2E_KEEP_TMP") {}
};

/// Writes `text` to `path` (truncating); throws on failure.
void write_file(const std::string& path, const std::string& text);
/// The whole content of `path`, or nullopt if it cannot be opened.
std::optional<std::string> read_file(const std::string& path);
/// True if `path` exists as any kind of file, dangling symlinks included (lstat).
bool path_exists(const std::string& path);

/// One device entry of the daemon's endpoints file.
struct Endpoint {
    std::string name;
    std::string tcp;      ///< "HOST:PORT" as written by the daemon
    std::string pty;      ///< path of the pty symlink
    std::string host;     ///< host part of `tcp`
    std::uint16_t port{}; ///< port part of `tcp`
};

/// The string value of `key` in a flat JSON object text, or nullopt (minimal extractor:
/// the endpoints file is tiny and has no nesting inside a device entry).
std::optional<std::string> json_string_value(const std::string& object_text,
                                             const std::string& key);
/// The device named `name` in an endpoints file text, or nullopt.
std::optional<Endpoint> find_endpoint(const std::string& endpoints_json,
                                      const std::string& name);

/// How a child process ended, with what it printed.
using launch::ProcessResult;

/// Runs rigsimd with `args` to completion (for --help, --check-config, bad flags) and
/// captures its output; SIGKILLs it after `timeout`.
ProcessResult run_rigsimd(const std::vector<std::string>& args, Millis timeout = Millis{10000});

/// Describes a wait status ("exited 0", "killed by signal 9") for messages.
using launch::describe_wait_status;

/// A running rigsimd in its own temp dir with ephemeral ports, a private pty dir and an
/// endpoints file (launch::RigsimdProcess). RAII: the destructor sends SIGTERM, SIGKILLs after
/// a deadline, reaps.
class Daemon {
public:
    struct Options {
        /// Rig config text; if non-empty it is written to <tmp>/rig.json and passed
        /// with --config.
        std::string config_json;
        /// A config file to pass with --config (ignored if `config_json` is set).
        std::string config_path;
        /// Further flags (e.g. {"--time-scale", "10"}).
        std::vector<std::string> extra_args;
    };
    /// Resource limits the daemon process starts with (setrlimit before exec).
    struct Limits {
        /// If set, RLIMIT_NOFILE (soft and hard).
        std::optional<unsigned long> max_open_files;
    };

    Daemon();
    explicit Daemon(Options options);
    Daemon(Options options, Limits limits);
    Daemon(const Daemon&) = delete;
    Daemon& operator=(const Daemon&) = delete;

    /// The endpoints of device `name` from the endpoints file; throws if absent.
    Endpoint endpoint(const std::string& name = "mcs0") const;
    /// The endpoints file as written by the daemon.
    const std::string& endpoints_json() const { return process_.endpoints_json(); }

    pid_t pid() const { return process_.pid(); }
    const TempDir& dir() const { return dir_; }
    /// Everything the daemon wrote to stderr so far (its log).
    std::string log() const { return process_.log(); }

    /// True while the process has not been reaped and has not exited.
    bool running() { return process_.running(); }
    /// Sends `signal` and waits up to `timeout` for the exit; returns the wait status, or
    /// nullopt if the daemon was still running at the deadline (it is then left running
    /// for the destructor to kill).
    std::optional<int> stop(int signal, Millis timeout = kShutdownTimeout)
    {
        return process_.stop(signal, timeout);
    }

private:
    /// The launch of rigsimd in `dir` (writes the config file and sanitizer settings it needs).
    static launch::LaunchOptions launch_options(const TempDir& dir, const Options& options, const Limits& limits);

    TempDir dir_;   // before process_: the daemon runs in it
    launch::RigsimdProcess process_;
};

/// A line-oriented MCS client over one fd (TCP socket or pty slave). Answers are returned
/// with their trailing '\n' so tests compare whole answers: `":P0,2000000\n"`.
class LineClient {
public:
    LineClient(const LineClient&) = delete;
    LineClient& operator=(const LineClient&) = delete;
    virtual ~LineClient();

    /// Writes all of `bytes`, polling for writability until `timeout`; throws on error or
    /// timeout.
    void send(const std::string& bytes, Millis timeout = Millis{10000});
    /// The next '\n'-terminated line (with its '\n'), or nullopt after `timeout`, end of
    /// stream or a read error.
    std::optional<std::string> read_line(Millis timeout = kAnswerTimeout);
    /// send(cmd) then read_line(); a lost answer comes back as "<no answer to ...>" so a
    /// CHECK against the expected answer fails readably.
    std::string request(const std::string& cmd, Millis timeout = kAnswerTimeout);
    /// Polls until the peer closes the stream (read returns 0 or an error), discarding any
    /// data; true if that happened before `timeout`.
    bool wait_for_eof(Millis timeout);
    /// Closes the fd (idempotent).
    void close();
    bool is_open() const { return fd_ >= 0; }
    int fd() const { return fd_; }

protected:
    LineClient() = default;
    int fd_ = -1;
    bool is_socket_ = false; ///< write with send(MSG_NOSIGNAL) rather than write()

private:
    /// One read of whatever is available within `timeout`: >0 bytes appended, 0 on
    /// timeout, -1 on end of stream or error.
    int fill(Millis timeout);

    std::string buffer_;
};

/// An MCS client on the daemon's TCP endpoint.
class TcpClient : public LineClient {
public:
    /// Connects to `endpoint.host:endpoint.port`; throws on failure.
    explicit TcpClient(const Endpoint& endpoint);
    /// Closes with an RST (SO_LINGER 0) rather than a FIN: an abrupt disconnect.
    void abort();
};

/// An MCS client on the daemon's pty: opens the symlink O_RDWR|O_NOCTTY, raw mode.
class PtyClient : public LineClient {
public:
    /// Opens `path` and sets raw mode at `baud` (a termios speed constant such as B115200).
    explicit PtyClient(const std::string& path, speed_t baud = B115200);
    /// Changes the line speed with tcsetattr (raw mode kept); throws on failure.
    void set_baud(speed_t baud);
    /// The input and output speed currently set on the line.
    speed_t baud() const;
};

/// Polls `:GS<channel>` until the answer is `:S<channel>,<state>`; true if that happened
/// within `timeout`. Every answer received is appended to `seen` if given.
bool poll_status_until(LineClient& client, int channel, int state, Millis timeout,
                       std::vector<std::string>* seen = nullptr);

/// The targets of the descriptors `pid` has open (readlink of /proc/<pid>/fd/*), such as
/// "anon_inode:inotify", "socket:[1234]", "/dev/pts/3".
std::vector<std::string> open_fds(pid_t pid);

/// Occurrences of `needle` in `text` (log lines, answers).
std::size_t count_of(const std::string& text, const std::string& needle);

/// A file of the e2e fixture directory (tests/e2e/<name>).
std::string fixture(const std::string& name);

} // namespace rigsim::e2e
