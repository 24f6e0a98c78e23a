#pragma once

#include "unique_fd.hpp"

#include <sys/types.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <thread>

namespace rigsim::bench {

/*
 * The floor: the cheapest server possible on each transport, so that the
 * daemon's round trip can be read as a ratio over what the kernel alone costs.
 * Each is one thread doing blocking read-then-write-back, no event loop.
 */

/// What the floor answers: each request of `request_bytes` gets `reply_bytes` back,
/// the request repeated to fill them. A fair floor has the sizes of the real
/// exchange: for APT MGMSG_MOT_REQ_POSCOUNTER, 6 bytes in and 12 out.
struct EchoShape {
    std::size_t request_bytes = 1;
    std::size_t reply_bytes = 1;
};

/// The reply an echo server of `reply_bytes` gives to `request`.
std::string echo_reply(const std::string& request, std::size_t reply_bytes);

/// Echoes what one TCP client sends, in `shape`; listens on 127.0.0.1, ephemeral port.
class TcpEchoServer {
public:
    /// Starts listening and the echo thread, pinned to `cpu` if given.
    TcpEchoServer(EchoShape shape, std::optional<int> cpu);
    ~TcpEchoServer();
    TcpEchoServer(const TcpEchoServer&) = delete;
    TcpEchoServer& operator=(const TcpEchoServer&) = delete;

    /// The port it listens on.
    std::uint16_t port() const { return port_; }
    /// The echo thread's id, for its CPU time in /proc/self/task.
    pid_t thread_id() const { return thread_id_; }

private:
    void run();

    EchoShape shape_;
    UniqueFd listener_;
    std::uint16_t port_ = 0;
    std::atomic<bool> stopping_{false};
    /// The accepted connection; closed by the destructor after the join.
    std::atomic<int> connection_fd_{-1};
    pid_t thread_id_ = 0;
    std::thread thread_;
};

/// Echoes what is written to a raw pty, in `shape`; clients open slave_path().
class PtyEchoServer {
public:
    /// Opens the pty and starts the echo thread, pinned to `cpu` if given.
    PtyEchoServer(EchoShape shape, std::optional<int> cpu);
    ~PtyEchoServer();
    PtyEchoServer(const PtyEchoServer&) = delete;
    PtyEchoServer& operator=(const PtyEchoServer&) = delete;

    /// The slave device, e.g. /dev/pts/7.
    const std::string& slave_path() const { return slave_path_; }
    /// The echo thread's id, for its CPU time in /proc/self/task.
    pid_t thread_id() const { return thread_id_; }

private:
    void run();

    EchoShape shape_;
    UniqueFd master_;
    /*
     * Held open for the server's lifetime: with no slave open, reads on the
     * master fail with EIO. Also the way to wake the thread on shutdown.
     */
    UniqueFd slave_;
    std::string slave_path_;
    std::atomic<bool> stopping_{false};
    pid_t thread_id_ = 0;
    std::thread thread_;
};

}  // namespace rigsim::bench
