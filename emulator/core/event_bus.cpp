#include "emulator/core/event_bus.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>

namespace rigsim {

namespace {

bool listed(const std::vector<std::string>& list, std::string_view v)
{
    return list.empty() || std::find(list.begin(), list.end(), v) != list.end();
}

} // namespace

bool EventFilter::passes(std::string_view device, std::string_view type) const
{
    return (device.empty() || listed(devices, device)) && listed(types, type);
}

bool EventBus::taken(std::string_view device, std::string_view type) const
{
    for (const auto& e : subscribers_)
        if (e.alive && e.filter.passes(device, type))
            return true;
    return false;
}

bool EventBus::wants(std::string_view device, std::string_view type) const
{
    if (subscribers_.empty())
        return false;
    if (taken(device, type))
        return true;
    if (!follow_up_ || std::find(follow_up_reads_.begin(), follow_up_reads_.end(), type) == follow_up_reads_.end())
        return false;
    for (const auto& made : follow_up_makes_)
        if (taken("", made))
            return true;
    return false;
}

std::uint64_t EventBus::subscribe(Subscriber s, EventFilter filter)
{
    if (subscribers_.empty() && on_active_)
        on_active_();
    const auto h = next_handle_++;
    subscribers_.push_back(Entry{h, std::move(filter), std::move(s), true});
    return h;
}

void EventBus::unsubscribe(std::uint64_t handle)
{
    const auto it = std::find_if(subscribers_.begin(), subscribers_.end(),
                                 [handle](const Entry& e) { return e.handle == handle; });
    if (it == subscribers_.end())
        return;
    if (publishing_ > 0)
        it->alive = false;   // erased when the outermost publish() is done
    else
        subscribers_.erase(it);
}

void EventBus::set_follow_up(Subscriber f, std::vector<std::string> reads, std::vector<std::string> makes)
{
    follow_up_ = std::move(f);
    follow_up_reads_ = std::move(reads);
    follow_up_makes_ = std::move(makes);
}

void EventBus::publish(std::string_view device, std::string_view type, double time_ms, nlohmann::json data)
{
    if (!wants(device, type))
        return;
    if (!data.is_object())
        data = nlohmann::json::object();
    // The data's own keys win (a wire entry's "seq" and "time_ms" are the log's).
    if (!data.contains("seq"))
        data["seq"] = seq_ + 1;
    if (!data.contains("time_ms"))
        data["time_ms"] = time_ms;
    if (!data.contains("type"))
        data["type"] = type;
    if (!device.empty() && !data.contains("device"))
        data["device"] = device;
    Event e{++seq_, std::string(device), std::string(type),
            data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)};
    ++built_;
    // A subscriber may unsubscribe (its connection failed), itself included, or subscribe while
    // being called: meanwhile entries are only appended or marked, and walked by index.
    ++publishing_;
    for (std::size_t i = 0; i < subscribers_.size(); ++i) {
        const auto& entry = subscribers_[i];
        if (entry.alive && entry.filter.passes(e.device, e.type))
            entry.subscriber(e);
    }
    if (follow_up_)
        follow_up_(e);
    if (--publishing_ == 0)
        subscribers_.erase(std::remove_if(subscribers_.begin(), subscribers_.end(),
                                          [](const Entry& x) { return !x.alive; }),
                           subscribers_.end());
}

} // namespace rigsim
