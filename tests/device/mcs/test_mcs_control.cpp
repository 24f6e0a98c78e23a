// The control API's side of an MCS device (docs/control-api/mcs.md): describe(), PATCH,
// faults and their effect on the wire, power cycle, wire log and its notes, events.
#include "mcs_harness.hpp"
#include "emulator/control/body_state.hpp"
#include "emulator/control/fault_book.hpp"

#include "emulator/core/control_surface.hpp"
#include "emulator/core/event_bus.hpp"
#include "emulator/core/wire_log.hpp"

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

namespace test_mcs_control {

using nlohmann::json;
using rigsim::test::McsHarness;
using rigsim::test::mcs_device_config;

namespace {

json describe(McsHarness& h)
{
    json out = json::object();
    rigsim::control::describe_device(h.device(), &h.world(), out);   // as the control API does
    return out;
}

rigsim::Refused patch(McsHarness& h, std::size_t index, const json& body)
{
    return h.device().patch_channel(index, body);
}

rigsim::Refused fault(McsHarness& h, std::uint64_t id, const std::string& kind, std::size_t channel = 0,
                      const json& params = json::object(), bool* kept = nullptr)
{
    rigsim::DeviceFault f;
    if (auto r = rigsim::parse_device_fault(kind, params, f))   // as the control API does
        return r;
    f.id = id;
    f.channel = channel;
    bool k = false;
    bool on_body = false;
    return rigsim::control::start_device_fault(h.device(), &h.world(), f, kept ? kept : &k, &on_body);
}

/// Ends a physical fault `fault` started, as the control API does.
void unfault(McsHarness& h, std::uint64_t id)
{
    rigsim::control::end_device_fault(h.device(), &h.world(), id, true);
}

/// The notes of every logged entry whose bytes are `bytes`, joined.
std::string notes_of(McsHarness& h, const std::string& bytes)
{
    std::string all;
    for (const auto& e : h.device().wire_log().to_json(1000))
        if (e["decoded"]["text"] == bytes)
            for (const auto& n : e["notes"])
                all += n.get<std::string>() + "|";
    return all;
}

} // namespace

TEST_CASE("MCS describe: a channel on its way and a channel at rest", "[device][mcs][control]")
{
    McsHarness h;
    CHECK(h.send(":MPA0,5000000,0\n") == ":E0,0\n");   // 10 mm/s top speed: 0.5 s
    h.advance_ms(100);
    const auto d = describe(h);
    REQUIRE(d["channels"].size() == 3);
    const auto& moving = d["channels"][0];
    CHECK(moving["index"] == 0);
    CHECK(moving["kind"] == "linear");
    CHECK(moving["position_si"].get<double>() == Approx(0.001));
    CHECK(moving["si_unit"] == "m");
    CHECK(moving["position_protocol"] == 1000000);
    CHECK(moving["protocol_unit"] == "nm");
    CHECK(moving["velocity_si"].get<double>() == Approx(0.01));
    CHECK(moving["moving"] == true);
    CHECK(moving["referenced"] == false);
    CHECK(moving["status"] == json{{"code", 4}, {"name", "targeting"}});
    const auto& rest = d["channels"][1];
    CHECK(rest["position_si"].get<double>() == 0.0);
    CHECK(rest["velocity_si"].get<double>() == 0.0);
    CHECK(rest["moving"] == false);
    CHECK(rest["status"] == json{{"code", 0}, {"name", "stopped"}});
    CHECK(rest["sensor"] == json{{"type", 1}, {"name", "S"}, {"mode", "enabled"}, {"failed", false}});
    CHECK(rest["limits"]["range_limit"].is_null());
    CHECK(rest["limits"]["end_stops_si"][0].get<double>() == Approx(-0.0105));
    CHECK(rest["queued"] == json::array());
    CHECK(d["communication_mode"] == "sync");
    CHECK(d["sensor_mode"] == "enabled");
    CHECK(d["keep_alive_ms"] == 0);
    CHECK(d["baudrate"] == 9600);
}

TEST_CASE("MCS describe: range limit, queued command, no sensor, end effector", "[device][mcs][control]")
{
    auto config = mcs_device_config(3);
    rigsim::mcs::config_of(config).channels[1].sensor_type = "none";
    rigsim::mcs::config_of(config).channels[2].kind = "end_effector";
    McsHarness h(config);
    CHECK(h.send(":SCM1\n:FRM0,0,0,0\n:SPL0,-1000,2000\n:ATC0,1792\n:MPA0,1000,0\n") == "");   // ATC: async only
    const auto d = describe(h);
    CHECK(d["channels"][0]["referenced"] == true);
    CHECK(d["channels"][0]["limits"]["range_limit"] == json{{"min", -1000}, {"max", 2000}});
    CHECK(d["channels"][0]["queued"] == json::array({json{{"text", "MPA0,1000,0"}, {"trigger_source", 1792}}}));
    CHECK(d["channels"][1]["position_protocol"].is_null());
    CHECK(d["channels"][1]["sensor"].is_null());
    CHECK(d["channels"][2]["kind"] == "end_effector");
}

TEST_CASE("MCS PATCH position_si places the stage at rest, within travel", "[device][mcs][control]")
{
    McsHarness h;
    CHECK_FALSE(patch(h, 0, {{"position_si", 0.002}}));
    CHECK(h.send(":GP0\n:GS0\n") == ":P0,2000000\n:S0,0\n");
    const auto out = patch(h, 0, {{"position_si", 0.02}});
    REQUIRE(out);
    CHECK(out->status == 400);
    CHECK_THAT(out->message, Catch::Contains("position_si"));
    const auto typed = patch(h, 0, {{"position_si", "far"}});
    REQUIRE(typed);
    CHECK(typed->status == 400);
    CHECK(h.send(":GP0\n") == ":P0,2000000\n");
}

TEST_CASE("MCS PATCH referenced sets and loses the physical position", "[device][mcs][control]")
{
    McsHarness h;
    CHECK(h.send(":MPR0,1500,0\n:GPPK0\n") == ":E0,0\n:PPK0,0\n");
    h.advance_ms(5);
    CHECK_FALSE(patch(h, 0, {{"referenced", true}}));
    CHECK(h.send(":GPPK0\n:GP0\n:SPL0,0,10\n") == ":PPK0,1\n:P0,1500\n:E0,0\n");   // mark at physical 0
    CHECK_FALSE(patch(h, 0, {{"referenced", false}}));
    CHECK(h.send(":GPPK0\n:GP0\n:SPL0,0,10\n") == ":PPK0,0\n:P0,1500\n:E0,148\n");
    const auto typed = patch(h, 0, {{"referenced", 1}});
    REQUIRE(typed);
    CHECK(typed->status == 400);
}

TEST_CASE("MCS PATCH sensor switches one channel's sensor power", "[device][mcs][control]")
{
    auto config = mcs_device_config(2);
    rigsim::mcs::config_of(config).channels[1].sensor_type = "none";
    McsHarness h(config);
    CHECK_FALSE(patch(h, 0, {{"sensor", "disabled"}}));
    CHECK(h.send(":GP0\n:MPA0,0,0\n") == ":E0,140\n:E0,140\n");
    CHECK_FALSE(patch(h, 0, {{"sensor", "power_save"}}));
    CHECK(h.send(":GCP0,134938625\n") == ":CPR0,134938625,2\n");
    CHECK(describe(h)["channels"][0]["sensor"]["mode"] == "power_save");
    const auto none = patch(h, 1, {{"sensor", "enabled"}});
    REQUIRE(none);
    CHECK(none->status == 400);
    const auto bad_value = patch(h, 0, {{"sensor", "on"}});
    REQUIRE(bad_value);
    CHECK(bad_value->status == 400);
}

TEST_CASE("MCS PATCH refusals: limit_switch, unknown key, bad index, a moving channel", "[device][mcs][control]")
{
    McsHarness h;
    const auto sw = patch(h, 0, {{"limit_switch", "forward"}});
    REQUIRE(sw);
    CHECK(sw->status == 400);
    CHECK_THAT(sw->message, Catch::Contains("limit_switch") && Catch::Contains("no limit switches"));
    const auto unknown = patch(h, 0, {{"colour", "red"}});
    REQUIRE(unknown);
    CHECK(unknown->status == 400);
    CHECK_THAT(unknown->message, Catch::Contains("colour"));
    const auto index = patch(h, 3, {{"referenced", true}});
    REQUIRE(index);
    CHECK(index->status == 404);
    CHECK(h.send(":MPA0,5000000,0\n") == ":E0,0\n");
    const auto busy = patch(h, 0, {{"position_si", 0.0}});
    REQUIRE(busy);
    CHECK(busy->status == 409);
    h.advance_ms(600);
    CHECK_FALSE(patch(h, 0, {{"position_si", 0.0}}));
}

TEST_CASE("MCS stall: closed-loop moves end at once with 142, steps make no way", "[device][mcs][control][faults]")
{
    McsHarness h;
    CHECK(h.send(":SCM1\n") == "");
    bool kept = false;
    CHECK_FALSE(fault(h, 1, "stall", 0, json::object(), &kept));
    CHECK(kept);
    CHECK(h.send(":MPA0,5000000,0\n") == ":E0,142\n");   // as at an end stop (appendix 4.2)
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,0\n");
    CHECK(h.send(":MST0,100,4095,1000\n") == "");
    h.advance_ms(200);
    CHECK(h.send(":GP0\n") == ":P0,0\n");
    unfault(h, 1);
    CHECK(h.send(":MPA0,1000000,0\n") == "");
    h.advance_ms(200);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,1000000\n");
}

TEST_CASE("MCS stall during a move: the stage stops where it is, 142 unprompted", "[device][mcs][control][faults]")
{
    McsHarness h;
    CHECK(h.send(":SCM1\n:MPA0,5000000,0\n") == "");
    h.advance_ms(100);
    CHECK_FALSE(fault(h, 1, "stall"));
    CHECK(h.send(":GS0\n") == ":E0,142\n:S0,0\n");
    h.advance_ms(500);
    CHECK(h.send(":GP0\n") == ":P0,1000000\n");
    CHECK(describe(h)["channels"][0]["last_outcome"] == "stalled");
}

TEST_CASE("MCS slip: steps shorter, closed-loop moves slower", "[device][mcs][control][faults]")
{
    McsHarness h;
    CHECK_FALSE(fault(h, 1, "slip", 0, {{"fraction", 0.5}}));
    CHECK(h.send(":MST0,10,4095,1000\n") == ":E0,0\n");
    h.advance_ms(20);
    const auto gp = h.send(":GP0\n");
    const auto p = std::stoll(gp.substr(4));
    CHECK(p > 4500);    // 10 steps of 500 nm ± 3 %, not 1000 nm
    CHECK(p < 5500);
    CHECK(h.send(":SP0,0\n:MPA0,1000000,0\n") == ":E0,0\n:E0,0\n");   // 100 ms at full speed
    h.advance_ms(150);
    CHECK(h.send(":GS0\n") == ":S0,4\n");
    h.advance_ms(60);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,1000000\n");
    unfault(h, 1);
    CHECK(h.send(":MPA0,2000000,0\n") == ":E0,0\n");
    h.advance_ms(110);
    CHECK(h.send(":GS0\n") == ":S0,0\n");
}

TEST_CASE("MCS fault params are validated, naming the field", "[device][mcs][control][faults]")
{
    McsHarness h;
    const auto range = fault(h, 1, "slip", 0, {{"fraction", 1.5}});
    REQUIRE(range);
    CHECK(range->status == 400);
    CHECK_THAT(range->message, Catch::Contains("fraction"));
    const auto unknown = fault(h, 2, "stall", 0, {{"force", 3}});
    REQUIRE(unknown);
    CHECK(unknown->status == 400);
    CHECK_THAT(unknown->message, Catch::Contains("force"));
    const auto kind = fault(h, 3, "melt");
    REQUIRE(kind);
    CHECK(kind->status == 400);
    const auto sw = fault(h, 4, "limit_switch", 0, {{"side", "forward"}});
    REQUIRE(sw);
    CHECK(sw->status == 400);
    CHECK_THAT(sw->message, Catch::Contains("limit_switch"));
    const auto counts = fault(h, 4, "slip", 0, {{"counts", 10}});   // a stepper's figure
    REQUIRE(counts);
    CHECK(counts->status == 400);
    CHECK_THAT(counts->message, Catch::Contains("counts"));
    const auto index = fault(h, 5, "stall", 9);
    REQUIRE(index);
    CHECK(index->status == 404);
    CHECK(h.send(":MPA0,1000,0\n") == ":E0,0\n");   // none of them acts
    h.advance_ms(5);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,1000\n");
}

TEST_CASE("MCS sensor_failure: 129 for closed loop, position lost, steps still run", "[device][mcs][control][faults]")
{
    McsHarness h;
    CHECK(h.send(":FRM0,0,0,0\n:MPA0,2000000,0\n") == ":E0,0\n:E0,0\n");
    h.advance_ms(100);   // on the way: the failure stops it
    CHECK_FALSE(fault(h, 7, "sensor_failure"));
    CHECK(h.send(":GS0\n:GP0\n:MPA0,0,0\n:FRM0,0,0,0\n:GPPK0\n") == ":S0,0\n:E0,129\n:E0,129\n:E0,129\n:PPK0,0\n");
    CHECK(h.send(":MST0,5,4095,1000\n") == ":E0,0\n");
    h.advance_ms(10);
    CHECK(h.send(":GS0\n") == ":S0,0\n");
    unfault(h, 7);
    CHECK(h.send(":GP0\n:GPPK0\n") == ":P0,0\n:PPK0,0\n");   // reading restarts at 0, position unknown
    CHECK(describe(h)["channels"][0]["position_si"].get<double>() > 0.0009);
}

TEST_CASE("MCS reference_lost: one-off, the physical position becomes unknown", "[device][mcs][control][faults]")
{
    McsHarness h;
    CHECK(h.send(":FRM0,0,0,0\n:MPA0,1000,0\n") == ":E0,0\n:E0,0\n");
    h.advance_ms(10);
    bool kept = true;
    CHECK_FALSE(fault(h, 9, "reference_lost", 0, json::object(), &kept));
    CHECK_FALSE(kept);
    CHECK(h.send(":GPPK0\n:GP0\n") == ":PPK0,0\n:P0,1000\n");
}

TEST_CASE("MCS power cycle keeps or erases saved settings, restores positions", "[device][mcs][control]")
{
    McsHarness h;
    CHECK(h.send(":SSC0,5000,0\n:CB57600\n:SCM1\n:SST1,9\n") == ":E-1,0\n:BR57142\n");
    CHECK(h.send(":MPA0,2000000,0\n") == "");
    h.advance_ms(300);
    h.device().power_cycle({true, false});
    CHECK(h.send(":GSC0\n:GCM\n:GST1\n:GP0\n") == ":SC0,5000,0\n:CM0\n:ST1,9\n:P0,0\n");
    CHECK(describe(h)["baudrate"] == 57600);   // CB took effect at the reset
    CHECK(describe(h)["channels"][0]["position_si"].get<double>() == Approx(0.002));
    h.device().power_cycle({false, true});
    CHECK(h.send(":GSC0\n:GST1\n") == ":SC0,0,0\n:ST1,1\n");
    CHECK(describe(h)["channels"][0]["position_si"].get<double>() == 0.0);
    h.device().power_cycle({true, false});
    CHECK(describe(h)["baudrate"] == 9600);
}

TEST_CASE("MCS reset and power cycle forget the last motion's outcome", "[device][mcs][control]")
{
    McsHarness h;
    CHECK(h.send(":SCM1\n:MPA0,1000,0\n") == "");
    h.advance_ms(100);
    CHECK(describe(h)["channels"][0]["last_outcome"] == "completed");
    h.device().power_cycle({true, true});   // POST /api/reset and the power_cycle fault
    CHECK(describe(h)["channels"][0]["last_outcome"] == "");
    CHECK(h.send(":MPA0,1000,0\n") == ":E0,0\n");   // the reset made the mode synchronous again
    h.advance_ms(100);
    CHECK(describe(h)["channels"][0]["last_outcome"] == "completed");
    CHECK(h.send(":R\n") == ":E-1,0\n");
    CHECK(describe(h)["channels"][0]["last_outcome"] == "");
}

TEST_CASE("MCS power cycle: a stall outlasts it", "[device][mcs][control][faults]")
{
    McsHarness h;
    CHECK_FALSE(fault(h, 1, "stall"));
    h.device().power_cycle({true, true});
    CHECK(h.send(":SCM1\n:MPA0,1000,0\n") == ":E0,142\n");
}

TEST_CASE("MCS wire log: every line each way, decoded with the manual's names", "[device][mcs][control][wirelog]")
{
    McsHarness h;
    CHECK(h.send(":GP0\n") == ":P0,0\n");
    const auto log = h.device().wire_log().to_json(10);
    REQUIRE(log.size() == 2);
    CHECK(log[0]["direction"] == "in");
    CHECK(log[0]["peer"] == "test");
    CHECK(log[0]["hex"] == "3a 47 50 30 0a");
    CHECK(log[0]["decoded"] == json{{"text", "GP0"}, {"command", "GP"}, {"name", "Get Position"},
                                     {"fields", {{"channelIndex", 0}}}});
    CHECK(log[0]["notes"] == json::array());
    CHECK(log[1]["direction"] == "out");
    CHECK(log[1]["unprompted"] == false);
    CHECK(log[1]["decoded"]["name"] == "Position");
    CHECK(log[1]["decoded"]["fields"] == json{{"channelIndex", 0}, {"position", 0}});
    CHECK(h.send(":SCM1\n") == "");
    CHECK(h.device().wire_log().size() == 3);   // an answerless command is logged alone
    CHECK_FALSE(fault(h, 1, "stall"));
    CHECK(h.send(":MPA0,10,0\n") == ":E0,142\n");
    const auto last = h.device().wire_log().to_json(1)[0];
    CHECK(last["unprompted"] == true);
    CHECK(last["decoded"]["name"] == "Error");
    CHECK(last["decoded"]["fields"]["meaning"] == "End Stop Reached Error");
}

TEST_CASE("MCS wire log notes: errors, out-of-range settings, blind moves, early requests, keep-alive",
          "[device][mcs][control][wirelog]")
{
    McsHarness h;
    CHECK(h.send(":GP9\n") == ":E-1,7\n");
    CHECK_THAT(notes_of(h, "GP9"), Catch::Contains("answered with an error: E-1,7 Invalid Parameter Error"));
    CHECK(h.send(":K50\n") == ":E-1,7\n");
    CHECK_THAT(notes_of(h, "K50"), Catch::Contains("setting out of the documented range"));
    CHECK(h.send(":MPA0,1000,0\n") == ":E0,0\n");
    CHECK_THAT(notes_of(h, "MPA0,1000,0"), Catch::Contains("physical position is unknown"));
    CHECK(h.send(":GS1\n") == ":S1,0\n");
    CHECK(notes_of(h, "GS1").empty());
    CHECK(h.send(":GS2\n:GP2\n") == ":S2,0\n:P2,0\n");
    CHECK(notes_of(h, "GS2").empty());
    CHECK_THAT(notes_of(h, "GP2"), Catch::Contains("before the answer to the previous command"));
    CHECK(h.send(":GP1:GS1\n") == ":S1,0\n");
    CHECK_THAT(notes_of(h, "GP1"), Catch::Contains("':' inside a command"));
    CHECK(h.send(":K100\n") == ":E-1,0\n");
    const auto before = h.device().wire_log().noted();
    h.advance_ms(150);
    CHECK(h.device().wire_log().noted() == before + 1);
    CHECK_THAT(notes_of(h, "E-1,0"), Catch::Contains("keep-alive expired"));
}

TEST_CASE("MCS wire log note: a request while a paced answer is still going out", "[device][mcs][control][wirelog]")
{
    auto config = mcs_device_config();
    config.faithful_timing = true;   // 9600 baud: ":P0,0\n" takes 6.25 ms
    McsHarness h(config);
    std::string sink;
    auto serial = h.open(sink, "pty");
    serial->receive(":GP0\n");
    serial->receive(":GP1\n");   // the same tick: GP0's answer is still on the line
    h.advance_ms(20);   // both answers are out after 12.5 ms
    serial->receive(":GP2\n");
    CHECK(sink == ":P0,0\n:P1,0\n:P2,0\n");
    CHECK(notes_of(h, "GP0").empty());
    CHECK_THAT(notes_of(h, "GP1"), Catch::Contains("still going out on the serial line"));
    CHECK(notes_of(h, "GP2").empty());
}

TEST_CASE("MCS events: move_started, status, move_ended with the outcome", "[device][mcs][control][events]")
{
    rigsim::EventBus bus;
    std::vector<json> events;
    std::size_t wire = 0;
    bus.subscribe([&](const rigsim::Event& e) {
        if (e.type == "wire")
            ++wire;
        else
            events.push_back(json::parse(e.json));
    });
    McsHarness h(mcs_device_config(), 1000, &bus);
    CHECK(h.send(":GS0\n") == ":S0,0\n");   // the first batch heard sets the baseline
    CHECK(wire == 2);                         // the wire log streams each line too
    CHECK(h.send(":MPA0,1000000,0\n") == ":E0,0\n");
    REQUIRE(events.size() == 2);
    CHECK(events[0]["type"] == "move_started");
    CHECK(events[0]["device"] == "mcs-test");
    CHECK(events[0]["channel"] == 0);
    CHECK(events[1]["type"] == "status");
    CHECK(events[1]["status"] == json{{"code", 4}, {"name", "targeting"}});
    h.advance_ms(200);
    REQUIRE(events.size() == 4);
    CHECK(events[2]["type"] == "status");
    CHECK(events[2]["status"]["code"] == 0);
    CHECK(events[3]["type"] == "move_ended");
    CHECK(events[3]["outcome"] == "completed");
    CHECK(events[3]["time_ms"].get<double>() >= 100.0);   // 1 mm at 10 mm/s
    CHECK(events[3]["time_ms"].get<double>() <= 102.0);
    CHECK(h.send(":MPA0,5000000,0\n:S0\n") == ":E0,0\n:E0,0\n");   // started and stopped in one batch
    CHECK(events.size() == 4);
    CHECK(h.send(":MPA0,5000000,0\n") == ":E0,0\n");
    h.advance_ms(10);
    CHECK_FALSE(fault(h, 1, "stall"));
    REQUIRE(events.size() == 8);
    CHECK(events[7]["type"] == "move_ended");
    CHECK(events[7]["outcome"] == "stalled");
}

TEST_CASE("MCS stall: a reference search meets end stops both ways at once, 144", "[device][mcs][control][faults]")
{
    McsHarness h;
    CHECK(h.send(":SCM1\n:SCLS0,1000000\n:MPR0,2000000,0\n") == "");
    h.advance_ms(2100);
    CHECK_FALSE(fault(h, 1, "stall"));
    CHECK(h.send(":FRM0,0,0,0\n") == ":E0,144\n");
    CHECK(h.send(":GS0\n:GPPK0\n") == ":S0,0\n:PPK0,0\n");
    unfault(h, 1);
    CHECK(h.send(":FRM0,1,0,0\n") == "");   // toward the mark at physical 0: 2 s at 1 mm/s
    h.advance_ms(500);
    CHECK_FALSE(fault(h, 2, "stall"));   // stalled on the way
    CHECK(h.send(":GS0\n:GPPK0\n") == ":E0,144\n:S0,0\n:PPK0,0\n");
    CHECK(describe(h)["channels"][0]["last_outcome"] == "reference_not_found");
}

TEST_CASE("MCS describe and PATCH on a rotary channel: radians and micro degrees", "[device][mcs][control]")
{
    McsHarness h;
    CHECK(h.send(":SST0,2\n") == ":E0,0\n");   // SR: rotary, endless, a mark per turn
    CHECK_FALSE(patch(h, 0, {{"position_si", 3.14159265358979323846 / 2}}));
    const auto ch = describe(h)["channels"][0];
    CHECK(ch["kind"] == "rotary");
    CHECK(ch["body"]["kind"] == "rotary");   // SST: another positioner is attached; the body follows
    CHECK(ch["si_unit"] == "rad");
    CHECK(ch["protocol_unit"] == "udeg");
    CHECK(ch["position_si"].get<double>() == Approx(3.14159265358979323846 / 2));
    CHECK(ch["position_protocol"] == 90000000);
    CHECK(ch["limits"]["end_stops_si"] == json::array({nullptr, nullptr}));
    CHECK(h.send(":GA0\n") == ":A0,90000000,0\n");
    // An endless stage has no end stops; a position beyond what the scale counts is refused
    // (1e305 rad is finite, in micro degrees it is not).
    const auto refused = patch(h, 0, {{"position_si", 1e305}});
    REQUIRE(refused);
    CHECK(refused->status == 400);
    CHECK(h.send(":GA0\n") == ":A0,90000000,0\n");
}

} // namespace test_mcs_control
