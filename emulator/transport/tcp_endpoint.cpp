#include "emulator/transport/tcp_endpoint.hpp"
#include "emulator/core/log_format.hpp"
#include "emulator/core/frame_queue.hpp"

#include <boost/asio/post.hpp>
#include <boost/asio/write.hpp>

#include <algorithm>
#include <array>

namespace rigsim {

namespace asio = boost::asio;
using asio::ip::tcp;

/// One client connection: reads into the session; writes each frame at once when nothing is
/// queued ahead of it, and queues what the kernel does not take, written in order as it does.
///
/// The session is released as soon as the connection ends, never later: the io_context may
/// outlive the device, and handlers still pending then must not reach it. It is never
/// released from inside a call into the device (its receive, or a send the device makes),
/// which may be iterating its sessions; such an end is finished by the pending read's
/// handler, or by TcpEndpoint::stop.
class TcpConnection : public std::enable_shared_from_this<TcpConnection> {
public:
    TcpConnection(tcp::socket socket, TcpEndpoint& endpoint, spdlog::logger& log)
        : socket_(std::move(socket)), endpoint_(endpoint), log_(log)
    {
        boost::system::error_code ec;
        const auto remote = socket_.remote_endpoint(ec);
        peer_ = ec ? "tcp ?" : "tcp " + remote.address().to_string() + ":" + std::to_string(remote.port());
        socket_.set_option(tcp::no_delay(true), ec);
        socket_.non_blocking(true, ec);   // send() writes at once what the kernel takes, never waits
    }

    const std::string& peer() const { return peer_; }

    void start(Device& device)
    {
        std::weak_ptr<TcpConnection> weak = shared_from_this();
        Connection conn;
        conn.hangup = [weak, executor = socket_.get_executor()](Hangup how) {
            // Never inside the call into or from the device that asked.
            asio::post(executor, [weak, how] {
                if (auto self = weak.lock())
                    self->hang_up(how);
            });
        };
        conn.queued_bytes = [weak] {
            auto self = weak.lock();
            return self ? self->queued_bytes_ : 0;
        };
        conn.max_queued_bytes = TcpEndpoint::kMaxQueuedBytes;
        conn.frame_overhead = TcpEndpoint::kQueuedFrameOverhead;
        session_ = device.open_connection(
            [weak](std::string_view bytes) {
                if (auto self = weak.lock())
                    self->send(bytes);
            },
            std::move(conn), peer_);
        read();
    }

    /// Closes the socket and releases the session; the endpoint has forgotten this
    /// connection (or is about to), so no handler reports back to it.
    void close()
    {
        close_socket();
        finished_ = true;
        session_.reset();
    }

private:
    void close_socket()
    {
        if (closed_)
            return;
        closed_ = true;
        boost::system::error_code ec;
        socket_.shutdown(tcp::socket::shutdown_both, ec);
        socket_.close(ec);
    }

    /// The wire asked (Connection::hangup): reset at once, or a half-close after the queue.
    void hang_up(Hangup how)
    {
        if (closed_ || half_closed_)
            return;
        // The session goes now: the device hears nothing more of this connection.
        session_.reset();
        switch (how) {
        case Hangup::Reset: {
            log_.info("{}: reset by a wire fault", peer_);
            // SO_LINGER 0 and no shutdown: close() sends RST and discards what is unsent.
            boost::system::error_code ec;
            socket_.set_option(asio::socket_base::linger(true, 0), ec);
            closed_ = true;
            socket_.close(ec);
            finish();
            return;
        }
        case Hangup::Close:
            log_.info("{}: closed by a wire fault", peer_);
            half_closed_ = true;
            if (queue_.empty())
                shut_down_send();
            return;   // the FIN follows the queue (on_write); reads go on until the client closes
        }
    }

    /// FIN after everything written; the connection reads (and drops) until the client's FIN.
    void shut_down_send()
    {
        boost::system::error_code ec;
        socket_.shutdown(tcp::socket::shutdown_send, ec);
    }

    void read()
    {
        socket_.async_read_some(asio::buffer(buffer_),
            [self = shared_from_this()](const boost::system::error_code& ec, std::size_t n) {
                self->on_read(ec, n);
            });
    }

