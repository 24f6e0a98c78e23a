#include "emulator/core/event_bus.hpp"

#include <nlohmann/json.hpp>

#include <vector>

namespace rigsim {

std::uint64_t EventBus::subscribe(Subscriber s)
{
    if (subscribers_.empty() && on_active_)
        on_active_();
    const auto h = next_handle_++;
    subscribers_.emplace(h, std::move(s));
    return h;
}

void EventBus::unsubscribe(std::uint64_t handle)
{
    subscribers_.erase(handle);
}

void EventBus::publish(std::string_view device, std::string_view type, double time_ms, const nlohmann::json& data)
{
    if (subscribers_.empty())
        return;
    nlohmann::json doc{{"seq", ++seq_}, {"time_ms", time_ms}, {"type", type}};
    if (!device.empty())
        doc["device"] = device;
    if (data.is_object())
        for (const auto& [k, v] : data.items())
            doc[k] = v;
    Event e{seq_, std::string(device), std::string(type),
            doc.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)};
    // A subscriber may unsubscribe (its connection failed) while being called.
    std::vector<Subscriber> targets;
    targets.reserve(subscribers_.size());
    for (const auto& [h, s] : subscribers_)
        targets.push_back(s);
    for (const auto& s : targets)
        s(e);
    if (follow_up_)
        follow_up_(e);
}

} // namespace rigsim
