#pragma once
// What the transport unit tests share: a device that records what each session receives and
// answers as the test says; the client's side as a plain non-blocking descriptor (a loopback
// socket or the pty slave); a loop that runs the io_context and the client in turn until a
// condition holds or a deadline passes. The test thread is the daemon's one thread and the
// client at once, so nothing here sleeps: when neither side has anything to do, the loop waits
// at most 1 ms for the next handler and looks again, until its deadline.

#include "emulator/core/device.hpp"

#include <catch2/catch.hpp>

#include <boost/asio/io_context.hpp>
#include <spdlog/logger.h>
#include <spdlog/sinks/ostream_sink.h>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace rigsim::test {

using SteadyClock = std::chrono::steady_clock;

/// How long a test waits for what it expects before calling it lost (generous: sanitizers).
inline constexpr std::chrono::seconds kTransportDeadline{20};

/// One session a device opened: what it received, and its way back to the client.
struct SessionRecord {
    std::string peer;
    std::string received;
    /// The session's SendFn: a test sends through it as a device sends unprompted output.
    SendFn send;
    /// What the transport told of the connection (Device::open_connection): a test hangs up
    /// through it as the link's wire faults do.
    Connection connection;
    bool open = true;   ///< false once the transport has released the session
};

/// A device that records every session it opens and answers each batch of bytes a session
/// receives with `answer` (by default it echoes them).
class RecordingDevice : public Device {
public:
    using Answer = std::function<void(SessionRecord& session, std::string_view bytes)>;

    std::unique_ptr<Session> open_session(SendFn send, std::string peer) override
    {
        auto record = std::make_shared<SessionRecord>();
        record->peer = std::move(peer);
        record->send = std::move(send);
        sessions.push_back(record);
        return std::make_unique<RecordingSession>(*this, std::move(record));
    }
    std::unique_ptr<Session> open_connection(SendFn send, Connection conn, std::string peer) override
    {
        auto session = open_session(std::move(send), std::move(peer));
        sessions.back()->connection = std::move(conn);
        return session;
    }

    /// Sessions not released yet.
    std::size_t open_sessions() const
    {
        std::size_t n = 0;
        for (const auto& s : sessions)
            n += s->open ? 1 : 0;
        return n;
    }

    /// Every session opened so far, in order, released ones included.
    std::vector<std::shared_ptr<SessionRecord>> sessions;
    Answer answer = [](SessionRecord& session, std::string_view bytes) { session.send(bytes); };

private:
    class RecordingSession : public Session {
    public:
        RecordingSession(RecordingDevice& device, std::shared_ptr<SessionRecord> record)
            : device_(device), record_(std::move(record))
        {
        }
        ~RecordingSession() override { record_->open = false; }
        void receive(std::string_view bytes) override
        {
            record_->received.append(bytes);
            device_.answer(*record_, bytes);
        }

    private:
        RecordingDevice& device_;
        std::shared_ptr<SessionRecord> record_;
    };
};

/// A logger whose lines the test reads (the endpoints' warnings are part of their contract).
class CapturedLog {
public:
    std::string text() const { return text_.str(); }
    /// Occurrences of `needle` in the log so far.
    std::size_t count(const std::string& needle) const
    {
        const auto all = text();
        std::size_t n = 0;
        for (auto at = all.find(needle); at != std::string::npos; at = all.find(needle, at + 1))
            ++n;
        return n;
    }

    std::ostringstream text_;
    std::shared_ptr<spdlog::logger> logger =
        std::make_shared<spdlog::logger>("transport", std::make_shared<spdlog::sinks::ostream_sink_st>(text_));
};

/// Runs the ready handlers of `io`, then asks `done` (which may read the client's side), until
/// it holds (true) or `budget` passes (false). When no handler was ready and `done` does not
/// hold, waits for the next handler at most 1 ms.
inline bool run_until(boost::asio::io_context& io, const std::function<bool()>& done,
                      SteadyClock::duration budget = kTransportDeadline)
{
    const auto deadline = SteadyClock::now() + budget;
    for (;;) {
        io.restart();
        const auto ran = io.poll();
        if (done())
            return true;
        if (SteadyClock::now() >= deadline)
            return false;
        if (ran == 0) {
            io.restart();
            io.run_one_for(std::chrono::milliseconds(1));
        }
    }
}

/// The client's end of a connection: a socket or the pty slave, non-blocking, closed on
/// destruction.
class ClientFd {
public:
    enum class Read { Data, Nothing, End };

    explicit ClientFd(int fd) : fd_(fd)
    {
        REQUIRE(fd_ >= 0);
        const int flags = ::fcntl(fd_, F_GETFL);
        REQUIRE(::fcntl(fd_, F_SETFL, flags | O_NONBLOCK) == 0);
    }
    ~ClientFd() { close(); }
    ClientFd(ClientFd&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
    ClientFd(const ClientFd&) = delete;
    ClientFd& operator=(const ClientFd&) = delete;
    ClientFd& operator=(ClientFd&& other) noexcept
    {
        if (this != &other) {
            close();
            fd_ = other.fd_;
            other.fd_ = -1;
        }
        return *this;
    }

    int get() const { return fd_; }
    void close()
    {
        if (fd_ >= 0)
            ::close(fd_);
        fd_ = -1;
    }

    /// Writes `bytes`, a request small enough for the kernel to take at once.
    void write(std::string_view bytes)
    {
        ssize_t n = ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL);
        if (n < 0 && errno == ENOTSOCK)
            n = ::write(fd_, bytes.data(), bytes.size());
        INFO("write: " << (n < 0 ? std::strerror(errno) : "short"));
        REQUIRE(n == static_cast<ssize_t>(bytes.size()));
    }

