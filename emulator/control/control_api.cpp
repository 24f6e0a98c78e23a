#include "emulator/control/control_api.hpp"

#include "emulator/control/body_state.hpp"

#include "emulator/control/json_reply.hpp"
#include "emulator/control/live_view.hpp"
#include "emulator/core/control_surface.hpp"
#include "emulator/core/wire_log.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace rigsim::control {

namespace {

using nlohmann::json;
using BadField = BadRequest;

/// `key`'s value as `true` (the only value pause, resume and run_until_idle take).
void require_true(const json& body, const char* key)
{
    const auto& v = body.at(key);
    if (!v.is_boolean() || !v.get<bool>())
        throw BadField{400, std::string("\"") + key + "\": expected true, got " + dump(v)};
}

/// The action keys of POST /api/clock; exactly one per request.
constexpr std::array<const char*, 5> kClockActions{"pause", "resume", "step_ms", "scale", "run_until_idle"};

/// The one action key of a POST /api/clock body; other keys are refused by name.
std::string clock_action(const json& body)
{
    std::optional<std::string> action;
    for (const auto& [key, value] : body.items()) {
        bool known = key == "max_ms";
        for (const auto* a : kClockActions)
            known = known || key == a;
        if (!known)
            throw BadField{400, "unknown key \"" + key + "\" (expected one of pause, resume, step_ms, scale, "
                           "run_until_idle)"};
        if (key == "max_ms")
            continue;
        if (action)
            throw BadField{400, "\"" + *action + "\" and \"" + key + "\": expected exactly one action"};
        action = key;
    }
    if (!action)
        throw BadField{400, "expected exactly one of pause, resume, step_ms, scale, run_until_idle"};
    if (*action != "run_until_idle" && body.contains("max_ms"))
        throw BadField{400, "\"max_ms\": only with run_until_idle"};
    return *action;
}

} // namespace

namespace {

std::vector<ControlledDevice> bare(std::vector<DeviceEndpoints> endpoints)
{
    std::vector<ControlledDevice> out;
    for (auto& e : endpoints)
        out.push_back(ControlledDevice{std::move(e), nullptr, nullptr});
    return out;
}

/// "/api/devices/x/log" -> {"api", "devices", "x", "log"} (percent-decoded; empty parts kept).
std::vector<std::string> split_path(std::string_view path)
{
    std::vector<std::string> parts;
    if (!path.empty() && path.front() == '/')
        path.remove_prefix(1);
    while (true) {
        const auto slash = path.find('/');
        const auto part = path.substr(0, slash);
        parts.push_back(percent_decode(part));
        if (slash == std::string_view::npos)
            break;
        path.remove_prefix(slash + 1);
    }
    return parts;
}

/// A file of the live view, with the headers that keep it to itself (live_view.hpp).
HttpReply live_view(const LiveViewFile& file)
{
    HttpReply reply{200, std::string(file.body), {}, {}, {}};
    reply.headers = {{"Content-Type", std::string(file.content_type)},
                     {"Content-Security-Policy", std::string(kLiveViewPolicy)},
                     {"X-Frame-Options", "DENY"},
                     {"Referrer-Policy", "no-referrer"},
                     {"Cache-Control", "no-cache"}};
    return reply;
}

HttpReply not_allowed(std::string_view method, std::string_view path, const char* allowed)
{
    return error(405, std::string(method) + " " + std::string(path) + ": method not allowed (" + allowed + ")");
}

} // namespace

ControlApi::ControlApi(Rig& rig)
    : ControlApi(rig.clock(), rig.ticker(), [&rig] { return rig.busy(); }, rig.controlled(), &rig.events(),
                 FrameSource{rig.kinematics(), joint_axes(rig.joint_bindings(), rig.controlled()),
                             rig.collision_pairs()},
                 &rig.world())
{
}

ControlApi::ControlApi(Clock& clock, Ticker& ticker, std::function<bool()> busy, std::vector<DeviceEndpoints> devices)
    : ControlApi(clock, ticker, std::move(busy), bare(std::move(devices)), nullptr)
{
}

