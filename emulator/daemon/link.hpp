#pragma once
// The wire between a device and its clients: the serial line's pace (faithful timing) and the
// faults on the wire (docs/control-api.md "Faults"): a cable unplugged, bytes dropped or
// corrupted, answers late, sliced or throttled, connections reset or closed, a serial unit's
// receive buffer overrun, a client at the wrong baud rate. The link sits between the
// transports and the device: the device never knows. All of it runs on clock time, so a paused
// clock holds paced and late answers and pending closes, and a step releases them; a scaled
// clock paces the line faster.

#include "emulator/core/device.hpp"
#include "emulator/core/rig_config.hpp"
#include "models/clock.hpp"

#include <spdlog/logger.h>

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace rigsim {

/// Bytes dropped or corrupted: each byte in the chosen direction(s) with a probability.
struct ByteFault {
    std::uint64_t id = 0;
    bool corrupt = false;        ///< flip one bit of the byte; else drop it
    bool inbound = true;         ///< client -> device
    bool outbound = true;        ///< device -> client
    double probability = 1.0;    ///< 0..1
    std::uint32_t seed = 1;
};

/// Answers (every byte the device sends) late by latency + a uniform 0..jitter.
struct LatencyFault {
    std::uint64_t id = 0;
    Ticks latency = 0;
    Ticks jitter = 0;
    std::uint32_t seed = 1;
};

/// Answers sliced into small writes: `slice_bytes` at a time, `gap` between one and the next.
struct SliceFault {
    std::uint64_t id = 0;
    std::size_t slice_bytes = 1;
    Ticks gap = 0;
};

/// A byte rate on the wire, each way it applies: a byte passes 1/bytes_per_s after the one
/// before it.
struct BandwidthFault {
    std::uint64_t id = 0;
    double bytes_per_s = 1;
    bool inbound = true;
    bool outbound = true;
};

/// How a closing wire fault ends a connection.
enum class CloseKind {
    Reset,          ///< `delay` after it starts: reset (TCP RST; pty hang-up), held answers lost
    SlowClose,      ///< `delay` after it starts: held answers go out, then the connection closes
    HangClose,      ///< at once nothing more passes; `delay` after it starts the connection closes
    CutAfter,       ///< `bytes` more bytes pass in one direction, then the connection closes
    GarbageClose,   ///< `delay` after it starts: `bytes` random bytes to the client, then it closes
};

/// A fault that ends connections. Its delay runs, on each connection, from the later of the
/// fault's start and the connection's first byte from its client (a connection opened while it
/// lasts is ended once it has been used, a pty once a client has written to it).
struct CloseFault {
    std::uint64_t id = 0;
    CloseKind kind = CloseKind::Reset;
    Ticks delay = 0;
    std::uint64_t bytes = 0;   ///< CutAfter: bytes let through; GarbageClose: random bytes sent
    bool inbound = false;      ///< CutAfter: counts the client's bytes (else the device's)
    std::uint32_t seed = 1;    ///< GarbageClose
};

/// A serial unit's receive buffer: `buffer_bytes` that its firmware empties at
/// `drain_bytes_per_s` of clock time; a client byte that finds it full is lost (a UART overrun).
struct OverrunFault {
    std::uint64_t id = 0;
    std::size_t buffer_bytes = 64;
    double drain_bytes_per_s = 1000;
};

/// A serial client whose termios baud rate is not the unit's: each side's UART samples the
/// other's bytes at its own rate (uart_resample).
struct BaudMismatchFault {
    std::uint64_t id = 0;
    bool inbound = true;
    bool outbound = true;
};

/// What a UART reading 8N1 at `read_baud` makes of `sent`, sent back to back 8N1 at `sent_baud`
/// on a line idle (mark) before and after: it waits for a falling edge, samples the start bit,
/// eight data bits and the stop bit in the middle of its own bit times, and keeps the byte
/// whatever the stop bit (a framing error still fills the data register); a start bit read high
/// is a glitch. The same rates give `sent` back.
std::string uart_resample(std::string_view sent, std::uint32_t sent_baud, std::uint32_t read_baud);

class Link : public Device, public Tickable {
public:
    /// Carries `inner`'s sessions; delays run on `clock`; drops of held bytes are logged to `log`
    /// (warnings, rate-limited per connection by the daemon's sink), if given.
    Link(Device& inner, Clock& clock, std::shared_ptr<spdlog::logger> log = nullptr);
    ~Link() override;
    Link(const Link&) = delete;
    Link& operator=(const Link&) = delete;

    std::unique_ptr<Session> open_session(SendFn send, std::string peer) override;
    std::unique_ptr<Session> open_connection(SendFn send, Connection conn, std::string peer) override;
    /// 0: the link paces a serial line itself, on clock time (the transport must not again).
    std::uint32_t serial_baud() const override { return 0; }
    std::uint32_t line_baud() const override { return inner_.line_baud(); }
    ControlSurface* control() override { return inner_.control(); }

    /// The link model (rig JSON "link"): the unit's processing time before each answer, and a
    /// USB-serial chip (usb_serial.hpp) between it and the client, on the pty's sessions and, with
    /// `tcp`, on TCP's too; client bytes reach the unit at the next USB frame. Sessions opened
    /// after the call have it.
    void set_model(const LinkModel& model) { model_ = model; }
    const std::optional<LinkModel>& model() const { return model_; }

    /// Unplugged: client bytes are lost and the device's answers too (the pty stays).
    void set_unplugged(std::uint64_t id, bool unplugged);
    bool unplugged() const { return unplugged_ != 0; }
    /// The active unplugged and latency faults' ids (0: none); one of each at a time.
    std::uint64_t unplugged_id() const { return unplugged_; }
    std::uint64_t latency_id() const { return latency_.id; }
    /// Bytes held for one connection (late, paced, sliced, throttled: not yet handed to the
    /// transport) when the transport tells no bound of its own (Connection::max_queued_bytes);
    /// with one, held bytes and the transport's queue share it. Client bytes held by a bandwidth
    /// fault are bounded by this too. Beyond: dropped, with a warning.
    static constexpr std::size_t kMaxHeldBytes = 1 << 20;
    /// What a held piece costs beyond its bytes when the transport does not say.
    static constexpr std::size_t kHeldFrameOverhead = 64;

    void add(const ByteFault& f);
    void add(const LatencyFault& f);
    void add(const SliceFault& f);
    void add(const BandwidthFault& f);
    void add(const CloseFault& f);
    void add(const OverrunFault& f);
    void add(const BaudMismatchFault& f);
    /// Ends fault `id` (held late bytes still go out at their time, a connection already closing
    /// closes); false if it is not a link fault.
    bool remove(std::uint64_t id);
    /// Bytes lost and changed so far, and answers held now.
    std::uint64_t dropped() const { return dropped_; }
    std::uint64_t corrupted() const { return corrupted_; }
    std::size_t held() const;
    /// Client writes held back from the device now (a bandwidth fault, the link model's USB frame).
    std::size_t held_requests() const;
    /// Back to a fresh wire (POST /api/reset): every fault ended, held bytes dropped, the line
    /// idle, the counters at 0.
    void reset();

    Ticks next_change(Ticks now) const override;
    void tick(Ticks now) override;

private:
    class LinkSession;
    struct ActiveByteFault {
        ByteFault f;
        std::mt19937 rng;
    };
    struct ActiveClose {
        CloseFault f;
        Ticks since = 0;   ///< when it started
    };

    /// Apply the byte faults of one direction to `bytes`.
    std::string filter(std::string_view bytes, bool inbound);
    /// When bytes sent now go out (now with no latency fault).
    Ticks due(Ticks now);
    /// The active closing fault of `kind`, or nullptr.
    const ActiveClose* close_fault(CloseKind kind) const;
    /// Something moved the link's next change outside its tick.
    void changed();

    Device& inner_;
    Clock& clock_;
    std::shared_ptr<spdlog::logger> log_;
    std::uint64_t unplugged_ = 0;   ///< the fault's id, 0: plugged in
    std::vector<ActiveByteFault> byte_faults_;
    LatencyFault latency_;
    std::mt19937 latency_rng_;
    SliceFault slice_;              ///< id 0: none
    BandwidthFault bandwidth_;      ///< id 0: none
    std::vector<ActiveClose> closes_;   ///< at most one of each kind
    OverrunFault overrun_;          ///< id 0: none
    BaudMismatchFault baud_;        ///< id 0: none
    std::optional<LinkModel> model_;
    std::vector<LinkSession*> sessions_;
    std::size_t held_pieces_ = 0;   ///< pieces held by all sessions together, both ways
    std::uint64_t dropped_ = 0;
    std::uint64_t corrupted_ = 0;
};

} // namespace rigsim
