#include "emulator/mcs2/device.hpp"

#include "emulator/core/event_bus.hpp"
#include "emulator/core/log_format.hpp"
#include "emulator/mcs2/line_framer.hpp"

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <cmath>

namespace rigsim::mcs2 {

class Mcs2Session : public Session {
public:
    Mcs2Session(Mcs2Device& device, SendFn send, Connection conn, std::string peer, Clock& clock)
        : device_(device), send_(std::move(send)), conn_(std::move(conn)), peer_(std::move(peer)), clock_(clock)
    {
    }
    ~Mcs2Session() override
    {
        device_.controller().forget(state_);
        device_.publish_changes();
        clock_.changed(device_);
    }

    void receive(std::string_view bytes) override
    {
        if (closing_)
            return;
        out_.clear();
        bool hangup = false;
        while (!bytes.empty() && !hangup) {
            const auto r = framer_.parse(bytes);
            bytes.remove_prefix(r.consumed);
            if (r.status == LineFramer::Status::Line)
                hangup = device_.execute(r.line, state_, peer_, out_);
            else if (r.status == LineFramer::Status::Overrun)
                device_.overrun(state_, peer_);
        }
        if (!out_.empty())
            send_(out_);
        device_.publish_changes();
        clock_.changed(device_);   // a command may have started a movement or a timer
        if (hangup && conn_.hangup) {   // *RST: "reconnect necessary!" (Table 6.1)
            closing_ = true;
            conn_.hangup(Hangup::Close);
        }
    }

private:
    Mcs2Device& device_;
    SendFn send_;
    Connection conn_;
    std::string peer_;
    Clock& clock_;
    LineFramer framer_;
    SessionState state_;
    std::string out_;
    bool closing_ = false;
};

Mcs2Device::Mcs2Device(const DeviceConfig& config, models::World& world, std::shared_ptr<spdlog::logger> log,
                       EventBus* events)
    : config_(config), clock_(world.clock()), log_(std::move(log)), controller_(config_of(config), world, config.name),
      events_(events), wire_log_(config.name, clock_.tick_hz(), events, log_)
{
    wire_log_.set_decoder([](const WireEntry& e, nlohmann::json& out) {
        std::string_view text = e.bytes;
        while (!text.empty() && (text.back() == '\n' || text.back() == '\r'))
            text.remove_suffix(1);
        out["text"] = std::string(text);
    });
    clock_.add(this, Clock::Schedule::Announced);
}

Mcs2Device::~Mcs2Device()
{
    clock_.remove(this);
}

std::unique_ptr<Session> Mcs2Device::open_session(SendFn send, std::string peer)
{
    return std::make_unique<Mcs2Session>(*this, std::move(send), Connection{}, std::move(peer), clock_);
}

std::unique_ptr<Session> Mcs2Device::open_connection(SendFn send, Connection conn, std::string peer)
{
    return std::make_unique<Mcs2Session>(*this, std::move(send), std::move(conn), std::move(peer), clock_);
}

bool Mcs2Device::execute(std::string_view message, SessionState& state, std::string_view peer, std::string& out)
{
    const auto queued_before = state.errors.count();
    auto r = controller_.execute(message, state);
    std::vector<std::string> notes;
    if (r.errors > 0) {
        // Errors are never answered (6.3.8): say what the client would only learn from the queue.
        notes.push_back(std::to_string(r.errors) + " error(s) queued, not answered: read them with :SYST:ERR? "
                        "(6.3.8); the queue holds " + std::to_string(state.errors.count()) + " now");
        if (state.errors.count() == ErrorQueue::kDepth && queued_before + r.errors > ErrorQueue::kDepth)
            notes.push_back("the error queue is full: the newest entry reads -350 \"Queue overflow\"");
        log_->warn("{}: \"{}\": {} error(s) queued", peer, printable(message), r.errors);
    } else if (log_->should_log(spdlog::level::debug)) {
        log_->debug("{}: \"{}\"", peer, printable(message));
    }
    std::string in(message);
    in += "\r\n";
    wire_log_.add(clock_.now(), true, peer, in, std::move(notes));
    if (r.answered) {
        const auto at = out.size();
        out += r.answer;
        out += "\r\n";   // both directions end in CR LF (6.1.1)
        wire_log_.add(clock_.now(), false, peer, std::string_view(out).substr(at));
    }
    return r.reset;
}

void Mcs2Device::overrun(SessionState& state, std::string_view peer)
{
    state.errors.push(static_cast<std::int32_t>(ScpiError::InputBufferOverrun),
                      scpi_error_text(ScpiError::InputBufferOverrun));
    log_->warn("{}: message longer than {} bytes discarded: -363 queued", peer, LineFramer::kDefaultMaxLine);
    std::vector<std::string> notes;
    notes.push_back("message longer than the input buffer (" + std::to_string(LineFramer::kDefaultMaxLine) +
                    " bytes): discarded, -363 \"Input buffer overrun\" queued");
    wire_log_.add(clock_.now(), true, peer, "", std::move(notes));
}

void Mcs2Device::tick(Ticks now)
{
    controller_.tick(now);
    publish_changes();
}

bool Mcs2Device::busy() const
{
    // A calibration, a power-save move delay or a finite hold runs on the device's own timers.
    return controller_.next_change(clock_.now()) != kNever;
}

// ---- control API ----

namespace {

constexpr double kPi = 3.14159265358979323846;

Refusal bad(std::string message)
{
    return Refusal{400, std::move(message)};
}

bool rotary(const Channel& ch)
{
    return ch.type().motion != Motion::Linear;
}

nlohmann::json finite_or_null(double v)
{
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

/// The activity the four low state bits name (2.6.7).
const char* activity(std::uint32_t s)
{
    if (s & state::kMoveDelayed)
        return "move_delayed";
    if (s & state::kReferencing)
        return "referencing";
    if (s & state::kCalibrating)
        return "calibrating";
    if ((s & state::kActivelyMoving) && (s & state::kClosedLoopActive))
        return "closed_loop_moving";
    if (s & state::kActivelyMoving)
        return "open_loop_moving";
    if (s & state::kClosedLoopActive)
        return "holding";
    return "stopped";
}

bool idle(std::uint32_t s)
{
    return (s & (state::kActivelyMoving | state::kMoveDelayed)) == 0;
}

const char* power_name(SensorPower p)
{
    switch (p) {
    case SensorPower::Disabled:
        return "disabled";
    case SensorPower::Enabled:
        return "enabled";
    case SensorPower::PowerSave:
        return "power_save";
    }
    return "enabled";
}

} // namespace

void Mcs2Device::channel_json(std::size_t i, nlohmann::json& j) const
{
    const auto& ch = controller_.channel(i);
    const auto s = controller_.channel_state(i);
    j["index"] = i;
    j["kind"] = rotary(ch) ? "rotary" : "linear";
    j["state"] = {{"word", s}, {"activity", activity(s)}};
    j["moving"] = !idle(s);
    j["position_protocol"] = ch.sensor_failed() ? nlohmann::json(nullptr) : nlohmann::json(ch.position());
    j["protocol_unit"] = rotary(ch) ? "ndeg" : "pm";
    j["target_protocol"] = ch.target();
    j["referenced"] = (s & state::kIsReferenced) != 0;
    j["calibrated"] = (s & state::kIsCalibrated) != 0;
    j["positioner_type"] = {{"code", ch.type_code()}, {"name", ch.type_name()}};
    j["sensor"] = {{"mode", power_name(ch.sensor_power())}, {"failed", ch.sensor_failed()}};
    j["channel_error"] = ch.last_error();
    const auto [tmin, tmax] = ch.travel();
    const double si = rotary(ch) ? 1e-9 * kPi / 180.0 : 1e-12;
    nlohmann::json range = nullptr;
    if (ch.settings().range_max > ch.settings().range_min)
        range = {{"min", ch.settings().range_min}, {"max", ch.settings().range_max}};
    j["limits"] = {{"range_limit", range}, {"end_stops_si", {finite_or_null(tmin * si), finite_or_null(tmax * si)}}};
    j["stalled"] = ch.body().blocked();
    j["slip"] = ch.body().slip();
    j["last_outcome"] = ch.last_outcome();
}

void Mcs2Device::describe(nlohmann::json& out) const
{
    auto channels = nlohmann::json::array();
    for (std::size_t i = 0; i < controller_.channel_count(); ++i) {
        nlohmann::json j = nlohmann::json::object();
        channel_json(i, j);
        channels.push_back(std::move(j));
    }
    out["channels"] = std::move(channels);
    out["serial_number"] = controller_.config().serial_number;
    out["device_name"] = controller_.device_name();
    out["modules"] = controller_.module_count();
    out["firmware"] = controller_.config().firmware == Firmware::Current ? "current" : "1.0.6";
    out["io_module"] = controller_.config().io_module;
    out["trigger_input"] = controller_.config().io_module ? nlohmann::json(controller_.trigger_input() ? "high" : "low")
                                                          : nlohmann::json(nullptr);
    out["locked"] = controller_.locked();
}

Refused Mcs2Device::axis_body_key(std::size_t index, std::string& out) const
{
    if (index >= controller_.channel_count())
        return Refusal{404, "no channel " + std::to_string(index) + " (the device has " +
                                std::to_string(controller_.channel_count()) + ")"};
    out = controller_.channel(index).body().key();
    return std::nullopt;
}

Refused Mcs2Device::patch_channel(std::size_t index, const nlohmann::json& body)
{
    if (index >= controller_.channel_count())
        return Refusal{404, "no channel " + std::to_string(index) + " (the device has " +
                                std::to_string(controller_.channel_count()) + ")"};
    if (!body.is_object())
        return bad("the body must be an object");
    auto& ch = controller_.channel(index);
    constexpr double kMaxPlace = 1e15;   // pm or n°
    for (const auto& [key, value] : body.items()) {
        if (key == "limit_switch")
            return bad("limit_switch: an MCS2 positioner has no limit switches (its end stops are mechanical; "
                       "see the stall fault)");
        if (key != "position_si" && key != "referenced" && key != "sensor" && key != "trig_in")
            return bad(key + ": unknown key (position_si, referenced, sensor, trig_in)");
        if (key == "trig_in") {
            if (!controller_.config().io_module)
                return bad("trig_in: the unit has no I/O module, so no trigger input (rig key mcs2.io_module)");
            if (!value.is_string() || (value != "high" && value != "low" && value != "pulse"))
                return bad("trig_in: \"high\", \"low\" or \"pulse\" is required");
            continue;
        }
        if (key == "position_si") {
            if (!value.is_number())
                return bad("position_si: a number is required");
            const double si = value.get<double>();
            const double physical = rotary(ch) ? si * 180.0 / kPi * 1e9 : si * 1e12;
            const auto [lo, hi] = ch.travel();
            if (!std::isfinite(physical) || std::abs(physical) > kMaxPlace || physical < lo - 1e-3 || physical > hi + 1e-3)
                return bad("position_si: outside the travel between the end stops");
        } else if (key == "referenced") {
            if (!value.is_boolean())
                return bad("referenced: true or false is required");
            if (ch.sensor_failed())
                return bad("referenced: the channel's sensor has failed");
        } else if (!value.is_string() || (value != "enabled" && value != "disabled" && value != "power_save")) {
            return bad("sensor: \"enabled\", \"disabled\" or \"power_save\" is required");
        }
    }
    // The trigger input is the device's (DIN-1, 2.17): any channel's PATCH drives it, moving or not.
    if (const auto it = body.find("trig_in"); it != body.end()) {
        if (*it == "pulse") {   // both edges in one tick
            controller_.set_trigger_input(!controller_.trigger_input());
            controller_.set_trigger_input(!controller_.trigger_input());
        } else {
            controller_.set_trigger_input(*it == "high");
        }
        if (body.size() == 1) {
            publish_changes();
            return std::nullopt;
        }
    }
    if (!idle(controller_.channel_state(index)))
        return Refusal{409, "channel " + std::to_string(index) + " is moving"};
    if (const auto it = body.find("sensor"); it != body.end())
        (void)ch.set_sensor_power(*it == "enabled" ? 1 : *it == "disabled" ? 0 : 2);
    if (const auto it = body.find("position_si"); it != body.end()) {
        const double si = it->get<double>();
        ch.body().place(rotary(ch) ? si * 180.0 / kPi * 1e6 : si * 1e9);
    }
    if (const auto it = body.find("referenced"); it != body.end())
        ch.set_referenced(it->get<bool>());
    publish_changes();
    return std::nullopt;
}

Refused Mcs2Device::fault_body(const DeviceFault& f, std::string& out) const
{
    return axis_body_key(f.channel.value_or(0), out);
}

void Mcs2Device::sync_sensor(std::size_t index)
{
    auto& ch = controller_.channel(index);
    ch.set_sensor_failed(ch.body().faults().sensor_failed);
}

void Mcs2Device::faults_changed()
{
    for (std::size_t i = 0; i < controller_.channel_count(); ++i)
        sync_sensor(i);
    tick(clock_.now());
}

Refused Mcs2Device::add_fault(const DeviceFault& f, bool* kept)
{
    if (kept)
        *kept = false;
    if (physical(f.kind))
        return bad("kind: " + std::string(fault_name(f.kind)) + " acts on the stage, not on the controller");
    const std::size_t index = f.channel.value_or(0);
    if (index >= controller_.channel_count())
        return Refusal{404, "no channel " + std::to_string(index)};
    controller_.channel(index).set_referenced(false);   // one-off: the position becomes unknown now
    publish_changes();
    return std::nullopt;
}

void Mcs2Device::power_cycle(const PowerCycle& how)
{
    if (!how.keep_saved)
        controller_.restore_defaults();
    if (how.restore_positions)
        for (std::size_t i = 0; i < controller_.channel_count(); ++i)
            controller_.channel(i).place_at_start();
    controller_.power_up();
    for (std::size_t i = 0; i < controller_.channel_count(); ++i)
        sync_sensor(i);
    publish_changes();
}

void Mcs2Device::publish_changes()
{
    const auto& name = config_.name;
    const bool moves = events_ && (events_->wants(name, "move_started") || events_->wants(name, "move_ended"));
    const bool statuses = events_ && events_->wants(name, "status");
    if (!moves && !statuses) {
        state_known_ = false;
        return;
    }
    const auto n = controller_.channel_count();
    const double time_ms = static_cast<double>(clock_.now()) * 1000.0 / clock_.tick_hz();
    if (!state_known_) {
        last_state_.resize(n);
        for (std::size_t i = 0; i < n; ++i)
            last_state_[i] = controller_.channel_state(i);
        state_known_ = true;
        return;
    }
    for (std::size_t i = 0; i < n; ++i) {
        const auto s = controller_.channel_state(i);
        const auto was = last_state_[i];
        if (s == was)
            continue;
        last_state_[i] = s;
        if (moves && idle(was) && !idle(s))
            events_->publish(name, "move_started", time_ms, {{"channel", i}});
        if (statuses)
            events_->publish(name, "status", time_ms, {{"channel", i}, {"state", {{"word", s}, {"activity", activity(s)}}}});
        if (moves && !idle(was) && idle(s))
            events_->publish(name, "move_ended", time_ms,
                             {{"channel", i}, {"outcome", controller_.channel(i).last_outcome()}});
    }
}

} // namespace rigsim::mcs2
