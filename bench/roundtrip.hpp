#pragma once

#include "unique_fd.hpp"

#include <cstddef>
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

/// How the client finds the end of a reply.
enum class ReplyEnd {
    /// MCS: the reply ends at the first '\n'.
    Newline,
    /// APT: the reply is a frame of a known length (the header gives it).
    Length,
};

/// One request and the exact reply a correct server gives to it.
struct Exchange {
    std::string request;
    std::string reply;
    ReplyEnd end = ReplyEnd::Newline;
};

/// Sends the request on fd, reads one reply (up to '\n', or reply.size() bytes)
/// and checks its bytes, `iterations` times; returns each round trip in ns.
/// Throws on I/O errors, end of file, or an unexpected reply.
std::vector<std::int64_t> round_trips(int fd, const Exchange& exchange, int iterations);

/// Sends `request` once and returns the `size` bytes that come back, unchecked:
/// for a reply whose variable part must be learnt before it can be checked.
std::string request_fixed_length(int fd, const std::string& request, std::size_t size);

/// `data` as text for a message: escaped text for Newline, hex bytes for Length.
std::string printable(const std::string& data, ReplyEnd end);

/// Median and 99th percentile of a set of round trips.
struct LatencyStats {
    double median_us = 0;
    double p99_us = 0;
};

/// Nearest-rank median and p99 of `samples_ns` (which it sorts).
LatencyStats latency_stats(std::vector<std::int64_t>& samples_ns);

}  // namespace rigsim::bench
