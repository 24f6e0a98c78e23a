#include "emulator/daemon/link.hpp"
#include "emulator/core/log_format.hpp"
#include "emulator/daemon/usb_serial.hpp"

#include <algorithm>
#include <cmath>

namespace rigsim {

std::string uart_resample(std::string_view sent, std::uint32_t sent_baud, std::uint32_t read_baud)
{
    if (sent_baud == 0 || read_baud == 0 || sent_baud == read_baud)
        return std::string(sent);
    // The line, one entry per bit at the sender's rate: start (0), 8 data bits LSB first,
    // stop (1); idle (1) before and after.
    std::vector<bool> line;
    line.reserve(sent.size() * 10);
    for (const char c : sent) {
        const auto byte = static_cast<unsigned char>(c);
        line.push_back(false);
        for (int bit = 0; bit < 8; ++bit)
            line.push_back(((byte >> bit) & 1) != 0);
        line.push_back(true);
    }
    const auto level = [&](double t) {   // t in the sender's bit times
        if (t < 0)
            return true;
        const auto i = static_cast<std::size_t>(t);
        return i >= line.size() ? true : static_cast<bool>(line[i]);
    };
    // One reader bit time in the sender's bit times.
    const double r = static_cast<double>(sent_baud) / static_cast<double>(read_baud);
    std::string out;
    double t = 0;
    for (;;) {
        // The next falling edge (mark to space) at or after t: edges fall on the sender's bit
        // boundaries.
        auto k = static_cast<std::size_t>(std::ceil(t));
        while (k < line.size() && (line[k] || (k > 0 && !line[k - 1])))
            ++k;
        if (k >= line.size())
            break;
        const double edge = static_cast<double>(k);
        if (level(edge + 0.5 * r)) {   // the start bit is gone by its middle: a glitch
            t = edge + 0.5 * r;
            if (t <= edge)
                t = edge + 1;
            continue;
        }
        unsigned byte = 0;
        for (int bit = 0; bit < 8; ++bit)
            if (level(edge + (1.5 + bit) * r))
                byte |= 1u << bit;
        out.push_back(static_cast<char>(byte));
        // Looks for the next start bit after the stop bit's middle (a framing error included).
        t = std::max(edge + 9.5 * r, edge + 1);
    }
    return out;
}

/// One connection through the link: client bytes to the device's session, the device's bytes
/// to the client, each through the link's faults.
class Link::LinkSession : public Session {
public:
    LinkSession(Link& link, SendFn send, Connection conn, std::string peer)
        : link_(link), send_(std::move(send)), conn_(std::move(conn)), serial_(is_serial_peer(peer)),
          peer_(peer)
    {
        link_.sessions_.push_back(this);
        if (const auto& m = link_.model_; m && (serial_ || m->tcp)) {
            const double hz = link_.clock_.tick_hz();
            usb_.emplace(UsbSerialTiming{m->latency_timer_ms * hz / 1e3, m->usb_frame_us * hz / 1e6, m->packet_bytes},
                         static_cast<double>(link_.clock_.now()));
        }
        // The device may end the connection itself (an MCS2's *RST): it goes through to the
        // transport; the other parts of the connection are the transport's as they are.
        Connection inner;
        if (conn_.hangup)   // a close goes after what the link still holds for the client
            inner.hangup = [this](Hangup how) {
                if (how == Hangup::Close)
                    begin_close();
                else if (state_ != State::Closed)
                    conn_.hangup(how);
            };
        inner.queued_bytes = conn_.queued_bytes;
        inner.max_queued_bytes = conn_.max_queued_bytes;
        inner.frame_overhead = conn_.frame_overhead;
        inner.client_baud = conn_.client_baud;
        inner_ = link_.inner_.open_connection([this](std::string_view bytes) { out(bytes); }, std::move(inner),
                                              std::move(peer));
    }
    ~LinkSession() override
    {
        // A client's last writes waiting for the USB frame still reach the unit: the host's driver
        // sends what was written before the port closes (a script's `printf ... > port`).
        // Closed first: the device's answers have no client any more, and a hang-up it asks for
        // has nothing to end.
        state_ = State::Closed;
        if (usb_)
            deliver_held_requests();
        inner_.reset();   // before the link forgets us: it may still send while closing
        link_.held_pieces_ -= held_.size() + in_held_.size() + (usb_ ? usb_->pieces() : 0);
        auto& s = link_.sessions_;
        s.erase(std::remove(s.begin(), s.end(), this), s.end());
        link_.changed();
    }

