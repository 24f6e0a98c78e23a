#pragma once
// A device's serial port over RFC 2217 (emulator/transport/rfc2217.hpp): a TcpEndpoint on this
// device serves pyserial's rfc2217:// and other RFC 2217 clients. Each connection's client bytes
// go through the codec: its answers back to the client at once, its serial data to the device
// as a serial line's (the session's peer is "rfc2217 <address>": faithful timing, the link
// model and a baud_mismatch fault treat it as they treat the pty, with the rate the client set
// over RFC 2217 as its rate); the device's bytes go to the client with 0xFF doubled, held while
// the client has suspended the flow (at most kMaxSuspendedBytes, dropped beyond with a warning).

#include "emulator/core/device.hpp"

#include <cstddef>
#include <memory>
#include <string>

namespace spdlog {
class logger;
}

namespace rigsim {

class Rfc2217Device : public Device {
public:
    /// Bytes held for a client that suspended the flow (FLOWCONTROL-SUSPEND).
    static constexpr std::size_t kMaxSuspendedBytes = 1 << 20;

    /// Serves `inner`'s sessions; what the clients get wrong is logged to `log`.
    Rfc2217Device(Device& inner, std::shared_ptr<spdlog::logger> log);

    std::unique_ptr<Session> open_session(SendFn send, std::string peer) override;
    std::unique_ptr<Session> open_connection(SendFn send, Connection conn, std::string peer) override;
    std::uint32_t serial_baud() const override { return inner_.serial_baud(); }
    std::uint32_t line_baud() const override { return inner_.line_baud(); }
    ControlSurface* control() override { return inner_.control(); }

private:
    Device& inner_;
    std::shared_ptr<spdlog::logger> log_;
};

} // namespace rigsim
