// The control API of the piezo, gauge and solenoid units on the real rigsimd (paused clock): a
// BPC303 bay's LUT loaded over TCP, armed by START with the input trigger, started by PATCH
// trig_in "pulse", read back through the trace route and the event stream; trace query errors;
// a motor fault on a TPZ001 refused while a link fault acts on it.
#include "apt_support.hpp"
#include "control_support.hpp"
#include "e2e_support.hpp"

#include <catch2/catch.hpp>

#include <string>

namespace control_piezo_test {

using namespace std::chrono_literals;
using rigsim::e2e::http;

constexpr const char* kRig = R"({"tick_hz": 1000, "devices": [
  {"name": "tpz", "protocol": "apt", "model": "TPZ001", "tcp_port": 0, "apt": {"actuator": {}}},
  {"name": "bpc", "protocol": "apt", "model": "BPC303", "tcp_port": 0,
   "apt": {"hardware_max_voltage_v": 150, "bays": [{"travel_um": 20, "max_voltage_v": 150}]}},
  {"name": "tsc", "protocol": "apt", "model": "TSC001", "tcp_port": 0, "apt": {"solenoid": {}}}]})";

bool has(const std::string& text, const std::string& needle)
{
    return text.find(needle) != std::string::npos;
}

std::string le16(int v)
{
    return {static_cast<char>(v & 0xff), static_cast<char>((v >> 8) & 0xff)};
}

/// A frame with `data` from the host (0x01) to bay 0x21 of a rack.
std::string to_bay(std::uint16_t id, const std::string& data)
{
    return le16(id) + le16(static_cast<int>(data.size())) + std::string("\xA1\x01", 2) + data;
}

/// Reads SSE lines until one contains `needle`; false at the timeout.
bool read_event_with(rigsim::e2e::LineClient& events, const std::string& needle)
{
    while (const auto line = events.read_line(3000ms))
        if (has(*line, needle))
            return true;
    return false;
}

