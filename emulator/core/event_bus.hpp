#pragma once
// The control API's event stream (GET /api/events, docs/control-api.md "Events"): devices and
// the control layer publish state changes; each subscriber (one SSE connection) takes the events
// its filter lets through, each as one JSON text built once for all of them. An event nobody
// takes is not built: callers ask wants(device, type) before they compose its data, so an
// unfiltered-out kind costs a few comparisons and no stream costs a branch.

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <deque>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rigsim {

/// One published event: {"seq", "time_ms", "device", "type", ...data} as compact JSON.
struct Event {
    std::uint64_t seq = 0;
    std::string device;   ///< empty for rig-wide events (clock, reset)
    std::string type;     ///< "move_started", "move_ended", "status", "fault_added", "wire", ...
    std::string json;
};

/// Which events a subscriber takes (`?device=`, `?type=` of the stream); an empty list takes all.
struct EventFilter {
    std::vector<std::string> devices;   ///< rig-wide events (no device) pass whatever it holds
    std::vector<std::string> types;

    bool passes(std::string_view device, std::string_view type) const;
};

class EventBus {
public:
    using Subscriber = std::function<void(const Event&)>;

    /// Someone listens (to anything).
    bool active() const { return !subscribers_.empty(); }
    /// Some subscriber takes events of `type` from `device` ("" for a rig-wide one), or the
    /// follow-up reads them to make what a subscriber takes: build such an event only then.
    bool wants(std::string_view device, std::string_view type) const;
    /// Returns a handle for unsubscribe(); `s` gets the events `filter` passes.
    std::uint64_t subscribe(Subscriber s, EventFilter filter = {});
    void unsubscribe(std::uint64_t handle);

    /// Sends `data` (an object; "seq", "time_ms", "device" and "type" are added unless it has
    /// them) to every subscriber that takes it, built once; nothing if wants() is false.
    /// `time_ms` is clock time.
    void publish(std::string_view device, std::string_view type, double time_ms, nlohmann::json data);

    /// Called with each event built, after every subscriber that takes it has it; it may publish
    /// events of its own, which then follow that one on every stream. It reads events of the
    /// types `reads` to make rig-wide events of the types `makes`: while a subscriber takes one
    /// of those, wants() is true for the types it reads. It is not a subscriber: it does not make
    /// the bus active(). An empty function removes it.
    void set_follow_up(Subscriber f, std::vector<std::string> reads = {}, std::vector<std::string> makes = {});

    /// Called when subscribe() makes the bus active(), before the subscriber is added: state
    /// kept to publish differences (the frames' poses) goes stale while no one listens, since
    /// publish() then sends nothing, and is taken afresh here. An empty function removes it.
    void set_on_active(std::function<void()> f) { on_active_ = std::move(f); }

    /// Events built since the bus was made (a test's view of the work publish() did).
    std::uint64_t built() const { return built_; }

private:
    struct Entry {
        std::uint64_t handle;
        EventFilter filter;
        Subscriber subscriber;
        bool alive = true;   ///< false once unsubscribed during a publish() (it may be running)
    };
    /// Some subscriber's filter passes (device, type).
    bool taken(std::string_view device, std::string_view type) const;

    Subscriber follow_up_;
    std::vector<std::string> follow_up_reads_;
    std::vector<std::string> follow_up_makes_;
    std::function<void()> on_active_;
    std::deque<Entry> subscribers_;   ///< a deque: appending moves no entry that is being called
    std::uint64_t next_handle_ = 1;
    std::uint64_t seq_ = 0;
    std::uint64_t built_ = 0;
    int publishing_ = 0;   ///< nesting depth of publish(): entries are erased only at depth 0
};

} // namespace rigsim
