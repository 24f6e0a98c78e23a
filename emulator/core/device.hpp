#pragma once
// The seam between transports and protocols. A transport owns a file descriptor and, per
// connection, a Session that it feeds bytes; the session answers through `send`.
// Neither side knows the other's details.

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace rigsim {

class ControlSurface;   // emulator/core/control_surface.hpp

/// Hands bytes to the client of one connection. Each call is one frame (or one batch of
/// answers) that the transport writes in one piece.
using SendFn = std::function<void(std::string_view bytes)>;

/// How a transport ends a connection when its wire says so (the link's wire faults,
/// docs/control-api.md "Faults").
enum class Hangup {
    /// After what was sent: TCP writes what it has queued, then sends FIN (a half-close: what
    /// the client sends afterwards is read and dropped until it closes its side); the pty hangs
    /// up once the client has read what was written (or after a bound).
    Close,
    /// At once, whatever is unsent lost: TCP resets the connection (RST: SO_LINGER 0, then
    /// close); the pty hangs up.
    Reset,
};

/// What a transport tells a session about its connection beyond SendFn (Device::open_connection).
struct Connection {
    /// Ends the connection (and releases the session); the transport does it once the current
    /// call into or from the device has returned, never inside it.
    std::function<void(Hangup how)> hangup;
    /// Bytes the transport holds for the client now, each frame counted with `frame_overhead`
    /// on top of its payload, as against `max_queued_bytes` (its per-connection output bound).
    std::function<std::size_t()> queued_bytes;
    std::size_t max_queued_bytes = 0;
    std::size_t frame_overhead = 0;
    /// The baud rate the client has set on a serial line (its termios output speed); 0 when
    /// there is none (a socket) or it is not a standard rate.
    std::function<std::uint32_t()> client_baud;
};

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
    /// The same, from a transport that can end the connection on request and tells its output
    /// bound (`conn`); a device that never ends a connection itself ignores it.
    virtual std::unique_ptr<Session> open_connection(SendFn send, Connection conn, std::string peer)
    {
        (void)conn;
        return open_session(std::move(send), std::move(peer));
    }
    /// Baud rate at which the serial port (pty) paces the device's output; 0 = no pacing
    /// (the rig's `faithful_timing` is off).
    virtual std::uint32_t serial_baud() const { return 0; }
    /// Baud rate the unit's own serial port is configured for (MCS: CB; APT: 115200), paced or
    /// not; 0: unknown. A `baud_mismatch` wire fault compares a serial client's rate with it.
    virtual std::uint32_t line_baud() const { return serial_baud(); }
    /// What the control API reads and steers (nullptr: a device with none, as in transport tests).
    virtual ControlSurface* control() { return nullptr; }
    /// Called once every device of the rig exists and the world is linked (World::link_all()):
    /// the device may now read other devices' bodies and restores its non-volatile settings.
    virtual void power_up() {}
    /// When power_up() runs among the rig's devices: lower phases first, file order within a
    /// phase. A device whose power-up state others read in theirs (a signal it routes to them)
    /// returns 0 so that it is restored before they replay their own saved settings.
    virtual int power_up_phase() const { return 1; }
};

/// Power every device of `entries` up (Device::power_up()), lower phases first, in the
/// given order within a phase; `device_of(entry)` is the entry's Device&.
template <class Range, class DeviceOf>
void power_up_in_phases(Range& entries, DeviceOf device_of)
{
    std::vector<Device*> order;
    for (auto& e : entries)
        order.push_back(&device_of(e));
    std::stable_sort(order.begin(), order.end(),
                     [](const Device* a, const Device* b) { return a->power_up_phase() < b->power_up_phase(); });
    for (auto* d : order)
        d->power_up();
}

/// Whether the connection named `peer` is a serial line to the unit: the pty ("pty ...") or an
/// RFC 2217 port ("rfc2217 ..."), where a TCP socket is not.
inline bool is_serial_peer(std::string_view peer)
{
    return peer.substr(0, 3) == "pty" || peer.substr(0, 8) == "rfc2217 ";
}

/// Printable form of client bytes for log lines (non-printable bytes as \xNN, at most `max` bytes).
std::string printable(std::string_view bytes, std::size_t max = 80);

} // namespace rigsim
