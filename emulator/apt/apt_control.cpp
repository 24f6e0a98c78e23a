// AptDevice's side of the control API (docs/control-api/apt.md): the state of its bays read
// from the world and the protocol machine, their set-up, the faults that act inside the unit,
// the power cycle, the wire log and the events.

#include "emulator/apt/apt_device.hpp"
#include "emulator/core/log_format.hpp"
#include "emulator/apt/piezo_module.hpp"
#include "emulator/apt/pzmot_module.hpp"
#include "emulator/apt/stage_file.hpp"
#include "emulator/apt/wire_decode.hpp"
#include "emulator/core/event_bus.hpp"
#include "emulator/core/state_store.hpp"
#include "models/axis.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <optional>
#include <utility>

namespace rigsim::apt {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// The "unit" key of a channel object: the kind of unit it belongs to.
const char* unit_name(UnitKind kind)
{
    switch (kind) {
    case UnitKind::Motor:
        return "motor";
    case UnitKind::Solenoid:
        return "solenoid";
    case UnitKind::Piezo:
        return "piezo";
    case UnitKind::StrainGauge:
        return "strain_gauge";
    case UnitKind::Flipper:
        return "flipper";
    case UnitKind::Polariser:
        return "polariser";
    case UnitKind::PiezoMotor:
        return "piezo_motor";
    }
    return "motor";
}

/// SI units (m or rad) per stage count: the stage's counts per mm (per degree for a rotation
/// stage or a goniometer).
double si_per_count(const StageModel& stage)
{
    return stage.angular() ? kPi / 180.0 / stage.counts_per_mm : 1e-3 / stage.counts_per_mm;
}

/// The unit of a channel's SI figures.
const char* si_unit(const StageModel& stage)
{
    return stage.angular() ? "rad" : "m";
}

std::string hex32(std::uint32_t v)
{
    char buf[12];
    std::snprintf(buf, sizeof buf, "0x%08x", v);
    return buf;
}

nlohmann::json status_json(std::uint32_t bits)
{
    return {{"bits", bits}, {"hex", hex32(bits)}, {"set", status_bit_names(bits)}};
}

Refusal bad(std::string message)
{
    return Refusal{400, std::move(message)};
}

} // namespace

void AptDevice::record(bool inbound, std::string_view peer, std::string_view frame, std::vector<std::string> notes,
                       bool unprompted)
{
    wire_log_.add(clock_.now(), inbound, peer, frame, std::move(notes), unprompted);
}

std::vector<std::string> AptDevice::update_notes() const
{
    // USB "server alive" (p. 80, p. 105): the unit counts the status update type messages it
    // sends without the acknowledgement (MOT_ACK_DCSTATUSUPDATE, PZ_ACK_PZSTATUSUPDATE,
    // PZMOT_ACK_STATUSUPDATE) and stops at the model's cut-off (50; a KIM101/TIM101 10).
    if (!updates_ || (updates_since_ack_ != updates_warn_at() && updates_since_ack_ != updates_without_ack()))
        return {};
    const auto* ack = find_message(model_.ack_id);
    const std::string ack_name = ack ? std::string(ack->name) : "the acknowledgement";
    const std::string page = model_.ack_id == MGMSG_MOT_ACK_DCSTATUSUPDATE ? "(p. 80)"
                             : model_.ack_id == MGMSG_PZMOT_ACK_STATUSUPDATE ? "(issue 37 p. 406)"
                                                                              : "(p. 105)";
    if (updates_since_ack_ == updates_warn_at())
        return {std::to_string(updates_warn_at()) + " of " + std::to_string(updates_without_ack())
                + " status update messages without " + ack_name + ": the unit stops sending them at "
                + std::to_string(updates_without_ack()) + " " + page};
    return {"cut-off: " + std::to_string(updates_without_ack()) + " status update messages without " + ack_name
            + "; the unit sends no more until the host acknowledges " + page};
}

