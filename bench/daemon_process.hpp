#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

namespace rigsim::bench {

/// Where the first device of the rig listens, from the endpoints file.
struct Endpoints {
    std::string tcp_host;
    std::uint16_t tcp_port = 0;
    std::string pty_path;
};

/// Extracts the first "tcp" ("HOST:PORT") and "pty" strings; nullopt if either is missing.
std::optional<Endpoints> parse_endpoints(const std::string& json);

/// rigsimd started with fork/exec on ephemeral ports in a fresh temporary directory.
class DaemonProcess {
public:
    /// Starts `path`, pinned to `cpu` if given, and waits (polling, up to `timeout`)
    /// for its endpoints file.
    DaemonProcess(const std::string& path, std::optional<int> cpu,
                  std::chrono::milliseconds timeout);
    /// Kills the daemon if still running and removes the temporary directory.
    ~DaemonProcess();
    DaemonProcess(const DaemonProcess&) = delete;
    DaemonProcess& operator=(const DaemonProcess&) = delete;

    /// The daemon's process id (-1 once it has been reaped).
    pid_t pid() const { return pid_; }
    /// Where the daemon's first device listens.
    const Endpoints& endpoints() const { return endpoints_; }

    /// Sends SIGTERM and waits up to `timeout` for the exit; throws if it does not
    /// exit in time (then kills it) or exits with a failure status.
    void terminate(std::chrono::milliseconds timeout);

private:
    /// Creates the directory, forks, execs and waits for the endpoints file.
    void start(const std::string& path, std::optional<int> cpu,
               std::chrono::milliseconds timeout);
    /// Kills and reaps the daemon if running; removes the temporary directory.
    void clean_up();
    /// Polls waitpid(WNOHANG); true once the child is reaped, with its status.
    bool reaped(int& status);

    std::string temp_dir_;
    pid_t pid_ = -1;
    Endpoints endpoints_;
};

}  // namespace rigsim::bench
