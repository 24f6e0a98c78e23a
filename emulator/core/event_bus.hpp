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

private:
    std::map<std::uint64_t, Subscriber> subscribers_;
    std::uint64_t next_handle_ = 1;
    std::uint64_t seq_ = 0;
};

} // namespace rigsim