ControlApi::ControlApi(Clock& clock, Ticker& ticker, std::function<bool()> busy, std::vector<ControlledDevice> devices,
                       EventBus* events, FrameSource frames, models::World* world)
    : clock_(clock), ticker_(ticker), busy_(std::move(busy)), devices_(std::move(devices)), events_(events),
      world_(world), faults_(clock_, devices_, world), frames_(std::move(frames))
{
    if (events_ && !frames_.empty()) {
        // It reads the events after which a frame's pose settles, to make "frames" events.
        events_->set_follow_up([this](const Event& e) { follow_up(e); },
                               {"move_ended", "lut_ended", "channel_set", "reset"}, {"frames"});
        // The first stream's "frames" events are the changes from the poses when it started.
        events_->set_on_active([this] { frames_.rebase(); });
    }
}

ControlApi::~ControlApi()
{
    ticker_.drop_jobs();   // their answers refer to this

    if (events_ && !frames_.empty()) {
        events_->set_follow_up({});
        events_->set_on_active({});
    }
}

HttpReply ControlApi::handle(std::string_view method, std::string_view target, std::string_view body)
{
    try {
        return route(method, target, body);
    } catch (const BadRequest& e) {
        return error(e.status, e.message);
    } catch (const std::exception& e) {
        // Any other failure is the request's (an out-of-range number the clock refused):
        // the daemon answers and goes on.
        return error(400, e.what());
    }
}

HttpReply ControlApi::route(std::string_view method, std::string_view target, std::string_view body)
{
    const auto path = path_of(target);
    const auto parts = split_path(path);
    const auto p = [&](std::size_t i) -> std::string_view { return i < parts.size() ? parts[i] : std::string_view{}; };
    if (const auto* file = live_view_file(path))
        return method == "GET" ? live_view(*file) : not_allowed(method, path, "GET");
    if (parts.size() < 2 || parts[0] != "api")
        return error(404, "no route " + dump(json(std::string(path))));
    if (parts.size() == 2 && p(1) == "rig")
        return method == "GET" ? get_rig() : not_allowed(method, path, "GET");
    if (parts.size() == 2 && p(1) == "clock") {
        if (method == "GET")
            return get_clock();
        return method == "POST" ? post_clock(body) : not_allowed(method, path, "GET, POST");
    }
    if (parts.size() == 2 && p(1) == "reset")
        return method == "POST" ? post_reset(body) : not_allowed(method, path, "POST");
    if (parts.size() == 2 && p(1) == "events")
        return method == "GET" ? get_events(target) : not_allowed(method, path, "GET");
    if (p(1) == "devices" && parts.size() >= 3)
        return device_route(method, parts, target, body);
    if (p(1) == "faults" && parts.size() <= 3)
        return fault_route(method, parts, body);
    if (p(1) == "frames" && parts.size() <= 3)
        return frames_route(method, parts, path);
    return error(404, "no route " + dump(json(std::string(path))));
}

ControlledDevice& ControlApi::device(const std::string& name)
{
    for (auto& d : devices_)
        if (d.endpoints.name == name)
            return d;
    std::string names;
    for (const auto& d : devices_)
        names += (names.empty() ? "" : ", ") + d.endpoints.name;
    throw BadRequest{404, "no device named " + dump(json(name)) + " (devices: " + names + ")"};
}

ControlSurface& ControlApi::surface(ControlledDevice& d)
{
    if (!d.surface)
        throw BadRequest{404, "device \"" + d.endpoints.name + "\" has no control surface"};
    return *d.surface;
}

void ControlApi::publish(std::string_view device, std::string_view type, const json& data)
{
    if (events_ && events_->wants(device, type))
        events_->publish(device, type, clock_.seconds(clock_.now()) * 1000.0, data);
}

