// APT: the control API's side of an APT unit (docs/control-api/apt.md): describe(), PATCH of a
// channel, the faults that act inside the unit, the power cycle, the wire log and the events,
// checked on the wire (frames in -> frames out) on a stepped clock.
#include "apt_harness.hpp"
#include "emulator/control/body_state.hpp"
#include "emulator/control/fault_book.hpp"

#include "emulator/core/event_bus.hpp"
#include "emulator/core/wire_log.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace test_apt_control {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;
using nlohmann::json;

namespace {

json describe(AptHarness& h)
{
    json out = json::object();
    rigsim::control::describe_device(h.device(), &h.world(), out);   // as the control API does
    return out;
}

json channel(AptHarness& h, std::size_t i = 0)
{
    return describe(h)["channels"].at(i);
}

bool has(const json& array, const std::string& name)
{
    return std::find(array.begin(), array.end(), json(name)) != array.end();
}

Refused patch(AptHarness& h, const json& body, std::size_t index = 0)
{
    return h.device().patch_channel(index, body);
}

Refused fault(AptHarness& h, std::uint64_t id, const std::string& kind, json params = json::object(),
              std::optional<std::size_t> ch = std::nullopt, bool* kept = nullptr)
{
    bool k = false;
    DeviceFault f;
    if (auto r = parse_device_fault(kind, params, f))   // as the control API does
        return r;
    f.id = id;
    f.channel = ch;
    bool on_body = false;
    return rigsim::control::start_device_fault(h.device(), &h.world(), f, kept ? kept : &k, &on_body);
}

/// Ends a physical fault `fault` started, as the control API does.
void unfault(AptHarness& h, std::uint64_t id)
{
    rigsim::control::end_device_fault(h.device(), &h.world(), id, true);
}

std::int32_t position_counter(AptHarness& h)
{
    return position_of(h.send("11 04 01 00 50 01"));   // REQ_POSCOUNTER
}

std::int32_t encoder_counter(AptHarness& h)
{
    return position_of(h.send("0A 04 01 00 50 01"));   // REQ_ENCCOUNTER
}

constexpr double kZ8CountsPerMetre = 34'304'000.0;   // MTS50-Z8: 34,304 counts/mm
constexpr const char* kMove100k = "53 04 06 00 D0 01 01 00 A0 86 01 00";   // MOVE_ABSOLUTE +100,000

} // namespace

TEST_CASE("control: describe() of a resting TDC001 reads the world and the protocol", "[device][apt][control]")
{
    AptHarness h;
    const json d = describe(h);
    CHECK(d["serial_number"] == 83'000'001);
    CHECK(d["status_updates"] == json{{"on", false}, {"unacknowledged", 0}, {"cut_off", false}});
    CHECK(d["end_of_move_messages"] == true);
    REQUIRE(d["channels"].size() == 1);
    const json c = d["channels"][0];
    CHECK(c["index"] == 0);
    CHECK(c["kind"] == "linear");
    CHECK(c["si_unit"] == "m");
    CHECK(c["position_si"].get<double>() == Approx(0.025));   // mid-travel at power-up
    CHECK(c["position_protocol"] == 0);
    CHECK(c["protocol_unit"] == "counts");
    CHECK(c["encoder"] == 0);
    CHECK(c["velocity_si"] == 0.0);
    CHECK(c["moving"] == false);
    CHECK(c["referenced"] == false);
    CHECK(c["enabled"] == true);
    CHECK(c["status"]["bits"] == (status::kMotorConnected | status::kSettled | status::kEnabled));
    CHECK(c["status"]["hex"] == "0x80002100");
    CHECK(c["status"]["set"] == json{"motor_connected", "settled", "enabled"});
    CHECK(c["limits"]["travel"]["max"] == 1'715'200);
    CHECK(c["limits"]["travel"]["max_si"].get<double>() == Approx(0.05));
    CHECK(c["limits"]["switch_pressed"] == json{{"forward", false}, {"reverse", false}});
    CHECK(c["limits"]["switch_params"]["cw_hard_limit"] == 2);
}