    void receive(std::string_view bytes) override
    {
        const Ticks now = link_.clock_.now();
        if (first_in_ == kNever) {
            first_in_ = now;
            if (!link_.closes_.empty())
                link_.changed();   // the closing faults' delays run from here
        }
        check(now);
        if (state_ != State::Open || link_.unplugged() || link_.close_fault(CloseKind::HangClose))
            return;
        std::string_view kept = bytes;
        bool cut = false;
        if (const auto* c = link_.close_fault(CloseKind::CutAfter); c && c->f.inbound) {
            const auto left = c->f.bytes - std::min(c->f.bytes, counted(*c));
            kept = kept.substr(0, static_cast<std::size_t>(std::min<std::uint64_t>(left, kept.size())));
            cut_count_ += kept.size();
            cut = cut_count_ >= c->f.bytes;
        }
        std::string filtered;
        if (!link_.byte_faults_.empty()) {
            filtered = link_.filter(kept, true);
            kept = filtered;
        }
        if (link_.baud_.id != 0 && link_.baud_.inbound)
            if (const auto rates = mismatched_rates(); rates.first != 0) {
                link_.corrupted_ += kept.size();
                filtered = uart_resample(kept, rates.first, rates.second);
                kept = filtered;
            }
        if (!kept.empty()) {
            if (link_.bandwidth_.id != 0 && link_.bandwidth_.inbound)
                throttle_in(kept, now);
            else if (usb_)   // the host sends them in the next USB frame, the chip's UART on
                hold_in(usb_in(kept.size(), now), std::string(kept));
            else if (in_held_.empty())
                deliver(kept, now);
            else
                hold_in(now, std::string(kept));
        }
        if (cut)
            begin_close();
    }

    /// Held bytes whose time has come go on, and closes whose time has come happen.
    void release(Ticks now)
    {
        while (!in_held_.empty() && in_held_.front().first <= now && state_ == State::Open) {
            in_held_bytes_ -= in_held_.front().second.size();
            --link_.held_pieces_;
            const auto bytes = std::move(in_held_.front().second);
            in_held_.pop_front();
            deliver(bytes, now);
        }
        while (!held_.empty() && held_.front().first <= now) {
            held_cost_ -= cost_of(held_.front().second.size());
            --link_.held_pieces_;
            const auto bytes = std::move(held_.front().second);
            held_.pop_front();
            send_(bytes);
        }
        if (usb_) {
            const auto before = usb_->pieces();
            usb_->release(now, [&](const std::string& packet) { send_(packet); });
            link_.held_pieces_ -= before - usb_->pieces();
        }
        check(now);
        finish_close();
    }
    Ticks next_due(Ticks now) const
    {
        Ticks next = held_.empty() ? kNever : held_.front().first;
        if (!in_held_.empty())
            next = std::min(next, in_held_.front().first);
        if (usb_)
            next = std::min(next, usb_->next_packet());
        if (state_ == State::Open)
            next = std::min(next, next_close(now));
        return next;
    }
    void drop_held()
    {
        link_.held_pieces_ -= held_.size() + in_held_.size() + (usb_ ? usb_->pieces() : 0);
        if (usb_)
            usb_->clear();
        held_.clear();
        in_held_.clear();
        held_cost_ = 0;
        in_held_bytes_ = 0;
        line_free_ = 0;
        in_line_free_ = 0;
        unit_free_ = 0;
        out_free_ = 0;
        in_free_ = 0;
        link_.changed();
    }
    std::size_t held() const { return held_.size() + (usb_ ? usb_->pieces() : 0); }
    std::size_t held_requests() const { return in_held_.size(); }

    /// Acts on the closing faults due by `now`.
    void check(Ticks now)
    {
        if (state_ != State::Open)
            return;
        for (const auto& c : link_.closes_) {
            if (c.f.kind == CloseKind::CutAfter) {
                if (counted(c) >= c.f.bytes)
                    begin_close();
            } else if (close_time(c) <= now) {
                fire(c, now);
            }
            if (state_ != State::Open)
                return;
        }
    }

private:
    enum class State {
        Open,
        Closing,   ///< a close is due: what is held goes out, then Hangup::Close
        Closed,    ///< the transport was asked to end the connection
    };