nlohmann::json AptDevice::channel_json(std::size_t bay) const
{
    char address[8];
    std::snprintf(address, sizeof address, "0x%02x", address_of(bay));
    if (bay >= channels_.size()) {   // a kind without a motor describes itself
        nlohmann::json out{{"index", bay}, {"unit", unit_name(model_.kind)}, {"address", address}};
        // "kind" is what the channel moves, as for the motor stages: a piezo stack extends along
        // a line; a solenoid's output and a gauge move nothing of their own.
        if (model_.kind == UnitKind::Piezo)
            out["kind"] = "linear";
        modules_[bay]->describe(out);
        // A solenoid's, piezo's or gauge's status dword by its bits' names too, in the unit's own
        // table (the wire log's). A flipper's is the motor table's read otherwise (its positions in
        // the limit bits): its object names its position instead.
        const auto status = out.find("status");
        if (status != out.end() && status->is_number_integer()
            && (model_.kind == UnitKind::Solenoid || model_.kind == UnitKind::Piezo || model_.kind == UnitKind::StrainGauge))
            out["status_set"] = status_bit_names(status->get<std::uint32_t>(), log_context(model_).unit);
        return out;
    }
    const MotorChannel& ch = *channels_[bay];
    const StageModel& stage = ch.stage();
    const models::Axis& axis = ch.axis();
    const double k = si_per_count(stage);
    const std::uint32_t bits = ch.status_bits();
    const double x = axis.position_counts();
    const auto& l = ch.limit_switch;
    const bool soft = ((l.mode & 0x7f) == 2 || (l.mode & 0x7f) == 3) && l.cw_soft > l.ccw_soft;
    const bool rotary = stage.kind == StageKind::Rotary;
    const bool at_forward = !rotary && (x >= axis.travel_max_counts() - 0.5 || ch.switch_pressed() > 0);
    const bool at_reverse = !rotary && (x <= axis.travel_min_counts() + 0.5 || ch.switch_pressed() < 0);
    nlohmann::json limits{
        {"switch_params",
         {{"cw_hard_limit", l.cw_hard}, {"ccw_hard_limit", l.ccw_hard}, {"cw_soft_limit", l.cw_soft},
          {"ccw_soft_limit", l.ccw_soft}, {"soft_limit_mode", l.mode}}},
        {"soft_limits", {{"active", soft}, {"forward", l.cw_soft}, {"reverse", l.ccw_soft}}},
        {"travel",
         {{"min", ch.min_position()}, {"max", ch.max_position()}, {"min_si", axis.travel_min_counts() * k},
          {"max_si", axis.travel_max_counts() * k}}},
        {"switch_pressed", {{"forward", at_forward}, {"reverse", at_reverse}}}};
    return {{"index", bay},
            {"unit", unit_name(model_.kind)},
            {"kind", kind_name(stage.kind)},
            {"stage", stage.name},
            {"address", address},
            {"position_protocol", ch.position()},
            {"protocol_unit", "counts"},
            {"encoder", ch.encoder()},
            {"encoder_failed", ch.encoder_failed()},
            {"moving", ch.moving()},
            {"referenced", ch.homed()},
            {"enabled", ch.enabled()},
            {"status", status_json(bits)},
            {"limits", std::move(limits)}};
}