TEST_CASE("control: describe() of a moving bay, and of each bay of a BSC203 rack", "[device][apt][control][rack]")
{
    AptHarness h;
    CHECK(h.send(kMove100k) == "");
    h.advance_ms(500);
    const json c = channel(h);
    CHECK(c["moving"] == true);
    CHECK(c["velocity_si"].get<double>() > 0);
    CHECK(has(c["status"]["set"], "moving_forward"));
    CHECK(!has(c["status"]["set"], "settled"));
    CHECK(c["position_protocol"].get<std::int32_t>() > 0);
    CHECK(c["position_si"].get<double>() == Approx(0.025 + c["position_protocol"].get<double>() / kZ8CountsPerMetre));

    AptHarness rack(apt_rack("BSC203", {"DRV014", "ZST225B"}));
    const json r = describe(rack);
    REQUIRE(r["channels"].size() == 2);
    CHECK(r["channels"][0]["address"] == "0x21");
    CHECK(r["channels"][1]["address"] == "0x22");
    CHECK(r["channels"][1]["index"] == 1);
    CHECK(r["channels"][1]["stage"] == "ZST225B");
    CHECK(r["channels"][1]["position_si"].get<double>() == Approx(0.0125));
}

TEST_CASE("control: PATCH position_si places the carriage, the counters follow", "[device][apt][control]")
{
    AptHarness h;
    CHECK(!patch(h, {{"position_si", 0.03}}));
    CHECK(channel(h)["position_si"].get<double>() == Approx(0.03));
    CHECK(position_counter(h) == 171'520);   // 5 mm further
    CHECK(encoder_counter(h) == 171'520);
    const auto r = patch(h, {{"position_si", 0.06}});
    REQUIRE(r);
    CHECK(r->status == 400);
    CHECK(r->message.find("position_si") != std::string::npos);
    CHECK(channel(h)["position_si"].get<double>() == Approx(0.03));
}

TEST_CASE("control: PATCH referenced sets and clears the homed bit", "[device][apt][control]")
{
    AptHarness h;
    CHECK(!patch(h, {{"referenced", true}}));
    CHECK((status_of(h.send("90 04 01 00 50 01")) & status::kHomed) != 0);   // REQ_DCSTATUSUPDATE
    CHECK(channel(h)["referenced"] == true);
    CHECK(!patch(h, {{"referenced", false}}));
    CHECK((status_of(h.send("90 04 01 00 50 01")) & status::kHomed) == 0);
}

TEST_CASE("control: PATCH limit_switch presses a switch: its bit, moves into it stop at once", "[device][apt][control]")
{
    AptHarness h;
    CHECK(!patch(h, {{"limit_switch", "forward"}}));
    CHECK((status_of(h.send("90 04 01 00 50 01")) & status::kForwardHardLimit) != 0);
    CHECK(channel(h)["limits"]["switch_pressed"]["forward"] == true);
    // MOVE_COMPLETED where it stood, at once (as a move to where the stage stands).
    const auto out = frames(h.send(kMove100k));
    REQUIRE(out.size() == 1);
    CHECK(out[0].substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(0));
    CHECK((status_of(out[0]) & status::kForwardHardLimit) != 0);
    h.advance_ms(1000);
    CHECK(h.take() == "");
    // Away from the switch it moves.
    CHECK(h.send("53 04 06 00 D0 01 01 00 " + le32(-1000)) == "");
    h.advance_ms(2000);
    CHECK(frames(h.take()).at(0).substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(-1000));
    CHECK(!patch(h, {{"limit_switch", "none"}}));
    CHECK((status_of(h.send("90 04 01 00 50 01")) & status::kForwardHardLimit) == 0);
    CHECK(h.send(kMove100k) == "");
    h.advance_ms(5000);
    CHECK(frames(h.take()).at(0).substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(100'000));
}

TEST_CASE("control: PATCH enabled false: a move is ignored as for MOD_SET_CHANENABLESTATE", "[device][apt][control]")
{
    AptHarness h;
    CHECK(!patch(h, {{"enabled", false}}));
    CHECK(h.send("11 02 01 00 50 01") == "12 02 01 02 01 50");   // REQ_CHANENABLESTATE: disabled
    CHECK(h.send(kMove100k) == "");
    h.advance_ms(5000);
    CHECK(h.take() == "");
    CHECK(!patch(h, {{"enabled", true}}));
    CHECK(h.send("11 02 01 00 50 01") == "12 02 01 01 01 50");
}

TEST_CASE("control: PATCH refusals: bad index, unknown key, sensor, bad types, moving", "[device][apt][control]")
{
    AptHarness h;
    auto r = patch(h, {{"referenced", true}}, 1);
    REQUIRE(r);
    CHECK(r->status == 404);
    r = patch(h, {{"speed", 1}});
    REQUIRE(r);
    CHECK(r->status == 400);
    CHECK(r->message.find("speed") != std::string::npos);
    r = patch(h, {{"sensor", "disabled"}});
    REQUIRE(r);
    CHECK(r->status == 400);
    CHECK(r->message.find("sensor") != std::string::npos);
    for (const json& body : {json{{"position_si", "0.01"}}, json{{"referenced", 1}}, json{{"limit_switch", "up"}},
                             json{{"enabled", "yes"}}}) {
        r = patch(h, body);
        REQUIRE(r);
        CHECK(r->status == 400);
        CHECK(r->message.find(body.begin().key()) != std::string::npos);
    }
    CHECK(h.send(kMove100k) == "");
    h.advance_ms(100);
    r = patch(h, {{"referenced", true}});
    REQUIRE(r);
    CHECK(r->status == 409);
    CHECK(channel(h)["referenced"] == false);
}

TEST_CASE("control: a stall fault ends a DC servo's move with HW_RESPONSE and the current limit", "[device][apt][control][fault]")
{
    AptHarness h;
    CHECK(!fault(h, 1, "stall"));
    CHECK(h.send(kMove100k) == "");
    h.advance_ms(10);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 2);
    CHECK(out[0] == "80 00 00 00 01 50");   // HW_RESPONSE (p. 19)
    CHECK(out[1].substr(0, 35) == "66 04 0E 00 81 50 01 00 " + le32(0));   // MOVE_STOPPED where it stood
    CHECK((status_of(out[1]) & status::kCurrentLimit) != 0);
    const auto stalled = channel(h);
    CHECK(stalled["position_si"].get<double>() == Approx(0.025));
    // The channel's body, as every family shows it: its key in the world, its kind, its faults.
    CHECK(stalled["body"]["key"] == "cube/1");
    CHECK(stalled["body"]["kind"] == "linear");
    CHECK(stalled["body"]["faults"]["stalled"] == true);
    CHECK(stalled["body"]["settling"] == false);
    unfault(h, 1);
    CHECK(channel(h)["body"]["faults"]["stalled"] == false);
    CHECK(h.send(kMove100k) == "");
    h.advance_ms(5000);
    const auto done = frames(h.take());
    REQUIRE(done.size() == 1);
    CHECK(done[0].substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(100'000));
    CHECK((status_of(done[0]) & status::kCurrentLimit) == 0);
}

TEST_CASE("control: a stall fault during a KDC101 move stops it with HW_RICHRESPONSE", "[device][apt][control][fault]")
{
    AptHarness h(apt_cube("KDC101", "Z825B"));
    CHECK(h.send(kMove100k) == "");
    h.advance_ms(200);
    const double moved = channel(h)["position_si"].get<double>();
    CHECK(!fault(h, 1, "stall"));
    h.advance_ms(10);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 2);
    CHECK(out[0].substr(0, 29) == "81 00 44 00 81 50 53 04 01 00");   // MsgIdent MOVE_ABSOLUTE, code 1
    CHECK(bytes(out[0]).substr(10, 36) == "Motor stalled: current limit reached");
    CHECK(out[1].substr(0, 17) == "66 04 0E 00 81 50");
    CHECK(channel(h)["position_si"].get<double>() == Approx(moved).epsilon(1e-4));
    CHECK(channel(h)["moving"] == false);
}

TEST_CASE("control: a stalled stepper loses its steps: the counter runs on, the carriage stays", "[device][apt][control][fault][stepper]")
{
    AptHarness h(apt_cube("KST101", "DRV014"));
    CHECK(!fault(h, 1, "stall"));
    CHECK(h.send(kMove100k) == "");
    h.advance_ms(10'000);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 1);
    CHECK(out[0].substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(100'000));   // MOVE_COMPLETED, no fault
    CHECK(channel(h)["position_si"].get<double>() == Approx(0.025));
}

TEST_CASE("control: slip makes a stepper fall short by the lost microsteps, a DC servo refuses it", "[device][apt][control][fault][stepper]")
{
    AptHarness h(apt_cube("KST101", "DRV014"));   // 25,600 microsteps/mm
    CHECK(!fault(h, 1, "slip", {{"counts", 2560}}));
    CHECK(h.send(kMove100k) == "");
    h.advance_ms(10'000);
    CHECK(frames(h.take()).at(0).substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(100'000));
    CHECK(channel(h)["position_si"].get<double>() == Approx(0.025 + (100'000 - 2560) / 25'600'000.0));
    unfault(h, 1);
    CHECK(!fault(h, 2, "slip", {{"fraction", 0.5}}));
    CHECK(h.send("53 04 06 00 D0 01 01 00 " + le32(200'000)) == "");
    h.advance_ms(10'000);
    CHECK(frames(h.take()).at(0).substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(200'000));
    CHECK(channel(h)["position_si"].get<double>() == Approx(0.025 + (100'000 - 2560 + 50'000) / 25'600'000.0));

    auto r = fault(h, 3, "slip", {{"fraction", 2}});
    REQUIRE(r);
    CHECK(r->message.find("fraction") != std::string::npos);
    r = fault(h, 3, "slip", json::object());
    REQUIRE(r);
    CHECK(r->status == 400);

    AptHarness dc;
    r = fault(dc, 1, "slip", {{"counts", 10}});
    REQUIRE(r);
    CHECK(r->status == 400);
    CHECK(r->message.find("encoder") != std::string::npos);
}

TEST_CASE("control: sensor_failure: a DC servo's counters freeze and it cannot move (motion error)", "[device][apt][control][fault]")
{
    AptHarness h;
    CHECK(!fault(h, 1, "sensor_failure"));
    CHECK((status_of(h.send("90 04 01 00 50 01")) & status::kMotionError) != 0);
    CHECK(h.send(kMove100k) == "");
    h.advance_ms(10);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 2);
    CHECK(out[0] == "80 00 00 00 01 50");
    CHECK((status_of(out[1]) & status::kMotionError) != 0);
    CHECK((status_of(out[1]) & status::kCurrentLimit) == 0);
    CHECK(channel(h)["encoder_failed"] == true);
    unfault(h, 1);
    CHECK((status_of(h.send("90 04 01 00 50 01")) & status::kMotionError) != 0);   // until the next move
    CHECK(h.send(kMove100k) == "");
    h.advance_ms(5000);
    CHECK(frames(h.take()).at(0).substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(100'000));
}

TEST_CASE("control: sensor_failure on a stepper freezes its encoder counter only", "[device][apt][control][fault][stepper]")
{
    AptHarness h(apt_cube("KST101", "DRV014"));
    CHECK(!fault(h, 1, "sensor_failure"));
    CHECK(h.send(kMove100k) == "");
    h.advance_ms(10'000);
    CHECK(frames(h.take()).at(0).substr(0, 35) == "64 04 0E 00 81 50 01 00 " + le32(100'000));
    CHECK(position_counter(h) == 100'000);
    CHECK(encoder_counter(h) == 0);
}

TEST_CASE("control: reference_lost clears the homed bit once, and is not kept", "[device][apt][control][fault]")
{
    AptHarness h;
    CHECK(h.send("43 04 01 00 50 01") == "");   // MOVE_HOME
    h.advance_ms(60'000);
    CHECK(frames(h.take()).back() == "44 04 01 00 01 50");   // MOVE_HOMED
    CHECK((status_of(h.send("90 04 01 00 50 01")) & status::kHomed) != 0);
    bool kept = true;
    CHECK(!fault(h, 1, "reference_lost", json::object(), 0, &kept));
    CHECK(kept == false);
    CHECK((status_of(h.send("90 04 01 00 50 01")) & status::kHomed) == 0);
}

TEST_CASE("control: a limit_switch fault trips a switch, params and channel are checked", "[device][apt][control][fault]")
{
    AptHarness h;
    CHECK(!fault(h, 1, "limit_switch", {{"side", "reverse"}}));
    CHECK((status_of(h.send("90 04 01 00 50 01")) & status::kReverseHardLimit) != 0);
    CHECK(frames(h.send("53 04 06 00 D0 01 01 00 " + le32(-50'000))).at(0).substr(0, 35)
          == "64 04 0E 00 81 50 01 00 " + le32(0));
    unfault(h, 1);
    CHECK((status_of(h.send("90 04 01 00 50 01")) & status::kReverseHardLimit) == 0);

    auto r = fault(h, 2, "limit_switch", {{"side", "up"}});
    REQUIRE(r);
    CHECK(r->status == 400);
    CHECK(r->message.find("side") != std::string::npos);
    r = fault(h, 2, "limit_switch", {{"side", "forward"}, {"force", 3}});
    REQUIRE(r);
    CHECK(r->message.find("force") != std::string::npos);
    r = fault(h, 2, "stall", json::object(), 1);
    REQUIRE(r);
    CHECK(r->status == 404);
    r = fault(h, 2, "melt");
    REQUIRE(r);
    CHECK(r->status == 400);
}

TEST_CASE("control: a limit_switch fault stops a move running toward it", "[device][apt][control][fault]")
{
    AptHarness h;
    CHECK(h.send(kMove100k) == "");
    h.advance_ms(300);
    CHECK(!fault(h, 1, "limit_switch", {{"side", "forward"}}));
    h.advance_ms(10);
    const auto out = frames(h.take());
    REQUIRE(out.size() == 1);
    CHECK(out[0].substr(0, 17) == "64 04 0E 00 81 50");
    const auto at = get_i32(bytes(out[0]), 8);
    CHECK(at > 0);
    CHECK(at < 100'000);
    CHECK(channel(h)["moving"] == false);
}

TEST_CASE("control: power_cycle keeps or erases the saved settings, updates off", "[device][apt][control][eeprom]")
{
    StateStore store;
    AptHarness h(tdc001(), &store);
    CHECK(h.send("13 04 0E 00 D0 01 01 00 00 00 00 00 10 00 00 00 00 10 00 00") == "");   // VELPARAMS
    CHECK(h.send("B9 04 04 00 D0 01 01 00 13 04") == "");                                // saved
    CHECK(h.send("3A 04 06 00 D0 01 01 00 00 0D 00 00") == "");                          // backlash, not saved
    CHECK(h.send("11 00 00 00 50 01") == "");                                            // START_UPDATEMSGS
    CHECK(h.send(kMove100k) == "");
    h.advance_ms(300);
    h.take();

    h.device().power_cycle(PowerCycle{true, false});
    CHECK(describe(h)["status_updates"]["on"] == false);
    CHECK(channel(h)["moving"] == false);
    CHECK(position_counter(h) == 0);   // the counter reads 0 where the stage stands
    CHECK(channel(h)["position_si"].get<double>() > 0.025);
    CHECK(h.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 01 00 00 00 00 00 10 00 00 00 00 10 00 00");
    CHECK(h.send("3B 04 01 00 50 01") == "3C 04 06 00 81 50 01 00 00 00 00 00");
    h.advance_ms(1000);
    CHECK(h.take() == "");   // no status updates

    h.device().power_cycle(PowerCycle{false, true});
    CHECK(store.device_state("cube").empty());
    CHECK(h.send("14 04 01 00 50 01") != "15 04 0E 00 81 50 01 00 00 00 00 00 10 00 00 00 00 10 00 00");
    CHECK(channel(h)["position_si"].get<double>() == Approx(0.025));
}

TEST_CASE("control: the wire log records frames both ways, decoded, updates unprompted", "[device][apt][control][wire]")
{
    AptHarness h;
    CHECK(h.send("11 04 01 00 50 01") == "12 04 06 00 81 50 01 00 00 00 00 00");
    const json log = h.device().wire_log().to_json(10);
    REQUIRE(log.size() == 2);
    CHECK(log[0]["direction"] == "in");
    CHECK(log[0]["hex"] == "11 04 01 00 50 01");
    CHECK(log[0]["decoded"]["name"] == "MGMSG_MOT_REQ_POSCOUNTER");
    CHECK(log[0]["decoded"]["id"] == "0x0411");
    CHECK(log[0]["decoded"]["destination"] == "0x50");
    CHECK(log[0]["decoded"]["fields"]["chan_ident"] == 1);
    CHECK(log[0]["notes"].empty());
    CHECK(log[1]["direction"] == "out");
    CHECK(log[1]["unprompted"] == false);
    CHECK(log[1]["decoded"]["name"] == "MGMSG_MOT_GET_POSCOUNTER");
    CHECK(log[1]["decoded"]["fields"] == json{{"chan_ident", 1}, {"position", 0}});

    CHECK(h.send("11 00 00 00 50 01") == "");
    h.advance_ms(100);
    h.take();
    const json update = h.device().wire_log().to_json(1)[0];
    CHECK(update["unprompted"] == true);
    CHECK(update["peer"] == "all");
    CHECK(update["decoded"]["name"] == "MGMSG_MOT_GET_DCSTATUSUPDATE");
    CHECK(has(update["decoded"]["fields"]["status_set"], "enabled"));

    // A second connection (the pty's session is always open) receives the next update too:
    // still one entry in the log.
    std::string second_out;
    auto second = h.device().open_session([&](std::string_view b) { second_out.append(b); }, "pty /tmp/x");
    const auto before = h.device().wire_log().last()->seq;
    h.advance_ms(100);
    h.take();
    CHECK_FALSE(second_out.empty());
    CHECK(h.device().wire_log().last()->seq == before + 1);
}

TEST_CASE("control: wire log notes: ignored messages, out-of-range SETs, moves while not homed", "[device][apt][control][wire]")
{
    AptHarness h;
    auto last_notes = [&] { return h.device().wire_log().last()->notes; };
    CHECK(h.send("11 04 02 00 50 01") == "");   // channel 2
    REQUIRE(last_notes().size() == 1);
    CHECK(last_notes()[0].find("ignored") != std::string::npos);
    CHECK(h.send("11 04 01 00 22 01") == "");   // no module at 0x22
    REQUIRE(last_notes().size() == 1);
    CHECK(last_notes()[0].find("0x22") != std::string::npos);
    CHECK(h.send("FF FF FF FF FF FF") == "");   // no message 0xFFFF (the last byte waits for the next)
    REQUIRE(last_notes().size() == 1);
    CHECK(last_notes()[0].find("5 byte(s) that start no valid message") != std::string::npos);
    CHECK(h.device().wire_log().to_json(1)[0]["hex"] == "ff ff ff ff ff");   // the entry carries them
    CHECK(h.send("11 04 01 00 50 01").size() > 0);   // the one byte left is noted before the frame
    const auto entries = h.device().wire_log().to_json(3);
    CHECK(entries[0]["hex"] == "ff");
    CHECK(entries[0]["decoded"]["name"] == "not a frame");
    REQUIRE(entries[0]["notes"].size() == 1);
    CHECK(entries[0]["notes"][0].get<std::string>().find("1 byte(s) that start no valid message") != std::string::npos);
    CHECK(entries[1]["hex"] == "11 04 01 00 50 01");
    CHECK(entries[1]["notes"].empty());
    CHECK(entries[2]["direction"] == "out");
    CHECK(h.send("13 04 0E 00 D0 01 01 00 00 00 00 00 00 00 00 00 00 10 00 00") == "");   // zero acceleration
    REQUIRE(last_notes().size() == 1);
    CHECK(last_notes()[0].find("acceleration") != std::string::npos);
    CHECK(h.send("90 04 01 00 50 01").size() > 0);   // a good request: no note on its answer or itself
    CHECK(last_notes().empty());
    CHECK(h.device().wire_log().to_json(2)[0]["notes"].empty());
    CHECK(h.send(kMove100k) == "");
    REQUIRE(h.device().wire_log().last()->inbound);
    REQUIRE(last_notes().size() == 1);
    CHECK(last_notes()[0].find("not homed") != std::string::npos);
    CHECK(!patch(h, {{"referenced", true}}) == false);   // moving: refused
    h.advance_ms(5000);
    h.take();
    CHECK(!patch(h, {{"referenced", true}}));
    CHECK(h.send("53 04 06 00 D0 01 01 00 " + le32(0)) == "");
    CHECK(h.device().wire_log().last()->notes.empty());
}

TEST_CASE("control: wire log notes the 40th unacknowledged status update and the cut-off at 50", "[device][apt][control][wire]")
{
    AptHarness h;
    CHECK(h.send("11 00 00 00 50 01") == "");
    h.advance_ms(3900);   // 39 updates
    CHECK(h.device().wire_log().noted() == 0);
    h.advance_ms(100);
    CHECK(h.device().wire_log().noted() == 1);
    CHECK(h.device().wire_log().last()->notes.at(0).find("40 of 50") != std::string::npos);
    h.advance_ms(1000);
    CHECK(h.device().wire_log().noted() == 2);
    CHECK(h.device().wire_log().last()->notes.at(0).find("cut-off") != std::string::npos);
    CHECK(describe(h)["status_updates"]["cut_off"] == true);
    h.advance_ms(1000);
    CHECK(h.device().wire_log().noted() == 2);
    h.take();
    CHECK(h.send("92 04 00 00 50 01") == "");   // ACK: counting starts again
    CHECK(describe(h)["status_updates"]["unacknowledged"] == 0);
}

TEST_CASE("control: events: move_started, status, move_ended with its outcome", "[device][apt][control][events]")
{
    EventBus bus;
    std::vector<json> seen;
    bus.subscribe([&](const Event& e) {
        if (e.type != "wire")
            seen.push_back(json::parse(e.json));
    });
    AptHarness h(tdc001(), nullptr, &bus);
    auto types = [&] {
        std::vector<std::string> t;
        for (const auto& e : seen)
            t.push_back(e["type"]);
        return t;
    };
    CHECK(h.send(kMove100k) == "");
    REQUIRE(types() == std::vector<std::string>{"move_started", "status"});
    CHECK(seen[0]["channel"] == 0);
    CHECK(seen[0]["device"] == "cube");
    CHECK(has(seen[1]["status"]["set"], "moving_forward"));
    seen.clear();
    h.advance_ms(5000);
    REQUIRE(types() == std::vector<std::string>{"move_ended", "status"});
    CHECK(seen[0]["outcome"] == "completed");
    CHECK(seen[0]["time_ms"].get<double>() > 0);
    CHECK(has(seen[1]["status"]["set"], "settled"));
    seen.clear();
    h.take();
    CHECK(h.send("65 04 01 02 50 01").substr(0, 17) == "66 04 0E 00 81 50");   // MOVE_STOP at rest: MOVE_STOPPED
    CHECK(seen.empty());

    CHECK(!fault(h, 1, "stall"));
    CHECK(h.send("53 04 06 00 D0 01 01 00 " + le32(0)) == "");
    seen.clear();
    h.advance_ms(10);
    REQUIRE(!seen.empty());
    CHECK(seen[0]["type"] == "move_ended");
    CHECK(seen[0]["outcome"] == "fault");
}

TEST_CASE("control: wire log notes messages a rack's motherboard or an empty bay ignores", "[device][apt][control][wire][rack]")
{
    AptHarness h(apt_rack("BBD203", {"MLS203-X"}));
    CHECK(h.send("53 04 06 00 A3 01 01 00 00 00 00 00") == "");   // MOVE_ABSOLUTE to bay 2: no stage
    auto notes = h.device().wire_log().last()->notes;
    REQUIRE(notes.size() == 1);
    CHECK(notes[0].find("no stage") != std::string::npos);
    CHECK(h.send("53 04 06 00 91 01 01 00 00 00 00 00") == "");   // to the motherboard
    notes = h.device().wire_log().last()->notes;
    REQUIRE(notes.size() == 1);
    CHECK(notes[0].find("motherboard") != std::string::npos);
    CHECK(h.send("60 00 00 00 11 01") == "61 00 00 01 01 11");      // RACK_REQ_BAYUSED: bay 0 used, no note
    CHECK(h.device().wire_log().last()->notes.empty());
}

TEST_CASE("control: a rotation stage is a rotary channel in radians, placed at any angle", "[device][apt][control][stage]")
{
    AptHarness h(apt_cube("KDC101", "PRM1-Z8"));
    json c = channel(h);
    CHECK(c["kind"] == "rotary");
    CHECK(c["si_unit"] == "rad");
    CHECK(c["position_si"].get<double>() == Approx(M_PI));   // half a turn from the home switch
    CHECK(!patch(h, {{"position_si", 4 * M_PI}}));
    c = channel(h);
    CHECK(c["position_si"].get<double>() == Approx(4 * M_PI));
    CHECK(c["limits"]["switch_pressed"] == json{{"forward", false}, {"reverse", false}});
    // No end stops, but the position counter is 32 bits: beyond it the PATCH is refused.
    const auto refused = patch(h, {{"position_si", 1e12}});
    REQUIRE(refused);
    CHECK(refused->status == 400);
    CHECK(channel(h)["position_si"].get<double>() == Approx(4 * M_PI));
}

} // namespace test_apt_control
