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
/// One read() of up to `size` bytes: retried on EINTR; an error or end of file throws.
std::size_t read_some(int fd, char* buffer, std::size_t size)
{
    for (;;) {
        const ssize_t n = ::read(fd, buffer, size);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            throw std::runtime_error(errno_message("read"));
        if (n == 0)
            throw std::runtime_error("peer closed the connection");
        return static_cast<std::size_t>(n);
    }
}

std::size_t read_line(int fd, char* buffer, std::size_t capacity)
{
    std::size_t used = 0;
    for (;;) {
        if (used == capacity)
            throw std::runtime_error("reply longer than " + std::to_string(capacity) +
                                     " bytes without '\\n'");
        const std::size_t n = read_some(fd, buffer + used, capacity - used);
        const bool complete = std::memchr(buffer + used, '\n', n);
        used += n;
        if (complete)
            return used;
    }
}

/// Reads exactly `size` bytes, never more: a longer reply leaves bytes behind that
/// the next comparison rejects.
void read_exactly(int fd, char* buffer, std::size_t size)
{
    for (std::size_t used = 0; used < size;)
        used += read_some(fd, buffer + used, size - used);
}

constexpr std::size_t kReplyCapacity = 256;

}  // namespace

std::string printable(const std::string& data, ReplyEnd end)
{
    std::string out;
    char hex[8];
    if (end == ReplyEnd::Length) {
        for (std::size_t i = 0; i < data.size(); ++i) {
            std::snprintf(hex, sizeof hex, i == 0 ? "%02x" : " %02x",
                          static_cast<unsigned char>(data[i]));
            out += hex;
        }
        return out;
    }
    for (const char c : data) {
        if (c == '\n')
            out += "\\n";
        else if (c == '\r')
            out += "\\r";
        else if (c < 0x20 || c > 0x7e) {
            std::snprintf(hex, sizeof hex, "\\x%02x", static_cast<unsigned char>(c));
            out += hex;
        } else
            out += c;
    }
    return out;
}

std::vector<std::int64_t> round_trips(int fd, const Exchange& exchange, int iterations)
{
    using Clock = std::chrono::steady_clock;
    const std::string& request = exchange.request;
    const std::string& expected = exchange.reply;
    if (exchange.end == ReplyEnd::Length && expected.size() > kReplyCapacity)
        throw std::logic_error("expected reply longer than the read buffer");
    std::vector<std::int64_t> samples_ns;
    samples_ns.reserve(static_cast<std::size_t>(std::max(iterations, 0)));
    char buffer[kReplyCapacity];
    for (int i = 0; i < iterations; ++i) {
        const auto start = Clock::now();
        write_all(fd, request.data(), request.size());
        std::size_t n = expected.size();
        if (exchange.end == ReplyEnd::Newline)
            n = read_line(fd, buffer, sizeof buffer);
        else
            read_exactly(fd, buffer, n);
        const auto stop = Clock::now();
        if (n != expected.size() || std::memcmp(buffer, expected.data(), n) != 0)
            throw std::runtime_error("sent \"" + printable(request, exchange.end) +
                                     "\", expected \"" + printable(expected, exchange.end) +
                                     "\", got \"" +
                                     printable(std::string(buffer, n), exchange.end) + "\"");
        samples_ns.push_back(
            std::chrono::duration_cast<std::chrono::nanoseconds>(stop - start).count());
    }
    return samples_ns;
}

std::string request_fixed_length(int fd, const std::string& request, std::size_t size)
{
    std::string reply(size, '\0');
    write_all(fd, request.data(), request.size());
    read_exactly(fd, reply.data(), size);
    return reply;
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