TEST_CASE("control piezo: a BPC303 LUT armed over TCP, triggered by PATCH, read by the trace route",
          "[e2e][control][piezo]")
{
    rigsim::e2e::Daemon daemon(rigsim::e2e::Daemon::Options{kRig, {}, {"--control", "127.0.0.1:0", "--paused"}});
    const auto control = rigsim::e2e::control_endpoint(daemon);
    rigsim::e2e::TcpClient events(control);
    events.send("GET /api/events?type=lut_started,lut_ended HTTP/1.1\r\nHost: localhost\r\n\r\n");
    REQUIRE(read_event_with(events, ": rigsim event stream"));
    rigsim::e2e::TcpClient api(control);
    rigsim::e2e::TcpClient bpc(daemon.endpoint("bpc"));

    const auto rig = http(api, "GET", "/api/rig");
    CHECK(has(rig.body, R"({"index":0,"kind":"linear","unit":"piezo"})"));
    CHECK(has(rig.body, R"({"index":0,"kind":null,"unit":"solenoid"})"));

    // 10 samples 1000 + 100 k, fixed 1 cycle with the input trigger (rising edge), then START.
    for (int k = 0; k < 10; ++k)
        bpc.send(to_bay(0x0700, le16(1) + le16(k) + le16(1000 + 100 * k)));   // PZ_SET_OUTPUTLUT
    const std::string params = le16(1) + le16(0x02 | 0x08 | 0x20) + le16(10) + rigsim::e2e::le32(1)
                               + rigsim::e2e::le32(1) + rigsim::e2e::le32(0) + rigsim::e2e::le32(0) + le16(0)
                               + rigsim::e2e::le32(0) + le16(0);
    bpc.send(to_bay(0x0703, params));                          // PZ_SET_OUTPUTLUTPARAMS (p. 108)
    bpc.send(std::string("\x06\x07\x01\x00\x21\x01", 6));      // PZ_START_LUTOUTPUT: arms
    bpc.send(std::string("\x04\x07\x01\x00\x21\x01", 6));      // REQ_OUTPUTLUTPARAMS: all handled once answered
    REQUIRE(rigsim::e2e::wait_for(bpc.fd(), 0x0705));
    const auto armed = http(api, "GET", "/api/devices/bpc/channels/0");
    REQUIRE(armed.status == 200);
    CHECK(has(armed.body, R"("armed":true)"));
    CHECK(has(armed.body, R"("running":false)"));

    const auto pulse = http(api, "PATCH", "/api/devices/bpc/channels/0", R"({"trig_in": "pulse"})");
    REQUIRE(pulse.status == 200);
    CHECK(has(pulse.body, R"("running":true)"));
    CHECK(read_event_with(events, "event: lut_started"));
    REQUIRE(http(api, "POST", "/api/clock", R"({"step_ms": 20})").status == 200);
    CHECK(read_event_with(events, R"("reason":"cycles_done")"));

    const auto trace = http(api, "GET", "/api/devices/bpc/channels/0/trace?from=0&max=16384");
    REQUIRE(trace.status == 200);
    CHECK(has(trace.body, R"("tick_hz":1000)"));
    CHECK(has(trace.body, ",1000,"));   // LUT[0] ...
    CHECK(has(trace.body, ",1900,"));   // ... to LUT[9], each with its index
    CHECK(has(trace.body, ",9]"));
    const auto two = http(api, "GET", "/api/devices/bpc/channels/0/trace?max=2");
    REQUIRE(two.status == 200);
    CHECK(has(two.body, R"("samples":[[)"));

    CHECK(has(http(api, "GET", "/api/devices/bpc/channels/0/trace?max=0").body, R"(\"max\")"));
    CHECK(http(api, "GET", "/api/devices/bpc/channels/0/trace?from=-1").status == 400);
    CHECK(has(http(api, "GET", "/api/devices/bpc/channels/0/trace?from=x").body, R"(\"from\")"));
    CHECK(http(api, "GET", "/api/devices/bpc/channels/0/trace?since=1").status == 400);
    const auto none = http(api, "GET", "/api/devices/tsc/channels/0/trace");
    CHECK(none.status == 404);
    CHECK(has(none.body, "no trace for this channel"));
    CHECK(http(api, "GET", "/api/devices/bpc/channels/7/trace").status == 404);
    CHECK(http(api, "POST", "/api/devices/bpc/channels/0/trace").status == 405);
}

TEST_CASE("control piezo: a TPZ001 refuses trig_in and motor faults, a link fault acts on it", "[e2e][control][piezo]")
{
    rigsim::e2e::Daemon daemon(rigsim::e2e::Daemon::Options{kRig, {}, {"--control", "127.0.0.1:0", "--paused"}});
    rigsim::e2e::TcpClient api(rigsim::e2e::control_endpoint(daemon));
    rigsim::e2e::TcpClient tpz(daemon.endpoint("tpz"));

    const auto trig = http(api, "PATCH", "/api/devices/tpz/channels/0", R"({"trig_in": true})");
    CHECK(trig.status == 400);
    CHECK(has(trig.body, "no trigger input"));
    const auto stall = http(api, "POST", "/api/faults", R"({"device": "tpz", "kind": "stall"})");
    CHECK(stall.status == 400);
    CHECK(has(stall.body, R"(\"kind\")"));
    CHECK(has(stall.body, "no motor"));

    const auto unplugged = http(api, "POST", "/api/faults", R"({"device": "tpz", "kind": "unplugged"})");
    REQUIRE(unplugged.status == 201);
    tpz.send(rigsim::e2e::header(0x0641, 1, 0));   // PZ_REQ_POSCONTROLMODE: no answer while unplugged
    CHECK_FALSE(rigsim::e2e::wait_for(tpz.fd(), 0x0642, 300ms));
    REQUIRE(http(api, "DELETE", "/api/faults").status == 200);
    tpz.send(rigsim::e2e::header(0x0641, 1, 0));
    CHECK(rigsim::e2e::wait_for(tpz.fd(), 0x0642));
}

} // namespace control_piezo_test
