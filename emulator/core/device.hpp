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

/// Printable form of client bytes for log lines (non-printable bytes as \xNN, at most `max` bytes).
std::string printable(std::string_view bytes, std::size_t max = 80);

} // namespace rigsim
