#pragma once
// The control-API side of rigsim_bench_soak (bench/README.md "Soak"): event streams that read
// (or do not), and a hostile API client (slowloris connections, oversized and slow bodies)
// beside an honest one whose requests must still be served. Plain POSIX sockets, one thread
// each, no library of the daemon.

#include "unique_fd.hpp"

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace rigsim::bench {

/// Where the control API listens ("http://127.0.0.1:PORT" of the endpoints file).
struct ApiAddress {
    std::string host;
    std::uint16_t port = 0;
};

/// The "control" URL of an endpoints file; throws if there is none.
ApiAddress parse_control(const std::string& endpoints_json);

/// Sends `method path` with `body` (JSON) on a fresh connection and reads the answer's status;
/// -1 when the connection was refused, closed without an answer or `timeout_ms` passed.
int http_status(const ApiAddress& api, const std::string& method, const std::string& path,
                const std::string& body, int timeout_ms);

/// Event streams (GET /api/events...) opened at construction (each waits for the stream's
/// opening comment: the subscription is live) and closed at destruction. Reading ones are read
/// by a thread of their own; the others are never read (the daemon should drop them).
class EventStreams {
public:
    EventStreams(const ApiAddress& api, const std::vector<std::string>& paths, bool reading);
    ~EventStreams();
    EventStreams(const EventStreams&) = delete;
    EventStreams& operator=(const EventStreams&) = delete;

    /// Bytes read so far (reading streams).
    std::uint64_t bytes() const { return bytes_.load(); }
    /// Streams the daemon has closed (seen without reading: end of stream or reset pending).
    std::size_t closed_by_daemon() const;

private:
    void read_loop();

    std::vector<UniqueFd> fds_;
    std::atomic<std::uint64_t> bytes_{0};
    std::atomic<bool> stop_{false};
    std::thread reader_;
};

/// What the hostile and the honest API clients saw.
struct HostileReport {
    std::uint64_t honest_ok = 0;       ///< honest GET /api/clock answered 200
    std::uint64_t honest_failed = 0;   ///< refused, closed or timed out
    std::vector<double> honest_ms;     ///< each answered request's time
    std::uint64_t slow_opened = 0;     ///< slowloris connections opened
    std::vector<double> slow_closed_after_s;   ///< lifetime of each the daemon closed
    std::uint64_t big_bodies = 0;      ///< oversized bodies sent
    std::uint64_t big_refused = 0;     ///< of which answered 413
    std::uint64_t slow_bodies_closed = 0;   ///< slow-body connections the daemon closed
};

/// The hostile client and, beside it, an honest one, in a thread of their own until stopped:
/// `slow` connections that send a request header one byte every `slow_interval_ms` (reopened
/// when the daemon closes one), optionally oversized bodies (Content-Length 1 MiB: 413) and a
/// body sent one byte a second, and an honest GET /api/clock every `honest_interval_ms`.
class HostileApiClient {
public:
    struct Settings {
        int slow = 64;
        int slow_interval_ms = 1000;
        bool bodies = true;
        int honest_interval_ms = 50;
        int honest_timeout_ms = 2000;
    };
    HostileApiClient(const ApiAddress& api, Settings settings);
    ~HostileApiClient();
    HostileApiClient(const HostileApiClient&) = delete;
    HostileApiClient& operator=(const HostileApiClient&) = delete;

    /// Stops the thread, closes every connection, and returns what it saw.
    HostileReport stop();

private:
    struct Slow;
    void run();
    void tend_slow(std::vector<Slow>& slow, bool body);

    ApiAddress api_;
    Settings settings_;
    HostileReport report_;
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

/// Device clients that send commands and never read their answers, until the daemon drops
/// them: what a hung client costs the daemon's memory (it must be bounded, and given back).
class NonReadingClients {
public:
    /// One client per (host, port, request) entry, each writing `request` over and over.
    struct Target {
        std::string host;
        std::uint16_t port = 0;
        std::string request;
    };
    explicit NonReadingClients(std::vector<Target> targets);
    ~NonReadingClients();
    NonReadingClients(const NonReadingClients&) = delete;
    NonReadingClients& operator=(const NonReadingClients&) = delete;

    /// Clients the daemon has dropped so far.
    std::size_t dropped() const { return dropped_.load(); }
    std::size_t count() const { return count_; }

private:
    void run(std::vector<UniqueFd> fds, std::vector<std::string> requests);

    std::size_t count_;
    std::atomic<std::size_t> dropped_{0};
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

} // namespace rigsim::bench
