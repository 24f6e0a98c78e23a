#pragma once
// The control API's event stream (GET /api/events, docs/control-api.md "Events"): devices and
// the control layer publish state changes; each subscriber (one SSE connection) gets every
// event as one JSON text. With no subscriber, publish() is not even called: callers test
// active() first, so an idle stream costs a branch.

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <utility>

namespace rigsim {

/// One published event: {"seq", "time_ms", "device", "type", ...data} as compact JSON.
struct Event {
    std::uint64_t seq = 0;
    std::string device;   ///< empty for rig-wide events (clock, reset)
    std::string type;     ///< "move_started", "move_ended", "status", "fault_added", "wire", ...
    std::string json;
};

class EventBus {
public:
    using Subscriber = std::function<void(const Event&)>;

    /// Someone listens: build and publish events (else skip the work).
    bool active() const { return !subscribers_.empty(); }
    /// Returns a handle for unsubscribe().
    std::uint64_t subscribe(Subscriber s);
    void unsubscribe(std::uint64_t handle);

    /// Sends `data` (an object; "seq", "time_ms", "device" and "type" are added) to every
    /// subscriber. `time_ms` is clock time.
    void publish(std::string_view device, std::string_view type, double time_ms, const nlohmann::json& data);

    /// Called with each event once every subscriber has it (only while active()); it may
    /// publish events of its own, which then follow that one on every stream. It is not a
    /// subscriber: it does not make the bus active(). An empty function removes it.
    void set_follow_up(Subscriber f) { follow_up_ = std::move(f); }

    /// Called when subscribe() makes the bus active(), before the subscriber is added: state
    /// kept to publish differences (the frames' poses) goes stale while no one listens, since
    /// publish() then sends nothing, and is taken afresh here. An empty function removes it.
    void set_on_active(std::function<void()> f) { on_active_ = std::move(f); }

private:
    Subscriber follow_up_;
    std::function<void()> on_active_;
    std::map<std::uint64_t, Subscriber> subscribers_;
    std::uint64_t next_handle_ = 1;
    std::uint64_t seq_ = 0;
};

} // namespace rigsim
