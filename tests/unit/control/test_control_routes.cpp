// The control API's device, fault, reset, log and event routes over a stand-in device (a
// ControlSurface that records what it was asked) and a real link: what each route hands the
// device, what it answers, and each refusal. No sockets; the clock is paused.
#include "emulator/control/control_api.hpp"
#include "emulator/core/control_surface.hpp"
#include "emulator/core/wire_log.hpp"
#include "models/stick_slip.hpp"
#include "models/world.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <boost/asio/io_context.hpp>

#include <string>
#include <vector>

namespace test_control_routes {

using namespace rigsim;
using rigsim::control::ControlApi;
using nlohmann::json;

namespace {

/// Records the calls; one channel at index 0, "moving" on request.
class FakeSurface : public ControlSurface {
public:
    FakeSurface(Clock& clock, EventBus* bus) : log_("dev", clock.tick_hz(), bus) {}

    void describe(json& out) const override
    {
        out["channels"] = json::array({json{{"index", 0}, {"kind", "linear"}, {"position_si", position},
                                            {"moving", moving}}});
        out["family_key"] = 1;
    }
    Refused patch_channel(std::size_t index, const json& body) override
    {
        if (index != 0)
            return Refusal{404, "no channel " + std::to_string(index)};
        if (moving)
            return Refusal{409, "channel 0 moves"};
        for (const auto& [k, v] : body.items()) {
            if (k != "position_si")
                return Refusal{400, "\"" + k + "\": unknown"};
            position = v.get<double>();
        }
        return std::nullopt;
    }
    /// The device's own faults (reference_lost).
    Refused add_fault(const DeviceFault& f, bool* kept) override
    {
        added.push_back(f.id);
        last_kind = f.kind;
        last_channel = f.channel;
        *kept = false;
        return std::nullopt;
    }
    void remove_fault(std::uint64_t id) override { removed.push_back(id); }
    /// Channel 0 moves the world body "dev/0".
    Refused fault_body(const DeviceFault& f, std::string& out) const override
    {
        if (f.channel.value_or(0) != 0)
            return Refusal{404, "no channel " + std::to_string(*f.channel)};
        out = "dev/0";
        return std::nullopt;
    }
    void faults_changed() override { ++changes; }
    void power_cycle(const PowerCycle& how) override { cycles.push_back(how); }
    WireLog& wire_log() override { return log_; }

    double position = 0;
    bool moving = false;
    std::vector<std::uint64_t> added, removed;
    int changes = 0;   ///< faults_changed() calls
    std::optional<FaultKind> last_kind;
    std::optional<std::size_t> last_channel;
    std::vector<PowerCycle> cycles;

private:
    WireLog log_;
};

/// A device that takes no bytes (the link needs one behind it).
class NullDevice : public Device {
public:
    std::unique_ptr<Session> open_session(SendFn, std::string) override { return nullptr; }
};

struct Fixture {
    std::pair<unsigned, json> call(const std::string& method, const std::string& target, const std::string& body = {})
    {
        const auto reply = api.handle(method, target, body);
        INFO(method << " " << target << " " << body << " -> " << reply.status << " " << reply.body);
        REQUIRE_FALSE(reply.stream);
        const auto parsed = json::parse(reply.body, nullptr, false);
        REQUIRE_FALSE(parsed.is_discarded());
        return {reply.status, parsed};
    }
    std::string error_of(const std::string& method, const std::string& target, const std::string& body, unsigned status)
    {
        const auto [got, answer] = call(method, target, body);
        CHECK(got == status);
        REQUIRE(answer.contains("error"));
        return answer["error"].get<std::string>();
    }

