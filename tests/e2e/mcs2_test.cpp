// The MCS2 over the real daemon's TCP endpoint (its only interface, MCS2 Programmer's Guide 1.0.6,
// 6.1): two clients at once, CR LF and LF line ends, pipelined messages, each client's own error
// queue, a client that goes stops its movements, *RST closes the connection, and the control API's
// clock, faults, state and wire log on the MCS2. What each command answers is tested on the stepped
// clock (tests/device/mcs2).

#include <catch2/catch.hpp>

#include <string>
#include <thread>

#include "control_support.hpp"
#include "e2e_support.hpp"

namespace mcs2_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {

const std::string kRig = RIGSIM_SOURCE_DIR "/config/examples/mcs2.json";

bool has(const std::string& text, const std::string& needle)
{
    return text.find(needle) != std::string::npos;
}

} // namespace

TEST_CASE("MCS2 over TCP: two clients at once, each with its own answers and its own error queue",
          "[e2e][mcs2]")
{
    Daemon daemon(Daemon::Options{{}, kRig, {"--paused"}});
    TcpClient a(daemon.endpoint("mcs2"));
    TcpClient b(daemon.endpoint("mcs2"));
    TcpClient api(control_endpoint(daemon));

    CHECK(a.request("*IDN?\r\n") == "SmarAct GmbH,MCS2,MCS2-00001234,current\r\n");
    CHECK(b.request(":DEV:NOCH?\n") == "6\r\n");   // a bare LF ends a message too; answers end in CR LF
    CHECK(b.request(":DEV:SNUM?;:CHAN0:PTYP?;PTYP:NAME?\r\n") == "\"MCS2-00001234\"; 300; \"SL...S1SS\"\r\n");

    // Pipelined, in one write: the answers come in order, one line per message.
    a.send(":CHAN0:POS?\r\n:CHAN1:POS?\r\n:CHAN2:PTYP:NAME?\r\n");
    CHECK(a.read_line() == "0\r\n");
    CHECK(a.read_line() == "0\r\n");
    CHECK(a.read_line() == "\"SL...S1LE\"\r\n");

    // A setting is not answered; its error goes to the queue of the client that sent it.
    b.send(":CHAN9:POS?\r\n:CHAN0:VEL 200000000000\r\n");
    CHECK(b.request(":SYST:ERR:COUN?\r\n") == "2\r\n");
    CHECK(a.request(":SYST:ERR:COUN?\r\n") == "0\r\n");
    CHECK(b.request(":SYST:ERR?\r\n") == "34,\"Invalid channel index\"\r\n");
    CHECK(b.request(":SYST:ERR:NEXT?\r\n") == "19,\"Invalid parameter\"\r\n");
    CHECK(b.request(":SYST:ERR?\r\n") == "0,\"No Error\"\r\n");

    // A move by one client, seen by the other, on the clock the control API runs.
    a.send(":CHAN0:MMOD 0;VEL 1000000000;HOLD 0\r\n:MOVE0 1000000000\r\n");
    // Settings are not answered: a query on the same connection orders them before what the other
    // connection and the control API do next (their bytes travel on sockets of their own).
    REQUIRE(a.request(":SYST:ERR:COUN?\r\n") == "0\r\n");
    CHECK(b.request(":CHAN0:STAT?\r\n") == "262243\r\n");   // moving, closed loop, sensor, calibrated, amplifier
    REQUIRE(http(api, "POST", "/api/clock", R"({"step_ms": 500})").status == 200);
    CHECK(b.request(":CHAN0:POS?\r\n") == "500000000\r\n");
    REQUIRE(http(api, "POST", "/api/clock", R"({"run_until_idle": true, "max_ms": 60000})").status == 200);
    CHECK(b.request(":CHAN0:POS?;STAT?\r\n") == "1000000000; 262240\r\n");
    CHECK(a.request(":CHAN0:ERR?\r\n") == "0\r\n");
}

