#pragma once
// An MCS controller: system-wide settings and its channels. No I/O.

#include "emulator/core/clock.hpp"
#include "emulator/core/rig_config.hpp"
#include "emulator/mcs/channel.hpp"

#include <cstdint>
#include <vector>

namespace rigsim::mcs {

/// GIV answer of the emulated firmware (RS232 form, manual 3.1).
struct InterfaceVersion {
    int high = 1;
    int low = 5;
    int update = 0;
};

class Controller : public Tickable {
public:
    Controller(const McsConfig& config, const Clock& clock);

    std::size_t channel_count() const { return channels_.size(); }
    /// The channel with this index, or nullptr when the index is out of range.
    Channel* channel(std::int32_t index);
    const Channel* channel(std::int32_t index) const;

    std::uint32_t system_id() const { return system_id_; }
    InterfaceVersion interface_version() const { return {}; }

    void stop_all();

    Ticks next_change(Ticks now) const override;
    void tick(Ticks now) override;

private:
    std::uint32_t system_id_;
    std::vector<Channel> channels_;
};

} // namespace rigsim::mcs
