#include "emulator/transport/tcp_endpoint.hpp"

#include <boost/asio/write.hpp>

#include <array>
#include <deque>

namespace rigsim {

namespace asio = boost::asio;
using asio::ip::tcp;

/// One client connection: reads into the session, writes each queued frame in one write.
class TcpConnection : public std::enable_shared_from_this<TcpConnection> {
public:
    /// A client that reads nothing while answers pile up beyond this is dropped.
    static constexpr std::size_t kMaxQueuedBytes = 4 << 20;

    TcpConnection(tcp::socket socket, TcpEndpoint& endpoint, spdlog::logger& log)
        : socket_(std::move(socket)), endpoint_(endpoint), log_(log)
    {
        boost::system::error_code ec;
        const auto remote = socket_.remote_endpoint(ec);
        peer_ = ec ? "tcp ?" : "tcp " + remote.address().to_string() + ":" + std::to_string(remote.port());
        socket_.set_option(tcp::no_delay(true), ec);
    }

    const std::string& peer() const { return peer_; }

    void start(Device& device)
    {
        std::weak_ptr<TcpConnection> weak = shared_from_this();
        session_ = device.open_session(
            [weak](std::string_view bytes) {
                if (auto self = weak.lock())
                    self->send(bytes);
            },
            peer_);
        read();
    }

    void close()
    {
        if (closed_)
            return;
        closed_ = true;
        boost::system::error_code ec;
        socket_.shutdown(tcp::socket::shutdown_both, ec);
        socket_.close(ec);
    }

private:
    void read()
    {
        socket_.async_read_some(asio::buffer(buffer_),
            [self = shared_from_this()](const boost::system::error_code& ec, std::size_t n) {
                self->on_read(ec, n);
            });
    }

    void on_read(const boost::system::error_code& ec, std::size_t n)
    {
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
        session_->receive(std::string_view(buffer_.data(), n));
        if (!closed_)
            read();
    }

    void send(std::string_view bytes)
    {
        if (closed_)
            return;
        queued_bytes_ += bytes.size();
        if (queued_bytes_ > kMaxQueuedBytes) {
            log_.warn("{}: client reads nothing ({} bytes queued): closing the connection", peer_, queued_bytes_);
            end();
            return;
        }
        queue_.emplace_back(bytes);
        if (queue_.size() == 1)
            write();
    }

    void write()
    {
        asio::async_write(socket_, asio::buffer(queue_.front()),
            [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
                self->on_write(ec);
            });
    }

    void on_write(const boost::system::error_code& ec)
    {
        if (ec) {
            if (ec != asio::error::operation_aborted)
                log_.warn("{}: write failed: {}", peer_, ec.message());
            end();
            return;
        }
        queued_bytes_ -= queue_.front().size();
        queue_.pop_front();
        if (!queue_.empty())
            write();
    }

    void end()
    {
        close();
        endpoint_.forget(shared_from_this());
    }

    tcp::socket socket_;
    TcpEndpoint& endpoint_;
    spdlog::logger& log_;
    std::string peer_;
    std::unique_ptr<Session> session_;
    std::array<char, 4096> buffer_{};
    std::deque<std::string> queue_;
    std::size_t queued_bytes_ = 0;
    bool closed_ = false;
};

TcpEndpoint::TcpEndpoint(asio::io_context& io, Device& device, const asio::ip::address& bind,
                         std::uint16_t port, std::shared_ptr<spdlog::logger> log)
    : io_(io), device_(device), acceptor_(io), log_(std::move(log))
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
    acceptor_.async_accept([this](const boost::system::error_code& ec, tcp::socket socket) {
        if (ec) {
            if (ec == asio::error::operation_aborted || stopped_)
                return;
            log_->warn("tcp: accept failed: {}", ec.message());
        } else {
            auto c = std::make_shared<TcpConnection>(std::move(socket), *this, *log_);
            log_->info("{}: connected", c->peer());
            connections_.insert(c);
            c->start(device_);
        }
        accept();
    });
}

void TcpEndpoint::forget(const std::shared_ptr<TcpConnection>& c)
{
    connections_.erase(c);
}

void TcpEndpoint::stop()
{
    if (stopped_)
        return;
    stopped_ = true;
    boost::system::error_code ec;
    acceptor_.close(ec);
    for (const auto& c : connections_)
        c->close();
    connections_.clear();
}

} // namespace rigsim
