#include "emulator/daemon/usb_serial.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace rigsim {
namespace {

/// Times within this of each other are the same (sums of fractional ticks).
constexpr double kSlack = 1e-9;

} // namespace

UsbSerialBuffer::UsbSerialBuffer(UsbSerialTiming timing, double since)
    : timing_(timing), timer_start_(0)
{
    timing_.latency_ticks = std::max(timing_.latency_ticks, kSlack);
    timing_.frame_ticks = std::max(timing_.frame_ticks, kSlack);
    timing_.packet_bytes = std::max<std::size_t>(timing_.packet_bytes, 1);
    timer_start_ = frame_at_or_after(since);
}

void UsbSerialBuffer::feed(double first, double per_byte, std::string bytes)
{
    if (bytes.empty())
        return;
    // The chip takes the bytes in the order the UART gives them: none before the last.
    per_byte = std::max(per_byte, 0.0);
    if (bytes_ > 0)
        first = std::max(first, last_);
    last_ = first + static_cast<double>(bytes.size() - 1) * per_byte;
    bytes_ += bytes.size();
    pieces_.push_back(Piece{first, per_byte, std::move(bytes), 0});
}

double UsbSerialBuffer::arrival(std::size_t n) const
{
    for (const auto& p : pieces_) {
        const auto left = p.bytes.size() - p.sent;
        if (n < left)
            return p.first + static_cast<double>(p.sent + n) * p.per_byte;
        n -= left;
    }
    return std::numeric_limits<double>::infinity();
}

std::size_t UsbSerialBuffer::come_by(double t, std::size_t limit) const
{
    std::size_t n = 0;
    for (const auto& p : pieces_) {
        if (n >= limit || p.first > t + kSlack)
            break;
        const auto left = p.bytes.size() - p.sent;
        std::size_t k = left;
        if (p.per_byte > 0) {
            const double came = std::floor(std::max(0.0, t - p.first + kSlack) / p.per_byte);
            const auto upto = static_cast<std::size_t>(came) + 1;
            k = upto > p.sent ? std::min(left, upto - p.sent) : 0;
        }
        n += k;
        if (k < left)
            break;
    }
    return std::min(n, limit);
}

double UsbSerialBuffer::frame_at_or_after(double t) const
{
    return std::ceil(t / timing_.frame_ticks - kSlack) * timing_.frame_ticks;
}

std::pair<double, std::size_t> UsbSerialBuffer::next() const
{
    if (bytes_ == 0)
        return {std::numeric_limits<double>::infinity(), 0};
    const auto full = timing_.packet_bytes;
    // A full packet goes at the frame after its last byte came.
    const double full_at = bytes_ >= full ? frame_at_or_after(arrival(full - 1))
                                          : std::numeric_limits<double>::infinity();
    // The timer expires every latency period while only status bytes go; the first expiry at or
    // after the first buffered byte came sends what has come by then.
    const double first = arrival(0);
    const double periods = std::max(1.0, std::ceil((first - timer_start_ - kSlack) / timing_.latency_ticks));
    const double timer_at = frame_at_or_after(timer_start_ + periods * timing_.latency_ticks);
    if (full_at <= timer_at + kSlack)
        return {full_at, full};
    // The first byte has come by then (the expiry is at or after it): at least it goes.
    return {timer_at, std::max<std::size_t>(1, come_by(timer_at, full))};
}

Ticks UsbSerialBuffer::next_packet() const
{
    const auto [at, n] = next();
    if (n == 0)
        return kNever;
    return static_cast<Ticks>(std::ceil(at - kSlack));
}

std::string UsbSerialBuffer::take(std::size_t n)
{
    std::string out;
    out.reserve(n);
    while (n > 0 && !pieces_.empty()) {
        auto& p = pieces_.front();
        const auto k = std::min(n, p.bytes.size() - p.sent);
        out.append(p.bytes, p.sent, k);
        p.sent += k;
        n -= k;
        bytes_ -= k;
        if (p.sent == p.bytes.size())
            pieces_.pop_front();
    }
    return out;
}

void UsbSerialBuffer::clear()
{
    pieces_.clear();
    bytes_ = 0;
}

} // namespace rigsim