    /// The rates a baud_mismatch fault compares (client, unit), or {0, 0} when they agree or
    /// this is not a serial line.
    std::pair<std::uint32_t, std::uint32_t> mismatched_rates() const
    {
        if (!serial_ || !conn_.client_baud)
            return {0, 0};
        const auto client = conn_.client_baud();
        const auto unit = link_.inner_.line_baud();
        if (client == 0 || unit == 0 || client == unit)
            return {0, 0};
        return {client, unit};
    }

    /// Bytes counted towards cut fault `c` on this connection.
    std::uint64_t counted(const ActiveClose& c)
    {
        if (cut_id_ != c.f.id) {
            cut_id_ = c.f.id;
            cut_count_ = 0;
        }
        return cut_count_;
    }

    /// When timed closing fault `c` acts here (kNever: no client byte yet).
    Ticks close_time(const ActiveClose& c) const
    {
        if (first_in_ == kNever)
            return kNever;
        return std::max(c.since, first_in_) + c.f.delay;
    }
    Ticks next_close(Ticks now) const
    {
        Ticks next = kNever;
        for (const auto& c : link_.closes_)
            if (c.f.kind != CloseKind::CutAfter)
                next = std::min(next, close_time(c));
        return next <= now ? now + 1 : next;
    }

    void fire(const ActiveClose& c, Ticks now)
    {
        switch (c.f.kind) {
        case CloseKind::Reset:
            drop_held();
            state_ = State::Closed;
            if (conn_.hangup)
                conn_.hangup(Hangup::Reset);
            return;
        case CloseKind::HangClose:
            drop_held();
            state_ = State::Closed;
            if (conn_.hangup)
                conn_.hangup(Hangup::Close);
            return;
        case CloseKind::SlowClose:
            begin_close();
            return;
        case CloseKind::GarbageClose: {
            drop_held();
            std::mt19937 rng(c.f.seed);
            std::string garbage(static_cast<std::size_t>(c.f.bytes), '\0');
            for (auto& b : garbage)
                b = static_cast<char>(rng() & 0xFF);
            push(now, std::move(garbage), now);
            begin_close();
            return;
        }
        case CloseKind::CutAfter:
            return;
        }
    }

    void begin_close()
    {
        if (state_ != State::Open)
            return;
        // What the link model's chip holds for its next frame reaches the device (the client
        // wrote it before the close), and its answers go out as those before; then nothing more
        // reaches the device, and what it said goes out first.
        if (usb_)
            deliver_held_requests();
        state_ = State::Closing;
        link_.held_pieces_ -= in_held_.size();
        in_held_.clear();
        in_held_bytes_ = 0;
        finish_close();
    }
    void finish_close()
    {
        if (state_ != State::Closing || !held_.empty() || (usb_ && usb_->bytes() > 0))
            return;
        state_ = State::Closed;
        if (conn_.hangup)
            conn_.hangup(Hangup::Close);
    }

    void out(std::string_view bytes)
    {
        if (state_ != State::Open || link_.unplugged() || link_.close_fault(CloseKind::HangClose))
            return;
        std::string filtered;
        if (!link_.byte_faults_.empty()) {
            filtered = link_.filter(bytes, false);
            if (filtered.empty())
                return;
            bytes = filtered;
        }
        if (link_.baud_.id != 0 && link_.baud_.outbound)
            if (const auto rates = mismatched_rates(); rates.first != 0) {
                link_.corrupted_ += bytes.size();
                filtered = uart_resample(bytes, rates.second, rates.first);
                bytes = filtered;
            }
        bool cut = false;
        if (const auto* c = link_.close_fault(CloseKind::CutAfter); c && !c->f.inbound) {
            const auto left = c->f.bytes - std::min(c->f.bytes, counted(*c));
            bytes = bytes.substr(0, static_cast<std::size_t>(std::min<std::uint64_t>(left, bytes.size())));
            cut_count_ += bytes.size();
            cut = cut_count_ >= c->f.bytes;
        }
        if (!bytes.empty()) {
            const Ticks now = link_.clock_.now();
            const double at = usb_ ? ready(now) : static_cast<double>(link_.due(now));
            if (link_.slice_.id == 0) {
                place(bytes, at, now);
            } else {
                for (std::size_t i = 0; i < bytes.size(); i += link_.slice_.slice_bytes) {
                    const double slice_at = sliced_ ? std::max(at, static_cast<double>(slice_last_ + link_.slice_.gap)) : at;
                    slice_last_ = place(bytes.substr(i, link_.slice_.slice_bytes), slice_at, now);
                    sliced_ = true;
                }
            }
        }
        if (cut)
            begin_close();
    }