    void on_read(const boost::system::error_code& ec, std::size_t n)
    {
        if (closed_) {
            finish();
            return;
        }
        if (ec) {
            if (ec != asio::error::operation_aborted) {
                if (ec == asio::error::eof)
                    log_.info("{}: disconnected", peer_);
                else
                    log_.warn("{}: read failed: {}", peer_, ec.message());
            }
            end();
            return;
        }
        if (!session_) {   // half-closed by a wire fault: the client's bytes go nowhere
            read();
            return;
        }
        ++device_calls_;
        session_->receive(std::string_view(buffer_.data(), n));
        --device_calls_;
        if (closed_) {
            finish();
            return;
        }
        read();
    }

    /// Called by the device (from the session's receive, or on its own for unprompted output).
    void send(std::string_view bytes)
    {
        if (closed_ || half_closed_)
            return;
        const std::size_t cost = bytes.size() + TcpEndpoint::kQueuedFrameOverhead;
        if (queued_bytes_ + cost > TcpEndpoint::kMaxQueuedBytes) {
            queued_bytes_ += cost;
            log_.warn("{}: client reads nothing ({} bytes queued): closing the connection", peer_, queued_bytes_);
            ++device_calls_;
            end();
            --device_calls_;
            return;
        }
        std::size_t written = 0;
        if (queue_.empty()) {
            // Nothing ahead of it: written now, as far as the kernel takes it (an answer, whole);
            // only what it leaves waits for the socket.
            boost::system::error_code ec;
            written = socket_.write_some(asio::buffer(bytes.data(), bytes.size()), ec);
            if (ec == asio::error::would_block || ec == asio::error::try_again) {
                written = 0;
            } else if (ec) {
                log_.warn("{}: write failed: {}", peer_, ec.message());
                ++device_calls_;
                end();
                --device_calls_;
                return;
            }
            if (written == bytes.size())
                return;
        }
        // Counted whole until written whole, its part already written included.
        queued_bytes_ += cost;
        queue_.push_back(bytes);
        if (queue_.size() == 1) {
            front_written_ = written;
            write();
        }
    }

    void write()
    {
        const auto front = queue_.front();
        asio::async_write(socket_, asio::buffer(front.data() + front_written_, front.size() - front_written_),
            [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
                self->on_write(ec);
            });
    }

    void on_write(const boost::system::error_code& ec)
    {
        if (closed_) {
            finish();
            return;
        }
        if (ec) {
            if (ec != asio::error::operation_aborted)
                log_.warn("{}: write failed: {}", peer_, ec.message());
            end();
            return;
        }
        queued_bytes_ -= queue_.front().size() + TcpEndpoint::kQueuedFrameOverhead;
        queue_.pop_front();
        front_written_ = 0;
        if (!queue_.empty())
            write();
        else if (half_closed_)
            shut_down_send();
    }

    /// The connection ends on its own (client gone, error, client reads nothing).
    void end()
    {
        close_socket();
        if (device_calls_ == 0)
            finish();
    }

    /// Releases the session and leaves the endpoint, once.
    void finish()
    {
        if (finished_)
            return;
        finished_ = true;
        session_.reset();
        endpoint_.forget(shared_from_this());
    }