    /// Appends what can be read now, at most `max` bytes, to `into`: Data, Nothing (nothing
    /// there yet) or End (end of stream, or a reset connection).
    Read read_some(std::string& into, std::size_t max = 1 << 16)
    {
        char buf[1 << 16];
        const auto n = ::read(fd_, buf, std::min(max, sizeof buf));
        if (n > 0) {
            into.append(buf, static_cast<std::size_t>(n));
            return Read::Data;
        }
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR))
            return Read::Nothing;
        return Read::End;
    }

private:
    int fd_;
};

/// A client connected to 127.0.0.1:`port`. `receive_buffer` > 0 shrinks its socket receive
/// buffer (set before connect, so that the window is small from the start): a peer that
/// reads slowly, or not at all, then holds little in the kernel.
inline ClientFd connect_tcp(std::uint16_t port, int receive_buffer = 0)
{
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    REQUIRE(fd >= 0);
    if (receive_buffer > 0)
        ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &receive_buffer, sizeof receive_buffer);
    const int one = 1;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(port);
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    // Blocking, and complete at once: the connection waits in the listener's backlog, from
    // which the endpoint accepts it once the test runs the io_context.
    const int rc = ::connect(fd, reinterpret_cast<const sockaddr*>(&to), sizeof to);
    const int error = errno;
    ClientFd client(fd);
    INFO("connect: " << std::strerror(error));
    REQUIRE(rc == 0);
    return client;
}

/// "tcp 127.0.0.1:<port>": how the TCP endpoint names `client`'s connection (Session peer).
inline std::string tcp_peer_of(const ClientFd& client)
{
    sockaddr_in local{};
    socklen_t size = sizeof local;
    REQUIRE(::getsockname(client.get(), reinterpret_cast<sockaddr*>(&local), &size) == 0);
    return "tcp 127.0.0.1:" + std::to_string(ntohs(local.sin_port));
}

/// A client of the pty at `path`, as a serial application opens its port: O_NOCTTY, raw.
inline ClientFd open_pty(const std::string& path)
{
    ClientFd client(::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC));
    termios tio{};
    REQUIRE(::tcgetattr(client.get(), &tio) == 0);
    ::cfmakeraw(&tio);
    REQUIRE(::tcsetattr(client.get(), TCSANOW, &tio) == 0);
    return client;
}

/// `length` bytes of an endless stream starting at `offset`: 8-byte records, each its own
/// index in 7 hex digits and '\n', so that a byte lost, doubled or moved shows, and where.
inline std::string stream_bytes(std::size_t offset, std::size_t length)
{
    std::string out;
    out.reserve(length);
    char record[9];
    for (std::size_t at = offset; at < offset + length;) {
        std::snprintf(record, sizeof record, "%07zx\n", (at / 8) & 0xfffffff);
        const std::size_t from = at % 8;
        const std::size_t take = std::min<std::size_t>(8 - from, offset + length - at);
        out.append(record + from, take);
        at += take;
    }
    return out;
}

/// "" if `got` == `want`, else their sizes and the first difference with some context: a
/// readable CHECK on megabytes.
inline std::string difference(const std::string& got, const std::string& want)
{
    if (got == want)
        return "";
    std::size_t at = 0;
    while (at < got.size() && at < want.size() && got[at] == want[at])
        ++at;
    const auto around = [at](const std::string& s) {
        const auto from = at < 16 ? 0 : at - 16;
        std::string text;
        for (const char c : from < s.size() ? s.substr(from, 40) : std::string())
            text += c == '\n' ? std::string("\\n") : std::string(1, c);
        return "\"" + text + "\"";
    };
    return "got " + std::to_string(got.size()) + " bytes, want " + std::to_string(want.size()) +
           "; first difference at byte " + std::to_string(at) + ": got " + around(got) + ", want " +
           around(want);
}

/// Reads from `client` in pieces of at most `piece` bytes, running `io` between reads, until
/// `want` bytes have come, the stream ends or the deadline passes; returns what came.
inline std::string read_in_pieces(boost::asio::io_context& io, ClientFd& client, std::size_t want,
                                  std::size_t piece)
{
    std::string got;
    const auto deadline = SteadyClock::now() + kTransportDeadline;
    while (got.size() < want && SteadyClock::now() < deadline) {
        io.restart();
        const auto ran = io.poll();
        const auto read = client.read_some(got, std::min(piece, want - got.size()));
        if (read == ClientFd::Read::End)
            break;
        if (ran == 0 && read == ClientFd::Read::Nothing) {
            io.restart();
            io.run_one_for(std::chrono::milliseconds(1));
        }
    }
    return got;
}

} // namespace rigsim::test