Refused AptDevice::axis_body_key(std::size_t index, std::string& out) const
{
    if (model_.kind == UnitKind::PiezoMotor) {
        // Its four actuators are channels 0 to 3 for faults and kinematics (its one channel object,
        // channel 0, lists them).
        const auto* pzmot = modules_.empty() ? nullptr : dynamic_cast<const PzMotorModule*>(modules_[0].get());
        if (!pzmot || index >= PzMotorModule::kChannels)
            return Refusal{404, "no channel " + std::to_string(index) + ": the " + config_.model
                                    + "'s actuators are channels 0 to 3"};
        out = pzmot->drive(index).key();
        return std::nullopt;
    }
    if (model_.bay_channels > 1) {
        // Two channels a card (an MMR601's MPZ601): channel 2 × bay + card channel - 1 for faults and
        // kinematics (its channel objects are the cards, channel = bay).
        const auto per_bay = static_cast<std::size_t>(model_.bay_channels);
        if (index >= modules_.size() * per_bay)
            return Refusal{404, "no channel " + std::to_string(index) + ": the " + config_.model + "'s piezo channels are 0 to "
                                    + std::to_string(modules_.size() * per_bay - 1) + " (2 × bay + card channel - 1)"};
        out = piezo_key(index / per_bay, index % per_bay);
        return std::nullopt;
    }
    if (index >= modules_.size())
        return Refusal{404, "no channel " + std::to_string(index) + ": the " + config_.model + " has "
                                + (modules_.size() == 1 ? "channel 0 only" : "channels 0 to " + std::to_string(modules_.size() - 1))};
    if (index >= channels_.size()) {   // a kind without a motor
        if (const auto* piezo = dynamic_cast<const PiezoModule*>(modules_[index].get())) {
            // The actuator is the world's: a power cycle's new module drives the same body.
            out = piezo->actuator().key();
            return std::nullopt;
        }
        const char* what = model_.kind == UnitKind::Solenoid  ? "a solenoid controller"
                           : model_.kind == UnitKind::Flipper ? "a flip mount"
                           : model_.kind == UnitKind::Polariser ? "a polarisation controller"
                                                              : "a strain gauge reader";
        return bad("channel " + std::to_string(index) + " of the " + config_.model + " (" + what + ") moves nothing");
    }
    // The axis is the world's; its carriage, not the counters (lost steps do not move it).
    out = channels_[index]->axis().key();
    return std::nullopt;
}

Refused AptDevice::channel_body_key(std::size_t index, std::string& out) const
{
    // A two-channel card's object lists its channels' bodies (PiezoCard::describe).
    if (model_.bay_channels > 1)
        return Refusal{400, "an " + std::string(model_.bay_model_name) + " card has two channels"};
    return axis_body_key(index, out);
}

void AptDevice::describe(nlohmann::json& out) const
{
    auto channels = nlohmann::json::array();
    for (std::size_t bay = 0; bay < modules_.size(); ++bay)
        channels.push_back(channel_json(bay));
    out["channels"] = std::move(channels);
    out["serial_number"] = serial_;
    out["status_updates"] = {{"on", updates_},
                             {"unacknowledged", updates_since_ack_},
                             {"cut_off", updates_ && updates_since_ack_ >= updates_without_ack()}};
    out["end_of_move_messages"] = end_of_move_messages_;
    if (model_.wrong_address_freezes)
        out["frozen"] = frozen_;
}