    boost::asio::io_context io;
    Clock clock{1000};
    Ticker ticker{io, clock, 1.0, Ticker::Start::Paused};
    models::World world{clock};
    models::StickSlipPositioner& stage = world.emplace<models::StickSlipPositioner>("dev/0", clock, models::StickSlipConfig{});
    EventBus bus;
    FakeSurface surface{clock, &bus};
    NullDevice null_device;
    Link link{null_device, clock};
    ControlApi api{clock, ticker, [] { return false; },
                   std::vector<ControlledDevice>{ControlledDevice{
                       DeviceEndpoints{"dev", "mcs", "MCS-3D", "127.0.0.1:1", "/tmp/x/dev", "1.2.44", ""}, &surface, &link}},
                   &bus, {}, &world};
};

} // namespace

TEST_CASE("GET /api/devices/{name}: the endpoints, the device's own state, its faults and its link", "[control]")
{
    Fixture f;
    f.surface.position = 0.25;
    const auto [status, state] = f.call("GET", "/api/devices/dev");
    CHECK(status == 200);
    CHECK(state["name"] == "dev");
    CHECK(state["protocol"] == "mcs");
    CHECK(state["endpoints"]["pty"] == "/tmp/x/dev");
    CHECK(state["channels"][0]["position_si"] == 0.25);
    CHECK(state["family_key"] == 1);
    CHECK(state["faults"] == json::array());
    CHECK(state["link"]["unplugged"] == false);
    CHECK(f.error_of("GET", "/api/devices/nope", "", 404).find("no device named \"nope\" (devices: dev)")
          != std::string::npos);
    CHECK(f.error_of("POST", "/api/devices/dev", "", 405).find("GET") != std::string::npos);
    const auto [rs, rig] = f.call("GET", "/api/rig");
    CHECK(rig["devices"][0]["channels"] == json::array({json{{"index", 0}, {"kind", "linear"}}}));
}

TEST_CASE("PATCH a channel: the device's answer, its refusals as their status, the channel after", "[control]")
{
    Fixture f;
    const auto [status, channel] = f.call("PATCH", "/api/devices/dev/channels/0", R"({"position_si": 0.5})");
    CHECK(status == 200);
    CHECK(channel["position_si"] == 0.5);
    CHECK(f.surface.position == 0.5);
    CHECK(f.error_of("PATCH", "/api/devices/dev/channels/0", R"({"colour": 1})", 400) == "\"colour\": unknown");
    CHECK(f.error_of("PATCH", "/api/devices/dev/channels/3", "{}", 404) == "no channel 3");
    CHECK(f.error_of("PATCH", "/api/devices/dev/channels/x", "{}", 404).find("no channel") != std::string::npos);
    CHECK(f.error_of("PATCH", "/api/devices/dev/channels/0", "[1]", 400).find("JSON object") != std::string::npos);
    f.surface.moving = true;
    CHECK(f.error_of("PATCH", "/api/devices/dev/channels/0", R"({"position_si": 1})", 409) == "channel 0 moves");
    CHECK(f.surface.position == 0.5);
    const auto [gs, got] = f.call("GET", "/api/devices/dev/channels/0");
    CHECK(got["moving"] == true);
}

TEST_CASE("POST /api/faults: a physical fault goes to the body the device names, with its params, is listed and removed",
          "[control]")
{
    Fixture f;
    const auto [status, record] = f.call("POST", "/api/faults", R"({"device":"dev","channel":0,"kind":"slip","fraction":0.25})");
    CHECK(status == 201);
    CHECK(record["id"] == 1);
    CHECK(record["active"] == true);
    CHECK(record["params"] == json{{"fraction", 0.25}});
    CHECK(f.stage.faults().slip_fraction == 0.25);   // parsed once, typed, on the body
    CHECK(f.stage.slip() == 0.25);
    CHECK(f.surface.changes == 1);   // the device heard of it
    CHECK(f.surface.added.empty());  // not the device's own fault
    CHECK(f.call("GET", "/api/faults").second["faults"].size() == 1);
    CHECK(f.call("GET", "/api/devices/dev").second["faults"][0]["kind"] == "slip");
    CHECK(f.call("DELETE", "/api/faults/1").second == json{{"id", 1}, {"removed", true}});
    CHECK(f.stage.faults().slip_fraction == 0.0);
    CHECK(f.surface.changes == 2);
    CHECK(f.surface.removed.empty());
    CHECK(f.error_of("DELETE", "/api/faults/1", "", 404) == "no active fault \"1\"");
    CHECK(f.call("GET", "/api/faults").second["faults"].empty());
}

TEST_CASE("POST /api/faults refuses what is wrong by name, and the device's own refusals", "[control]")
{
    Fixture f;
    CHECK(f.error_of("POST", "/api/faults", R"({"kind":"stall"})", 400) == "\"device\": required (the device's name)");
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"x","kind":"stall"})", 404).find("no device named")
          != std::string::npos);
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"melt"})", 400).find("unknown fault \"melt\"")
          != std::string::npos);
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev"})", 400).find("\"kind\": required") == 0);
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"stall","channel":-1})", 400)
          == "\"channel\": expected an integer 0..255, got -1");
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"stall","bad":1})", 400)
          == "\"bad\": not a parameter of a stall fault (it takes none)");
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"slip","fraction":2})", 400)
          == "\"fraction\": expected a number from 0 to 1, got 2");
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"limit_switch","side":"up"})", 400)
          == "\"side\": \"forward\" or \"reverse\" is required, got \"up\"");
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"limit_switch","side":"forward"})", 400)
          .find("\"kind\": limit_switch: a stick-slip positioner has no limit switches") == 0);   // the body's refusal
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"stall","channel":2})", 404)
          == "no channel 2");   // the device's
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"unplugged","channel":0})", 400)
          == "\"channel\": a unplugged fault acts on the whole device");
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"latency"})", 400)
          == "\"latency_ms\": required for a latency fault");
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"drop_bytes","direction":"up"})", 400)
          == "\"direction\": expected \"in\", \"out\" or \"both\", got \"up\"");
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"corrupt_bytes","probability":2})", 400)
          == "\"probability\": expected a number 0.0..1.0, got 2");
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"unplugged","for_ms":2})", 400)
          == "\"for_ms\": not a parameter of a unplugged fault (it takes none)");
    CHECK(f.surface.added.empty());
    CHECK(f.call("GET", "/api/faults").second["faults"].empty());
}

