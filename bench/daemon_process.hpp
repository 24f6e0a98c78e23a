#pragma once

#include "tests/support/rigsimd_process.hpp"

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rigsim::bench {

/// Where one device of the rig listens, from the endpoints file.
struct DeviceEndpoints {
    std::string name;
    /// "mcs" or "apt".
    std::string protocol;
    std::string model;
    std::string tcp_host;
    std::uint16_t tcp_port = 0;
    std::string pty_path;
};

/// Parses the endpoints file, {"devices":[{"name","protocol","model","tcp","pty"}]} with
/// "tcp" as "HOST:PORT"; throws std::runtime_error saying what is missing or malformed.
std::vector<DeviceEndpoints> parse_endpoints(const std::string& json);

/// rigsimd started on ephemeral ports in a fresh temporary directory, by the launcher the e2e
/// tests share (tests/support/rigsimd_process.hpp), its devices read from its endpoints file.
class DaemonProcess {
public:
    /// Starts `path`, pinned to `cpu` if given, with `extra_args` after its own (e.g.
    /// `--config FILE`), and waits (polling, up to `timeout`) for its endpoints file.
    DaemonProcess(const std::string& path, std::optional<int> cpu,
                  std::chrono::milliseconds timeout, std::vector<std::string> extra_args = {});
    DaemonProcess(const DaemonProcess&) = delete;
    DaemonProcess& operator=(const DaemonProcess&) = delete;

    /// The daemon's process id (-1 once it has been reaped).
    pid_t pid() const { return process_.wait_status() ? -1 : process_.pid(); }
    /// Where each of the daemon's devices listens, in the order of the endpoints file.
    const std::vector<DeviceEndpoints>& devices() const { return devices_; }
    /// The device called `name` speaking `protocol`; throws if the rig has none.
    const DeviceEndpoints& device(const std::string& name, const std::string& protocol) const;
    /// The endpoints file as the daemon wrote it (its "control" URL, if the API is on).
    const std::string& endpoints_json() const { return process_.endpoints_json(); }

    /// Sends SIGTERM and waits up to `timeout` for the exit; throws if it does not
    /// exit in time (then kills it) or exits with a failure status.
    void terminate(std::chrono::milliseconds timeout);

private:
    /// Removed with what it holds when the benchmark is done with the daemon.
    launch::TempDir dir_;
    /// Killed (SIGKILL) on destruction if still running.
    launch::RigsimdProcess process_;
    std::vector<DeviceEndpoints> devices_;
};

}  // namespace rigsim::bench
