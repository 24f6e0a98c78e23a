#pragma once
// The seam between transports and protocols. A transport owns a file descriptor and, per
// connection, a Session that it feeds bytes; the session answers through `send`.
// Neither side knows the other's details.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

namespace rigsim {

class ControlSurface;   // emulator/core/control_surface.hpp

/// Hands bytes to the client of one connection. Each call is one frame (or one batch of
/// answers) that the transport writes in one piece.
using SendFn = std::function<void(std::string_view bytes)>;

/// One client connection's protocol state (its framer) bound to a device.
class Session {
public:
    virtual ~Session() = default;
    /// Bytes from the client, in whatever pieces the transport read them.
    virtual void receive(std::string_view bytes) = 0;
};

/// A device of the rig as the transports see it.
class Device {
public:
    virtual ~Device() = default;
    /// A new connection; `peer` names it in logs ("tcp 127.0.0.1:53122", "pty").
    virtual std::unique_ptr<Session> open_session(SendFn send, std::string peer) = 0;
    /// Baud rate at which the serial port (pty) paces the device's output; 0 = no pacing
    /// (the rig's `faithful_timing` is off).
    virtual std::uint32_t serial_baud() const { return 0; }
    /// What the control API reads and steers (nullptr: a device with none, as in transport tests).
    virtual ControlSurface* control() { return nullptr; }
    /// Called once every device of the rig exists and the world is linked (World::link_all()):
    /// the device may now read other devices' bodies and restores its non-volatile settings.
    virtual void power_up() {}
};

/// Printable form of client bytes for log lines (non-printable bytes as \xNN, at most `max` bytes).
std::string printable(std::string_view bytes, std::size_t max = 80);

} // namespace rigsim
