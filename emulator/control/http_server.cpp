#include "emulator/control/http_server.hpp"
#include "emulator/core/log_format.hpp"

#include "emulator/transport/tcp_endpoint.hpp"

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <array>
#include <deque>
#include <optional>
#include <set>
#include <utility>

namespace rigsim::control {

namespace beast = boost::beast;
namespace http = beast::http;
using boost::asio::ip::tcp;

class Session;

struct HttpServer::State {
    State(boost::asio::io_context& io, Router r, std::shared_ptr<spdlog::logger> l, HttpServerLimits lim,
          HttpAccess a)
        : acceptor(io), backoff_timer(io), router(std::move(r)), log(std::move(l)), limits(lim), access(std::move(a))
    {
    }

    tcp::acceptor acceptor;
    /// After an accept that failed for want of resources (EMFILE...), the next waits: the
    /// pending connection keeps the acceptor readable, so retrying at once would spin.
    boost::asio::steady_timer backoff_timer;
    std::chrono::milliseconds backoff{0};
    std::size_t accept_failures = 0;
    Router router;
    std::shared_ptr<spdlog::logger> log;
    HttpServerLimits limits;
    HttpAccess access;
    std::set<Session*> sessions;   ///< open connections, closed by stop()
    std::size_t streams = 0;       ///< of which event streams (they never idle out)
    bool stopped = false;
};

namespace {

std::string error_body(const std::string& message)
{
    return nlohmann::json{{"error", message}}.dump() + "\n";
}

/// A request the parser refused: its status (413 for a body over the limit, 400 otherwise).
unsigned status_of_parse_error(const boost::system::error_code& ec)
{
    return ec == http::error::body_limit ? 413 : 400;
}

/// A header's value, if the request has it.
std::optional<std::string_view> field(const http::request<http::string_body>& req, http::field name)
{
    const auto it = req.find(name);
    if (it == req.end())
        return std::nullopt;
    return std::string_view(it->value().data(), it->value().size());
}

/// A header without a Beast name (Sec-Fetch-Site), if the request has it.
std::optional<std::string_view> field(const http::request<http::string_body>& req, std::string_view name)
{
    const auto it = req.find(boost::beast::string_view(name.data(), name.size()));
    if (it == req.end())
        return std::nullopt;
    return std::string_view(it->value().data(), it->value().size());
}

/// What the access rules read of a request whose headers have been parsed.
RequestHead head_of(const http::request_parser<http::string_body>& parser)
{
    const auto& req = parser.get();
    RequestHead head;
    head.method = std::string_view(req.method_string().data(), req.method_string().size());
    head.version = req.version();
    head.host = field(req, http::field::host);
    head.origin = field(req, http::field::origin);
    head.sec_fetch_site = field(req, "Sec-Fetch-Site");
    head.content_type = field(req, http::field::content_type);
    head.authorization = field(req, http::field::authorization);
    head.chunked = parser.chunked();
    head.has_body = parser.content_length().value_or(0) > 0;
    return head;
}

bool is_parse_error(const boost::system::error_code& ec)
{
    return ec.category() == http::make_error_code(http::error::bad_target).category()
           && ec != http::error::end_of_stream && ec != http::error::partial_message;
}

} // namespace

/// One connection: read a request, answer it, read the next (keep-alive); any error closes it.
class Session : public std::enable_shared_from_this<Session> {
public:
    Session(tcp::socket socket, std::shared_ptr<HttpServer::State> state)
        : stream_(std::move(socket)), state_(std::move(state))
    {
        state_->sessions.insert(this);
    }
    ~Session()
    {
        end_stream();
        state_->sessions.erase(this);
    }

    void start() { read(); }

    /// Close the socket: the pending operation completes with an error and the session ends.
    void close()
    {
        end_stream();
        boost::system::error_code ignored;
        stream_.socket().shutdown(tcp::socket::shutdown_both, ignored);
        stream_.close();
    }

private:
    /// Read a request's headers; its body is read only once they pass the access rules.
    void read()
    {
        parser_.emplace();
        parser_->body_limit(state_->limits.max_body_bytes);
        parser_->header_limit(static_cast<std::uint32_t>(state_->limits.max_header_bytes));
        stream_.expires_after(state_->limits.idle_timeout);
        http::async_read_header(stream_, buffer_, *parser_,
                                [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
                                    self->on_header(ec);
                                });
    }