TEST_CASE("MCS2 over TCP: a client that goes stops its movements, *RST closes the connection", "[e2e][mcs2]")
{
    Daemon daemon(Daemon::Options{{}, kRig, {"--paused"}});
    TcpClient b(daemon.endpoint("mcs2"));
    TcpClient api(control_endpoint(daemon));
    {
        TcpClient a(daemon.endpoint("mcs2"));
        a.send(":CHAN1:MMOD 0;VEL 1000000;:MOVE1 1000000000\r\n");
        CHECK(a.request(":CHAN1:STAT?\r\n") == "262243\r\n");
        a.abort();   // the cable pulled: "all movements that were sent over the disconnected interface are stopped"
    }
    // The daemon learns of the reset when it reads it, on its own socket: wait for that (the
    // paused clock has not moved the stage meanwhile).
    std::string state;
    for (const auto deadline = SteadyClock::now() + 5s; SteadyClock::now() < deadline;) {
        state = b.request(":CHAN1:STAT?\r\n");
        if (state != "262243\r\n")
            break;
        std::this_thread::sleep_for(10ms);
    }
    CHECK(state == "262240\r\n");
    CHECK(b.request(":CHAN1:ERR?\r\n") == "25\r\n");   // ABORTED
    b.send("*RST\r\n");   // "resets the device (reconnect necessary!)"
    CHECK(b.wait_for_eof(5000ms));
    TcpClient c(daemon.endpoint("mcs2"));
    CHECK(c.request(":DEV:NOBM?\r\n") == "2\r\n");
}

TEST_CASE("MCS2 and the control API: state, a stall fault, the wire log's notes and events", "[e2e][mcs2][control]")
{
    Daemon daemon(Daemon::Options{{}, kRig, {"--paused"}});
    TcpClient m(daemon.endpoint("mcs2"));
    TcpClient api(control_endpoint(daemon));

    const auto device = http(api, "GET", "/api/devices/mcs2");
    REQUIRE(device.status == 200);
    CHECK(has(device.body, "\"protocol\":\"mcs2\""));
    CHECK(has(device.body, "\"serial_number\":\"MCS2-00001234\""));
    CHECK(has(device.body, "\"positioner_type\":{\"code\":342,\"name\":\"SL...S1LE\"}"));
    CHECK(has(device.body, "\"protocol_unit\":\"ndeg\""));   // the rotary stage of channel 4

    REQUIRE(http(api, "POST", "/api/faults", R"({"device":"mcs2","channel":3,"kind":"stall"})").status == 201);
    m.send(":CHAN3:MMOD 1;VEL 1000000000\r\n:MOVE3 1000000000\r\n");
    REQUIRE(m.request(":SYST:ERR:COUN?\r\n") == "0\r\n");   // the move started: ordered before the clock runs
    REQUIRE(http(api, "POST", "/api/clock", R"({"run_until_idle": true, "max_ms": 60000})").status == 200);
    CHECK(m.request(":CHAN3:POS?;ERR?\r\n") == "0; 512\r\n");   // END_STOP_REACHED: it could not move
    const auto channel = http(api, "GET", "/api/devices/mcs2/channels/3");
    CHECK(has(channel.body, "\"stalled\":true"));
    CHECK(has(channel.body, "\"last_outcome\":\"end_stop\""));

    m.send(":CHAN0:NOPE?\r\n");
    CHECK(m.request(":SYST:ERR:COUN?\r\n") == "1\r\n");
    const auto log = http(api, "GET", "/api/devices/mcs2/log");
    REQUIRE(log.status == 200);
    CHECK(has(log.body, "1 error(s) queued, not answered"));
    CHECK(has(log.body, "\"text\":\":CHAN0:NOPE?\""));

    const auto reference_lost = http(api, "POST", "/api/faults", R"({"device":"mcs2","channel":0,"kind":"reference_lost"})");
    CHECK(reference_lost.status == 201);
    CHECK(http(api, "PATCH", "/api/devices/mcs2/channels/0", R"({"referenced": true})").status == 200);
    CHECK(m.request(":CHAN0:STAT?\r\n") == "262368\r\n");   // + IS_REFERENCED
    CHECK(http(api, "PATCH", "/api/devices/mcs2/channels/9", "{}").status == 404);
}

} // namespace mcs2_test
