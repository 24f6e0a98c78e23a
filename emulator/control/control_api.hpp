#pragma once
// The control API's routes (docs/control-api.md): a pure function of (method, target, body)
// over the rig, so that it is tested without sockets. The HTTP server (http_server.hpp)
// only carries requests here.

#include "emulator/control/http_server.hpp"
#include "emulator/core/rig.hpp"
#include "emulator/core/ticker.hpp"
#include "models/clock.hpp"

#include <functional>
#include <string_view>
#include <vector>

namespace rigsim::control {

/// Longest clock time one step_ms or run_until_idle may cover (one day): the daemon answers
/// nothing else meanwhile, so a mistyped number must not stall it for hours.
inline constexpr std::int64_t kMaxStepMs = 86'400'000;

class ControlApi {
public:
    /// The routes over a running rig.
    explicit ControlApi(Rig& rig);
    /// The routes over a clock, its ticker, "something moves" and a device list (tests).
    ControlApi(Clock& clock, Ticker& ticker, std::function<bool()> busy, std::vector<DeviceEndpoints> devices);

    /// Answer one request; never throws for any input.
    HttpReply handle(std::string_view method, std::string_view target, std::string_view body);

private:
    HttpReply get_rig();
    HttpReply get_clock();
    HttpReply post_clock(std::string_view body);

    Clock& clock_;
    Ticker& ticker_;
    std::function<bool()> busy_;
    std::vector<DeviceEndpoints> devices_;
};

} // namespace rigsim::control