    /// Holds `piece` until the line (serial pace, bandwidth) has carried it, from `at`; returns
    /// when its last byte has left the unit.
    Ticks place(std::string_view piece, double at, Ticks now)
    {
        const double tick_hz = link_.clock_.tick_hz();
        const auto baud = serial_ ? link_.inner_.serial_baud() : 0;
        if (link_.bandwidth_.id != 0 && link_.bandwidth_.outbound) {
            // Each byte passes 1/rate after the one before it, as the clock ticks: the bytes of
            // one tick go together.
            double per_byte = tick_hz / link_.bandwidth_.bytes_per_s;
            if (baud > 0)
                per_byte = std::max(per_byte, 10.0 * tick_hz / baud);
            double t = std::max(out_free_, at);
            std::size_t start = 0;
            Ticks piece_at = 0;
            for (std::size_t i = 0; i < piece.size(); ++i) {
                t += per_byte;
                const auto byte_at = static_cast<Ticks>(std::ceil(t));
                if (i > start && byte_at != piece_at) {
                    hand(static_cast<double>(piece_at), 0, piece.substr(start, i - start), now);
                    start = i;
                }
                piece_at = byte_at;
            }
            out_free_ = t;
            hand(static_cast<double>(piece_at), 0, piece.substr(start), now);
            return piece_at;
        }
        // Faithful timing (a serial line: the pty, "pty <path>", or an RFC 2217 port): the bytes arrive when
        // the line has carried them, 10 bits per byte at the device's baud rate, after
        // whatever it still carries.
        if (baud > 0) {
            const double per_byte = 10.0 * tick_hz / baud;
            const double start = std::max(line_free_, at);
            line_free_ = start + static_cast<double>(piece.size()) * per_byte;
            hand(start + per_byte, per_byte, piece, now);
            return static_cast<Ticks>(std::ceil(line_free_ - 1e-9));
        }
        hand(at, 0, piece, now);
        return static_cast<Ticks>(std::ceil(at - 1e-9));
    }

    /// Bytes that have left the unit, byte i at `first + i * per_byte`: to the USB-serial chip
    /// if there is one, else to the client once the last has come.
    void hand(double first, double per_byte, std::string_view piece, Ticks now)
    {
        if (!usb_) {
            const double last = first + static_cast<double>(piece.size() - 1) * per_byte;
            push(static_cast<Ticks>(std::ceil(last - 1e-9)), std::string(piece), now);
            return;
        }
        if (!admit(piece.size()))
            return;
        usb_->feed(first, per_byte, std::string(piece));
        ++link_.held_pieces_;
        link_.changed();
    }

    /// When `size` client bytes written now reach the unit: in the next USB frame, then as the
    /// chip's UART carries them on a paced serial line.
    Ticks usb_in(std::size_t size, Ticks now)
    {
        const auto frame = static_cast<double>(next_frame(now));
        const auto baud = serial_ ? link_.inner_.serial_baud() : 0;
        if (baud == 0)
            return static_cast<Ticks>(frame);
        in_line_free_ = std::max(in_line_free_, frame) + static_cast<double>(size) * 10.0 * link_.clock_.tick_hz() / baud;
        return static_cast<Ticks>(std::ceil(in_line_free_ - 1e-9));
    }

    /// When an answer the unit begins now is ready: after the answers before it on this
    /// connection and the link model's processing time.
    double ready(Ticks now)
    {
        const auto at = static_cast<double>(link_.due(now));
        const auto processing = link_.model_->processing_us;
        if (processing == 0)
            return at;
        unit_free_ = std::max(unit_free_, at) + processing * link_.clock_.tick_hz() / 1e6;
        return unit_free_;
    }

