#pragma once
// The unit's side of a USB-serial link (an FTDI chip, as in every Thorlabs APT controller and
// many a serial unit's cable): the bytes the unit's UART hands to the chip wait in its buffer
// until the host is sent them in a USB packet, and a packet goes only
//   - when the buffer holds a full packet's data (62 bytes: 64 less the chip's 2 status bytes),
//     at the next USB frame (1 ms at full speed), or
//   - when the latency timer expires (16 ms by default, 1..255 ms), with whatever the buffer
//     holds (nothing but the status bytes when it is empty),
// and each packet sent, full or not, restarts the latency timer (FTDI application note
// AN232B-04, "Data Throughput, Latency and Handshaking", sections 3.1 and 3.3). A 12-byte answer
// thus waits for the timer, and a 90-byte one goes in two packets: 62 bytes at the frame after the
// 62nd byte came, the last 28 one latency period later.
//
// All times are clock ticks as doubles (a tick may be shorter or longer than a USB frame); a
// packet's time is rounded up to a whole tick when it is released.

#include "models/clock.hpp"

#include <cmath>
#include <cstddef>
#include <deque>
#include <string>

namespace rigsim {

/// The chip's timing, in clock ticks.
struct UsbSerialTiming {
    double latency_ticks = 16;    ///< the latency timer
    double frame_ticks = 1;       ///< one USB frame
    std::size_t packet_bytes = 62;   ///< the data of a full packet
};

class UsbSerialBuffer {
public:
    /// The latency timer runs from `since` (when the chip was plugged in: the session opened).
    UsbSerialBuffer(UsbSerialTiming timing, double since);

    /// Bytes from the unit's UART: byte i has come at `first + i * per_byte`.
    void feed(double first, double per_byte, std::string bytes);
    /// The tick at which the next packet goes to the host, kNever when the buffer is empty.
    Ticks next_packet() const;
    /// Hands the packets due by `now` to `emit(std::string)`, in order.
    template <typename Emit>
    void release(Ticks now, Emit&& emit);

    /// Bytes and feeds buffered (a feed counts until its last byte has gone).
    std::size_t bytes() const { return bytes_; }
    std::size_t pieces() const { return pieces_.size(); }
    /// Drops every buffered byte; the latency timer keeps its phase.
    void clear();

private:
    struct Piece {
        double first = 0;
        double per_byte = 0;
        std::string bytes;
        std::size_t sent = 0;   ///< bytes of it already in a packet
    };

    /// The time of the next packet (fractional ticks; +inf when empty) and its size.
    std::pair<double, std::size_t> next() const;
    /// When the `n`th buffered byte (0-based) has come.
    double arrival(std::size_t n) const;
    /// How many buffered bytes (at most `limit`) have come by `t`.
    std::size_t come_by(double t, std::size_t limit) const;
    /// The first USB frame boundary at or after `t`.
    double frame_at_or_after(double t) const;
    /// Takes `n` bytes from the front.
    std::string take(std::size_t n);

    UsbSerialTiming timing_;
    double timer_start_;      ///< the last packet (or the plug-in): the latency timer runs from it
    std::deque<Piece> pieces_;
    std::size_t bytes_ = 0;
    double last_ = 0;         ///< when the last buffered byte comes
};

template <typename Emit>
void UsbSerialBuffer::release(Ticks now, Emit&& emit)
{
    for (;;) {
        const auto [at, n] = next();
        if (n == 0 || static_cast<Ticks>(std::ceil(at - 1e-9)) > now)
            return;
        timer_start_ = at;
        emit(take(n));
    }
}

} // namespace rigsim
