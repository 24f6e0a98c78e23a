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
#include <string>
#include <utility>
#include <vector>

namespace rigsim::control {

namespace beast = boost::beast;
namespace http = beast::http;
using boost::asio::ip::tcp;

class Session;

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
    std::vector<std::weak_ptr<Session>> to_flush;
    Router router;
    std::shared_ptr<spdlog::logger> log;
    HttpServerLimits limits;
    HttpAccess access;
    std::set<Session*> sessions;   ///< open connections, closed by stop()
    std::size_t streams = 0;       ///< of which event streams (they never idle out)
    std::size_t stream_backlog = 0;   ///< bytes queued for the streams' clients
    std::function<void()> on_closed;
    std::chrono::steady_clock::time_point last_warning{};
    std::size_t warnings_left_out = 0;
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

} // namespace

/// Bytes read from a connection at a time (a request's buffer holds at most the header limit and this).
constexpr std::size_t kReadChunk = 8 * 1024;
/// What a chunk queued for a stream costs beyond its bytes (its place in the queue).
constexpr std::size_t kStreamChunkOverhead = 32;
/// Chunks gathered into one write of a stream.
constexpr std::size_t kMaxGather = 64;

void schedule_flush(const std::shared_ptr<HttpServer::State>& state, const std::shared_ptr<Session>& s);

/// One connection: read a request, answer it, read the next (keep-alive); any error closes it.
///
/// A request is read in two parts, each with a deadline (HttpServerLimits::header_timeout,
/// body_timeout: mod_reqtimeout's rule, ReadDeadline), so that a client that sends a byte now
/// and then cannot hold the connection; between requests it may idle for idle_timeout.
class Session : public std::enable_shared_from_this<Session> {
public:
    /// What the connection waits for now.
    enum class Phase {
        Idle,     ///< a kept-alive connection, waiting for the next request's first byte
        Header,   ///< a request's header
        Body,     ///< its body
        Busy,     ///< routing, an answer to come (a clock step) or being written
        Stream,   ///< an event stream
    };

    Session(tcp::socket socket, std::shared_ptr<HttpServer::State> state)
        : stream_(std::move(socket)), deadline_timer_(stream_.get_executor()), state_(std::move(state)),
          buffer_(state_->limits.max_header_bytes + kReadChunk)
    {
        boost::system::error_code ec;
        const auto remote = stream_.socket().remote_endpoint(ec);
        peer_ = ec ? "?" : remote.address().to_string() + ":" + std::to_string(remote.port());
        state_->sessions.insert(this);
    }
    ~Session()
    {
        end_stream();
        state_->stream_backlog -= backlog_;
        state_->sessions.erase(this);
        if (state_->on_closed && !state_->stopped)
            state_->on_closed();
    }

    /// The first request's header is due from the connection's start.
    void start()
    {
        new_request();
        begin(Phase::Header);
        read_more();
    }

    /// Close the socket: the pending operations complete with an error and the session ends.
    void close()
    {
        end_stream();
        boost::system::error_code ignored;
        deadline_timer_.cancel();
        stream_.socket().shutdown(tcp::socket::shutdown_both, ignored);
        stream_.close();
    }

    /// Open, and waiting for a client's bytes: it may make room for a new connection.
    bool evictable() const { return !closed_ && (phase_ == Phase::Idle || phase_ == Phase::Header || phase_ == Phase::Body); }
    bool open() const { return !closed_; }
    std::chrono::steady_clock::time_point waiting_since() const { return phase_since_; }
    const std::string& peer() const { return peer_; }

    /// Write what is queued for the stream (the server's flush timer).
    void flush()
    {
        flush_pending_ = false;
        if (!closed_ && !writing_ && !out_.empty())
            write_chunks();
    }

private:
    // ---- Reading a request: the header (checked against the access rules), then the body.

    void new_request()
    {
        parser_.emplace();
        parser_->body_limit(state_->limits.max_body_bytes);
        parser_->header_limit(static_cast<std::uint32_t>(state_->limits.max_header_bytes));
    }

    /// The next request of a kept-alive connection.
    void read()
    {
        new_request();
        if (buffer_.size() == 0 && buffer_.capacity() > 2 * kReadChunk)
            buffer_.shrink_to_fit();   // a large request's room is not kept between requests
        if (buffer_.size() > 0) {   // it came with the last one
            begin(Phase::Header);
            parse();
            return;
        }
        begin(Phase::Idle);
        read_more();
    }