    tcp::socket socket_;
    TcpEndpoint& endpoint_;
    spdlog::logger& log_;
    std::string peer_;
    std::unique_ptr<Session> session_;
    std::array<char, 4096> buffer_{};
    FrameQueue queue_;   ///< what the kernel did not take yet, in pages of its own
    std::size_t front_written_ = 0;   ///< bytes of the front frame send() wrote before queuing it
    std::size_t queued_bytes_ = 0;
    int device_calls_ = 0;   ///< nesting depth of calls into or from the device
    bool closed_ = false;    ///< the socket is closed
    bool half_closed_ = false;   ///< a wire fault closed it: FIN once the queue is written
    bool finished_ = false;  ///< the session is released and the endpoint told
};

TcpEndpoint::TcpEndpoint(asio::io_context& io, Device& device, const asio::ip::address& bind,
                         std::uint16_t port, std::shared_ptr<spdlog::logger> log, TcpConnectionBudget& budget)
    : device_(device), acceptor_(io), log_(std::move(log)), budget_(budget), backoff_timer_(io),
      refusal_timer_(io)
{
    const tcp::endpoint ep(bind, port);
    acceptor_.open(ep.protocol());
    acceptor_.set_option(tcp::acceptor::reuse_address(true));
    acceptor_.bind(ep);
    acceptor_.listen();
    port_ = acceptor_.local_endpoint().port();
}

TcpEndpoint::~TcpEndpoint()
{
    stop();
    alive_.reset();
}

tcp::endpoint TcpEndpoint::local_endpoint() const
{
    return acceptor_.local_endpoint();
}

void TcpEndpoint::start()
{
    accept();
}

void TcpEndpoint::accept()
{
    std::weak_ptr<bool> alive = alive_;
    acceptor_.async_accept([this, alive](const boost::system::error_code& ec, tcp::socket socket) {
        if (!alive.lock() || stopped_ || ec == asio::error::operation_aborted)
            return;
        if (ec) {
            on_accept_failed(ec);
            return;
        }
        if (accept_failures_ > 0)
            log_->info("tcp: accepting again after {} failed accept(s)", accept_failures_);
        accept_failures_ = 0;
        backoff_ = std::chrono::milliseconds{0};
        admit(std::move(socket));
        accept();
    });
}

void TcpEndpoint::on_accept_failed(const boost::system::error_code& ec)
{
    ++accept_failures_;
    // A client that gave up before we took it: nothing wrong here, take the next one.
    if (ec == asio::error::connection_aborted || ec == asio::error::connection_reset) {
        log_->info("tcp: accept failed: {}", ec.message());
        accept();
        return;
    }
    // Out of descriptors or memory (EMFILE, ENFILE, ENOBUFS, ENOMEM), or anything else
    // that would fail again at once: the pending connection stays in the backlog and the
    // acceptor stays readable, so retrying now would spin. Retry after a growing delay.
    backoff_ = std::clamp(backoff_ * 2, kAcceptBackoffMin, kAcceptBackoffMax);
    log_->warn("tcp: accept failed {} time(s) in a row: {}; retrying in {} ms", accept_failures_,
               ec.message(), backoff_.count());
    backoff_timer_.expires_after(backoff_);
    std::weak_ptr<bool> alive = alive_;
    backoff_timer_.async_wait([this, alive](const boost::system::error_code& wait_ec) {
        if (!alive.lock() || stopped_ || wait_ec)
            return;
        accept();
    });
}

void TcpEndpoint::admit(tcp::socket socket)
{
    if (connections_.size() >= budget_.max_per_device) {
        refuse(std::move(socket), "--max-connections-per-device", budget_.max_per_device, connections_.size());
        return;
    }
    if (budget_.open_total >= budget_.max_total) {
        refuse(std::move(socket), "--max-connections", budget_.max_total, budget_.open_total);
        return;
    }
    auto c = std::make_shared<TcpConnection>(std::move(socket), *this, *log_);
    log_->info("{}: connected", c->peer());
    connections_.insert(c);
    ++budget_.open_total;
    c->start(device_);
}

void TcpEndpoint::refuse(tcp::socket socket, const char* limit_name, std::size_t limit, std::size_t open)
{
    boost::system::error_code ec;
    // One line per second at most, however many clients come: a flood of refused
    // connections must not flood the log. Logged before the close that the client sees.
    if (refusal_timer_armed_) {
        ++refusals_unreported_;
    } else {
        const auto remote = socket.remote_endpoint(ec);
        log_->warn("tcp {}:{}: connection refused: {} open, the limit ({} {})", remote.address().to_string(),
                   remote.port(), open, limit_name, limit);
        refusal_timer_armed_ = true;
        arm_refusal_timer();
    }
    socket.close(ec);
}

void TcpEndpoint::arm_refusal_timer()
{
    refusal_timer_.expires_after(std::chrono::seconds(1));
    std::weak_ptr<bool> alive = alive_;
    refusal_timer_.async_wait([this, alive](const boost::system::error_code& wait_ec) {
        if (!alive.lock() || wait_ec)
            return;
        report_refusals();
    });
}

void TcpEndpoint::report_refusals()
{
    if (refusals_unreported_ == 0 || stopped_) {
        refusal_timer_armed_ = false;
        return;
    }
    log_->warn("tcp: refused {} more connection(s) in the last second (limits: {} per device, {} in all)",
               refusals_unreported_, budget_.max_per_device, budget_.max_total);
    refusals_unreported_ = 0;
    arm_refusal_timer();
}

void TcpEndpoint::forget(const std::shared_ptr<TcpConnection>& c)
{
    if (connections_.erase(c) > 0)
        --budget_.open_total;
}

void TcpEndpoint::stop()
{
    if (stopped_)
        return;
    stopped_ = true;
    boost::system::error_code ec;
    acceptor_.close(ec);
    backoff_timer_.cancel();
    refusal_timer_.cancel();
    for (const auto& c : connections_)
        c->close();
    budget_.open_total -= connections_.size();
    connections_.clear();
}

} // namespace rigsim
