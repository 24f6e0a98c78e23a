#pragma once
// The wire log's reading of an APT frame (docs/control-api/apt.md "Wire log"): the manual's
// name, source, destination and the fields of the codec's struct by name. Runs only when
// someone reads the log or listens to its events.

#include "emulator/apt/catalogue.hpp"

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string_view>
#include <vector>

namespace rigsim::apt {

/// Whose table names a status word's bits: they mean other things on other units.
enum class StatusTable {
    Motor,         ///< MOT_GET_STATUSUPDATE / DCSTATUSUPDATE (p. 77-79)
    Solenoid,      ///< the same messages from a TSC001/KSC101 (D-4: output, interlock, key)
    Piezo,         ///< PZ_GET_PZSTATUSBITS / PZSTATUSUPDATE (p. 101-104: TPZ001 and BPC tables)
    StrainGauge,   ///< the same piezo messages from a TSG001/KSG101 (bit 0: a gauge connected)
    Rack,          ///< RACK_GET_STATUSBITS (p. 25): the USER IO lines 1..4
};

/// What a frame's bytes alone do not tell: the unit on whose wire it crossed.
struct LogContext {
    /// MOVE_COMPLETED and MOVE_STOPPED carry MOT_GET_STATUSUPDATE's structure (position, encoder
    /// count, status bits: a stepper's, p. 44) rather than MOT_GET_DCSTATUSUPDATE's.
    bool stepper_status = false;
    /// The unit's kind: the motor messages' bits are the solenoid's on a solenoid unit, the piezo
    /// messages' a reader's on a strain gauge unit.
    StatusTable unit = StatusTable::Motor;
};

/// What the wire log must know of a unit of `model` (its motor kind, its unit kind).
LogContext log_context(const ControllerModel& model);

/// One recorded frame as {"id": "0x0453", "name", "source": "0x01", "destination": "0x50",
/// "fields": {...}}; bytes that are no whole frame as {"name": "not a frame"}.
void decode_for_log(std::string_view frame, nlohmann::json& out, const LogContext& unit = {});

/// The field names of message `id` in wire order, from its codec struct's RIGSIM_APT_FIELDS, or
/// nullptr for a message without fields (HW_DISCONNECT, ...), an end-of-move message (its status
/// structure's fields depend on the unit) or an ID outside the table.
const std::vector<std::string_view>* field_names(std::uint16_t id);

/// The names of the status bits set in `bits` in `table` ("homed", "enabled", ...), lowest first.
std::vector<std::string_view> status_bit_names(std::uint32_t bits, StatusTable table = StatusTable::Motor);

} // namespace rigsim::apt