    /// The tick of the first USB frame after `now`.
    Ticks next_frame(Ticks now) const
    {
        const double frame = link_.model_->usb_frame_us * link_.clock_.tick_hz() / 1e6;
        const double t = (std::floor(static_cast<double>(now) / frame + 1e-9) + 1) * frame;
        return std::max(now, static_cast<Ticks>(std::ceil(t - 1e-9)));
    }

    /// Bytes the USB-serial chip holds, as the output bound counts them.
    std::size_t usb_cost() const
    {
        return usb_ ? usb_->bytes() + usb_->pieces() * cost_of(0) : 0;
    }

    /// Whether `size` more bytes may be held for the client: held bytes, the chip's and what the
    /// transport has queued share the connection's output bound. Beyond it they are dropped,
    /// with a warning, as the transport would.
    bool admit(std::size_t size)
    {
        const auto cost = cost_of(size);
        const std::size_t queued = conn_.queued_bytes ? conn_.queued_bytes() : 0;
        const std::size_t bound = conn_.max_queued_bytes > 0 ? conn_.max_queued_bytes : kMaxHeldBytes;
        if (held_cost_ + usb_cost() + queued + cost > bound) {
            // Nobody reads, or the faults hold more than the connection may.
            if (dropping_ == 0 && link_.log_)
                link_.log_->warn("{}: {} bytes held back by the wire and {} queued: dropping answers "
                                 "beyond the connection's bound ({} bytes)",
                                 peer_, held_cost_ + usb_cost(), queued, bound);
            dropping_ += size;
            link_.dropped_ += size;
            return false;
        }
        if (dropping_ > 0 && link_.log_)
            link_.log_->warn("{}: dropped {} bytes of answers held back by the wire's faults", peer_, dropping_);
        dropping_ = 0;
        return true;
    }

    std::size_t cost_of(std::size_t bytes) const
    {
        return bytes + (conn_.max_queued_bytes > 0 ? conn_.frame_overhead : kHeldFrameOverhead);
    }

    /// Sends `bytes` at `at`: now if nothing is held ahead of them, else in order behind what is.
    void push(Ticks at, std::string bytes, Ticks now)
    {
        if (at <= now && held_.empty()) {
            send_(bytes);
            return;
        }
        if (!admit(bytes.size()))
            return;
        held_cost_ += cost_of(bytes.size());
        ++link_.held_pieces_;
        // A wire keeps its order: a later answer never overtakes an earlier one.
        held_.emplace_back(std::max(at, held_.empty() ? at : held_.back().first), std::move(bytes));
        link_.changed();   // held: the link is due when they are
    }

    /// Client bytes through a bandwidth fault: each passes 1/rate after the one before it.
    void throttle_in(std::string_view bytes, Ticks now)
    {
        const double per_byte = link_.clock_.tick_hz() / link_.bandwidth_.bytes_per_s;
        double t = std::max(in_free_, static_cast<double>(now));
        std::size_t start = 0;
        Ticks piece_at = 0;
        for (std::size_t i = 0; i < bytes.size(); ++i) {
            t += per_byte;
            const auto byte_at = static_cast<Ticks>(std::ceil(t));
            if (i > start && byte_at != piece_at) {
                hold_in(piece_at, std::string(bytes.substr(start, i - start)));
                start = i;
            }
            piece_at = byte_at;
        }
        in_free_ = t;
        hold_in(piece_at, std::string(bytes.substr(start)));
    }
    /// The client bytes held for the link model's USB frame, to the device now.
    void deliver_held_requests()
    {
        const Ticks now = link_.clock_.now();
        while (!in_held_.empty()) {
            in_held_bytes_ -= in_held_.front().second.size();
            --link_.held_pieces_;
            const auto bytes = std::move(in_held_.front().second);
            in_held_.pop_front();
            deliver(bytes, now);
        }
    }

    void hold_in(Ticks at, std::string bytes)
    {
        if (in_held_bytes_ + bytes.size() > kMaxHeldBytes) {
            if (!dropping_in_ && link_.log_)
                link_.log_->warn("{}: {} client bytes held back by a bandwidth fault: dropping input beyond {} bytes",
                                 peer_, in_held_bytes_, kMaxHeldBytes);
            dropping_in_ = true;
            link_.dropped_ += bytes.size();
            return;
        }
        dropping_in_ = false;
        in_held_bytes_ += bytes.size();
        at = std::max(at, in_held_.empty() ? at : in_held_.back().first);
        if (!in_held_.empty() && in_held_.back().first == at) {   // one piece per tick, however many writes
            in_held_.back().second += bytes;
            return;
        }
        ++link_.held_pieces_;
        in_held_.emplace_back(at, std::move(bytes));
        link_.changed();
    }