HttpReply ControlApi::device_route(std::string_view method, const std::vector<std::string>& parts,
                                   std::string_view target, std::string_view body)
{
    const auto path = path_of(target);
    auto& d = device(parts[2]);
    if (parts.size() == 3)
        return method == "GET" ? get_device(d) : not_allowed(method, path, "GET");
    if (parts.size() == 4 && parts[3] == "log") {
        if (method == "GET")
            return get_log(d, target);
        if (method != "DELETE")
            return not_allowed(method, path, "GET, DELETE");
        surface(d).wire_log().clear();
        return ok(json{{"device", d.endpoints.name}, {"cleared", true}});
    }
    if (parts.size() == 5 && parts[3] == "channels") {
        if (method == "PATCH")
            return patch_channel(d, parts[4], body);
        if (method != "GET")
            return not_allowed(method, path, "GET, PATCH");
        ticker_.sync();
        auto state = json::object();
        describe_device(surface(d), world_, state);
        const auto& channels = state["channels"];
        for (const auto& ch : channels)
            if (ch.value("index", -1) >= 0 && std::to_string(ch.value("index", -1)) == parts[4])
                return ok(ch);
        throw BadRequest{404, "device \"" + d.endpoints.name + "\" has no channel " + dump(json(parts[4]))};
    }
    if (parts.size() == 6 && parts[3] == "channels" && parts[5] == "trace")
        return method == "GET" ? get_trace(d, parts[4], target) : not_allowed(method, path, "GET");
    return error(404, "no route " + dump(json(std::string(path))));
}

HttpReply ControlApi::get_device(const ControlledDevice& d)
{
    ticker_.sync();
    json state{{"name", d.endpoints.name},
               {"protocol", d.endpoints.protocol},
               {"model", d.endpoints.model},
               {"firmware", d.endpoints.firmware},
               {"endpoints", {{"tcp", d.endpoints.tcp}, {"pty", d.endpoints.pty}}}};
    if (!d.endpoints.rfc2217.empty())
        state["endpoints"]["rfc2217"] = d.endpoints.rfc2217;
    if (d.surface)
        describe_device(*d.surface, world_, state);
    state["faults"] = faults_.list(&d.endpoints.name);
    if (d.link)
        state["link"] = json{{"unplugged", d.link->unplugged()},
                             {"dropped_bytes", d.link->dropped()},
                             {"corrupted_bytes", d.link->corrupted()},
                             {"held_answers", d.link->held()},
                             {"held_requests", d.link->held_requests()}};
    return ok(state);
}

HttpReply ControlApi::patch_channel(ControlledDevice& d, const std::string& index, std::string_view text)
{
    auto& s = surface(d);
    const auto body = parse_object(text);
    std::size_t n = 0;
    if (index.empty() || index.size() > 3 || index.find_first_not_of("0123456789") != std::string::npos)
        throw BadRequest{404, "device \"" + d.endpoints.name + "\" has no channel " + dump(json(index))};
    n = static_cast<std::size_t>(std::stoul(index));
    ticker_.sync();
    const auto refused = s.patch_channel(n, body);
    ticker_.reschedule();
    if (refused)
        throw BadRequest{refused->status, refused->message};
    auto state = json::object();
    describe_device(s, world_, state);
    for (const auto& ch : state["channels"])
        if (ch.value("index", -1) == static_cast<int>(n)) {
            publish(d.endpoints.name, "channel_set", json{{"channel", n}, {"set", body}});
            return ok(ch);
        }
    return ok(json::object());
}

HttpReply ControlApi::get_log(ControlledDevice& d, std::string_view target)
{
    auto& log = surface(d).wire_log();
    std::size_t last = log.capacity();
    const auto q = query_of(target);
    if (const auto it = q.find("last"); it != q.end()) {
        const auto& v = it->second;
        if (v.empty() || v.size() > 9 || v.find_first_not_of("0123456789") != std::string::npos)
            throw BadRequest{400, "\"last\": expected a count of entries, got " + dump(json(v))};
        last = std::stoul(v);
    }
    return ok(json{{"device", d.endpoints.name},
                   {"capacity", log.capacity()},
                   {"noted", log.noted()},
                   {"entries", log.to_json(last)}});
}