TEST_CASE("link faults act on the device's link, and one-off faults act and are not kept", "[control]")
{
    Fixture f;
    const auto [s1, unplugged] = f.call("POST", "/api/faults", R"({"device":"dev","kind":"unplugged"})");
    CHECK(s1 == 201);
    CHECK(unplugged["channel"] == nullptr);
    CHECK(f.link.unplugged());
    CHECK(f.call("GET", "/api/devices/dev").second["link"]["unplugged"] == true);
    f.call("POST", "/api/faults", R"({"device":"dev","kind":"latency","latency_ms":20,"jitter_ms":5,"seed":3})");
    f.call("POST", "/api/faults", R"({"device":"dev","kind":"drop_bytes","direction":"in","probability":0.5})");
    CHECK(f.call("GET", "/api/faults").second["faults"].size() == 3);
    f.call("DELETE", "/api/faults/" + std::to_string(unplugged["id"].get<int>()));
    CHECK_FALSE(f.link.unplugged());

    const auto [s2, cycle] = f.call("POST", "/api/faults", R"({"device":"dev","kind":"power_cycle"})");
    CHECK(s2 == 201);
    CHECK(cycle["active"] == false);
    REQUIRE(f.surface.cycles.size() == 1);
    CHECK(f.surface.cycles[0].keep_saved);
    CHECK_FALSE(f.surface.cycles[0].restore_positions);
    const auto [s3, lost] = f.call("POST", "/api/faults", R"({"device":"dev","kind":"reference_lost"})");
    CHECK(lost["active"] == false);
    CHECK(f.surface.last_kind == FaultKind::ReferenceLost);   // the device's own, typed
    CHECK(f.surface.last_channel == std::nullopt);
    CHECK(f.call("GET", "/api/faults").second["faults"].size() == 2);
    CHECK(f.call("DELETE", "/api/faults").second["removed"].size() == 2);
    CHECK(f.call("GET", "/api/faults").second["faults"].empty());
}

