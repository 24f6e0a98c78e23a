#pragma once
// A small HTTP/1.1 server for the control API (Boost.Beast, on the daemon's one io_context):
// keep-alive, one request at a time per connection, bounded bodies and connections. A request's
// headers are read first and checked against the access rules (http_access.hpp) before its body
// is read. It knows no route: each request goes to a Router. Beast stays in http_server.cpp.

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

/// Queues bytes of a stream for its client (called on the io_context thread).
using StreamWriter = std::function<void(std::string_view bytes)>;
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

struct HttpServerLimits {
    std::size_t max_body_bytes = 64 * 1024;   ///< a larger body gets 413 and the connection closes
    std::size_t max_header_bytes = 8 * 1024;  ///< larger headers get 400
    std::size_t max_connections = 64;         ///< more are accepted and closed at once
    std::chrono::steady_clock::duration idle_timeout = std::chrono::seconds(60);   ///< then closed (not streams)
    std::size_t max_stream_backlog_bytes = 4 * 1024 * 1024;   ///< a stream's client this far behind is closed
    std::size_t max_streams = 16;   ///< event streams open at once; more are answered 503
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

    /// The listener and its connections (opaque; shared with the connections, which may end
    /// after the server object).
    struct State;

private:
    std::shared_ptr<State> state_;
};

} // namespace rigsim::control
