#pragma once
// An MCS controller as a rig device: framer + codec + handler per connection, one
// Controller shared by all connections.

#include "models/clock.hpp"
#include "models/world.hpp"
#include "emulator/core/device.hpp"
#include "emulator/mcs/config.hpp"
#include "emulator/mcs/controller.hpp"
#include "emulator/mcs/handler.hpp"

#include <memory>
#include <vector>

namespace spdlog {
class logger;
}

namespace rigsim {
class EventBus;   // emulator/core/event_bus.hpp
}

namespace rigsim::mcs {

class McsSession;

class McsDevice : public Device, public Tickable {
public:
    /// The device's bodies join `world` under "<device name>/<channel>".
    McsDevice(const DeviceConfig& config, models::World& world, std::shared_ptr<spdlog::logger> log,
              EventBus* events = nullptr);
    ~McsDevice() override;
    McsDevice(const McsDevice&) = delete;
    McsDevice& operator=(const McsDevice&) = delete;

    std::unique_ptr<Session> open_session(SendFn send, std::string peer) override;
    /// With `faithful_timing`, the serial line runs at the controller's baud rate (1.2, CB).
    std::uint32_t serial_baud() const override
    {
        return config_.faithful_timing ? static_cast<std::uint32_t>(controller_.baudrate()) : 0;
    }

    Controller& controller() { return controller_; }

    /// Handle one framed command string; appends the encoded answer (if any) to `out`.
    void execute(std::string_view line, std::string_view peer, std::string& out);
    /// Send what the controller has to say by itself to every connection.
    void flush_outbox();

    void attach(McsSession* s) { sessions_.push_back(s); }
    void detach(McsSession* s);

    Ticks next_change(Ticks now) const override { return controller_.next_change(now); }
    void tick(Ticks now) override;

private:
    DeviceConfig config_;
    Clock& clock_;
    std::shared_ptr<spdlog::logger> log_;
    Controller controller_;
    Handler handler_;
    std::vector<McsSession*> sessions_;
    EventBus* events_;   ///< the control API's event stream, or nullptr
};

} // namespace rigsim::mcs
