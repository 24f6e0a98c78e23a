#pragma once

#include "unique_fd.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace rigsim::bench {

/// Connects to host:port over TCP with TCP_NODELAY set.
UniqueFd connect_tcp(const std::string& host, std::uint16_t port);

/// Opens a pty slave (or a symlink to one) O_RDWR|O_NOCTTY in raw mode, flushed.
UniqueFd open_pty(const std::string& path);

/// Puts a terminal in raw mode: cfmakeraw, blocking reads of at least one byte.
void make_raw(int fd);

/// Sends `request` on fd, reads up to and including '\n', and checks the bytes
/// against `expected`, `iterations` times; returns each round trip in ns.
/// Throws on I/O errors, end of file, or an unexpected reply.
std::vector<std::int64_t> round_trips(int fd, const std::string& request,
                                      const std::string& expected, int iterations);

/// Median and 99th percentile of a set of round trips.
struct LatencyStats {
    double median_us = 0;
    double p99_us = 0;
};

/// Nearest-rank median and p99 of `samples_ns` (which it sorts).
LatencyStats latency_stats(std::vector<std::int64_t>& samples_ns);

}  // namespace rigsim::bench