TEST_CASE("the wire kinds' parameters are checked, each refusal naming its field, one of each kind at a time",
          "[control]")
{
    Fixture f;
    const std::pair<const char*, const char*> refused[] = {
        {R"({"device":"dev","kind":"slicer","slice_bytes":0})", "\"slice_bytes\": expected an integer 1..65536, got 0"},
        {R"({"device":"dev","kind":"slicer","gap_ms":-1})", "\"gap_ms\": expected an integer 0..60000, got -1"},
        {R"({"device":"dev","kind":"slicer","size":3})",
         "\"size\": not a parameter of a slicer fault (it takes slice_bytes, gap_ms)"},
        {R"({"device":"dev","kind":"bandwidth"})", "\"bytes_per_s\": required for a bandwidth fault"},
        {R"({"device":"dev","kind":"bandwidth","bytes_per_s":1.5})",
         "\"bytes_per_s\": expected an integer 1..100000000, got 1.5"},
        {R"({"device":"dev","kind":"bandwidth","bytes_per_s":10,"direction":"up"})",
         "\"direction\": expected \"in\", \"out\" or \"both\", got \"up\""},
        {R"({"device":"dev","kind":"reset","after_ms":600001})", "\"after_ms\": expected an integer 0..600000, got 600001"},
        {R"({"device":"dev","kind":"slow_close"})", "\"delay_ms\": required for a slow_close fault"},
        {R"({"device":"dev","kind":"hang_close","close_after_ms":"1"})",
         "\"close_after_ms\": expected an integer 0..600000, got \"1\""},
        {R"({"device":"dev","kind":"cut_after"})", "\"bytes\": required for a cut_after fault"},
        {R"({"device":"dev","kind":"cut_after","bytes":3,"direction":"both"})",
         "\"direction\": expected \"in\" or \"out\", got \"both\""},
        {R"({"device":"dev","kind":"garbage_close","bytes":0})", "\"bytes\": expected an integer 1..65536, got 0"},
        {R"({"device":"dev","kind":"overrun","buffer_bytes":0})", "\"buffer_bytes\": expected an integer 1..65536, got 0"},
        {R"({"device":"dev","kind":"overrun","drain_bytes_per_s":0})",
         "\"drain_bytes_per_s\": expected an integer 1..10000000, got 0"},
        {R"({"device":"dev","kind":"baud_mismatch","baud":9600})",
         "\"baud\": not a parameter of a baud_mismatch fault (it takes direction)"},
        {R"({"device":"dev","kind":"reset","channel":0})", "\"channel\": a reset fault acts on the whole device"},
    };
    for (const auto& [body, error] : refused) {
        INFO(body);
        CHECK(f.error_of("POST", "/api/faults", body, 400) == error);
    }
    CHECK(f.call("GET", "/api/faults").second["faults"].empty());
    const char* accepted[] = {
        R"({"device":"dev","kind":"slicer","slice_bytes":2,"gap_ms":5})",
        R"({"device":"dev","kind":"bandwidth","bytes_per_s":960,"direction":"out"})",
        R"({"device":"dev","kind":"reset","after_ms":100})",
        R"({"device":"dev","kind":"slow_close","delay_ms":100})",
        R"({"device":"dev","kind":"hang_close","close_after_ms":100})",
        R"({"device":"dev","kind":"cut_after","bytes":10,"direction":"in"})",
        R"({"device":"dev","kind":"garbage_close","bytes":8,"seed":2,"after_ms":5})",
        R"({"device":"dev","kind":"overrun","buffer_bytes":16,"drain_bytes_per_s":960})",
        R"({"device":"dev","kind":"baud_mismatch","direction":"in"})",
    };
    for (const auto* body : accepted) {
        INFO(body);
        const auto [status, record] = f.call("POST", "/api/faults", body);
        CHECK(status == 201);
        CHECK(record["channel"] == nullptr);
        CHECK(f.error_of("POST", "/api/faults", body, 409)
              == "the device has a " + record["kind"].get<std::string>() + " fault already (fault "
                     + std::to_string(record["id"].get<int>()) + "): delete it first");
    }
    CHECK(f.call("GET", "/api/faults").second["faults"].size() == 9);
    CHECK(f.call("DELETE", "/api/faults").second["removed"].size() == 9);
    REQUIRE(f.call("POST", "/api/faults", accepted[2]).first == 201);   // ended: again allowed
}

