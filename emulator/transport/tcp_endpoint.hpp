#pragma once
// TCP endpoint of one device: an acceptor and its connections. Bytes in, bytes out; the
// protocol lives in the Session each connection opens on the device.
//
// Resources are bounded: a connection beyond the per-device or the rig-wide limit is
// accepted and closed at once (one warning per second, however many are refused), and an
// accept that fails for want of descriptors or memory (EMFILE, ENFILE, ENOBUFS, ENOMEM) is
// retried after a back-off (100 ms doubling to 1 s) rather than at once, which would spin.

#include "emulator/core/device.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <spdlog/logger.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <set>

namespace rigsim {

class TcpConnection;

/// Connection limits and the count of open connections, shared by every TCP endpoint of a rig.
struct TcpConnectionBudget {
    std::size_t max_total = 256;        ///< all devices together (--max-connections)
    std::size_t max_per_device = 32;    ///< one device (--max-connections-per-device)
    std::size_t open_total = 0;         ///< connections open now, all devices together
};

class TcpEndpoint {
public:
    /// A client that reads nothing while answers pile up beyond this is dropped.
    static constexpr std::size_t kMaxQueuedBytes = 4 << 20;
    /// What a queued frame is counted beyond its bytes against kMaxQueuedBytes, so that the
    /// bound is one of memory, not payload, whatever the frames' size (set when each frame was a
    /// string of its own; a FrameQueue holds 4 bytes beside each frame, in pages of its own,
    /// and the bound is kept so that a client is dropped where it always was).
    static constexpr std::size_t kQueuedFrameOverhead = 64;
    /// First delay before an accept that failed for want of resources is retried.
    static constexpr std::chrono::milliseconds kAcceptBackoffMin{100};
    /// The delay doubles after each failure up to this.
    static constexpr std::chrono::milliseconds kAcceptBackoffMax{1000};

    /// Binds and listens at once (throws boost::system::system_error if it cannot).
    /// `budget` is shared with the rig's other endpoints and must outlive this one.
    TcpEndpoint(boost::asio::io_context& io, Device& device, const boost::asio::ip::address& bind,
                std::uint16_t port, std::shared_ptr<spdlog::logger> log, TcpConnectionBudget& budget);
    ~TcpEndpoint();
    TcpEndpoint(const TcpEndpoint&) = delete;
    TcpEndpoint& operator=(const TcpEndpoint&) = delete;

    /// The port actually bound (the ephemeral one when 0 was asked for).
    std::uint16_t port() const { return port_; }
    boost::asio::ip::tcp::endpoint local_endpoint() const;
    void start();
    /// Stop accepting, close every connection and release its session.
    void stop();

    /// Called by a connection when it ends.
    void forget(const std::shared_ptr<TcpConnection>& c);

private:
    void accept();
    void on_accept_failed(const boost::system::error_code& ec);
    /// Accepts `socket` as a connection, or refuses it (closes it) beyond a limit.
    void admit(boost::asio::ip::tcp::socket socket);
    void refuse(boost::asio::ip::tcp::socket socket, const char* limit_name, std::size_t limit,
                std::size_t open);
    void report_refusals();
    /// report_refusals() in one second.
    void arm_refusal_timer();

    Device& device_;
    boost::asio::ip::tcp::acceptor acceptor_;
    std::uint16_t port_;
    std::shared_ptr<spdlog::logger> log_;
    TcpConnectionBudget& budget_;
    std::set<std::shared_ptr<TcpConnection>> connections_;
    boost::asio::steady_timer backoff_timer_;
    std::chrono::milliseconds backoff_{0};
    std::size_t accept_failures_ = 0;    ///< consecutive failed accepts
    boost::asio::steady_timer refusal_timer_;
    bool refusal_timer_armed_ = false;
    std::size_t refusals_unreported_ = 0;
    bool stopped_ = false;
    std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

} // namespace rigsim