Refused AptDevice::patch_channel(std::size_t index, const nlohmann::json& body)
{
    if (index >= modules_.size())
        return Refusal{404, "no channel " + std::to_string(index) + ": the " + config_.model + " has "
                                + (modules_.size() == 1 ? "channel 0 only" : "channels 0 to " + std::to_string(modules_.size() - 1))};
    if (!body.is_object())
        return bad("the body must be an object");
    if (index >= channels_.size()) {   // a kind without a motor patches itself
        auto refused = modules_[index]->patch(body);
        flush();
        return refused;
    }
    MotorChannel& ch = *channels_[index];
    const models::Axis& axis = ch.axis();
    const double k = si_per_count(ch.stage());
    for (const auto& [key, value] : body.items()) {
        if (key == "position_si") {
            if (!value.is_number())
                return bad("position_si must be a number (" + std::string(si_unit(ch.stage())) + ")");
            const double x = value.get<double>() / k;
            // A rotation stage has no end stops: its bound is what the position counter holds.
            if (!std::isfinite(x) || std::abs(x) > 2147483647.0)
                return bad("position_si " + value.dump() + " is beyond what the position counter can hold");
            const bool outside = x < axis.travel_min_counts() - 0.5 || x > axis.travel_max_counts() + 0.5;
            if (ch.stage().kind == StageKind::Linear && outside)
                return bad("position_si " + value.dump() + " m is outside the travel of the " + ch.stage().name
                           + " (0 to " + std::to_string(axis.travel_max_counts() * k) + " m)");
            if (ch.stage().kind == StageKind::Goniometer && outside)
                return bad("position_si " + value.dump() + " rad is outside the angle range of the goniometer "
                           + ch.stage().name + " (" + std::to_string(axis.travel_min_counts() * k) + " to "
                           + std::to_string(axis.travel_max_counts() * k) + " rad)");
        } else if (key == "referenced" || key == "enabled") {
            if (!value.is_boolean())
                return bad(key + " must be true or false");
        } else if (key == "limit_switch") {
            if (!value.is_string() || (value != "forward" && value != "reverse" && value != "none"))
                return bad("limit_switch must be \"forward\", \"reverse\" or \"none\"");
        } else if (key == "sensor") {
            return bad("sensor: an APT stage's encoder has no power modes of its own (it is powered with the "
                       "motor); the sensor_failure fault makes it fail");
        } else {
            return bad("unknown key \"" + key + "\" (APT channels take position_si, referenced, limit_switch, enabled)");
        }
    }
    if (ch.moving())
        return Refusal{409, "channel " + std::to_string(index) + " is moving"};
    if (const auto it = body.find("position_si"); it != body.end()) {   // through the body's physical face
        models::Axis& axis_body = ch.axis();
        if (axis_body.travel() == models::Travel::Line)
            axis_body.place_m(it->get<double>());
        else
            axis_body.place_rad(it->get<double>());
    }
    if (const auto it = body.find("referenced"); it != body.end())
        ch.set_homed(it->get<bool>());
    if (const auto it = body.find("limit_switch"); it != body.end()) {
        const auto side = it->get<std::string>();
        ch.axis().set_switch_held(side == "forward" ? 1 : side == "reverse" ? -1 : 0);
    }
    if (const auto it = body.find("enabled"); it != body.end())
        ch.set_enabled(it->get<bool>());
    flush();   // events of the change (status)
    return std::nullopt;
}

Refused AptDevice::fault_body(const DeviceFault& f, std::string& out) const
{
    if (model_.kind == UnitKind::PiezoMotor) {
        // A KIM101/TIM101's actuators suffer the physical faults their bodies take (stall, slip);
        // the unit keeps no reference to lose (open loop).
        if (!physical(f.kind))
            return bad("\"kind\": " + std::string(fault_name(f.kind)) + ": the " + config_.model
                       + " counts pulses open loop: it has no reference to lose");
        return axis_body_key(f.channel.value_or(0), out);
    }
    if (model_.kind != UnitKind::Motor)   // every physical fault kind acts on a motor and its stage
        return bad("\"kind\": " + std::string(fault_name(f.kind)) + " is a motor fault and the " + config_.model
                   + " (a " + unit_name(model_.kind) + " unit) has no motor; its link faults (unplugged, drop_bytes, "
                   "corrupt_bytes, latency) and power_cycle act on it");
    const std::size_t bay = f.channel.value_or(0);
    if (bay >= channels_.size())
        return Refusal{404, "no channel " + std::to_string(bay) + " on " + config_.name};
    out = channels_[bay]->axis().key();
    return std::nullopt;
}

void AptDevice::faults_changed()
{
    for (auto& ch : channels_)
        ch->sync_faults();
    flush();   // events of the change (status)
}

Refused AptDevice::add_fault(const DeviceFault& f, bool* kept)
{
    *kept = false;
    std::string key;
    if (auto refused = fault_body(f, key))   // the same checks: reference_lost is a motor's too
        return refused;
    if (physical(f.kind))   // the control API starts these on the body (fault_body)
        return bad("\"kind\": " + std::string(fault_name(f.kind)) + " acts on the stage, not on the controller");
    const std::size_t bay = f.channel.value_or(0);
    channels_[bay]->set_homed(false);   // one-off: homing finds it again
    log_->info("control: fault {} (reference_lost) on channel {}", f.id, bay);
    flush();
    return std::nullopt;
}