    /// Client bytes reach the unit: through its receive buffer if it overruns.
    void deliver(std::string_view bytes, Ticks now)
    {
        if (serial_ && link_.overrun_.id != 0) {
            const auto& o = link_.overrun_;
            if (level_at_ < now)
                level_ = std::max(0.0, level_ - static_cast<double>(now - level_at_) * o.drain_bytes_per_s
                                                    / link_.clock_.tick_hz());
            level_at_ = now;
            const double room = std::floor(static_cast<double>(o.buffer_bytes) - level_);
            const auto fit = static_cast<std::size_t>(std::clamp(room, 0.0, static_cast<double>(bytes.size())));
            level_ += static_cast<double>(fit);
            link_.dropped_ += bytes.size() - fit;
            bytes = bytes.substr(0, fit);
            if (bytes.empty())
                return;
        }
        inner_->receive(bytes);
    }

    Link& link_;
    SendFn send_;
    Connection conn_;
    std::unique_ptr<Session> inner_;
    bool serial_;
    std::optional<UsbSerialBuffer> usb_;   ///< the link model's chip, on this connection
    std::string peer_;
    State state_ = State::Open;
    Ticks first_in_ = kNever;   ///< when the client's first byte came
    std::uint64_t cut_id_ = 0;  ///< the cut_after fault cut_count_ counts for
    std::uint64_t cut_count_ = 0;
    double line_free_ = 0;   ///< tick (fractional) at which the serial line has sent all it was given
    double out_free_ = 0;    ///< the same for a bandwidth fault, device to client
    double in_free_ = 0;     ///< and client to device
    double in_line_free_ = 0;   ///< the link model's chip has sent the unit all it was given
    double unit_free_ = 0;      ///< the link model: the unit has processed this connection's messages by then
    bool sliced_ = false;    ///< a slice went out (slice_last_ holds when)
    Ticks slice_last_ = 0;
    std::deque<std::pair<Ticks, std::string>> held_;      ///< to the client
    std::size_t held_cost_ = 0;                           ///< held_'s bytes and overhead
    std::deque<std::pair<Ticks, std::string>> in_held_;   ///< to the device
    std::size_t in_held_bytes_ = 0;
    std::size_t dropping_ = 0;     ///< answer bytes dropped at the bound since the last that fit
    bool dropping_in_ = false;
    double level_ = 0;             ///< overrun: bytes in the unit's receive buffer at level_at_
    Ticks level_at_ = 0;
};

Link::Link(Device& inner, Clock& clock, std::shared_ptr<spdlog::logger> log)
    : inner_(inner), clock_(clock), log_(std::move(log))
{
    // Its next change moves only when it holds bytes or a close comes due (announced there),
    // when held bytes go (a tick, a session closed, a reset) or when the clock ticks.
    clock_.add(this, Clock::Schedule::Announced);
}

Link::~Link()
{
    clock_.remove(this);
}

std::unique_ptr<Session> Link::open_session(SendFn send, std::string peer)
{
    return std::make_unique<LinkSession>(*this, std::move(send), Connection{}, std::move(peer));
}

std::unique_ptr<Session> Link::open_connection(SendFn send, Connection conn, std::string peer)
{
    return std::make_unique<LinkSession>(*this, std::move(send), std::move(conn), std::move(peer));
}

void Link::changed()
{
    clock_.changed(*this);
}

void Link::set_unplugged(std::uint64_t id, bool unplugged)
{
    unplugged_ = unplugged ? id : 0;
}

void Link::add(const ByteFault& f)
{
    byte_faults_.push_back(ActiveByteFault{f, std::mt19937(f.seed)});
}

void Link::add(const LatencyFault& f)
{
    latency_ = f;
    latency_rng_.seed(f.seed);
}

void Link::add(const SliceFault& f)
{
    slice_ = f;
}

void Link::add(const BandwidthFault& f)
{
    bandwidth_ = f;
}

void Link::add(const CloseFault& f)
{
    closes_.push_back(ActiveClose{f, clock_.now()});
    // Nothing more passes from now on a hanging wire: what it holds is lost.
    const auto sessions = sessions_;
    for (auto* s : sessions) {
        if (f.kind == CloseKind::HangClose)
            s->drop_held();
        s->check(clock_.now());
    }
    changed();
}

void Link::add(const OverrunFault& f)
{
    overrun_ = f;
}

void Link::add(const BaudMismatchFault& f)
{
    baud_ = f;
}

bool Link::remove(std::uint64_t id)
{
    if (id == 0)
        return false;
    if (unplugged_ == id) {
        unplugged_ = 0;
        return true;
    }
    if (latency_.id == id) {
        latency_ = LatencyFault{};
        return true;
    }
    if (slice_.id == id) {
        slice_ = SliceFault{};
        return true;
    }
    if (bandwidth_.id == id) {
        bandwidth_ = BandwidthFault{};
        return true;
    }
    if (overrun_.id == id) {
        overrun_ = OverrunFault{};
        return true;
    }
    if (baud_.id == id) {
        baud_ = BaudMismatchFault{};
        return true;
    }
    const auto close = std::find_if(closes_.begin(), closes_.end(), [&](const ActiveClose& c) { return c.f.id == id; });
    if (close != closes_.end()) {
        closes_.erase(close);
        changed();
        return true;
    }
    const auto it = std::find_if(byte_faults_.begin(), byte_faults_.end(),
                                 [&](const ActiveByteFault& a) { return a.f.id == id; });
    if (it == byte_faults_.end())
        return false;
    byte_faults_.erase(it);
    return true;
}

void Link::reset()
{
    unplugged_ = 0;
    byte_faults_.clear();
    latency_ = LatencyFault{};
    slice_ = SliceFault{};
    bandwidth_ = BandwidthFault{};
    closes_.clear();
    overrun_ = OverrunFault{};
    baud_ = BaudMismatchFault{};
    for (auto* s : sessions_)
        s->drop_held();
    dropped_ = 0;
    corrupted_ = 0;
}

std::size_t Link::held() const
{
    std::size_t n = 0;
    for (const auto* s : sessions_)
        n += s->held();
    return n;
}

std::size_t Link::held_requests() const
{
    std::size_t n = 0;
    for (const auto* s : sessions_)
        n += s->held_requests();
    return n;
}

const Link::ActiveClose* Link::close_fault(CloseKind kind) const
{
    for (const auto& c : closes_)
        if (c.f.kind == kind)
            return &c;
    return nullptr;
}

std::string Link::filter(std::string_view bytes, bool inbound)
{
    std::string out(bytes);
    for (auto& a : byte_faults_) {
        if (inbound ? !a.f.inbound : !a.f.outbound)
            continue;
        std::uniform_real_distribution<double> chance(0.0, 1.0);
        std::string kept;
        kept.reserve(out.size());
        for (const char c : out) {
            if (chance(a.rng) >= a.f.probability) {
                kept.push_back(c);
            } else if (a.f.corrupt) {
                kept.push_back(static_cast<char>(static_cast<unsigned char>(c) ^ (1u << (a.rng() % 8))));
                ++corrupted_;
            } else {
                ++dropped_;
            }
        }
        out.swap(kept);
    }
    return out;
}

Ticks Link::due(Ticks now)
{
    if (latency_.id == 0)
        return now;
    Ticks jitter = 0;
    if (latency_.jitter > 0)
        jitter = std::uniform_int_distribution<Ticks>(0, latency_.jitter)(latency_rng_);
    return now + latency_.latency + jitter;
}

Ticks Link::next_change(Ticks now) const
{
    // Asked at every wake-up of the clock, for every device: nothing held and nothing to close
    // is the usual answer.
    if (held_pieces_ == 0 && closes_.empty())
        return kNever;
    Ticks next = kNever;
    for (const auto* s : sessions_)
        next = std::min(next, s->next_due(now));
    return next <= now ? now + 1 : next;
}

void Link::tick(Ticks now)
{
    // A session may close while it sends (a write error): walk a copy.
    const auto sessions = sessions_;
    for (auto* s : sessions)
        if (std::find(sessions_.begin(), sessions_.end(), s) != sessions_.end())
            s->release(now);
}

} // namespace rigsim
