#pragma once
// An MCS2 as a rig device: per connection a line framer and an error queue, one Controller shared
// by all connections (several TCP clients at once), the wire log with its notes, the control API's
// view (docs/control-api/mcs2.md) and its events.

#include "emulator/core/control_surface.hpp"
#include "emulator/core/device.hpp"
#include "emulator/core/rig_config.hpp"
#include "emulator/core/wire_log.hpp"
#include "emulator/mcs2/config.hpp"
#include "emulator/mcs2/controller.hpp"
#include "models/clock.hpp"
#include "models/world.hpp"

#include <memory>
#include <string>
#include <vector>

namespace spdlog {
class logger;
}

namespace rigsim {
class EventBus;
}

namespace rigsim::mcs2 {

class Mcs2Session;

/// The MCS2 section of `device` (a default one if it has none yet).
inline Config& config_of(DeviceConfig& device)
{
    return section_of<Config>(device);
}
inline const Config& config_of(const DeviceConfig& device)
{
    return section_of<Config>(device);
}
/// The model of an MCS2 whose config names none.
inline constexpr const char* kDefaultModel = "MCS2";

class Mcs2Device : public Device, public Tickable, public ControlSurface {
public:
    Mcs2Device(const DeviceConfig& config, models::World& world, std::shared_ptr<spdlog::logger> log,
               EventBus* events = nullptr);
    ~Mcs2Device() override;
    Mcs2Device(const Mcs2Device&) = delete;
    Mcs2Device& operator=(const Mcs2Device&) = delete;

    std::unique_ptr<Session> open_session(SendFn send, std::string peer) override;
    std::unique_ptr<Session> open_connection(SendFn send, Connection conn, std::string peer) override;
    ControlSurface* control() override { return this; }
    Controller& controller() { return controller_; }

    /// One message of `peer`; the answer line (with its CR LF) appended to `out`. True when the
    /// connection is to be closed after the answer (*RST).
    bool execute(std::string_view message, SessionState& state, std::string_view peer, std::string& out);
    /// A message longer than the input buffer: -363 queued, and the wire log says so.
    void overrun(SessionState& state, std::string_view peer);
    void publish_changes();

    // ---- ControlSurface (docs/control-api/mcs2.md) ----
    void describe(nlohmann::json& out) const override;
    Refused patch_channel(std::size_t index, const nlohmann::json& body) override;
    Refused add_fault(const DeviceFault& f, bool* kept) override;
    Refused fault_body(const DeviceFault& f, std::string& out) const override;
    void faults_changed() override;
    void power_cycle(const PowerCycle& how) override;
    bool busy() const override;
    Refused axis_body_key(std::size_t index, std::string& out) const override;
    WireLog& wire_log() override { return wire_log_; }

    Ticks next_change(Ticks now) const override { return controller_.next_change(now); }
    void tick(Ticks now) override;

private:
    void channel_json(std::size_t index, nlohmann::json& out) const;
    void sync_sensor(std::size_t index);

    DeviceConfig config_;
    Clock& clock_;
    std::shared_ptr<spdlog::logger> log_;
    Controller controller_;
    EventBus* events_;
    WireLog wire_log_;
    std::vector<std::uint32_t> last_state_;   ///< per channel, for "status" events
    bool state_known_ = false;
};

} // namespace rigsim::mcs2
