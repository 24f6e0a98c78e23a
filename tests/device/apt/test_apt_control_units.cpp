// APT: the control API of the solenoid, piezo and strain gauge units (docs/control-api/apt.md):
// the "unit" key of every channel object, the piezo and gauge describe, PATCH trig_in of a BPC30x
// bay (the LUT's input trigger, manual p. 108) and noise_um of a gauge, the output trace, the
// lut_started / lut_ended / solenoid events, and motor faults refused on units without a motor.
#include "apt_harness.hpp"
#include "emulator/control/fault_book.hpp"

#include "emulator/core/event_bus.hpp"
#include "models/piezo_actuator.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>
#include <vector>

namespace test_apt_control_units {

using nlohmann::json;
using rigsim::DeviceConfig;
using rigsim::test::AptHarness;

DeviceConfig unit(const std::string& name, const std::string& model)
{
    DeviceConfig c;
    c.name = name;
    c.protocol = "apt";
    c.model = model;
    rigsim::apt::config_of(c);   // the family's config, at its defaults
    return c;
}

DeviceConfig bpc303()
{
    auto c = unit("rack", "BPC303");
    rigsim::apt::PiezoBayConfig bay;
    bay.actuator.max_voltage_v = 150;
    bay.actuator.hysteresis = 0;
    bay.actuator.creep = 0;
    rigsim::apt::config_of(c).piezo_bays.assign(3, bay);
    return c;
}

DeviceConfig tpz001()
{
    auto c = unit("tpz", "TPZ001");
    auto& a = rigsim::apt::config_of(c).actuator;
    a.hysteresis = 0;
    a.creep = 0;
    return c;
}

DeviceConfig tsg001(const std::string& mounted_on)
{
    auto c = unit("tsg", "TSG001");
    rigsim::apt::config_of(c).gauge.mounted_on = mounted_on;
    return c;
}

std::string le16(int v)
{
    char b[8];
    std::snprintf(b, sizeof b, "%02X %02X", v & 0xFF, (v >> 8) & 0xFF);
    return b;
}

std::string le32(std::int64_t v)
{
    return le16(static_cast<int>(v & 0xFFFF)) + " " + le16(static_cast<int>((v >> 16) & 0xFFFF));
}

/// PZ_SET_OUTPUTLUTPARAMS (p. 108) to bay 0x21: `mode`, `length` samples, `cycles`, DelayTime 1, no rests.
std::string lut_params(int mode, int length, std::int64_t cycles)
{
    return "03 07 1E 00 A1 01 01 00 " + le16(mode) + " " + le16(length) + " " + le32(cycles) + " " + le32(1) + " "
           + le32(0) + " " + le32(0) + " 00 00 00 00 00 00 00 00";
}

const std::string kStart = "06 07 01 00 21 01";   // PZ_START_LUTOUTPUT, bay 0x21
const std::string kStop = "07 07 01 00 21 01";    // PZ_STOP_LUTOUTPUT
constexpr int kFixed = 0x02;
constexpr int kInputTrig = 0x08;
constexpr int kInputTrigSenseHi = 0x20;

/// LUT sample k of the tests: 1000 + 100 k (positive: open-loop volts, no clipping).
int sample(int k)
{
    return 1000 + 100 * k;
}

void load(AptHarness& h, int n)
{
    for (int k = 0; k < n; ++k)
        REQUIRE(h.send("00 07 06 00 A1 01 01 00 " + le16(k) + " " + le16(sample(k))).empty());
}

json channel(AptHarness& h, std::size_t i = 0, std::size_t d = 0)
{
    json out = json::object();
    h.device(d).describe(out);
    return out["channels"].at(i);
}

json trace(AptHarness& h, std::int64_t from = 0, std::size_t max = rigsim::kTraceSamples, std::size_t i = 0)
{
    json out = json::object();
    const auto refused = h.device().trace(i, from, max, out);
    REQUIRE(!refused);
    return out;
}


TEST_CASE("control units: every APT channel names its unit, kind stays the motion", "[device][apt][control][units]")
{
    AptHarness motor;
    CHECK(channel(motor)["unit"] == "motor");
    CHECK(channel(motor)["kind"] == "linear");

    AptHarness sol(unit("sol", "TSC001"));
    CHECK(channel(sol)["unit"] == "solenoid");
    CHECK(!channel(sol).contains("kind"));
    CHECK(channel(sol)["status_set"] == json::array({"interlock"}));   // the default interlock mode (D-4)
    CHECK(!channel(motor).contains("status_set"));   // a motor's status object names its bits in "set"

    AptHarness h(tpz001());
    REQUIRE(h.add_device(tsg001("tpz")) == 1);
    CHECK(h.send("43 06 04 00 D0 01 01 00 77 77").empty());   // 70 V of 75 V (p. 96)
    h.advance_ms(50);
    const auto piezo = channel(h);
    CHECK(piezo["unit"] == "piezo");
    CHECK(piezo["kind"] == "linear");
    CHECK(piezo["output_code"] == 0x7777);
    CHECK(piezo["output_voltage_v"].get<double>() == Approx(70.0).epsilon(1e-4));
    const double x = h.world().find_as<rigsim::models::PiezoActuator>("tpz/1")->extension_um();
    CHECK(x > 1.0);
    CHECK(piezo["position_um"].get<double>() == Approx(x));
    CHECK(piezo["feedback"] == "hub_a");
    CHECK(piezo["trig_in"].is_null());
    CHECK(piezo["lut"]["running"] == false);
    CHECK(piezo["lut"]["params"]["mode"] == 1);
    // The status dword by its bits' names, as the wire log names them (p. 101-104).
    const auto piezo_bits = piezo["status"].get<std::uint32_t>();
    CHECK(piezo_bits == 0x101);
    CHECK(piezo["status_set"] == json::array({"actuator_connected", "gauge_connected"}));
    const auto gauge = channel(h, 0, 1);
    CHECK(gauge["status"] == 1);
    CHECK(gauge["status_set"] == json::array({"gauge_connected"}));
    CHECK(gauge["unit"] == "strain_gauge");
    CHECK(!gauge.contains("kind"));
    CHECK(gauge["position_um"].get<double>() == Approx(x));
    CHECK(gauge["reading"]["unit"] == "um");
    CHECK(gauge["reading"]["value"].get<double>() == Approx(x).margin(0.01));
    CHECK(gauge["mounted_on"] == "tpz/1");

    AptHarness rack(bpc303());
    json out = json::object();
    rack.device().describe(out);
    REQUIRE(out["channels"].size() == 3);
    for (const auto& ch : out["channels"]) {
        CHECK(ch["unit"] == "piezo");
        CHECK(ch["trig_in"] == false);
        CHECK(ch["feedback"].is_null());
    }
}

TEST_CASE("control units: an armed BPC303 LUT waits for the TRIG IN edge PATCH raises", "[device][apt][control][units][lut]")
{
    AptHarness h(bpc303());
    load(h, 10);
    REQUIRE(h.send(lut_params(kFixed | kInputTrig | kInputTrigSenseHi, 10, 1)).empty());
    REQUIRE(h.send(kStart).empty());
    h.advance_ms(20);
    CHECK(channel(h)["lut"]["armed"] == true);
    CHECK(channel(h)["lut"]["running"] == false);
    CHECK(channel(h)["output_code"] == 0);   // p. 108: START only armed it

    CHECK(!h.device().patch_channel(0, json{{"trig_in", "pulse"}}));
    CHECK(channel(h)["trig_in"] == false);
    CHECK(channel(h)["lut"]["running"] == true);
    CHECK(channel(h)["output_code"] == sample(0));
    h.advance_ms(4);
    CHECK(channel(h)["output_code"] == sample(4));
    h.advance_ms(20);
    CHECK(channel(h)["lut"]["running"] == false);
    CHECK(channel(h)["output_code"] == sample(9));   // the last value holds

    // Falling-edge sense (0x20 clear): the rising edge does nothing, the falling edge starts it.
    REQUIRE(h.send(lut_params(kFixed | kInputTrig, 10, 1)).empty());
    REQUIRE(h.send(kStart).empty());
    CHECK(!h.device().patch_channel(0, json{{"trig_in", true}}));
    CHECK(channel(h)["lut"]["running"] == false);
    CHECK(!h.device().patch_channel(0, json{{"trig_in", false}}));
    CHECK(channel(h)["lut"]["running"] == true);
    CHECK(channel(h)["output_code"] == sample(0));

    // Without the input trigger mode an edge starts nothing.
    REQUIRE(h.send(kStop).empty());
    REQUIRE(h.send(lut_params(kFixed, 10, 1)).empty());
    CHECK(!h.device().patch_channel(0, json{{"trig_in", "pulse"}}));
    CHECK(channel(h)["lut"]["running"] == false);

    const auto bad = h.device().patch_channel(0, json{{"trig_in", 1}});
    REQUIRE(bad);
    CHECK(bad->status == 400);
    CHECK(bad->message.find("trig_in") != std::string::npos);
    const auto unknown = h.device().patch_channel(1, json{{"noise_um", 0.1}});
    REQUIRE(unknown);
    CHECK(unknown->message.find("noise_um") != std::string::npos);
    CHECK(h.device().patch_channel(3, json{{"trig_in", true}})->status == 404);
}

TEST_CASE("control units: a TPZ001 has no trigger input, a gauge's noise_um is PATCHed", "[device][apt][control][units]")
{
    AptHarness h(tpz001());
    REQUIRE(h.add_device(tsg001("tpz")) == 1);
    const auto refused = h.device().patch_channel(0, json{{"trig_in", "pulse"}});
    REQUIRE(refused);
    CHECK(refused->status == 400);
    CHECK(refused->message.find("no trigger input") != std::string::npos);
    CHECK(refused->message.find("TPZ001") != std::string::npos);

    CHECK(!h.device(1).patch_channel(0, json{{"noise_um", 0.25}}));
    CHECK(channel(h, 0, 1)["noise_um"] == 0.25);
    for (const json& v : {json(-0.1), json("x"), json(nullptr)}) {
        const auto r = h.device(1).patch_channel(0, json{{"noise_um", v}});
        REQUIRE(r);
        CHECK(r->status == 400);
        CHECK(r->message.find("noise_um") != std::string::npos);
    }
    CHECK(channel(h, 0, 1)["noise_um"] == 0.25);
}

TEST_CASE("control units: the trace of a 100-sample LUT run follows the table sample by sample", "[device][apt][control][units][trace]")
{
    AptHarness h(bpc303());
    load(h, 100);
    REQUIRE(h.send(lut_params(kFixed, 100, 1)).empty());
    const auto start = h.device().clock().now();
    REQUIRE(h.send(kStart).empty());
    h.advance_ms(150);
    const auto t = trace(h);
    CHECK(t["tick_hz"] == 1000);
    CHECK(t["capacity"] == rigsim::kTraceSamples);
    const auto& samples = t["samples"];
    int lut_samples = 0;
    for (const auto& s : samples) {
        REQUIRE(s.size() == 5);
        if (s[4].is_null())
            continue;
        const int k = s[4];
        CHECK(s[0].get<std::int64_t>() == start + k);   // DelayTime 1: one 1 ms sample per tick
        CHECK(s[1] == sample(k));
        CHECK(s[2].get<double>() == Approx(sample(k) / 32767.0 * 150.0));
        ++lut_samples;
    }
    CHECK(lut_samples == 100);
    CHECK(samples.back()[1] == sample(99));   // after the run: the held last value
    CHECK(samples.back()[4].is_null());

    // Paging: from a tick, at most max samples, next_from continues.
    const auto page = trace(h, start + 10, 5);
    REQUIRE(page["samples"].size() == 5);
    CHECK(page["samples"][0][0] == start + 10);
    CHECK(page["next_from"] == start + 15);
    CHECK(trace(h, page["next_from"].get<std::int64_t>(), 1)["samples"][0][4] == 15);

    // Channels without an output to trace.
    json out = json::object();
    AptHarness motor;
    CHECK(motor.device().trace(0, 0, 10, out)->message == "no trace for this channel");
    AptHarness sol(unit("sol", "TSC001"));
    CHECK(sol.device().trace(0, 0, 10, out)->status == 404);
    CHECK(h.device().trace(3, 0, 10, out)->status == 404);
}

TEST_CASE("control units: events lut_started, lut_ended with its reason, solenoid edges", "[device][apt][control][units][events]")
{
    rigsim::EventBus bus;
    std::vector<json> seen;
    bus.subscribe([&](const rigsim::Event& e) {
        if (e.type != "wire")
            seen.push_back(json::parse(e.json));
    });
    AptHarness h(bpc303(), nullptr, &bus);
    load(h, 10);
    REQUIRE(h.send(lut_params(kFixed, 10, 2)).empty());
    REQUIRE(h.send(kStart).empty());
    REQUIRE(seen.size() == 1);
    CHECK(seen[0]["type"] == "lut_started");
    CHECK(seen[0]["channel"] == 0);
    CHECK(seen[0]["by"] == "start");
    const double started_ms = seen[0]["time_ms"];
    h.advance_ms(30);
    REQUIRE(seen.size() == 2);
    CHECK(seen[1]["type"] == "lut_ended");
    CHECK(seen[1]["reason"] == "cycles_done");
    CHECK(seen[1]["cycles"] == 2);
    CHECK(seen[1]["time_ms"].get<double>() == Approx(started_ms + 20));   // 2 cycles of 10 x 1 ms

    REQUIRE(h.send(lut_params(0x01, 10, 1)).empty());   // continuous
    REQUIRE(h.send(kStart).empty());
    h.advance_ms(5);
    REQUIRE(h.send(kStart).empty());
    h.advance_ms(5);
    REQUIRE(h.send(kStop).empty());
    REQUIRE(seen.size() == 6);
    CHECK(seen[3]["reason"] == "restarted");
    CHECK(seen[4]["type"] == "lut_started");
    CHECK(seen[5]["reason"] == "stop");
    h.advance_ms(100);
    CHECK(seen.size() == 6);

    seen.clear();
    AptHarness sol(unit("sol", "TSC001"), nullptr, &bus);
    // Auto mode, 1 s on / 1 s off, 2 cycles (p. 85-87), then ON.
    REQUIRE(sol.send("C0 04 01 03 50 01").empty());
    REQUIRE(sol.send("C3 04 0E 00 D0 01 01 00 A0 0F 00 00 A0 0F 00 00 02 00 00 00").empty());
    REQUIRE(sol.send("CB 04 01 01 50 01").empty());
    sol.advance_ms(5000);
    std::vector<std::string> edges;
    std::vector<double> at;
    for (const auto& e : seen)
        if (e["type"] == "solenoid") {
            edges.push_back(e["output"]);
            at.push_back(e["time_ms"]);
        }
    REQUIRE(edges == std::vector<std::string>{"on", "off", "on", "off"});
    CHECK(at[1] - at[0] == Approx(1000));
    CHECK(at[2] - at[0] == Approx(2000));
    CHECK(at[3] - at[0] == Approx(3000));
}

TEST_CASE("control units: motor faults on a unit without a motor are 400 naming kind", "[device][apt][control][units][fault]")
{
    for (const auto& config : {tpz001(), unit("sol", "TSC001"), tsg001(""), bpc303()}) {
        INFO(config.model);
        AptHarness h(config);
        for (const char* kind : {"stall", "slip", "sensor_failure", "reference_lost", "limit_switch"}) {
            rigsim::DeviceFault f;
            REQUIRE_FALSE(rigsim::parse_device_fault(kind, kind == std::string("limit_switch")
                                                               ? json{{"side", "forward"}}
                                                               : kind == std::string("slip") ? json{{"counts", 1}}
                                                                                             : json::object(),
                                                     f));
            f.id = 1;
            bool kept = false;
            bool on_body = false;
            const auto r = rigsim::control::start_device_fault(h.device(), &h.world(), f, &kept, &on_body);
            REQUIRE(r);
            CHECK(r->status == 400);
            CHECK(r->message.find("\"kind\"") == 0);
            CHECK(r->message.find("no motor") != std::string::npos);
        }
    }
}

} // namespace test_apt_control_units
