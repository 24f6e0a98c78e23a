#pragma once
// The device clients of rigsim_bench_soak (bench/README.md "Soak"): many clients of the rig's
// devices over TCP and the ptys, one command in flight each, driven by one epoll loop. Each
// answer is checked against the command its client sent last (an MCS answer's prefix, an APT
// answer's message id), so that an answer lost, duplicated or delivered to another client is
// counted; clients disconnect at random (TCP: sometimes with an answer unread) and reconnect.

#include "daemon_process.hpp"
#include "unique_fd.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace rigsim::bench {

/// A command a client may send and what its answer starts with: MCS, the answer's first
/// bytes (":P0,"); APT, the answer's message id (2 bytes, little-endian).
struct SoakCommand {
    std::string request;
    std::string expect;
};

/// A device and the commands its clients choose from (each with a distinct answer, so that
/// an answer to another command, or to another client, does not pass).
struct SoakDevice {
    DeviceEndpoints endpoints;
    std::vector<SoakCommand> commands;
};

/// The devices of `endpoints` with their commands: MCS queries and relative moves of its
/// channels; for APT, the requests of a fixed list that the device answers (asked once each).
std::vector<SoakDevice> soak_devices(const std::vector<DeviceEndpoints>& endpoints);

/// Round trips in ns, per transport.
struct RoundTrips {
    std::vector<std::int64_t> tcp;
    std::vector<std::int64_t> pty;
};

struct SoakTotals {
    std::uint64_t answered = 0;    ///< answers that matched their command
    std::uint64_t lost = 0;        ///< commands never answered (10 s), or cut off by the daemon
    std::uint64_t misrouted = 0;   ///< answers to another command (or client), or unasked bytes
    std::uint64_t abandoned = 0;   ///< commands whose client disconnected before the answer
    std::uint64_t reconnects = 0;
    std::uint64_t refused = 0;     ///< connections the daemon closed at once (its limits)
};

class DeviceClients {
public:
    /// A client of `device` (over its pty when `pty`, else TCP).
    struct Spec {
        const SoakDevice* device;
        bool pty;
    };
    /// Opens every client; `disconnect_every`: the mean number of commands between two
    /// disconnects of a client (0: never).
    DeviceClients(std::vector<Spec> specs, std::uint32_t seed, int disconnect_every);
    ~DeviceClients();
    DeviceClients(const DeviceClients&) = delete;
    DeviceClients& operator=(const DeviceClients&) = delete;

    /// Every client sends `commands` more commands, one in flight, each answer checked; the
    /// round trips are appended to `into`; `every_100ms` is called meanwhile (RSS sampling).
    void run_block(int commands, RoundTrips& into, const std::function<void()>& every_100ms);
    /// Closes every client (the daemon sees them go).
    void close_all();
    const SoakTotals& totals() const { return totals_; }

private:
    struct Client;
    void open(Client& c);
    void reopen(Client& c);
    void send_next(Client& c, int goal);
    void on_readable(Client& c, RoundTrips& into, int goal);
    /// Checks the complete answers at the front of c's input; false if the client must reconnect.
    bool take_answers(Client& c, RoundTrips& into);

    std::vector<std::unique_ptr<Client>> clients_;
    UniqueFd epoll_;
    std::mt19937 rng_;
    int disconnect_every_;
    SoakTotals totals_;
};

} // namespace rigsim::bench