    /// A read failed: a malformed request is answered (its framing is lost, so the connection
    /// closes after); end of stream, a timeout, a reset or a stop end the session quietly.
    void on_read_error(const boost::system::error_code& ec)
    {
        if (is_parse_error(ec) && !state_->stopped) {
            state_->log->warn("control: bad request: {}", ec.message());
            write(HttpReply{status_of_parse_error(ec), error_body("bad request: " + ec.message()), {}, {}, {}}, 11,
                  false);
        }
    }

    void on_header(const boost::system::error_code& ec)
    {
        if (ec) {
            on_read_error(ec);
            return;
        }
        const auto head = head_of(*parser_);
        if (const auto refused = check_access(state_->access, head)) {
            state_->log->warn("control: refused {} {}: {}", std::string(head.method),
                              std::string(parser_->get().target()), refused->message);
            HttpReply reply{refused->status, error_body(refused->message), {}, {}, {}};
            if (refused->status == 401)
                reply.headers.emplace_back("WWW-Authenticate", "Bearer realm=\"rigsim\"");
            // The body is not read: the connection's framing ends here.
            write(std::move(reply), head.version, false);
            return;
        }
        const auto expect = field(parser_->get(), http::field::expect);
        if (expect && beast::iequals(beast::string_view(expect->data(), expect->size()), "100-continue") && !parser_->is_done()) {
            // curl waits a second for this before it sends a body over 1 KiB.
            continue_ = "HTTP/1.1 100 Continue\r\n\r\n";
            boost::asio::async_write(stream_, boost::asio::buffer(continue_),
                                     [self = shared_from_this()](const boost::system::error_code& wec, std::size_t) {
                                         if (wec)
                                             self->close();
                                         else
                                             self->read_body();
                                     });
            return;
        }
        read_body();
    }

    void read_body()
    {
        http::async_read(stream_, buffer_, *parser_,
                         [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
                             self->on_read(ec);
                         });
    }

    void on_read(const boost::system::error_code& ec)
    {
        if (ec) {
            on_read_error(ec);
            return;
        }
        const auto& req = parser_->get();
        HttpReply reply;
        try {
            reply = state_->router(std::string_view(req.method_string().data(), req.method_string().size()),
                                   std::string_view(req.target().data(), req.target().size()), req.body());
        } catch (const std::exception& e) {
            state_->log->error("control: {} {}: {}", std::string(req.method_string()), std::string(req.target()),
                               e.what());
            reply = HttpReply{500, error_body(std::string("internal error: ") + e.what()), {}, {}, {}};
        }
        if (reply.later) {
            answer_later(std::move(reply.later), req.version(), req.keep_alive());
            return;
        }
        if (reply.stream && state_->streams >= state_->limits.max_streams)
            write(HttpReply{503,
                            error_body(std::to_string(state_->streams)
                                       + " event streams are open, the most the daemon serves at once: close one"),
                            {}, {}, {}},
                  req.version(), false);
        else if (reply.stream)
            start_stream(std::move(reply.stream));
        else
            write(std::move(reply), req.version(), req.keep_alive());
    }

    /// The answer comes when `later` calls back; meanwhile the connection reads nothing (one
    /// request at a time) and has no deadline (a long clock step is not an idle client).
    void answer_later(std::function<void(Respond)> later, unsigned version, bool keep_alive)
    {
        stream_.expires_never();
        // The answer keeps the session (no read or write of it is pending meanwhile); dropped
        // unanswered (the daemon stops), it lets the session go.
        auto respond = [self = shared_from_this(), version, keep_alive](HttpReply reply) {
            if (!self->closed_)
                self->write(std::move(reply), version, keep_alive);
        };
        try {
            later(std::move(respond));
        } catch (const std::exception& e) {
            state_->log->error("control: a deferred answer failed: {}", e.what());
            write(HttpReply{500, error_body(std::string("internal error: ") + e.what()), {}, {}, {}}, version, false);
        }
    }