TEST_CASE("one cable, one delay: a second unplugged or latency fault is 409, and a device takes 64 faults", "[control]")
{
    Fixture f;
    const auto [s1, first] = f.call("POST", "/api/faults", R"({"device":"dev","kind":"latency","latency_ms":5})");
    REQUIRE(s1 == 201);
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"latency","latency_ms":9})", 409)
          == "the device has a latency fault already (fault 1): delete it first");
    f.call("POST", "/api/faults", R"({"device":"dev","kind":"unplugged"})");
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"unplugged"})", 409)
          == "the device is unplugged already (fault 2)");
    CHECK(f.link.latency_id() == 1);
    for (int i = 2; i < 64; ++i)
        REQUIRE(f.call("POST", "/api/faults", R"({"device":"dev","kind":"drop_bytes","probability":0})").first == 201);
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"stall"})", 409).find("64 active faults") != std::string::npos);
    CHECK(f.call("GET", "/api/faults").second["faults"].size() == 64);
}

TEST_CASE("bodies nested deeper than 32 levels are refused before anything copies or prints them", "[control]")
{
    Fixture f;
    const std::string deep = "{\"device\":\"dev\",\"kind\":\"stall\",\"x\":" + std::string(40, '[') + std::string(40, ']') + "}";
    CHECK(f.error_of("POST", "/api/faults", deep, 400) == "body: nested deeper than 32 levels");
    CHECK(f.surface.added.empty());
    const std::string deep_clock = "{\"scale\":" + std::string(5000, '[') + std::string(5000, ']') + "}";
    CHECK(f.error_of("POST", "/api/clock", deep_clock, 400) == "body: nested deeper than 32 levels");
}

TEST_CASE("a key twice in one body is refused, naming the object that holds it", "[control]")
{
    Fixture f;
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"stall","kind":"slip"})", 400)
          == "body: duplicate key \"kind\"");
    CHECK(f.surface.added.empty());
    CHECK(f.error_of("POST", "/api/faults", R"({"device":"dev","kind":"latency","params":{"latency_ms":1,"latency_ms":2}})", 400)
          == "body/params: duplicate key \"latency_ms\"");
}

TEST_CASE("path parts are percent-decoded, '+' and '&' are themselves", "[control]")
{
    Fixture f;
    CHECK(f.call("GET", "/api/devices/d%65v").first == 200);
    CHECK(f.error_of("GET", "/api/devices/d+v", "", 404).find("\"d+v\"") != std::string::npos);
    CHECK(f.error_of("GET", "/api/devices/dev&x=1", "", 404).find("\"dev&x=1\"") != std::string::npos);
}

TEST_CASE("POST /api/reset: every fault ends, every device power-cycles to its start, logs are cleared", "[control]")
{
    Fixture f;
    f.call("POST", "/api/faults", R"({"device":"dev","kind":"stall"})");
    f.call("POST", "/api/faults", R"({"device":"dev","kind":"unplugged"})");
    f.surface.wire_log().add(0, true, "pty", "x");
    const auto [status, answer] = f.call("POST", "/api/reset", "");
    CHECK(status == 200);
    CHECK(answer["reset"] == json::array({"dev"}));
    CHECK_FALSE(f.stage.faults().stalled);   // the stall left the body
    CHECK_FALSE(f.stage.blocked());
    CHECK_FALSE(f.link.unplugged());
    REQUIRE(f.surface.cycles.size() == 1);
    CHECK(f.surface.cycles[0].keep_saved);
    CHECK(f.surface.cycles[0].restore_positions);
    CHECK(f.surface.wire_log().size() == 0);
    f.call("POST", "/api/reset", R"({"keep_saved": false})");
    CHECK_FALSE(f.surface.cycles.back().keep_saved);
    CHECK(f.error_of("POST", "/api/reset", R"({"keep": 1})", 400) == "unknown key \"keep\" (expected keep_saved)");
    CHECK(f.error_of("GET", "/api/reset", "", 405).find("POST") != std::string::npos);
}