HttpReply ControlApi::get_trace(ControlledDevice& d, const std::string& index, std::string_view target)
{
    auto& s = surface(d);
    if (index.empty() || index.size() > 3 || index.find_first_not_of("0123456789") != std::string::npos)
        throw BadRequest{404, "device \"" + d.endpoints.name + "\" has no channel " + dump(json(index))};
    // A count of ticks or samples: digits only, within `limit`; 400 naming the field otherwise.
    const auto count = [](const std::string& key, const std::string& v, std::uint64_t limit) {
        if (v.empty() || v.size() > 18 || v.find_first_not_of("0123456789") != std::string::npos
            || std::stoull(v) > limit)
            throw BadRequest{400, "\"" + key + "\": expected " + (key == "from" ? "a tick (an integer >= 0)" : "a count of samples from 1 to " + std::to_string(kTraceSamples)) + ", got " + dump(json(v))};
        return std::stoull(v);
    };
    std::int64_t from = 0;
    std::size_t max = kTraceSamples;
    for (const auto& [key, value] : query_of(target)) {
        if (key == "from")
            from = static_cast<std::int64_t>(count(key, value, static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())));
        else if (key == "max")
            max = static_cast<std::size_t>(count(key, value, kTraceSamples));
        else
            throw BadRequest{400, "unknown query parameter \"" + key + "\" (expected from, max)"};
        if (key == "max" && max == 0)
            throw BadRequest{400, "\"max\": expected a count of samples from 1 to " + std::to_string(kTraceSamples) + ", got \"0\""};
    }
    ticker_.sync();
    auto out = json{{"device", d.endpoints.name}};
    if (const auto refused = s.trace(static_cast<std::size_t>(std::stoul(index)), from, max, out))
        throw BadRequest{refused->status, refused->message};
    return ok(out);
}

HttpReply ControlApi::fault_route(std::string_view method, const std::vector<std::string>& parts, std::string_view body)
{
    const std::string path = "/api/faults" + (parts.size() == 3 ? "/" + parts[2] : std::string());
    if (parts.size() == 2) {
        if (method == "GET")
            return ok(json{{"faults", faults_.list()}});
        if (method == "DELETE") {
            ticker_.sync();
            const auto ended = faults_.list();
            const auto ids = faults_.remove_all();
            ticker_.reschedule();
            for (const auto& f : ended)
                publish(f["device"].get<std::string>(), "fault_removed", json{{"id", f["id"]}});
            return ok(json{{"removed", ids}});
        }
        if (method != "POST")
            return not_allowed(method, path, "GET, POST, DELETE");
        const auto request = parse_object(body);
        ticker_.sync();
        const auto record = faults_.add(request);
        ticker_.reschedule();
        publish(record["device"].get<std::string>(), "fault_added", record);
        return ok(record, 201);
    }
    const auto& id_text = parts[2];
    const bool numeric = !id_text.empty() && id_text.size() <= 18
                         && id_text.find_first_not_of("0123456789") == std::string::npos;
    const std::uint64_t id = numeric ? std::stoull(id_text) : 0;
    if (method == "GET") {
        for (const auto& f : faults_.list())
            if (numeric && f["id"] == id)
                return ok(f);
        throw BadRequest{404, "no active fault " + dump(json(id_text))};
    }
    if (method != "DELETE")
        return not_allowed(method, path, "GET, DELETE");
    ticker_.sync();
    std::string device;
    for (const auto& f : faults_.list())
        if (numeric && f["id"] == id)
            device = f["device"].get<std::string>();
    if (!numeric || !faults_.remove(id))
        throw BadRequest{404, "no active fault " + dump(json(id_text))};
    ticker_.reschedule();
    publish(device, "fault_removed", json{{"id", id}});
    return ok(json{{"id", id}, {"removed", true}});
}

