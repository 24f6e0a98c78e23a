#pragma once
// What the control API asks of a device (docs/control-api.md): its state read from the world
// and the protocol machine, set-up of a channel, the faults that act inside the device, a power
// cycle, and its wire log. Core defines the seam; each protocol family implements it. The faults
// that act on the wire (unplugged, dropped or corrupted bytes, latency) are core's own: the
// device never sees them.

#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace rigsim {

class WireLog;

/// A control request the device refuses: 400 (a bad field, named), 404 (no such channel),
/// 409 (not now: the channel moves).
struct Refusal {
    unsigned status = 400;
    std::string message;
};
using Refused = std::optional<Refusal>;

/// The faults that act inside a device, on the stage a channel drives (docs/control-api.md
/// "Faults"). Stall, slip, limit_switch and sensor_failure are physical: they act on the world
/// body the channel moves, the same for every family (the control API starts them through
/// models::World::add_fault on the body ControlSurface::fault_body() names, and the body says
/// which it can suffer). reference_lost is the device's: its protocol state forgets the reference.
enum class FaultKind { Stall, Slip, SensorFailure, ReferenceLost, LimitSwitch };

/// Whether a fault of `kind` acts on a body of the world rather than on the device.
constexpr bool physical(FaultKind kind)
{
    return kind != FaultKind::ReferenceLost;
}

/// Every FaultKind, in the order the API lists them.
inline constexpr FaultKind kFaultKinds[] = {FaultKind::Stall, FaultKind::Slip, FaultKind::SensorFailure,
                                            FaultKind::ReferenceLost, FaultKind::LimitSwitch};

/// The API's name of a fault kind: "stall", "slip", "sensor_failure", "reference_lost", "limit_switch".
std::string_view fault_name(FaultKind kind);

/// A device fault as the control API's JSON gives it, parsed once (parse_device_fault).
struct DeviceFault {
    std::uint64_t id = 0;
    FaultKind kind = FaultKind::Stall;
    std::optional<std::size_t> channel;  ///< MCS channel index, APT bay index (0-based); absent: the device picks (0)
    std::optional<double> slip_counts;   ///< slip: steps lost per move (a stepper's microsteps), >= 0
    std::optional<double> slip_fraction; ///< slip: the part of each move lost, 0..1
    int limit_side = 0;                  ///< limit_switch: +1 the forward switch, -1 the reverse one
};

/// Fills `out.kind` and its parameters from `kind` and `params` (the POST body's keys other
/// than "device", "kind" and "channel"; an object); a 400 naming the field for an unknown kind,
/// an unknown parameter or a value out of its range.
Refused parse_device_fault(std::string_view kind, const nlohmann::json& params, DeviceFault& out);

/// Samples a channel's trace keeps (GET .../channels/{index}/trace): the newest ones.
constexpr std::size_t kTraceSamples = 16384;

/// What POST /api/reset and the power_cycle fault do.
struct PowerCycle {
    bool keep_saved = true;          ///< saved settings (non-volatile memory) survive
    bool restore_positions = false;  ///< stages back to their configured start positions (reset only)
};

class ControlSurface {
public:
    virtual ~ControlSurface() = default;

    /// GET /api/devices/{name}: fills `out` (an object) with "channels" (one object per
    /// channel, bay or module: physical position in SI units and in the protocol's units,
    /// velocity, moving, referenced/homed, status decoded, limits, queued commands) and the
    /// family's device-wide state. Core adds name, protocol, model, endpoints and faults.
    virtual void describe(nlohmann::json& out) const = 0;
    /// PATCH /api/devices/{name}/channels/{index}: test set-up (physical position, reference
    /// known or lost, limit switch pressed, sensor power). 409 while the channel moves.
    virtual Refused patch_channel(std::size_t index, const nlohmann::json& body) = 0;
    /// GET /api/devices/{name}/channels/{index}/trace: fills `out` with the channel's sampled
    /// output trace from tick `from_tick` on, at most `max` samples (docs/control-api.md
    /// "Traces"). A channel without an output to trace answers 404.
    virtual Refused trace(std::size_t index, std::int64_t from_tick, std::size_t max, nlohmann::json& out) const
    {
        (void)index, (void)from_tick, (void)max, (void)out;
        return Refusal{404, "no trace for this channel"};
    }
    /// The key of the world body that channel `index` moves (filled in `out`): what a kinematic
    /// joint and a collision address (models/body.hpp, its physical face). 404 "no channel N";
    /// 400 for a channel that moves nothing (a solenoid, a gauge, an end effector).
    virtual Refused axis_body_key(std::size_t index, std::string& out) const
    {
        (void)index, (void)out;
        return Refusal{400, "this device has no axis to mount"};
    }
    /// The world body the channel object `index` of describe() shows (its position_si, body): by
    /// default the one axis_body_key() gives; a device whose channel objects hold several bodies
    /// (an APT card of two channels) names none here and lists them itself.
    virtual Refused channel_body_key(std::size_t index, std::string& out) const { return axis_body_key(index, out); }
    /// The world body a physical fault `f` (physical(f.kind)) acts on: its key in `out`, after
    /// the checks only the device can make. By default the body channel `f.channel` (0 if absent)
    /// moves (axis_body_key); a family adds its own checks (an MCS channel needs a sensor to fail).
    virtual Refused fault_body(const DeviceFault& f, std::string& out) const
    {
        return axis_body_key(f.channel.value_or(0), out);
    }
    /// The physical faults on one of the device's bodies changed: the device reacts as the unit
    /// would (a move the fault ended is reported, a failed sensor freezes the readings).
    virtual void faults_changed() {}
    /// Start the device's own fault `f` (not physical(f.kind): reference_lost), validating its
    /// params; a fault whose effect is one-off acts at once and is not kept (*kept = false).
    virtual Refused add_fault(const DeviceFault& f, bool* kept) = 0;
    /// End the device's own fault `id`: its lasting effect goes away as the hardware's would once
    /// fixed (the families keep none today: reference_lost is one-off).
    virtual void remove_fault(std::uint64_t id) { (void)id; }
    /// Power down and up: protocol state back to power-up.
    virtual void power_cycle(const PowerCycle& how) = 0;
    /// Something inside the device changes by itself that a test waits for: a calibration, a
    /// move delay, a hold time, a piezo settling or a LUT running (not a periodic report such as
    /// status updates or a keep-alive deadline). The rig is idle when the world and every device
    /// are (POST /api/clock run_until_idle).
    virtual bool busy() const { return false; }
    virtual WireLog& wire_log() = 0;
};

} // namespace rigsim
