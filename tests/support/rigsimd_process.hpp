#pragma once
// Starting the real rigsimd as a user's harness does: fork/exec with --ephemeral-ports, its ptys
// and its endpoints file in a directory of its own, a poll (with a deadline, never a fixed
// sleep) until the endpoints file is there, then SIGTERM, and SIGKILL after a deadline.
//
// The one launcher of the C++ e2e tests (tests/e2e/e2e_support.hpp: Daemon) and the benches of
// the whole daemon (bench/daemon_process.hpp: DaemonProcess); each reads the endpoints file its
// own way. It lives with the tests' shared code and is built whenever the tests or the benches
// are (its own library, rigsim_launcher, tests/support/CMakeLists.txt), since the sanitizer
// pass builds the e2e tests without the benches. It uses the C++ standard library and POSIX
// only: the e2e tests link no library of the daemon, so that they see it exactly as a user does.

#include <sys/types.h>

#include <chrono>
#include <csignal>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rigsim::launch {

using SteadyClock = std::chrono::steady_clock;
using Millis = std::chrono::milliseconds;

/// Polls `pred` every few ms until it holds (true) or `timeout` passes (false).
bool wait_until(const std::function<bool()>& pred, Millis timeout);

/// Describes a wait status ("exited 0", "killed by signal 9") for messages.
std::string describe_wait_status(int status);

/// A fresh directory from mkdtemp (<$TMPDIR or /tmp>/<prefix>-XXXXXX), removed with its
/// contents on destruction, unless the environment variable `keep_variable` (if given) is set:
/// then kept for post-mortems.
class TempDir {
public:
    explicit TempDir(const std::string& prefix, const char* keep_variable = nullptr);
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::string& path() const { return path_; }
    /// `path()/name`.
    std::string file(const std::string& name) const { return path_ + "/" + name; }

private:
    std::string path_;
    const char* keep_variable_;
};

/// How a child process ended, with what it printed.
struct ProcessResult {
    bool exited = false;     ///< exited normally (not killed by a signal or by us)
    int exit_code = -1;      ///< valid if `exited`
    bool timed_out = false;  ///< we had to SIGKILL it
    std::string out;         ///< stdout
    std::string err;         ///< stderr
};

/// Runs `argv` (argv[0] the binary: rigsimd for --help, --check-config, bad flags) to completion
/// and captures its output; SIGKILLs it after `timeout`.
ProcessResult run_to_completion(const std::vector<std::string>& argv, Millis timeout);

/// How to start rigsimd.
struct LaunchOptions {
    /// Where its output goes.
    enum class Output {
        /// stdout to <dir>/stdout.log, stderr (its log) to <dir>/rigsimd.log: log() reads it.
        Files,
        /// Both to this process's stderr (a bench keeps its stdout for its figures).
        Stderr,
    };

    std::string binary;   ///< the rigsimd to run
    /// The directory it runs in: --pty-dir, and the endpoints file <dir>/endpoints.json. It must
    /// exist and outlive the process (a TempDir declared before the RigsimdProcess).
    std::string dir;
    /// Flags after --ephemeral-ports --pty-dir DIR --endpoints-json DIR/endpoints.json.
    std::vector<std::string> args;
    Output output = Output::Files;
    /// How long the daemon may take to write its endpoints file.
    Millis start_timeout{15000};
    /// How long the destructor waits after SIGTERM before SIGKILL; zero: SIGKILL at once.
    Millis stop_timeout{5000};
    /// What the daemon gets when this process dies (PR_SET_PDEATHSIG).
    int parent_death_signal = SIGKILL;
    /// Pinned to this CPU (every thread of the daemon: set before exec).
    std::optional<int> cpu;
    /// RLIMIT_NOFILE (soft and hard), if set.
    std::optional<unsigned long> max_open_files;
    /// "NAME=value" entries added to this process's environment (replacing NAME's value).
    std::vector<std::string> environment;
};

/// A running rigsimd. The constructor starts it and waits for its endpoints file (throws
/// std::runtime_error saying why not, with the daemon's log when it went to a file); the
/// destructor stops it if it still runs (SIGTERM, SIGKILL after `stop_timeout`) and reaps it.
class RigsimdProcess {
public:
    explicit RigsimdProcess(LaunchOptions options);
    ~RigsimdProcess();
    RigsimdProcess(const RigsimdProcess&) = delete;
    RigsimdProcess& operator=(const RigsimdProcess&) = delete;

    pid_t pid() const { return pid_; }
    /// The endpoints file as the daemon wrote it, and where.
    const std::string& endpoints_json() const { return endpoints_json_; }
    std::string endpoints_path() const { return options_.dir + "/endpoints.json"; }
    /// Everything the daemon wrote to stderr so far ("<no log>" if none, or it went to ours).
    std::string log() const;

    /// True while the process has not been reaped and has not exited.
    bool running();
    /// The wait status once the process has been reaped (-1 if another waiter reaped it).
    const std::optional<int>& wait_status() const { return wait_status_; }
    /// Sends `signal` (if it still runs) and waits up to `timeout` for the exit; returns the wait
    /// status, or nullopt if the daemon was still running at the deadline (it is left running).
    std::optional<int> stop(int signal, Millis timeout);
    /// SIGKILL (if it still runs) and reap.
    void kill();

private:
    void start();
    void wait_for_endpoints();
    /// waitpid(WNOHANG); records the status when the child has ended.
    bool reap_nohang();

    LaunchOptions options_;
    pid_t pid_ = -1;
    std::optional<int> wait_status_;
    std::string endpoints_json_;
};

} // namespace rigsim::launch
