#include "roundtrip.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace rigsim::bench {

std::string errno_message(const std::string& what)
{
    return what + ": " + std::strerror(errno);
}

UniqueFd connect_tcp(const std::string& host, std::uint16_t port)
{
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(port);
    if (::inet_pton(AF_INET, host.c_str(), &addr.sin_addr) != 1)
        throw std::runtime_error("not an IPv4 address: " + host);

    UniqueFd fd{::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0)};
    if (fd.get() < 0)
        throw std::runtime_error(errno_message("socket"));
    const int one = 1;
    if (::setsockopt(fd.get(), IPPROTO_TCP, TCP_NODELAY, &one, sizeof one) < 0)
        throw std::runtime_error(errno_message("setsockopt TCP_NODELAY"));
    if (::connect(fd.get(), reinterpret_cast<const sockaddr*>(&addr), sizeof addr) < 0)
        throw std::runtime_error(errno_message("connect " + host + ":" + std::to_string(port)));
    return fd;
}

void make_raw(int fd)
{
    termios tio{};
    if (::tcgetattr(fd, &tio) < 0)
        throw std::runtime_error(errno_message("tcgetattr"));
    ::cfmakeraw(&tio);
    tio.c_cc[VMIN] = 1;
    tio.c_cc[VTIME] = 0;
    if (::tcsetattr(fd, TCSANOW, &tio) < 0)
        throw std::runtime_error(errno_message("tcsetattr"));
}

UniqueFd open_pty(const std::string& path)
{
    UniqueFd fd{::open(path.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC)};
    if (fd.get() < 0)
        throw std::runtime_error(errno_message("open " + path));
    make_raw(fd.get());
    ::tcflush(fd.get(), TCIOFLUSH);
    return fd;
}

namespace {

void write_all(int fd, const char* data, std::size_t size)
{
    while (size > 0) {
        const ssize_t n = ::write(fd, data, size);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            throw std::runtime_error(errno_message("write"));
        }
        data += n;
        size -= static_cast<std::size_t>(n);
    }
}

/// Reads until a '\n' arrives; returns the byte count (the '\n' is the last byte
/// unless the peer sent more, which the caller's comparison then rejects).
std::size_t read_line(int fd, char* buffer, std::size_t capacity)
{
    std::size_t used = 0;
    for (;;) {
        if (used == capacity)
            throw std::runtime_error("reply longer than " + std::to_string(capacity) +
                                     " bytes without '\\n'");
        const ssize_t n = ::read(fd, buffer + used, capacity - used);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            throw std::runtime_error(errno_message("read"));
        }
        if (n == 0)
            throw std::runtime_error("peer closed the connection");
        const bool complete = std::memchr(buffer + used, '\n', static_cast<std::size_t>(n));
        used += static_cast<std::size_t>(n);
        if (complete)
            return used;
    }
}

std::string printable(const char* data, std::size_t size)
{
    std::string out;
    for (std::size_t i = 0; i < size; ++i) {
        const char c = data[i];
        if (c == '\n')
            out += "\\n";
        else if (c == '\r')
            out += "\\r";
        else if (c < 0x20 || c > 0x7e) {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02x", static_cast<unsigned char>(c));
            out += hex;
        } else
            out += c;
    }
    return out;
}

}  // namespace

std::vector<std::int64_t> round_trips(int fd, const std::string& request,
                                      const std::string& expected, int iterations)
{
    using Clock = std::chrono::steady_clock;
    std::vector<std::int64_t> samples_ns;
    samples_ns.reserve(static_cast<std::size_t>(std::max(iterations, 0)));
    char buffer[256];
    for (int i = 0; i < iterations; ++i) {
        const auto start = Clock::now();
        write_all(fd, request.data(), request.size());
        const std::size_t n = read_line(fd, buffer, sizeof buffer);
        const auto stop = Clock::now();
        if (n != expected.size() || std::memcmp(buffer, expected.data(), n) != 0)
            throw std::runtime_error("sent \"" + printable(request.data(), request.size()) +
                                     "\", expected \"" +
                                     printable(expected.data(), expected.size()) +
                                     "\", got \"" + printable(buffer, n) + "\"");
        samples_ns.push_back(
            std::chrono::duration_cast<std::chrono::nanoseconds>(stop - start).count());
    }
    return samples_ns;
}

LatencyStats latency_stats(std::vector<std::int64_t>& samples_ns)
{
    if (samples_ns.empty())
        return {};
    std::sort(samples_ns.begin(), samples_ns.end());
    // Nearest rank: the smallest sample with at least p% of samples at or below it.
    const auto rank = [&](double p) {
        const auto n = samples_ns.size();
        auto r = static_cast<std::size_t>(std::ceil(p * static_cast<double>(n)));
        return samples_ns[std::clamp<std::size_t>(r, 1, n) - 1];
    };
    return {rank(0.50) / 1e3, rank(0.99) / 1e3};
}

}  // namespace rigsim::bench
