#include "emulator/mcs/controller.hpp"

#include <algorithm>

namespace rigsim::mcs {

Controller::Controller(const McsConfig& config, const Clock& clock) : system_id_(config.system_id)
{
    channels_.reserve(config.channels.size());
    for (const auto& c : config.channels)
        channels_.emplace_back(c, clock);
}

Channel* Controller::channel(std::int32_t index)
{
    if (index < 0 || static_cast<std::size_t>(index) >= channels_.size())
        return nullptr;
    return &channels_[static_cast<std::size_t>(index)];
}

const Channel* Controller::channel(std::int32_t index) const
{
    return const_cast<Controller*>(this)->channel(index);
}

void Controller::stop_all()
{
    for (auto& c : channels_)
        c.stop();
}

Ticks Controller::next_change(Ticks now) const
{
    Ticks next = kNever;
    for (const auto& c : channels_)
        next = std::min(next, c.next_change(now));
    return next;
}

void Controller::tick(Ticks now)
{
    for (auto& c : channels_)
        if (c.next_change(now - 1) <= now)
            c.tick(now);
}

} // namespace rigsim::mcs
