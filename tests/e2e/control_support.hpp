#pragma once
// An HTTP client for the control API's e2e tests: a LineClient on a TCP socket (status line
// and headers are lines; every JSON body the daemon sends is one line).
#include "e2e_support.hpp"

#include <catch2/catch.hpp>

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <string>

namespace rigsim::e2e {

/// An HTTP answer: status code and body.
struct HttpAnswer {
    int status = 0;
    std::string body;
    std::string headers;   ///< the header lines in lower case, "name: value\r\n" each
};

/// The control API's address from the endpoints file's "control": "http://HOST:PORT".
inline Endpoint control_endpoint(const Daemon& daemon)
{
    const auto url = json_string_value(daemon.endpoints_json(), "control");
    REQUIRE(url);
    const std::string scheme = "http://";
    REQUIRE(url->rfind(scheme, 0) == 0);
    Endpoint e;
    e.tcp = url->substr(scheme.size());
    const auto colon = e.tcp.rfind(':');
    REQUIRE(colon != std::string::npos);
    e.host = e.tcp.substr(0, colon);
    e.port = static_cast<std::uint16_t>(std::stoi(e.tcp.substr(colon + 1)));
    return e;
}

/// Reads one answer from `c`: the status line (within `timeout`), the headers, Content-Length
/// bytes of body.
inline HttpAnswer read_answer(LineClient& c, Millis timeout = kAnswerTimeout)
{
    HttpAnswer a;
    const auto status_line = c.read_line(timeout);
    REQUIRE(status_line);
    REQUIRE(status_line->rfind("HTTP/1.1 ", 0) == 0);
    a.status = std::stoi(status_line->substr(9, 3));
    std::size_t length = 0;
    for (;;) {
        const auto header = c.read_line();
        REQUIRE(header);
        if (*header == "\r\n")
            break;
        const std::string name = "content-length:";
        std::string lower;
        for (char ch : *header)
            lower += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        if (lower.rfind(name, 0) == 0)
            length = std::stoul(header->substr(name.size()));
        a.headers += lower;
    }
    while (a.body.size() < length) {
        const auto line = c.read_line();
        REQUIRE(line);
        a.body += *line;
    }
    return a;
}

/// One request on the keep-alive connection `c`.
inline HttpAnswer http(LineClient& c, const std::string& method, const std::string& path, const std::string& body = {})
{
    c.send(method + " " + path + " HTTP/1.1\r\nHost: localhost\r\nContent-Type: application/json\r\n"
           + "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body);
    return read_answer(c);
}

/// What a client's raw reads gave: the bytes, and how the stream ended.
struct Reads {
    std::string bytes;
    enum class End { Open, Eof, Error } end = End::Open;
    int error = 0;   ///< errno of End::Error
};

/// Reads `fd` until `want` bytes have come, the stream ends, or `timeout` passes with nothing
/// more: never a wait for a fault to act (the steps do that), only for the bytes in flight.
inline Reads read_fd(int fd, std::size_t want, Millis timeout = Millis(300))
{
    Reads r;
    const auto deadline = SteadyClock::now() + timeout;
    while (r.bytes.size() < want) {
        const auto left = std::chrono::duration_cast<Millis>(deadline - SteadyClock::now()).count();
        if (left <= 0)
            break;
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, static_cast<int>(left)) <= 0)
            break;
        char buf[4096];
        const auto n = ::read(fd, buf, std::min(sizeof buf, want - r.bytes.size()));
        if (n > 0) {
            r.bytes.append(buf, static_cast<std::size_t>(n));
            continue;
        }
        if (n == 0) {
            r.end = Reads::End::Eof;
            break;
        }
        if (errno == EAGAIN || errno == EINTR)
            continue;
        r.end = Reads::End::Error;
        r.error = errno;
        break;
    }
    return r;
}

} // namespace rigsim::e2e
