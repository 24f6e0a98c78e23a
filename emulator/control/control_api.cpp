#include "emulator/control/control_api.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace rigsim::control {

namespace {

using nlohmann::json;

/// `value` as compact JSON; bytes that are not UTF-8 (a raw request target) become U+FFFD
/// rather than an exception.
std::string dump(const json& value)
{
    return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

HttpReply ok(const json& body)
{
    return HttpReply{200, dump(body) + "\n"};
}

HttpReply error(unsigned status, const std::string& message)
{
    return HttpReply{status, dump(json{{"error", message}}) + "\n"};
}

/// An error naming the field that was wrong; thrown while reading a body, caught in handle().
struct BadField {
    std::string message;
};

/// `key`'s value as `true` (the only value pause, resume and run_until_idle take).
void require_true(const json& body, const char* key)
{
    const auto& v = body.at(key);
    if (!v.is_boolean() || !v.get<bool>())
        throw BadField{std::string("\"") + key + "\": expected true, got " + dump(v)};
}

/// `key`'s value as an integer in lo..hi (a float with no fraction is refused too: the
/// contract is an integer).
std::int64_t require_int(const json& body, const char* key, std::int64_t lo, std::int64_t hi)
{
    const auto& v = body.at(key);
    const bool integer = v.is_number_integer() || v.is_number_unsigned();
    if (integer && v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(hi))
        throw BadField{std::string("\"") + key + "\": expected an integer " + std::to_string(lo) + ".."
                       + std::to_string(hi) + ", got " + dump(v)};
    if (!integer || v.get<std::int64_t>() < lo || v.get<std::int64_t>() > hi)
        throw BadField{std::string("\"") + key + "\": expected an integer " + std::to_string(lo) + ".."
                       + std::to_string(hi) + ", got " + dump(v)};
    return v.get<std::int64_t>();
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
            throw BadField{"unknown key \"" + key + "\" (expected one of pause, resume, step_ms, scale, "
                           "run_until_idle)"};
        if (key == "max_ms")
            continue;
        if (action)
            throw BadField{"\"" + *action + "\" and \"" + key + "\": expected exactly one action"};
        action = key;
    }
    if (!action)
        throw BadField{"expected exactly one of pause, resume, step_ms, scale, run_until_idle"};
    if (*action != "run_until_idle" && body.contains("max_ms"))
        throw BadField{"\"max_ms\": only with run_until_idle"};
    return *action;
}

/// The path of a request target: without its query string.
std::string_view path_of(std::string_view target)
{
    return target.substr(0, target.find('?'));
}

} // namespace

ControlApi::ControlApi(Rig& rig)
    : ControlApi(rig.clock(), rig.ticker(), [&rig] { return rig.busy(); }, rig.endpoints())
{
}

ControlApi::ControlApi(Clock& clock, Ticker& ticker, std::function<bool()> busy, std::vector<DeviceEndpoints> devices)
    : clock_(clock), ticker_(ticker), busy_(std::move(busy)), devices_(std::move(devices))
{
}

HttpReply ControlApi::handle(std::string_view method, std::string_view target, std::string_view body)
{
    const auto path = path_of(target);
    try {
        if (path == "/api/rig") {
            if (method != "GET")
                return error(405, std::string(method) + " " + std::string(path) + ": method not allowed (GET)");
            return get_rig();
        }
        if (path == "/api/clock") {
            if (method == "GET")
                return get_clock();
            if (method == "POST")
                return post_clock(body);
            return error(405, std::string(method) + " " + std::string(path) + ": method not allowed (GET, POST)");
        }
    } catch (const BadField& e) {
        return error(400, e.message);
    } catch (const std::exception& e) {
        // Any other failure is the request's (an out-of-range number the clock refused):
        // the daemon answers and goes on.
        return error(400, e.what());
    }
    return error(404, "no route " + dump(json(std::string(path))));
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
    for (const auto& d : devices_)
        devices.push_back({{"name", d.name}, {"protocol", d.protocol}, {"model", d.model},
                           {"tcp", d.tcp}, {"pty", d.pty}});
    return ok(json{{"clock", clock_state(clock_, ticker_)}, {"devices", devices}});
}

HttpReply ControlApi::post_clock(std::string_view text)
{
    json body;
    try {
        body = json::parse(text.begin(), text.end());
    } catch (const json::parse_error& e) {
        throw BadField{"body: expected a JSON object, got invalid JSON (at byte " + std::to_string(e.byte) + ")"};
    } catch (const json::out_of_range&) {
        throw BadField{"body: expected a JSON object, got a number too large for a double"};
    }
    if (!body.is_object())
        throw BadField{"body: expected a JSON object, got " + std::string(body.type_name())};
    const auto action = clock_action(body);
    ticker_.sync();
    std::optional<Ticks> reached;
    if (action == "pause") {
        require_true(body, "pause");
        ticker_.pause();
    } else if (action == "resume") {
        require_true(body, "resume");
        ticker_.resume();
    } else if (action == "step_ms") {
        ticker_.step(clock_.ticks_from_ms(require_int(body, "step_ms", 0, kMaxStepMs)));
    } else if (action == "scale") {
        const auto& v = body.at("scale");
        if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() <= 0)
            throw BadField{"\"scale\": expected a finite number > 0, got " + dump(v)};
        ticker_.set_time_scale(v.get<double>());
    } else {
        require_true(body, "run_until_idle");
        if (!body.contains("max_ms"))
            throw BadField{"\"max_ms\": required with run_until_idle"};
        const auto max_ms = require_int(body, "max_ms", 1, kMaxStepMs);
        reached = ticker_.run_until_idle(clock_.ticks_from_ms(max_ms), busy_);
    }
    ticker_.reschedule();
    auto state = clock_state(clock_, ticker_);
    if (reached)
        state["reached_ms"] = clock_.seconds(*reached) * 1000.0;
    return ok(state);
}

} // namespace rigsim::control
