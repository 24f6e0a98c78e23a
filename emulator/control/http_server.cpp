#include "emulator/control/http_server.hpp"
#include "emulator/control/http_session.hpp"
#include "emulator/core/log_format.hpp"

#include "emulator/transport/tcp_endpoint.hpp"

#include <algorithm>
#include <chrono>
#include <utility>

namespace rigsim::control {

namespace {

void accept(const std::shared_ptr<HttpServer::State>& state);

/// Room for one more connection: true when fewer than max_connections are open, or when one of
/// them was waiting for a client's bytes and has been closed for it (the one that has waited
/// longest: a slow or idle client gives way to a new one); false when every one is busy
/// (streams, answers to come).
bool make_room(HttpServer::State& state)
{
    std::size_t open = 0;
    HttpConnection* oldest = nullptr;
    for (auto* s : state.sessions) {
        if (!s->open())
            continue;
        ++open;
        if (s->evictable() && (!oldest || s->waiting_since() < oldest->waiting_since()))
            oldest = s;
    }
    if (open < state.limits.max_connections)
        return true;
    if (!oldest)
        return false;
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - oldest->waiting_since()).count();
    state.warn_limited(fmt::format("control: {} connections open: closing {}, which waited {:.1f} s for a request, "
                                   "for a new one",
                                   open, oldest->peer(), waited));
    oldest->close();
    return true;
}

/// Retry accepting after a delay that doubles per failure in a row (the device endpoints' back-off).
void accept_later(const std::shared_ptr<HttpServer::State>& state, const boost::system::error_code& ec)
{
    state->backoff = std::clamp(state->backoff * 2, TcpEndpoint::kAcceptBackoffMin, TcpEndpoint::kAcceptBackoffMax);
    state->log->warn("control: accept failed {} time(s) in a row: {}; retrying in {} ms", state->accept_failures,
                     ec.message(), state->backoff.count());
    state->backoff_timer.expires_after(state->backoff);
    state->backoff_timer.async_wait([state](const boost::system::error_code& wait_ec) {
        if (!wait_ec && !state->stopped)
            accept(state);
    });
}

void accept(const std::shared_ptr<HttpServer::State>& state)
{
    state->acceptor.async_accept([state](const boost::system::error_code& ec, tcp::socket socket) {
        if (ec == boost::asio::error::operation_aborted || state->stopped)
            return;
        if (ec && ec != boost::asio::error::connection_aborted && ec != boost::asio::error::connection_reset) {
            ++state->accept_failures;
            accept_later(state, ec);
            return;
        }
        if (state->accept_failures > 0 && !ec) {
            state->log->info("control: accepting again after {} failed accept(s)", state->accept_failures);
            state->accept_failures = 0;
            state->backoff = std::chrono::milliseconds{0};
        }
        if (ec) {
            // A client that gave up before we took it: nothing wrong here, take the next one.
            state->log->info("control: accept failed: {}", ec.message());
        } else if (make_room(*state)) {
            start_connection(std::move(socket), state);
        } else {
            state->warn_limited(fmt::format("control: {} connections open, every one busy: closing a new one",
                                            state->sessions.size()));
            boost::system::error_code ignored;
            socket.close(ignored);
        }
        accept(state);
    });
}

} // namespace

HttpServer::HttpServer(boost::asio::io_context& io, const boost::asio::ip::address& address, std::uint16_t port,
                       Router router, std::shared_ptr<spdlog::logger> log, HttpServerLimits limits,
                       HttpAccess access)
    : state_(std::make_shared<State>(io, std::move(router), std::move(log), limits, std::move(access)))
{
    const tcp::endpoint endpoint(address, port);
    state_->acceptor.open(endpoint.protocol());
    state_->acceptor.set_option(tcp::acceptor::reuse_address(true));
    state_->acceptor.bind(endpoint);
    state_->acceptor.listen();
}

HttpServer::~HttpServer()
{
    stop();
}

void HttpServer::start()
{
    accept(state_);
}

void HttpServer::stop()
{
    if (state_->stopped)
        return;
    state_->stopped = true;
    boost::system::error_code ignored;
    state_->acceptor.close(ignored);
    state_->backoff_timer.cancel();
    state_->flush_timer.cancel();
    // close() may end a session at once; copy the set first.
    const auto sessions = state_->sessions;
    for (auto* s : sessions)
        s->close();
}

tcp::endpoint HttpServer::local_endpoint() const
{
    return state_->acceptor.local_endpoint();
}

std::size_t HttpServer::connections() const
{
    return state_->sessions.size();
}

std::size_t HttpServer::streams() const
{
    return state_->streams;
}

std::size_t HttpServer::stream_backlog_bytes() const
{
    return state_->stream_backlog;
}

void HttpServer::on_connection_closed(std::function<void()> f)
{
    state_->on_closed = std::move(f);
}

void ReadDeadline::start(const ReadTimeout& t, TimePoint now)
{
    deadline_ = now + t.initial;
    cap_ = now + std::max(t.initial, t.max);
    per_byte_ = t.min_rate_bytes_per_s == 0
                    ? std::chrono::nanoseconds(0)
                    : std::chrono::nanoseconds(1'000'000'000 / static_cast<std::int64_t>(t.min_rate_bytes_per_s));
    bytes_ = 0;
}

void ReadDeadline::received(std::size_t bytes)
{
    bytes_ += bytes;
    // As mod_reqtimeout: each byte moves the deadline itself on (not "now"), so a client slower
    // than the rate falls behind, however it spreads its bytes.
    const auto room = cap_ - deadline_;
    const auto step = per_byte_ * static_cast<std::int64_t>(std::min<std::size_t>(bytes, 1u << 30));
    deadline_ += std::min<std::chrono::steady_clock::duration>(room, step);
}

} // namespace rigsim::control