    void begin(Phase p)
    {
        phase_ = p;
        phase_since_ = std::chrono::steady_clock::now();
        const auto& limits = state_->limits;
        switch (p) {
        case Phase::Idle:
            deadline_.start(ReadTimeout{std::chrono::duration_cast<std::chrono::milliseconds>(limits.idle_timeout),
                                        std::chrono::duration_cast<std::chrono::milliseconds>(limits.idle_timeout), 0},
                            phase_since_);
            break;
        case Phase::Header:
            deadline_.start(limits.header_timeout, phase_since_);
            break;
        case Phase::Body:
            deadline_.start(limits.body_timeout, phase_since_);
            break;
        case Phase::Busy:
        case Phase::Stream:
            deadline_timer_.cancel();
            return;
        }
        arm_deadline();
    }

    void arm_deadline()
    {
        deadline_timer_.expires_at(deadline_.deadline());
        deadline_timer_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
            self->on_deadline(ec);
        });
    }

    void on_deadline(const boost::system::error_code& ec)
    {
        if (ec || closed_ || !evictable())
            return;
        const auto now = std::chrono::steady_clock::now();
        if (!deadline_.expired(now)) {   // bytes came meanwhile and moved it on
            arm_deadline();
            return;
        }
        const char* what = phase_ == Phase::Idle ? "no new request" : phase_ == Phase::Header ? "request header" : "request body";
        const double seconds = std::chrono::duration<double>(now - phase_since_).count();
        if (phase_ == Phase::Idle)
            state_->log->debug("control: {}: {} for {:.0f} s: closing", peer_, what, seconds);
        else
            state_->warn_limited(fmt::format("control: {}: {} too slow ({} bytes in {:.1f} s; limits: {} ms, then "
                                             "{} bytes/s, at most {} ms): closing",
                                             peer_, what, deadline_.bytes(), seconds, timeout_of(phase_).initial.count(),
                                             timeout_of(phase_).min_rate_bytes_per_s, timeout_of(phase_).max.count()));
        close();
    }

    const ReadTimeout& timeout_of(Phase p) const
    {
        return p == Phase::Body ? state_->limits.body_timeout : state_->limits.header_timeout;
    }

    void read_more()
    {
        const auto room = buffer_.max_size() - buffer_.size();
        stream_.socket().async_read_some(buffer_.prepare(std::min(room, kReadChunk)),
                                         [self = shared_from_this()](const boost::system::error_code& ec, std::size_t n) {
                                             self->on_bytes(ec, n);
                                         });
    }

    /// End of stream, a reset, a stop: the session ends quietly (a request cut short too).
    void on_bytes(const boost::system::error_code& ec, std::size_t n)
    {
        if (closed_)
            return;
        if (ec) {
            close();
            return;
        }
        buffer_.commit(n);
        if (phase_ == Phase::Idle)
            begin(Phase::Header);
        deadline_.received(n);
        parse();
    }

    /// Parse what is buffered; read more, or go on with a whole header or a whole request.
    void parse()
    {
        for (;;) {
            if (phase_ == Phase::Header && parser_->is_header_done()) {
                on_header();
                return;
            }
            if (phase_ == Phase::Body && parser_->is_done()) {
                on_request();
                return;
            }
            if (buffer_.size() == 0) {
                read_more();
                return;
            }
            boost::system::error_code ec;
            const auto used = parser_->put(buffer_.data(), ec);
            buffer_.consume(used);
            if (ec == http::error::need_more && used == 0 && buffer_.size() == buffer_.max_size())
                ec = http::error::header_limit;   // a header that cannot end within the buffer
            if (ec == http::error::need_more) {
                if (used == 0) {
                    read_more();
                    return;
                }
                continue;
            }
            if (ec) {
                on_read_error(ec);
                return;
            }
        }
    }

    /// A malformed request is answered (its framing is lost, so the connection closes after).
    void on_read_error(const boost::system::error_code& ec)
    {
        if (state_->stopped) {
            close();
            return;
        }
        state_->log->warn("control: bad request: {}", ec.message());
        write(HttpReply{status_of_parse_error(ec), error_body("bad request: " + ec.message()), {}, {}, {}}, 11, false);
    }

    void on_header()
    {
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
            boost::asio::async_write(stream_.socket(), boost::asio::buffer(continue_),
                                     [self = shared_from_this()](const boost::system::error_code& wec, std::size_t) {
                                         if (wec)
                                             self->close();
                                         else if (!self->closed_)
                                             self->read_body();
                                     });
            return;
        }
        read_body();
    }

    void read_body()
    {
        begin(Phase::Body);
        parser_->eager(true);
        parse();
    }

    void on_request()
    {
        begin(Phase::Busy);
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
    // The answer has no length: it ends when the connection closes (RFC 9112 6.3). Events are
    // queued as shared chunks (one copy for every stream) and written together by the server's
    // flush timer: a write per stream per interval, not per event.

    void start_stream(StreamStart start)
    {
        ++state_->streams;
        streaming_ = true;
        begin(Phase::Stream);
        stream_.expires_never();
        queue(std::make_shared<const std::string>(
            "HTTP/1.1 200 OK\r\nServer: rigsimd\r\nContent-Type: text/event-stream\r\n"
            "Cache-Control: no-cache\r\nConnection: close\r\n\r\n"));
        std::weak_ptr<Session> weak = shared_from_this();
        stop_stream_ = start([weak](StreamChunk bytes) {
            if (auto self = weak.lock())
                self->queue(std::move(bytes));
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

    void queue(StreamChunk chunk)
    {
        if (closed_ || !chunk)
            return;
        const auto cost = chunk->size() + kStreamChunkOverhead;
        if (backlog_ + cost > state_->limits.max_stream_backlog_bytes) {
            state_->warn_limited(fmt::format("control: {}: an event stream's client is {} bytes behind: closing it",
                                             peer_, backlog_ + cost));
            close();
            return;
        }
        backlog_ += cost;
        state_->stream_backlog += cost;
        out_.push_back(std::move(chunk));
        if (!writing_ && !flush_pending_) {
            flush_pending_ = true;
            schedule_flush(state_, shared_from_this());
        }
    }

    /// Writes the queued chunks (at most kMaxGather) in one gathered write.
    void write_chunks()
    {
        writing_ = true;
        gather_.clear();
        for (const auto& c : out_) {
            gather_.emplace_back(c->data(), c->size());
            if (gather_.size() == kMaxGather)
                break;
        }
        boost::asio::async_write(stream_.socket(), gather_,
                                 [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
                                     self->on_chunks_written(ec);
                                 });
    }

    void on_chunks_written(const boost::system::error_code& ec)
    {
        writing_ = false;
        if (ec || closed_) {
            close();
            return;
        }
        for (std::size_t i = 0; i < gather_.size(); ++i) {
            const auto cost = out_.front()->size() + kStreamChunkOverhead;
            backlog_ -= cost;
            state_->stream_backlog -= cost;
            out_.pop_front();
        }
        gather_.clear();
        if (!out_.empty())
            write_chunks();   // what came during the write: already a batch
        else
            out_.shrink_to_fit();   // a burst's queue is not kept
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
        if (!writing_) {   // a pending write still reads the queue's chunks
            state_->stream_backlog -= backlog_;
            backlog_ = 0;
            std::deque<StreamChunk>().swap(out_);
        }
    }

    void write(HttpReply reply, unsigned version, bool keep_alive)
    {
        begin(Phase::Busy);
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
                              self->response_ = {};   // its body is not kept between requests
                              if (ec || !keep_alive || self->state_->stopped || self->closed_) {
                                  self->close();
                                  return;
                              }
                              self->read();
                          });
    }

    beast::tcp_stream stream_;
    boost::asio::steady_timer deadline_timer_;
    std::shared_ptr<HttpServer::State> state_;
    std::string peer_;
    beast::flat_buffer buffer_;
    std::optional<http::request_parser<http::string_body>> parser_;
    http::response<http::string_body> response_;
    Phase phase_ = Phase::Header;
    std::chrono::steady_clock::time_point phase_since_{};
    ReadDeadline deadline_;
    // A stream's state.
    std::function<void()> stop_stream_;
    std::deque<StreamChunk> out_;
    std::vector<boost::asio::const_buffer> gather_;   ///< the chunks being written
    std::size_t backlog_ = 0;
    bool writing_ = false;
    bool flush_pending_ = false;
    bool closed_ = false;
    bool streaming_ = false;
    std::array<char, 512> sink_{};
    std::string continue_;   ///< "100 Continue" while it is written
};

void schedule_flush(const std::shared_ptr<HttpServer::State>& state, const std::shared_ptr<Session>& s)
{
    state->to_flush.push_back(s);
    if (state->flush_armed)
        return;
    state->flush_armed = true;
    state->flush_timer.expires_after(state->limits.stream_flush_interval);
    state->flush_timer.async_wait([state](const boost::system::error_code& ec) {
        state->flush_armed = false;
        if (ec)
            return;
        auto sessions = std::move(state->to_flush);
        state->to_flush.clear();
        for (const auto& weak : sessions)
            if (auto session = weak.lock())
                session->flush();
    });
}

namespace {

void accept(const std::shared_ptr<HttpServer::State>& state);

/// Room for one more connection: true when fewer than max_connections are open, or when one of
/// them was waiting for a client's bytes and has been closed for it (the one that has waited
/// longest: a slow or idle client gives way to a new one); false when every one is busy
/// (streams, answers to come).
bool make_room(HttpServer::State& state)
{
    std::size_t open = 0;
    Session* oldest = nullptr;
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
            std::make_shared<Session>(std::move(socket), state)->start();
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
