#pragma once
// The physical half of a device's state as the control API shows it (docs/control-api.md
// "Devices"): what the world's bodies say of the channels that move them, written the same way
// for every family, beside what the device says of its protocol (ControlSurface::describe).

#include "emulator/core/control_surface.hpp"
#include "models/world.hpp"

#include <nlohmann/json.hpp>

namespace rigsim::control {

/// `surface.describe(out)`, then, for every channel of out["channels"] whose axis is a body of
/// `world` (ControlSurface::axis_body_key): "position_si" and "velocity_si" in the body's SI unit,
/// "si_unit" ("m" along a line, "rad" about an axis), and "body": its "key", "kind", whether it is
/// "settling", and the physical "faults" acting on it. `world` nullptr: the device's part only.
void describe_device(const ControlSurface& surface, const models::World* world, nlohmann::json& out);

} // namespace rigsim::control