TEST_CASE("GET /api/devices/{name}/log: the last N entries, oldest first, and DELETE clears it", "[control]")
{
    Fixture f;
    auto& log = f.surface.wire_log();
    log.add(1, true, "pty", ":GP0\n");
    log.add(1, false, "pty", ":P0,5\n", {"a note"});
    log.add(2000, false, "pty", "\x01\x02", {}, true);
    const auto [status, all] = f.call("GET", "/api/devices/dev/log");
    CHECK(status == 200);
    REQUIRE(all["entries"].size() == 3);
    CHECK(all["entries"][0]["direction"] == "in");
    CHECK(all["entries"][0]["hex"] == "3a 47 50 30 0a");
    CHECK(all["entries"][1]["notes"] == json::array({"a note"}));
    CHECK(all["entries"][2]["time_ms"] == 2000.0);
    CHECK(all["entries"][2]["unprompted"] == true);
    CHECK(all["noted"] == 1);
    const auto [s2, last] = f.call("GET", "/api/devices/dev/log?last=1");
    REQUIRE(last["entries"].size() == 1);
    CHECK(last["entries"][0]["seq"] == 3);
    CHECK(f.error_of("GET", "/api/devices/dev/log?last=-1", "", 400).find("\"last\"") == 0);
    f.call("DELETE", "/api/devices/dev/log");
    CHECK(f.call("GET", "/api/devices/dev/log").second["entries"].empty());
    log.add(3000, true, "pty", ":GS0\n");
    const auto [s3, fresh] = f.call("GET", "/api/devices/dev/log");
    CHECK(fresh["entries"][0]["seq"] == 1);   // counted again from the clear
    CHECK(fresh["noted"] == 0);
}

TEST_CASE("the wire log keeps the last `capacity` entries", "[control]")
{
    Clock clock{1000};
    WireLog log("d", clock.tick_hz(), nullptr, nullptr, 3);
    for (int i = 0; i < 5; ++i)
        log.add(i, true, "p", std::string(1, static_cast<char>('a' + i)));
    const auto j = log.to_json(10);
    REQUIRE(j.size() == 3);
    CHECK(j[0]["seq"] == 3);
    CHECK(j[2]["hex"] == "65");
}

TEST_CASE("GET /api/events: a stream of the bus's events, filtered by device and type, ended by the client", "[control]")
{
    Fixture f;
    auto reply = f.api.handle("GET", "/api/events?device=dev&type=wire,fault_added", "");
    REQUIRE(reply.stream);
    std::string got;
    auto stop = reply.stream([&](control::StreamChunk b) { got.append(*b); });
    CHECK(got == ": rigsim event stream\n\n");
    CHECK(f.bus.active());
    f.surface.wire_log().add(5, true, "pty", "x");
    f.bus.publish("other", "wire", 0, json::object());
    f.bus.publish("dev", "status", 0, json::object());
    f.call("POST", "/api/faults", R"({"device":"dev","kind":"stall"})");
    CHECK(got.find("event: wire\nid: 1\ndata: {") != std::string::npos);
    CHECK(got.find("\"device\":\"dev\"") != std::string::npos);
    CHECK(got.find("event: fault_added\n") != std::string::npos);
    got.clear();
    auto all = f.api.handle("GET", "/api/events?type=fault_removed", "");
    auto stop_all = all.stream([&](control::StreamChunk b) { got.append(*b); });
    f.call("DELETE", "/api/faults/1");
    CHECK(got.find("event: fault_removed\n") != std::string::npos);
    CHECK(got.find("\"device\":\"dev\"") != std::string::npos);   // which device it ended on
    stop_all();
    CHECK(got.find("\"other\"") == std::string::npos);
    CHECK(got.find("event: status") == std::string::npos);
    stop();
    CHECK_FALSE(f.bus.active());
    CHECK(f.api.handle("GET", "/api/events?device=nope", "").status == 404);
    CHECK(f.api.handle("GET", "/api/events?colour=red", "").status == 400);
}

} // namespace test_control_routes
