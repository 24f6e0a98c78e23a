#include "emulator/control/http_session.hpp"
#include "emulator/core/frame_queue.hpp"
#include "emulator/core/log_format.hpp"

#include <boost/asio/write.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <deque>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rigsim::control {

namespace beast = boost::beast;
namespace http = beast::http;

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
    head.target = std::string_view(req.target().data(), req.target().size());
    head.chunked = parser.chunked();
    head.has_body = parser.content_length().value_or(0) > 0;
    return head;
}

} // namespace

namespace {

/// Bytes read from a connection at a time (a request's buffer holds at most the header limit and this).
constexpr std::size_t kReadChunk = 8 * 1024;
/// What a chunk queued for a stream is counted beyond its bytes (its place in the queue: 4 bytes in
/// the FrameQueue; the bound is kept as it was when the queue held pointers to shared chunks).
constexpr std::size_t kStreamChunkOverhead = 32;
/// Chunks gathered into one write of a stream.
constexpr std::size_t kMaxGather = 64;

/// One connection: read a request, answer it, read the next (keep-alive); any error closes it.
///
/// A request is read in two parts, each with a deadline (HttpServerLimits::header_timeout,
/// body_timeout: mod_reqtimeout's rule, ReadDeadline), so that a client that sends a byte now
/// and then cannot hold the connection; between requests it may idle for idle_timeout.
class Session : public HttpConnection, public std::enable_shared_from_this<Session> {
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
    ~Session() override
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
    void close() override
    {
        end_stream();
        boost::system::error_code ignored;
        deadline_timer_.cancel();
        stream_.socket().shutdown(tcp::socket::shutdown_both, ignored);
        stream_.close();
    }

    /// Open, and waiting for a client's bytes: it may make room for a new connection.
    bool evictable() const override { return !closed_ && (phase_ == Phase::Idle || phase_ == Phase::Header || phase_ == Phase::Body); }
    bool open() const override { return !closed_; }
    std::chrono::steady_clock::time_point waiting_since() const override { return phase_since_; }
    const std::string& peer() const override { return peer_; }

    /// Write what is queued for the stream (the server's flush timer).
    void flush() override
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
    // The answer has no length: it ends when the connection closes (RFC 9112 6.3). Each event is
    // framed once for every stream (a shared chunk) and copied into each stream's queue, whose
    // pages are its own (FrameQueue: a client that falls megabytes behind leaves no holes in the
    // heap when it goes), and written together by the server's flush timer: a write per stream
    // per interval, not per event.

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
        out_.push_back(*chunk);
        backlog_ += cost;
        state_->stream_backlog += cost;
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
        out_.for_each_front(kMaxGather, [this](std::string_view c) { gather_.emplace_back(c.data(), c.size()); });
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
            const auto cost = out_.front().size() + kStreamChunkOverhead;
            backlog_ -= cost;
            state_->stream_backlog -= cost;
            out_.pop_front();
        }
        gather_.clear();
        if (!out_.empty())
            write_chunks();   // what came during the write: already a batch
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
            out_.clear();
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
    FrameQueue out_;   ///< the stream's backlog
    std::vector<boost::asio::const_buffer> gather_;   ///< the chunks being written
    std::size_t backlog_ = 0;
    bool writing_ = false;
    bool flush_pending_ = false;
    bool closed_ = false;
    bool streaming_ = false;
    std::array<char, 512> sink_{};
    std::string continue_;   ///< "100 Continue" while it is written
};

} // namespace

void start_connection(tcp::socket socket, const std::shared_ptr<HttpServer::State>& state)
{
    std::make_shared<Session>(std::move(socket), state)->start();
}

void schedule_flush(const std::shared_ptr<HttpServer::State>& state, const std::shared_ptr<HttpConnection>& s)
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

} // namespace rigsim::control
