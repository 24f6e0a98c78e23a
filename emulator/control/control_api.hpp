#pragma once
// The control API's routes (docs/control-api.md): a pure function of (method, target, body)
// over the rig, so that it is tested without sockets. The HTTP server (http_server.hpp)
// only carries requests here.

#include "emulator/control/fault_book.hpp"
#include "emulator/control/frame_book.hpp"
#include "emulator/control/http_server.hpp"
#include "emulator/core/event_bus.hpp"
#include "emulator/daemon/rig.hpp"
#include "emulator/daemon/ticker.hpp"
#include "models/clock.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

namespace rigsim::control {

/// Longest clock time one step_ms or run_until_idle may cover (one day). The daemon serves its
/// devices and other requests while it runs (in slices), yet a mistyped number must not keep
/// the answer away for hours.
inline constexpr std::int64_t kMaxStepMs = 86'400'000;
/// The time scales POST /api/clock takes (those of --time-scale and the rig JSON's clock).
inline constexpr double kMinTimeScale = 0.001;
inline constexpr double kMaxTimeScale = 1000;

class ControlApi {
public:
    /// The routes over a running rig.
    explicit ControlApi(Rig& rig);
    /// The routes over a clock, its ticker, "something moves" and a device list (tests).
    ControlApi(Clock& clock, Ticker& ticker, std::function<bool()> busy, std::vector<DeviceEndpoints> devices);
    /// The routes over a clock, its ticker, "something moves", devices, their event stream, the
    /// rig's frames and the world its physical faults act in (tests).
    ControlApi(Clock& clock, Ticker& ticker, std::function<bool()> busy, std::vector<ControlledDevice> devices,
               EventBus* events, FrameSource frames = {}, models::World* world = nullptr);
    ~ControlApi();
    ControlApi(const ControlApi&) = delete;
    ControlApi& operator=(const ControlApi&) = delete;

    /// Answer one request; never throws for any input.
    HttpReply handle(std::string_view method, std::string_view target, std::string_view body);

private:
    /// A route of /api/...; throws BadRequest.
    HttpReply route(std::string_view method, std::string_view target, std::string_view body);
    HttpReply get_rig();
    HttpReply get_clock();
    HttpReply post_clock(std::string_view body);
    /// step_ms and run_until_idle: checked now, run in slices on the loop, answered when done.
    HttpReply clock_job(const std::string& action, const nlohmann::json& body);
    HttpReply device_route(std::string_view method, const std::vector<std::string>& parts, std::string_view target,
                           std::string_view body);
    HttpReply get_device(const ControlledDevice& d);
    HttpReply patch_channel(ControlledDevice& d, const std::string& index, std::string_view body);
    HttpReply get_log(ControlledDevice& d, std::string_view target);
    /// GET /api/devices/{name}/channels/{index}/trace?from=&max= (docs/control-api.md "Traces").
    HttpReply get_trace(ControlledDevice& d, const std::string& index, std::string_view target);
    HttpReply fault_route(std::string_view method, const std::vector<std::string>& parts, std::string_view body);
    HttpReply post_reset(std::string_view body);
    HttpReply get_events(std::string_view target);
    /// GET /api/frames, GET /api/frames/{name} (docs/control-api.md "Frames").
    HttpReply frames_route(std::string_view method, const std::vector<std::string>& parts, std::string_view path);
    /// After an event on the stream: a "frames" event when a motion's end, a PATCH or a reset
    /// moved frames.
    void follow_up(const Event& e);
    /// The device named `name`; throws BadRequest 404.
    ControlledDevice& device(const std::string& name);
    ControlSurface& surface(ControlledDevice& d);
    void publish(std::string_view device, std::string_view type, const nlohmann::json& data);

    Clock& clock_;
    Ticker& ticker_;
    std::function<bool()> busy_;
    std::vector<ControlledDevice> devices_;
    EventBus* events_;
    models::World* world_;   ///< the rig's bodies (nullptr in tests without one)
    FaultBook faults_;   ///< after devices_, which it refers to
    FrameBook frames_;
    /// The last event framed for the streams (Server-Sent Events text), shared by all of them.
    struct SseFrame {
        std::uint64_t seq = 0;
        StreamChunk text;
    };
    std::shared_ptr<SseFrame> sse_frames_ = std::make_shared<SseFrame>();
};

} // namespace rigsim::control
