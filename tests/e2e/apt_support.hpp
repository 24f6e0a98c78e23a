#pragma once
// APT frames for the e2e tests: build requests, read whole frames (header, then the data
// packet if the data flag is set) from an fd with a deadline.
#include "e2e_support.hpp"

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <optional>
#include <string>

namespace rigsim::e2e {

using namespace std::chrono_literals;

struct AptFrame {
    std::uint16_t id = 0;
    std::string data;   ///< empty for header-only frames
};

inline std::string header(std::uint16_t id, std::uint8_t p1, std::uint8_t p2)
{
    return {static_cast<char>(id & 0xff), static_cast<char>(id >> 8), static_cast<char>(p1),
            static_cast<char>(p2), '\x50', '\x01'};
}

inline std::string with_data(std::uint16_t id, const std::string& data)
{
    std::string h{static_cast<char>(id & 0xff), static_cast<char>(id >> 8),
                  static_cast<char>(data.size() & 0xff), static_cast<char>(data.size() >> 8),
                  static_cast<char>(0x50 | 0x80), '\x01'};
    return h + data;
}

inline std::string le32(std::int32_t v)
{
    const auto u = static_cast<std::uint32_t>(v);
    return {static_cast<char>(u), static_cast<char>(u >> 8), static_cast<char>(u >> 16), static_cast<char>(u >> 24)};
}

inline std::int32_t get32(const std::string& s, std::size_t at)
{
    return static_cast<std::int32_t>(static_cast<std::uint8_t>(s[at]) | static_cast<std::uint8_t>(s[at + 1]) << 8
                                     | static_cast<std::uint8_t>(s[at + 2]) << 16
                                     | static_cast<std::uint32_t>(static_cast<std::uint8_t>(s[at + 3])) << 24);
}

/// Reads exactly n bytes from fd within the deadline (polling, no fixed sleep).
inline bool read_exact(int fd, std::string& out, std::size_t n, Millis timeout)
{
    const auto deadline = SteadyClock::now() + timeout;
    while (out.size() < n) {
        const auto left = std::chrono::duration_cast<Millis>(deadline - SteadyClock::now()).count();
        if (left <= 0)
            return false;
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, static_cast<int>(left)) <= 0)
            continue;
        char buf[512];
        const auto got = ::read(fd, buf, std::min(sizeof buf, n - out.size()));
        // A non-blocking pty may answer EAGAIN although poll() saw input (the bytes still on
        // their way through the line discipline): wait again, as for no input at all.
        if (got < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR))
            continue;
        if (got <= 0)
            return false;
        out.append(buf, static_cast<std::size_t>(got));
    }
    return true;
}

/// The next whole frame: a 6-byte header, then the data packet if the data flag is set.
inline std::optional<AptFrame> read_frame(int fd, Millis timeout = 5000ms)
{
    std::string h;
    if (!read_exact(fd, h, 6, timeout))
        return std::nullopt;
    AptFrame f;
    f.id = static_cast<std::uint16_t>(static_cast<std::uint8_t>(h[0]) | static_cast<std::uint8_t>(h[1]) << 8);
    if (static_cast<std::uint8_t>(h[4]) & 0x80) {
        const std::size_t len = static_cast<std::uint8_t>(h[2]) | static_cast<std::uint8_t>(h[3]) << 8;
        if (!read_exact(fd, f.data, len, timeout))
            return std::nullopt;
    }
    return f;
}

/// Frames until one with `id` arrives (status updates may come in between).
inline std::optional<AptFrame> wait_for(int fd, std::uint16_t id, Millis timeout = 10'000ms)
{
    const auto deadline = SteadyClock::now() + timeout;
    while (SteadyClock::now() < deadline) {
        auto f = read_frame(fd, std::chrono::duration_cast<Millis>(deadline - SteadyClock::now()));
        if (!f)
            return std::nullopt;
        if (f->id == id)
            return f;
    }
    return std::nullopt;
}

} // namespace rigsim::e2e