HttpReply ControlApi::post_reset(std::string_view text)
{
    const auto body = parse_object(text, true);
    for (const auto& [key, value] : body.items())
        if (key != "keep_saved")
            throw BadRequest{400, "unknown key \"" + key + "\" (expected keep_saved)"};
    const bool keep = !body.contains("keep_saved") || require_bool(body, "keep_saved");
    ticker_.sync();
    for (const auto& f : faults_.list())
        publish(f["device"].get<std::string>(), "fault_removed", json{{"id", f["id"]}});
    faults_.remove_all();
    auto names = json::array();
    for (auto& d : devices_) {
        if (d.link)
            d.link->reset();   // no answer of the last test reaches the next
        if (d.surface) {
            d.surface->power_cycle(PowerCycle{keep, true});
            d.surface->wire_log().clear();
        }
        names.push_back(d.endpoints.name);
    }
    ticker_.reschedule();
    json answer{{"reset", names}, {"keep_saved", keep}, {"now_ms", clock_.seconds(clock_.now()) * 1000.0}};
    publish("", "reset", answer);
    return ok(answer);
}

HttpReply ControlApi::get_events(std::string_view target)
{
    if (!events_)
        throw BadRequest{404, "no event stream here"};
    const auto q = query_of(target);
    std::vector<std::string> only_devices, only_types;
    const auto list = [](const std::string& text) {
        std::vector<std::string> out;
        std::size_t start = 0;
        while (start <= text.size()) {
            const auto comma = text.find(',', start);
            const auto item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
            if (!item.empty())
                out.push_back(item);
            if (comma == std::string::npos)
                break;
            start = comma + 1;
        }
        return out;
    };
    EventFilter filter;
    for (const auto& [key, value] : q) {
        if (key == "device")
            filter.devices = list(value);
        else if (key == "type")
            filter.types = list(value);
        else
            throw BadRequest{400, "unknown query parameter \"" + key + "\" (expected device, type)"};
    }
    for (const auto& name : filter.devices)
        device(name);   // 404 for a name that is not a device
    HttpReply reply;
    reply.stream = [bus = events_, frames = sse_frames_, filter](StreamWriter write) -> std::function<void()> {
        write(std::make_shared<const std::string>(": rigsim event stream\n\n"));
        // The bus passes the events the filter takes (rig-wide ones, such as clock and reset,
        // reach every stream that takes their type); each is framed once for every stream.
        const auto handle = bus->subscribe(
            [frames, write = std::move(write)](const Event& e) {
                if (frames->seq != e.seq || !frames->text) {
                    frames->seq = e.seq;
                    frames->text = std::make_shared<const std::string>(
                        "event: " + e.type + "\nid: " + std::to_string(e.seq) + "\ndata: " + e.json + "\n\n");
                }
                write(frames->text);
            },
            filter);
        return [bus, handle] { bus->unsubscribe(handle); };
    };
    return reply;
}

HttpReply ControlApi::frames_route(std::string_view method, const std::vector<std::string>& parts,
                                   std::string_view path)
{
    if (method != "GET")
        return not_allowed(method, path, "GET");
    ticker_.sync();
    if (parts.size() == 2)
        return ok(frames_.all());
    if (auto frame = frames_.one(parts[2]))
        return ok(*frame);
    throw BadRequest{404, "no frame named " + dump(json(parts[2]))};
}

void ControlApi::follow_up(const Event& e)
{
    // A motion's end (a piezo's LUT run too), a stage placed by PATCH, a reset: the moments a
    // frame's pose settles. Events during a motion are left out: one event per move, not per tick.
    if (e.type != "move_ended" && e.type != "lut_ended" && e.type != "channel_set" && e.type != "reset")
        return;
    auto changed = frames_.changed();
    if (changed.empty())
        return;
    json cause{{"type", e.type}};
    if (!e.device.empty())
        cause["device"] = e.device;
    publish("", "frames", json{{"frames", std::move(changed)}, {"after", std::move(cause)}});
}

