#pragma once
// The worked example of docs/architecture.md, "A new family": "toy", a made-up controller of one
// linear servo stage with a line protocol (MOV <mm>, POS?, STA?, STP). It is written as a new
// family is: its config section, its Device with a session and a control surface of protocol
// state only. Its stage is a body of the world (models::Axis): kinematic joints, collisions,
// physical faults and the control API's physical state reach it by its key, with no code here.

#include "emulator/core/control_surface.hpp"
#include "emulator/core/device.hpp"
#include "emulator/core/family_registry.hpp"
#include "emulator/core/wire_log.hpp"
#include "models/axis.hpp"

#include <memory>
#include <string>
#include <string_view>

namespace rigsim::toy {

/// The device object's "toy" section: {"travel_mm": 1..1000}.
struct ToyConfig {
    double travel_mm = 50;
};

class ToyDevice : public Device, public ControlSurface {
public:
    ToyDevice(const DeviceConfig& config, const DeviceContext& context);
    ~ToyDevice() override;

    // Device
    std::unique_ptr<Session> open_session(SendFn send, std::string peer) override;
    ControlSurface* control() override { return this; }

    // ControlSurface: protocol state only
    void describe(nlohmann::json& out) const override;
    Refused patch_channel(std::size_t index, const nlohmann::json& body) override;
    Refused axis_body_key(std::size_t index, std::string& out) const override;
    Refused add_fault(const DeviceFault& f, bool* kept) override;
    void power_cycle(const PowerCycle& how) override;
    WireLog& wire_log() override { return log_; }

    /// One command line (without its '\n') and its answer.
    std::string handle(const std::string& line);
    /// Log one line crossing the wire of connection `peer`.
    void record(bool inbound, std::string_view peer, std::string_view bytes);

private:
    const Clock& clock_;
    models::Axis& axis_;   ///< µm counts; the world's body "<name>/0"
    WireLog log_;
    bool stalled_ = false;   ///< the last move ended against something
};

/// The family as the registry takes it: "toy", its loader and its factory.
Family toy_family();

} // namespace rigsim::toy
