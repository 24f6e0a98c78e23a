#pragma once
// A device's wire log (GET /api/devices/{name}/log, docs/control-api.md "Wire log"): the last
// N frames each way, with the clock time, the connection, the raw bytes and the notes where the
// client did something the manual warns against. Recording is a copy into a ring; decoding
// (manual names and fields) happens only when someone reads the log, streams events, or runs at
// debug level.

#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace spdlog {
class logger;
}

namespace rigsim {

class EventBus;

/// One frame on the wire.
struct WireEntry {
    std::uint64_t seq = 0;           ///< since the daemon started (or the log was cleared)
    std::int64_t tick = 0;           ///< clock tick it crossed the wire at
    bool inbound = true;             ///< client -> device
    bool unprompted = false;         ///< device -> client without a request (status updates, async events)
    std::string peer;                ///< "tcp 127.0.0.1:53122", "pty"
    std::string bytes;               ///< one frame (APT) or one line (MCS), raw
    std::vector<std::string> notes;  ///< client mistakes (docs/control-api.md "Notes")
};

class WireLog {
public:
    static constexpr std::size_t kDefaultCapacity = 1000;
    /// The frame's decoded form: {"name": manual name, "fields": {...}, ...}.
    using Decoder = std::function<void(const WireEntry&, nlohmann::json& out)>;

    /// `device` names events and log lines; `tick_hz` turns ticks into ms; `bus` and `log` may be null.
    WireLog(std::string device, std::uint32_t tick_hz, EventBus* bus = nullptr,
            std::shared_ptr<spdlog::logger> log = nullptr, std::size_t capacity = kDefaultCapacity);
    ~WireLog();

    void set_decoder(Decoder decoder) { decoder_ = std::move(decoder); }

    /// Record one frame. Publishes a "wire" event when someone listens, and writes a debug line
    /// to the device's log.
    void add(std::int64_t tick, bool inbound, std::string_view peer, std::string_view bytes,
             std::vector<std::string> notes = {}, bool unprompted = false);
    /// Notes on the most recent entry (a mistake found after the frame was recorded).
    void annotate_last(std::string note);

    /// The last `n` entries, oldest first, decoded: [{"seq","time_ms","direction","peer","bytes",
    /// "hex" (APT), "decoded", "notes"}].
    nlohmann::json to_json(std::size_t n) const;
    /// One entry as to_json() shows it.
    nlohmann::json entry_json(const WireEntry& e) const;
    std::size_t size() const { return count_; }
    std::size_t capacity() const { return ring_.size(); }
    /// Entries with at least one note, ever (not only those still in the ring).
    std::uint64_t noted() const { return noted_; }
    void clear();

    /// The most recent entry, or nullptr.
    const WireEntry* last() const;

private:
    /// The debug line and the "wire" event of entry `e` (someone reads them: off the usual path).
    [[gnu::noinline, gnu::cold]] void show(const WireEntry& e) const;

    std::string device_;
    std::uint32_t tick_hz_;
    EventBus* bus_;
    std::shared_ptr<spdlog::logger> log_;
    Decoder decoder_;
    std::vector<WireEntry> ring_;
    std::size_t next_ = 0;    ///< slot of the next entry
    std::size_t count_ = 0;   ///< entries held (<= capacity)
    std::uint64_t seq_ = 0;
    std::uint64_t noted_ = 0;
};

/// `bytes` as spaced hex: "23 02 00 00 50 01".
std::string hex_bytes(std::string_view bytes);

} // namespace rigsim
