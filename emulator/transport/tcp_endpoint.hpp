#pragma once
// TCP endpoint of one device: an acceptor and its connections. Bytes in, bytes out; the
// protocol lives in the Session each connection opens on the device.

#include "emulator/core/device.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <spdlog/logger.h>

#include <cstdint>
#include <memory>
#include <set>

namespace rigsim {

class TcpConnection;

class TcpEndpoint {
public:
    /// Binds and listens at once (throws boost::system::system_error if it cannot).
    TcpEndpoint(boost::asio::io_context& io, Device& device, const boost::asio::ip::address& bind,
                std::uint16_t port, std::shared_ptr<spdlog::logger> log);
    ~TcpEndpoint();

    /// The port actually bound (the ephemeral one when 0 was asked for).
    std::uint16_t port() const { return port_; }
    boost::asio::ip::tcp::endpoint local_endpoint() const;
    void start();
    void stop();

    /// Called by a connection when it ends.
    void forget(const std::shared_ptr<TcpConnection>& c);

private:
    void accept();

    boost::asio::io_context& io_;
    Device& device_;
    boost::asio::ip::tcp::acceptor acceptor_;
    std::uint16_t port_;
    std::shared_ptr<spdlog::logger> log_;
    std::set<std::shared_ptr<TcpConnection>> connections_;
    bool stopped_ = false;
};

} // namespace rigsim