    // ---- A stream (GET /api/events): headers, then events as they come, until the client goes.
    // The answer has no length: it ends when the connection closes (RFC 9112 6.3).

    void start_stream(StreamStart start)
    {
        ++state_->streams;
        streaming_ = true;
        stream_.expires_never();
        queue("HTTP/1.1 200 OK\r\nServer: rigsimd\r\nContent-Type: text/event-stream\r\n"
              "Cache-Control: no-cache\r\nConnection: close\r\n\r\n");
        std::weak_ptr<Session> weak = shared_from_this();
        stop_stream_ = start([weak](std::string_view bytes) {
            if (auto self = weak.lock())
                self->queue(bytes);
        });
        // The client sends nothing more; a read ends when it closes the connection.
        drain_client();
    }

    /// Bytes a stream's client sent anyway are read and ignored.
    void drain_client()
    {
        stream_.socket().async_read_some(boost::asio::buffer(sink_),
                                         [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
                                             if (ec)
                                                 self->close();
                                             else
                                                 self->drain_client();
                                         });
    }

    void queue(std::string_view bytes)
    {
        if (closed_)
            return;
        backlog_ += bytes.size();
        if (backlog_ > state_->limits.max_stream_backlog_bytes) {
            state_->log->warn("control: an event stream's client is {} bytes behind, closing it", backlog_);
            close();
            return;
        }
        out_.emplace_back(bytes);
        if (out_.size() == 1)
            write_next();
    }

    void write_next()
    {
        boost::asio::async_write(stream_.socket(), boost::asio::buffer(out_.front()),
                                 [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
                                     if (ec || self->closed_) {
                                         self->close();
                                         return;
                                     }
                                     self->backlog_ -= self->out_.front().size();
                                     self->out_.pop_front();
                                     if (!self->out_.empty())
                                         self->write_next();
                                 });
    }

    void end_stream()
    {
        closed_ = true;
        if (streaming_) {
            streaming_ = false;
            --state_->streams;
        }
        if (auto stop = std::move(stop_stream_)) {
            stop_stream_ = nullptr;
            stop();
        }
    }

    void write(HttpReply reply, unsigned version, bool keep_alive)
    {
        response_ = {};
        response_.version(version);
        response_.result(reply.status);
        response_.set(http::field::server, "rigsimd");
        response_.set(http::field::content_type, "application/json");
        response_.set("X-Content-Type-Options", "nosniff");
        for (const auto& [name, value] : reply.headers)
            response_.set(name, value);
        response_.keep_alive(keep_alive);
        response_.body() = std::move(reply.body);
        response_.prepare_payload();
        stream_.expires_after(state_->limits.idle_timeout);
        http::async_write(stream_, response_,
                          [self = shared_from_this(), keep_alive](const boost::system::error_code& ec, std::size_t) {
                              if (ec || !keep_alive || self->state_->stopped) {
                                  self->close();
                                  return;
                              }
                              self->read();
                          });
    }

    beast::tcp_stream stream_;
    std::shared_ptr<HttpServer::State> state_;
    beast::flat_buffer buffer_;
    std::optional<http::request_parser<http::string_body>> parser_;
    http::response<http::string_body> response_;
    // A stream's state.
    std::function<void()> stop_stream_;
    std::deque<std::string> out_;
    std::size_t backlog_ = 0;
    bool closed_ = false;
    bool streaming_ = false;
    std::array<char, 512> sink_{};
    std::string continue_;   ///< "100 Continue" while it is written
};

namespace {

void accept(const std::shared_ptr<HttpServer::State>& state);

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
        } else if (state->sessions.size() >= state->limits.max_connections) {
            state->log->warn("control: {} connections open, closing a new one", state->sessions.size());
            boost::system::error_code ignored;
            socket.close(ignored);
        } else {
            std::make_shared<Session>(std::move(socket), state)->start();
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

} // namespace rigsim::control
