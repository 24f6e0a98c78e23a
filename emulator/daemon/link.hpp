#pragma once
// The wire between a device and its clients: the serial line's pace (faithful timing) and the
// faults on the wire (docs/control-api.md "Faults"): a cable unplugged, bytes dropped or
// corrupted, answers late. The link sits between the transports and the device: the device
// never knows. Both run on clock time, so a paused clock holds paced and late answers and a
// step releases them; a scaled clock paces the line faster.

#include "emulator/core/device.hpp"
#include "models/clock.hpp"

#include <cstdint>
#include <deque>
#include <memory>
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

class Link : public Device, public Tickable {
public:
    /// Carries `inner`'s sessions; delays run on `clock`.
    Link(Device& inner, Clock& clock);
    ~Link() override;
    Link(const Link&) = delete;
    Link& operator=(const Link&) = delete;

    std::unique_ptr<Session> open_session(SendFn send, std::string peer) override;
    /// 0: the link paces a serial line itself, on clock time (the transport must not again).
    std::uint32_t serial_baud() const override { return 0; }
    ControlSurface* control() override { return inner_.control(); }

    /// Unplugged: client bytes are lost and the device's answers too (the pty stays).
    void set_unplugged(std::uint64_t id, bool unplugged);
    bool unplugged() const { return unplugged_ != 0; }
    /// The active unplugged and latency faults' ids (0: none); one of each at a time.
    std::uint64_t unplugged_id() const { return unplugged_; }
    std::uint64_t latency_id() const { return latency_.id; }
    /// Bytes held for one serial connection (paced, not yet sent) beyond which new answers are
    /// dropped: nobody reads the port (the pty keeps as much).
    static constexpr std::size_t kMaxHeldBytes = 1 << 20;

    void add(const ByteFault& f);
    void add(const LatencyFault& f);
    /// Ends fault `id` (held late bytes still go out at their time); false if it is not a link fault.
    bool remove(std::uint64_t id);
    /// Bytes lost and changed so far, and answers held now.
    std::uint64_t dropped() const { return dropped_; }
    std::uint64_t corrupted() const { return corrupted_; }
    std::size_t held() const;
    /// Back to a fresh wire (POST /api/reset): every fault ended, held answers dropped, the line
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

    /// Apply the byte faults of one direction to `bytes`.
    std::string filter(std::string_view bytes, bool inbound);
    /// When bytes sent now go out (now with no latency fault).
    Ticks due(Ticks now);

    Device& inner_;
    Clock& clock_;
    std::uint64_t unplugged_ = 0;   ///< the fault's id, 0: plugged in
    std::vector<ActiveByteFault> byte_faults_;
    LatencyFault latency_;
    std::mt19937 latency_rng_;
    std::vector<LinkSession*> sessions_;
    std::size_t held_frames_ = 0;   ///< answers held by all sessions together
    std::uint64_t dropped_ = 0;
    std::uint64_t corrupted_ = 0;
};

} // namespace rigsim