void AptDevice::power_cycle(const PowerCycle& how)
{
    for (std::size_t bay = 0; bay < modules_.size(); ++bay) {
        modules_[bay]->power_down(how.restore_positions);
        modules_[bay] = make_module(bay);
        connect_events(bay);
    }
    for (std::size_t bay = 0; bay < channels_.size(); ++bay) {
        if (how.restore_positions)
            channels_[bay]->axis().set_switch_held(0);
        channels_[bay]->sync_faults();   // a stall, a slip or a dead encoder outlasts the power cycle
        was_moving_[bay] = false;
        stalled_[bay] = false;
    }
    if (model_.rack) {
        motherboard_ = std::make_unique<RackMotherboard>(unit_, modules_.size(), *log_);
        for (std::size_t i = 0; i < empty_bays_.size(); ++i)
            empty_bays_[i] = std::make_unique<EmptyBay>(unit_, modules_.size() + i, model_.motor != MotorKind::Stepper, *log_);
    }
    updates_ = false;
    next_update_ = kNever;
    updates_since_ack_ = 0;
    end_of_move_messages_ = true;
    frozen_ = false;
    host_ = kHost;
    last_set_.clear();
    // The unit's own memory (the rig's "eeprom") always comes back; what clients saved only when kept.
    if (!how.keep_saved && store_)
        store_->erase(config_.name);
    restore_from_eeprom(false);
    log_->info("control: power cycle ({} saved settings{})", how.keep_saved ? "kept" : "erased",
               how.restore_positions ? ", stages back at their start positions" : "");
    flush();
}

Refused AptDevice::trace(std::size_t index, std::int64_t from_tick, std::size_t max, nlohmann::json& out) const
{
    if (index >= modules_.size())
        return Refusal{404, "no channel " + std::to_string(index) + " on " + config_.name};
    out["tick_hz"] = clock_.tick_hz();
    out["channel"] = index;
    return modules_[index]->trace(from_tick, max, out);
}

void AptDevice::connect_events(std::size_t bay)
{
    modules_[bay]->set_event_sink([this, bay](std::string_view type, const nlohmann::json& data) {
        if (!events_ || !events_->wants(config_.name, type))
            return;
        nlohmann::json with = data;
        with["channel"] = bay;
        events_->publish(config_.name, type, clock_.seconds(clock_.now()) * 1000.0, std::move(with));
    });
}

void AptDevice::publish_events(std::size_t bay, const std::vector<MotorEvent>& events)
{
    const bool moving = channels_[bay]->moving();
    const auto& name = config_.name;
    const bool statuses = events_ && events_->wants(name, "status");
    if (!statuses && !(events_ && (events_->wants(name, "move_started") || events_->wants(name, "move_ended")))) {
        was_moving_[bay] = moving;
        return;
    }
    const double ms = clock_.seconds(clock_.now()) * 1000.0;
    auto publish = [&](const char* type, nlohmann::json data) {
        data["channel"] = bay;
        events_->publish(config_.name, type, ms, std::move(data));
    };
    bool in_move = was_moving_[bay];
    for (const auto e : events) {
        if (e == MotorEvent::Fault) {
            stalled_[bay] = true;   // the Stopped that follows ends the move
            continue;
        }
        if (!in_move && e == MotorEvent::Stopped && !stalled_[bay])
            continue;   // MOVE_STOP at rest: no move ended
        if (!in_move)
            publish("move_started", nlohmann::json::object());
        const char* outcome = e == MotorEvent::MoveCompleted ? "completed"
                              : e == MotorEvent::Homed       ? "homed"
                              : stalled_[bay]                ? "fault"
                                                             : "stopped";
        stalled_[bay] = false;
        publish("move_ended", {{"outcome", outcome}});
        in_move = false;
    }
    if (moving && !in_move)
        publish("move_started", nlohmann::json::object());
    was_moving_[bay] = moving;
    const std::uint32_t bits = channels_[bay]->status_bits();
    if (bits != published_status_[bay]) {
        published_status_[bay] = bits;
        if (statuses)
            publish("status", {{"status", status_json(bits)}});
    }
}

} // namespace rigsim::apt
