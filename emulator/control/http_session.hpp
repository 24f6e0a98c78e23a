#pragma once
// Inside the control API's HTTP server (http_server.hpp): the state its listener and its
// connections share, and a connection as the listener sees it. A connection (http_session.cpp,
// the one file that uses Boost.Beast) reads a request under deadlines, hands it to the router and
// writes the answer, or serves an event stream.

#include "emulator/control/http_server.hpp"

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>

#include <spdlog/logger.h>

#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace rigsim::control {

/// One connection of the server, as the listener sees it.
class HttpConnection {
public:
    virtual ~HttpConnection() = default;
    /// Close the socket: the pending operations complete with an error and the connection ends.
    virtual void close() = 0;
    /// Not closed yet.
    virtual bool open() const = 0;
    /// Open, and waiting for a client's bytes (a request, its body): it may make room for a new
    /// connection.
    virtual bool evictable() const = 0;
    /// Since when it waits for what it waits for now.
    virtual std::chrono::steady_clock::time_point waiting_since() const = 0;
    /// "ADDRESS:PORT" of the client.
    virtual const std::string& peer() const = 0;
    /// Write what is queued for its event stream (the server's flush timer).
    virtual void flush() = 0;
};

using boost::asio::ip::tcp;

struct HttpServer::State {
    State(boost::asio::io_context& io, Router r, std::shared_ptr<spdlog::logger> l, HttpServerLimits lim,
          HttpAccess a)
        : acceptor(io), backoff_timer(io), flush_timer(io), router(std::move(r)), log(std::move(l)), limits(lim),
          access(std::move(a))
    {
    }

    /// A warning that a flood could repeat (slow clients closed, connections replaced): one line
    /// a second at most, with the count of those left out since the last.
    void warn_limited(const std::string& line)
    {
        const auto now = std::chrono::steady_clock::now();
        if (now - last_warning < std::chrono::seconds(1)) {
            ++warnings_left_out;
            return;
        }
        if (warnings_left_out > 0)
            log->warn("{} ({} more such in the last second)", line, warnings_left_out);
        else
            log->warn("{}", line);
        last_warning = now;
        warnings_left_out = 0;
    }

    tcp::acceptor acceptor;
    /// After an accept that failed for want of resources (EMFILE...), the next waits: the
    /// pending connection keeps the acceptor readable, so retrying at once would spin.
    boost::asio::steady_timer backoff_timer;
    std::chrono::milliseconds backoff{0};
    std::size_t accept_failures = 0;
    /// Writes the streams' queued events, one write per stream per stream_flush_interval.
    boost::asio::steady_timer flush_timer;
    bool flush_armed = false;
    std::vector<std::weak_ptr<HttpConnection>> to_flush;
    Router router;
    std::shared_ptr<spdlog::logger> log;
    HttpServerLimits limits;
    HttpAccess access;
    std::set<HttpConnection*> sessions;   ///< open connections, closed by stop()
    std::size_t streams = 0;       ///< of which event streams (they never idle out)
    std::size_t stream_backlog = 0;   ///< bytes queued for the streams' clients
    std::function<void()> on_closed;
    std::chrono::steady_clock::time_point last_warning{};
    std::size_t warnings_left_out = 0;
    bool stopped = false;
};

/// Starts a connection on `socket`: it reads its first request (the header due from now) and
/// keeps itself alive while it has work.
void start_connection(tcp::socket socket, const std::shared_ptr<HttpServer::State>& state);

/// `c` has events queued: written at the next tick of the server's flush timer.
void schedule_flush(const std::shared_ptr<HttpServer::State>& state, const std::shared_ptr<HttpConnection>& c);

} // namespace rigsim::control