namespace {

/// The body of GET /api/clock.
json clock_state(const Clock& clock, const Ticker& ticker)
{
    return json{{"now_ticks", clock.now()},
                {"now_ms", clock.seconds(clock.now()) * 1000.0},
                {"tick_hz", clock.tick_hz()},
                {"time_scale", ticker.time_scale()},
                {"paused", ticker.paused()}};
}

} // namespace

HttpReply ControlApi::get_clock()
{
    ticker_.sync();
    return ok(clock_state(clock_, ticker_));
}

HttpReply ControlApi::get_rig()
{
    ticker_.sync();
    auto devices = json::array();
    for (const auto& d : devices_) {
        const auto& e = d.endpoints;
        json entry{{"name", e.name}, {"protocol", e.protocol}, {"model", e.model},
                   {"firmware", e.firmware}, {"tcp", e.tcp}, {"pty", e.pty}};
        if (!e.rfc2217.empty())
            entry["rfc2217"] = e.rfc2217;
        if (d.surface) {
            auto state = json::object();
            d.surface->describe(state);
            auto channels = json::array();
            for (const auto& ch : state["channels"]) {
                // "kind": what the channel moves (null for a channel that moves nothing: a solenoid,
                // a gauge); "unit": the kind of unit (APT: motor, solenoid, piezo, strain_gauge).
                json entry_ch{{"index", ch.value("index", -1)}, {"kind", ch.contains("kind") ? ch["kind"] : json(nullptr)}};
                if (ch.contains("unit"))
                    entry_ch["unit"] = ch["unit"];
                channels.push_back(std::move(entry_ch));
            }
            entry["channels"] = channels;
        }
        devices.push_back(entry);
    }
    return ok(json{{"clock", clock_state(clock_, ticker_)}, {"devices", devices}});
}

HttpReply ControlApi::post_clock(std::string_view text)
{
    const auto body = parse_object(text);
    const auto action = clock_action(body);
    ticker_.sync();
    if (action == "pause") {
        require_true(body, "pause");
        ticker_.pause();
    } else if (action == "resume") {
        require_true(body, "resume");
        ticker_.resume();
    } else if (action == "scale") {
        // The range of --time-scale: beyond it the wall-time arithmetic of the ticker overflows.
        ticker_.set_time_scale(require_number(body, "scale", kMinTimeScale, kMaxTimeScale));
    } else {
        return clock_job(action, body);
    }
    ticker_.reschedule();
    auto state = clock_state(clock_, ticker_);
    publish("", "clock", state);
    return ok(state);
}

HttpReply ControlApi::clock_job(const std::string& action, const nlohmann::json& body)
{
    // Checked before anything is queued: a bad request is answered at once and changes nothing.
    Ticks ticks = 0;
    if (action == "step_ms") {
        ticks = clock_.ticks_from_ms(require_int(body, "step_ms", 0, kMaxStepMs));
    } else {
        require_true(body, "run_until_idle");
        if (!body.contains("max_ms"))
            throw BadField{400, "\"max_ms\": required with run_until_idle"};
        ticks = clock_.ticks_from_ms(require_int(body, "max_ms", 1, kMaxStepMs));
    }
    const bool until_idle = action == "run_until_idle";
    HttpReply reply;
    // The step runs in slices on the loop (Ticker::queue_step): devices and other requests are
    // served meanwhile, and this answer comes when it is done.
    reply.later = [this, ticks, until_idle](Respond respond) {
        auto done = [this, until_idle, respond = std::move(respond)](Ticks reached) {
            auto state = clock_state(clock_, ticker_);
            if (until_idle) {
                state["reached_ms"] = clock_.seconds(reached) * 1000.0;
                state["idle"] = !busy_();
            }
            publish("", "clock", state);
            respond(ok(state));
        };
        if (until_idle)
            ticker_.queue_run_until_idle(ticks, busy_, std::move(done));
        else
            ticker_.queue_step(ticks, std::move(done));
    };
    return reply;
}

} // namespace rigsim::control
