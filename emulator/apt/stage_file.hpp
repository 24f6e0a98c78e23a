#pragma once
// A stage described in JSON: a shipped stage file (config/stages/<NAME>.json) or a rig's inline
// stage object (apt.stage, apt.bays[i]). One schema for both (docs/config.md, "APT stages").

#include "emulator/apt/catalogue.hpp"

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace rigsim {
class ConfigReader;
}

namespace rigsim::apt {

/// The stage object `object` at `pointer`: its keys (unknown ones, those of another kind of
/// stage), types and ranges; throws ConfigError through `reader` naming the pointer of the
/// offending value. The controller it sits on is checked by the caller (config.cpp).
StageModel read_stage(const ConfigReader& reader, const nlohmann::json& object, const std::string& pointer);

/// The stage's kind as the schema spells it: "linear", "rotary", "goniometer".
const char* kind_name(StageKind kind);
/// The stage's motor as the schema spells it: "dc_servo", "stepper", "brushless".
const char* motor_name(MotorKind motor);

} // namespace rigsim::apt
