#pragma once
// An MCS controller as a rig device: framer + codec + handler per connection, one
// Controller shared by all connections.

#include "models/clock.hpp"
#include "models/world.hpp"
#include "emulator/core/control_surface.hpp"
#include "emulator/core/device.hpp"
#include "emulator/core/wire_log.hpp"
#include "emulator/mcs/config.hpp"
#include "emulator/mcs/controller.hpp"
#include "emulator/mcs/handler.hpp"

#include <memory>
#include <string>
#include <vector>

namespace spdlog {
class logger;
}

namespace rigsim {
class EventBus;   // emulator/core/event_bus.hpp
}

namespace rigsim::mcs {

class McsSession;

class McsDevice : public Device, public Tickable, public ControlSurface {
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
    /// The controller's baud rate (CB), paced or not.
    std::uint32_t line_baud() const override { return static_cast<std::uint32_t>(controller_.baudrate()); }

    Controller& controller() { return controller_; }
    ControlSurface* control() override { return this; }

    /// A command the client sent before the previous answer could have reached it (a note).
    enum class Early { No, SameRead, Paced };
    /// Handle one framed command string; appends the encoded answer (if any) to `out`. `frame`:
    /// the command as it crossed the wire (':' to '\n', LineFramer::Result::frame) when the
    /// framer has it, else empty (composed from `line`).
    void execute(std::string_view line, std::string_view peer, std::string& out, Early early = Early::No,
                 std::string_view frame = {});
    /// Record an answer the session made without the handler (oversize line: error 1).
    void log_answer(std::string_view peer, std::string_view bytes, std::string note);
    /// Record an unfinished command that a ':' cut off (no answer).
    void log_dropped(std::string_view peer, std::string_view partial);
    /// After a batch of commands or a tick: "status", "move_started", "move_ended" events.
    void publish_changes();

    // ---- ControlSurface (docs/control-api/mcs.md) ----
    void describe(nlohmann::json& out) const override;
    Refused patch_channel(std::size_t index, const nlohmann::json& body) override;
    /// reference_lost: the position becomes unknown (a channel with a sensor).
    Refused add_fault(const DeviceFault& f, bool* kept) override;
    /// The channel's positioner; a sensor_failure needs a sensor on the channel.
    Refused fault_body(const DeviceFault& f, std::string& out) const override;
    /// Each channel's sensor as its body's faults leave it; a movement a stall or a dead sensor
    /// ended is reported now (142 in async mode).
    void faults_changed() override;
    void power_cycle(const PowerCycle& how) override;
    /// A channel calibrating, waiting out a power-save move delay or holding for a finite time,
    /// or an end effector ramping or zeroing (not the keep-alive deadline).
    bool busy() const override { return controller_.busy(clock_.now()); }
    /// The positioner's body; end effectors move nothing (400).
    Refused axis_body_key(std::size_t index, std::string& out) const override;
    WireLog& wire_log() override { return wire_log_; }
    /// Send what the controller has to say by itself to every connection.
    void flush_outbox();

    void attach(McsSession* s) { sessions_.push_back(s); }
    void detach(McsSession* s);

    Ticks next_change(Ticks now) const override { return controller_.next_change(now); }
    void tick(Ticks now) override;

private:
    /// Channel `index`'s sensor as its body's faults leave it (sensor_failure).
    void sync_sensor(std::size_t index);
    void channel_json(std::size_t index, nlohmann::json& out) const;
    /// Appendix 4.1 status code of channel `index` (positioner or end effector).
    int status_code(std::size_t index) const;
    /// Notes for the inbound entry of `line` answered with `reply` (docs/control-api/mcs.md "Notes").
    void note_command(const Command* command, const Reply& reply, std::vector<std::string>& notes) const;

    DeviceConfig config_;
    Clock& clock_;
    std::shared_ptr<spdlog::logger> log_;
    Controller controller_;
    Handler handler_;
    std::vector<McsSession*> sessions_;
    EventBus* events_;   ///< the control API's event stream, or nullptr
    WireLog wire_log_;
    /// The inbound command string as it crossed the wire, while execute() runs (note_command()
    /// reads it): the framer's bytes, or line_text_.
    std::string_view line_;
    std::string line_text_;   ///< scratch: line_ composed when the framer had no bytes of its own
    std::vector<int> last_status_;   ///< per channel, for "status" events
    bool status_known_ = false;      ///< last_status_ is current (someone listened last time)
};

} // namespace rigsim::mcs
