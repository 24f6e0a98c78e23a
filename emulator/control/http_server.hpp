#pragma once
// A small HTTP/1.1 server for the control API (Boost.Beast, on the daemon's one io_context):
// keep-alive, one request at a time per connection, bounded bodies, times and connections
// (docs/control-api.md "Limits"). A request's headers are read first and checked against the
// access rules (http_access.hpp) before its body is read. It knows no route: each request goes to
// a Router. Beast stays in http_session.cpp (a connection); http_server.cpp is the listener.

#include "emulator/control/http_access.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>

#include <spdlog/logger.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rigsim::control {

/// Bytes of a stream, shared by every stream that sends them (an event is framed once).
using StreamChunk = std::shared_ptr<const std::string>;
/// Queues bytes of a stream for its client (called on the io_context thread).
using StreamWriter = std::function<void(StreamChunk bytes)>;
/// Starts a stream on a connection: called once with its writer; returns what ends the stream
/// (called once when the client goes away or the server stops).
using StreamStart = std::function<std::function<void()>(StreamWriter writer)>;

struct HttpReply;
/// Sends the answer of a request that is answered later (called at most once, on the io_context
/// thread; after the client went away it does nothing).
using Respond = std::function<void(HttpReply reply)>;

/// A route's answer: an HTTP status and a JSON body, or a stream (Server-Sent Events), or an
/// answer that comes later.
struct HttpReply {
    unsigned status = 200;
    std::string body;
    /// Set: the answer is `200 text/event-stream` that lasts until the client closes; `body` unused.
    StreamStart stream;
    /// Set: the answer comes later (a clock step that runs in slices between other work): called
    /// once with what sends it; `status` and `body` unused. The connection reads nothing meanwhile.
    std::function<void(Respond respond)> later;
    /// Header lines to add (name, value), e.g. WWW-Authenticate on a 401.
    std::vector<std::pair<std::string, std::string>> headers;
};

/// (method, target, body) -> reply; called on the io_context thread, one request at a time.
using Router = std::function<HttpReply(std::string_view method, std::string_view target, std::string_view body)>;

/// How long one part of a request may take to arrive, as Apache's mod_reqtimeout counts it
/// (`header=5-20,MinRate=500`): `initial` to start with, then each byte received moves the
/// deadline on by 1 s / `min_rate_bytes_per_s`, up to `max` after the part began. A client that
/// sends slower than the rate falls behind its deadline and is closed; one that sends at the
/// rate or faster has at most `max`.
struct ReadTimeout {
    std::chrono::milliseconds initial{5000};
    std::chrono::milliseconds max{20000};
    std::size_t min_rate_bytes_per_s = 500;   ///< 0: no extension (the deadline stays `initial`)
};

/// The deadline of one part of a request under a ReadTimeout, on the clock the caller passes
/// (pure: tests step the time points).
class ReadDeadline {
public:
    using TimePoint = std::chrono::steady_clock::time_point;

    /// The part begins at `now`.
    void start(const ReadTimeout& t, TimePoint now);
    /// `bytes` more arrived: the deadline moves on, never past the cap.
    void received(std::size_t bytes);
    TimePoint deadline() const { return deadline_; }
    bool expired(TimePoint now) const { return now >= deadline_; }
    /// Bytes received since start().
    std::size_t bytes() const { return bytes_; }

private:
    TimePoint deadline_{};
    TimePoint cap_{};
    std::chrono::nanoseconds per_byte_{0};
    std::size_t bytes_ = 0;
};

struct HttpServerLimits {
    std::size_t max_body_bytes = 64 * 1024;   ///< a larger body gets 413 and the connection closes
    std::size_t max_header_bytes = 8 * 1024;  ///< larger headers get 400
    /// Open at once; a new one beyond replaces the connection that has waited longest for a
    /// request (or its body), else it is closed at once.
    std::size_t max_connections = 64;
    /// A kept-alive connection with no new request for this long is closed.
    std::chrono::steady_clock::duration idle_timeout = std::chrono::seconds(60);
    /// A request's header, from the connection's start (or its first byte on a kept-alive one).
    ReadTimeout header_timeout{std::chrono::seconds(5), std::chrono::seconds(20), 500};
    /// A request's body, from the end of its header.
    ReadTimeout body_timeout{std::chrono::seconds(5), std::chrono::seconds(30), 500};
    std::size_t max_stream_backlog_bytes = 4 * 1024 * 1024;   ///< a stream's client this far behind is closed
    std::size_t max_streams = 16;   ///< event streams open at once; more are answered 503
    /// Events queued for the streams are written together at most this often (one write per
    /// stream per interval, however many events came).
    std::chrono::milliseconds stream_flush_interval{2};
};

class HttpServer {
public:
    /// Listens on `address:port` (port 0: an ephemeral one); throws on failure to bind.
    HttpServer(boost::asio::io_context& io, const boost::asio::ip::address& address, std::uint16_t port,
               Router router, std::shared_ptr<spdlog::logger> log, HttpServerLimits limits = {},
               HttpAccess access = {});
    ~HttpServer();
    HttpServer(const HttpServer&) = delete;
    HttpServer& operator=(const HttpServer&) = delete;

    void start();
    /// Close the acceptor and every connection; their handlers then run out on the io_context.
    void stop();

    boost::asio::ip::tcp::endpoint local_endpoint() const;
    /// Connections open now.
    std::size_t connections() const;
    /// Event streams open now.
    std::size_t streams() const;
    /// Bytes queued for the event streams' clients now (each stream's share counted).
    std::size_t stream_backlog_bytes() const;
    /// Called after a connection has gone and released its buffers (the daemon returns freed
    /// memory to the system then, MemoryTrim).
    void on_connection_closed(std::function<void()> f);

    /// The listener and its connections (opaque; shared with the connections, which may end
    /// after the server object).
    struct State;

private:
    std::shared_ptr<State> state_;
};

} // namespace rigsim::control
