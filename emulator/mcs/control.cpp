// McsDevice as the control API sees it (docs/control-api/mcs.md): state, set-up, faults,
// power cycle, wire-log notes and events. Nothing here runs on the wire's hot path except
// note_command() (a few compares unless the client slipped) and publish_changes() (a branch
// unless someone listens).

#include "emulator/mcs/mcs_device.hpp"

#include "emulator/core/event_bus.hpp"
#include "emulator/mcs/sensor_types.hpp"
#include "emulator/mcs/wire_names.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

namespace rigsim::mcs {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Appendix 4.1 (8 per the errata).
const char* status_name(int code)
{
    static constexpr const char* kNames[] = {"stopped",     "stepping",    "scanning",
                                             "holding",     "targeting",   "move_delay",
                                             "calibrating", "finding_reference_mark", "gripper_moving",
                                             "locked"};
    return code >= 0 && code <= 9 ? kNames[code] : "unknown";
}

const char* sensor_mode_name(SensorMode m)
{
    switch (m) {
    case SensorMode::Disabled:
        return "disabled";
    case SensorMode::Enabled:
        return "enabled";
    case SensorMode::PowerSave:
        return "power_save";
    }
    return "enabled";
}

bool idle(int status)
{
    return status == static_cast<int>(ChannelStatus::Stopped) || status == static_cast<int>(ChannelStatus::Locked);
}

/// nm (µ°) -> m (rad).
double si_of(const Channel& ch, double physical)
{
    return ch.rotary() ? physical * 1e-6 * kPi / 180.0 : physical * 1e-9;
}

nlohmann::json finite_or_null(double v)
{
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

Refusal bad(std::string message)
{
    return Refusal{400, std::move(message)};
}

/// PATCH position_si: the body is put there through its physical face (m or rad, by its kind).
void place_si(models::Body& body, double si)
{
    if (body.travel() == models::Travel::Line)
        body.place_m(si);
    else
        body.place_rad(si);
}

} // namespace

int McsDevice::status_code(std::size_t i) const
{
    const auto index = static_cast<std::int32_t>(i);
    if (const auto* ee = controller_.effector(index))
        return static_cast<int>(ee->status());
    const auto* ch = controller_.channel(index);
    return ch ? static_cast<int>(ch->status()) : 0;
}

void McsDevice::channel_json(std::size_t i, nlohmann::json& j) const
{
    const auto index = static_cast<std::int32_t>(i);
    const int code = status_code(i);
    j["index"] = i;
    j["status"] = {{"code", code}, {"name", status_name(code)}};
    j["moving"] = !idle(code);
    if (const auto* ee = controller_.effector(index)) {
        j["kind"] = "end_effector";
        j["type"] = static_cast<int>(ee->type());
        std::int32_t v = 0;
        j["opening_cv"] = ee->opening_cv(v) ? nlohmann::json(nullptr) : nlohmann::json(v);
        j["force_dun"] = ee->force_dun(v) ? nlohmann::json(nullptr) : nlohmann::json(v);
        return;
    }
    const auto& ch = *controller_.channel(index);
    const auto& body = ch.body();
    j["kind"] = ch.rotary() ? "rotary" : "linear";
    // position_si, velocity_si, si_unit: the body's, added by the control API (body_state.cpp).
    const bool readable = ch.rotary() ? !ch.check_angular_sensor() : !ch.check_linear_sensor();
    j["position_protocol"] = readable ? nlohmann::json(ch.position()) : nlohmann::json(nullptr);
    j["protocol_unit"] = ch.rotary() ? "udeg" : "nm";
    j["referenced"] = ch.physical_position_known();
    const auto [tmin, tmax] = ch.travel();
    nlohmann::json range = nullptr;
    if (const auto [lo, hi] = ch.range_limit(); lo != hi)
        range = {{"min", lo}, {"max", hi}};
    j["limits"] = {{"range_limit", range},
                   {"end_stops_si", {finite_or_null(si_of(ch, tmin)), finite_or_null(si_of(ch, tmax))}}};
    auto queued = nlohmann::json::array();
    for (const auto& [source, command] : ch.queued())
        queued.push_back({{"text", command_text(command)}, {"trigger_source", source}});
    j["queued"] = std::move(queued);
    j["queue_armed"] = ch.armed_queue_source() ? nlohmann::json(*ch.armed_queue_source()) : nlohmann::json(nullptr);
    if (const auto* s = ch.sensor())
        j["sensor"] = {{"type", s->code}, {"name", s->symbol}, {"mode", sensor_mode_name(ch.sensor_mode())},
                       {"failed", ch.sensor_failed()}};
    else
        j["sensor"] = nullptr;
    j["stalled"] = body.blocked();
    j["slip"] = body.slip();
    j["last_outcome"] = ch.last_outcome();
}

Refused McsDevice::axis_body_key(std::size_t index, std::string& out) const
{
    if (index >= controller_.channel_count())
        return Refusal{404, "no channel " + std::to_string(index) + " (the device has "
                                + std::to_string(controller_.channel_count()) + ")"};
    const auto i = static_cast<std::int32_t>(index);
    if (controller_.effector(i))
        return bad("channel " + std::to_string(index) + " is an end effector (gripper, force sensor): it moves nothing");
    // The body is the world's: it outlives the channel's protocol state (a power cycle keeps it).
    out = controller_.channel(i)->body().key();
    return std::nullopt;
}

void McsDevice::describe(nlohmann::json& out) const
{
    auto channels = nlohmann::json::array();
    for (std::size_t i = 0; i < controller_.channel_count(); ++i) {
        nlohmann::json j = nlohmann::json::object();
        channel_json(i, j);
        channels.push_back(std::move(j));
    }
    out["channels"] = std::move(channels);
    out["communication_mode"] = controller_.communication_mode() == CommunicationMode::Sync ? "sync" : "async";
    out["sensor_mode"] = sensor_mode_name(controller_.sensor_mode());
    out["keep_alive_ms"] = controller_.keep_alive_ms();
    out["baudrate"] = controller_.baudrate();
    out["baudrate_after_reset"] = controller_.configured_baudrate();
    out["system_id"] = controller_.system_id();
    out["emergency_stop_mode"] = controller_.emergency_stop_mode();
}

Refused McsDevice::patch_channel(std::size_t index, const nlohmann::json& body)
{
    if (index >= controller_.channel_count())
        return Refusal{404, "no channel " + std::to_string(index) + " (the device has "
                                + std::to_string(controller_.channel_count()) + ")"};
    if (!body.is_object())
        return bad("the body must be an object");
    auto* ch = controller_.channel(static_cast<std::int32_t>(index));
    // Validate every key before changing anything.
    // nm or µ°: a million revolutions of a rotary stage, far inside an int64 and a double's integers.
    constexpr double kMaxPlace = 360e6 * 1e6;
    for (const auto& [key, value] : body.items()) {
        if (key == "limit_switch")
            return bad("limit_switch: an MCS positioner has no limit switches (its end stops are mechanical; "
                       "see the stall fault)");
        if (key != "position_si" && key != "referenced" && key != "sensor")
            return bad(key + ": unknown key (position_si, referenced, sensor)");
        if (!ch)
            return bad(key + ": channel " + std::to_string(index) + " is an end effector");
        if (key == "position_si") {
            if (!value.is_number())
                return bad("position_si: a number is required");
            const auto [lo, hi] = ch->travel();
            const double si = value.get<double>();
            const double physical = ch->rotary() ? si * 180.0 / kPi * 1e6 : si * 1e9;
            // An endless rotary stage has no end stops: its bound is what the scale can count.
            if (!std::isfinite(physical) || std::abs(physical) > kMaxPlace || physical < lo - 1e-6 || physical > hi + 1e-6)
                return bad("position_si: outside the travel between the end stops");
        } else if (key == "referenced") {
            if (!value.is_boolean())
                return bad("referenced: true or false is required");
            if (!ch->sensor() || ch->sensor_failed())
                return bad("referenced: the channel has no working sensor");
        } else {
            if (!value.is_string() || (value != "enabled" && value != "disabled" && value != "power_save"))
                return bad("sensor: \"enabled\", \"disabled\" or \"power_save\" is required");
            if (!ch->sensor())
                return bad("sensor: the channel has no sensor (2.2.5)");
        }
    }
    if (ch && ch->status() != ChannelStatus::Stopped && ch->status() != ChannelStatus::Locked)
        return Refusal{409, "channel " + std::to_string(index) + " is not stopped (status "
                                + std::to_string(static_cast<int>(ch->status())) + ")"};
    if (!ch)
        return std::nullopt;   // an empty body on an end effector
    if (const auto it = body.find("sensor"); it != body.end())
        ch->set_sensor_mode(*it == "enabled" ? SensorMode::Enabled
                                             : *it == "disabled" ? SensorMode::Disabled : SensorMode::PowerSave);
    if (const auto it = body.find("position_si"); it != body.end())
        place_si(ch->body(), it->get<double>());
    if (const auto it = body.find("referenced"); it != body.end())
        ch->set_referenced(it->get<bool>());
    publish_changes();
    return std::nullopt;
}

void McsDevice::sync_sensor(std::size_t index)
{
    if (auto* ch = controller_.channel(static_cast<std::int32_t>(index)))
        ch->set_sensor_failed(ch->body().faults().sensor_failed);
}

Refused McsDevice::fault_body(const DeviceFault& f, std::string& out) const
{
    const std::size_t index = f.channel.value_or(0);
    if (auto refused = axis_body_key(index, out))
        return refused;
    if (f.kind == FaultKind::SensorFailure && !controller_.channel(static_cast<std::int32_t>(index))->sensor())
        return bad("kind: channel " + std::to_string(index) + " has no sensor");
    return std::nullopt;
}

void McsDevice::faults_changed()
{
    for (std::size_t i = 0; i < controller_.channel_count(); ++i)
        sync_sensor(i);
    tick(clock_.now());   // a movement the fault ended is over now: its 142 goes out (async mode)
}

Refused McsDevice::add_fault(const DeviceFault& f, bool* kept)
{
    if (kept)
        *kept = false;
    if (physical(f.kind))   // the control API starts these on the body (fault_body)
        return bad("kind: " + std::string(fault_name(f.kind)) + " acts on the stage, not on the controller");
    const std::size_t index = f.channel.value_or(0);
    if (index >= controller_.channel_count())
        return Refusal{404, "no channel " + std::to_string(index)};
    auto* ch = controller_.channel(static_cast<std::int32_t>(index));
    if (!ch)
        return bad("channel: channel " + std::to_string(index) + " is an end effector");
    if (!ch->sensor())
        return bad("kind: channel " + std::to_string(index) + " has no sensor");
    ch->set_referenced(false);   // one-off: the position becomes unknown now
    publish_changes();
    return std::nullopt;
}

void McsDevice::power_cycle(const PowerCycle& how)
{
    if (!how.keep_saved)
        controller_.restore_defaults();
    if (how.restore_positions)
        controller_.place_at_start();
    controller_.reset();   // R: the stages read 0 where they stand, position unknown
    for (std::size_t i = 0; i < controller_.channel_count(); ++i)
        sync_sensor(i);   // a dead sensor outlasts the power cycle (a stall too: it is the body's)
    publish_changes();
}

void McsDevice::log_answer(std::string_view peer, std::string_view bytes, std::string note)
{
    std::vector<std::string> notes;
    notes.push_back(std::move(note));
    wire_log_.add(clock_.now(), false, peer, bytes, std::move(notes));
}

void McsDevice::note_command(const Command* command, const Reply& reply, std::vector<std::string>& notes) const
{
    if (const auto* err = std::get_if<Error>(&reply)) {
        const auto code = static_cast<int>(err->code);
        const std::string answer = "E" + std::to_string(err->channel) + "," + std::to_string(code) + " "
                                   + std::string(error_name(code)) + " (appendix 4.2)";
        const bool setting = line_.size() > 1 && (line_[1] == 'S' || line_[1] == 'K' || line_.rfind(":CB", 0) == 0);
        if (err->code == ErrorCode::InvalidParameter && setting)
            notes.push_back("setting out of the documented range: answered " + answer);
        else
            notes.push_back("answered with an error: " + answer);
        return;
    }
    if (!command)
        return;
    // An absolute closed-loop target means a physical place only once the position is
    // known (2.3.3: at power-up "it simply assumes its starting position as the zero").
    std::int32_t index = -1;
    if (const auto* c = std::get_if<MovePositionAbsolute>(command))
        index = c->channel;
    else if (const auto* c = std::get_if<MoveAngleAbsolute>(command))
        index = c->channel;
    if (index < 0)
        return;
    if (const auto* ch = controller_.channel(index); ch && !ch->physical_position_known())
        notes.push_back("absolute move while the physical position is unknown (GPPK 0): the target is relative "
                        "to where the stage stood at power-up or SP (2.3.3); FRM first");
}

void McsDevice::publish_changes()
{
    const auto& name = config_.name;
    const bool moves = events_ && (events_->wants(name, "move_started") || events_->wants(name, "move_ended"));
    const bool statuses = events_ && events_->wants(name, "status");
    if (!moves && !statuses) {
        status_known_ = false;
        return;
    }
    const auto n = controller_.channel_count();
    const double time_ms = static_cast<double>(clock_.now()) * 1000.0 / clock_.tick_hz();
    if (!status_known_) {   // someone started listening: the state now is the baseline
        last_status_.resize(n);
        for (std::size_t i = 0; i < n; ++i)
            last_status_[i] = status_code(i);
        status_known_ = true;
        return;
    }
    for (std::size_t i = 0; i < n; ++i) {
        const int code = status_code(i);
        const int was = last_status_[i];
        if (code == was)
            continue;
        last_status_[i] = code;
        if (moves && idle(was) && !idle(code))
            events_->publish(config_.name, "move_started", time_ms, {{"channel", i}});
        if (statuses)
            events_->publish(config_.name, "status", time_ms,
                             {{"channel", i}, {"status", {{"code", code}, {"name", status_name(code)}}}});
        if (moves && !idle(was) && idle(code)) {
            const auto* ch = controller_.channel(static_cast<std::int32_t>(i));
            events_->publish(config_.name, "move_ended", time_ms,
                             {{"channel", i}, {"outcome", ch ? ch->last_outcome() : "completed"}});
        }
    }
}

} // namespace rigsim::mcs
