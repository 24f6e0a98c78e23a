#pragma once
// Device-test harness: framer + codec + handler + controller on a stepped clock.
// No sockets, no sleeps: h.send(":MPA0,1000000,0\n"); h.advance_ms(2000); h.send(":GP0\n").

#include "models/clock.hpp"
#include "models/world.hpp"
#include "emulator/mcs/config.hpp"
#include "emulator/mcs/mcs_device.hpp"

#include <spdlog/logger.h>
#include <spdlog/sinks/null_sink.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <string>

namespace rigsim::test {

/// Three linear S channels, ±10.5 mm of travel, 10 mm/s top speed: the default rig's MCS.
inline DeviceConfig mcs_device_config(std::size_t channels = 3)
{
    DeviceConfig c;
    c.name = "mcs-test";
    c.protocol = "mcs";
    c.model = "MCS-3D";
    auto& section = mcs::config_of(c);
    section.system_id = 3118100;
    section.channels.resize(channels);
    return c;
}

class McsHarness {
public:
    explicit McsHarness(const DeviceConfig& config = mcs_device_config(), std::uint32_t tick_hz = 1000,
                        EventBus* events = nullptr)
        : clock_(tick_hz), world_(clock_),
          device_(config, world_,
                  std::make_shared<spdlog::logger>("mcs-test", std::make_shared<spdlog::sinks::null_sink_st>()),
                  events),
          session_(device_.open_session([this](std::string_view b) { out_.append(b); }, "test"))
    {
    }

    /// Bytes in; out comes everything the device sent this connection since the last
    /// send(): unprompted messages from clock advances first, then the answers.
    std::string send(std::string_view bytes)
    {
        session_->receive(bytes);
        std::string result = std::move(out_);
        out_.clear();
        return result;
    }
    /// A second connection to the same device.
    std::unique_ptr<Session> open(std::string& sink, std::string peer = "test2")
    {
        return device_.open_session([&sink](std::string_view b) { sink.append(b); }, std::move(peer));
    }

    /// Run the clock as the daemon's rig does (models/clock.hpp, "The schedule"): it keeps the
    /// device's next change between its announcements. Only for tests that reach the device
    /// through its sessions and the clock alone (the control API announces its requests; a test
    /// calling the device's ControlSurface directly does not).
    void keep_schedule()
    {
        clock_.changed_all();
        clock_.keep_schedule();
    }

    void advance_ms(std::int64_t ms) { clock_.advance_ms(ms); }
    void advance_ticks(Ticks n) { clock_.advance(n); }
    Clock& clock() { return clock_; }
    models::World& world() { return world_; }
    mcs::McsDevice& device() { return device_; }

private:
    Clock clock_;
    models::World world_;
    mcs::McsDevice device_;
    std::string out_;
    std::unique_ptr<Session> session_;
};

} // namespace rigsim::test
