// The control API's device routes on the real rigsimd: state read while a client moves a
// stage, PATCH for set-up (409 while moving), a stall the client sees, the wire log with a
// note, the event stream of a move, and POST /api/reset.
#include "apt_support.hpp"
#include "control_support.hpp"
#include "e2e_support.hpp"

#include <catch2/catch.hpp>

#include <string>

namespace control_devices_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {

bool has(const std::string& text, const std::string& needle)
{
    return text.find(needle) != std::string::npos;
}

/// Reads SSE lines until one contains `needle`; false at the timeout.
bool read_event_with(LineClient& events, const std::string& needle)
{
    while (const auto line = events.read_line(3000ms))
        if (has(*line, needle))
            return true;
    return false;
}

} // namespace

TEST_CASE("control: a device's state follows its client's move, PATCH sets up a channel and waits for rest",
          "[e2e][control][devices]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0", "--paused"}});
    TcpClient api(control_endpoint(daemon));
    TcpClient mcs(daemon.endpoint("mcs0"));

    const auto at_rest = http(api, "GET", "/api/devices/mcs0");
    REQUIRE(at_rest.status == 200);
    CHECK(has(at_rest.body, "\"protocol\":\"mcs\""));
    CHECK(has(at_rest.body, "\"index\":0"));
    CHECK(has(at_rest.body, "\"moving\":false"));
    CHECK(has(at_rest.body, "\"status\":{\"code\":0,\"name\":\"stopped\"}"));

    REQUIRE(mcs.request(":MPR0,1000000,0\n") == ":E0,0\n");
    const auto moving = http(api, "GET", "/api/devices/mcs0/channels/0");
    REQUIRE(moving.status == 200);
    CHECK(has(moving.body, "\"moving\":true"));
    CHECK(has(moving.body, "\"code\":4"));   // targeting (appendix 4.1)
    const auto refused = http(api, "PATCH", "/api/devices/mcs0/channels/0", R"({"position_si": 0.001})");
    CHECK(refused.status == 409);
    CHECK(has(refused.body, "\"error\":"));

    REQUIRE(http(api, "POST", "/api/clock", R"({"run_until_idle": true, "max_ms": 60000})").status == 200);
    const auto arrived = http(api, "GET", "/api/devices/mcs0/channels/0");
    CHECK(has(arrived.body, "\"moving\":false"));
    CHECK(has(arrived.body, "\"position_protocol\":1000000"));

    const auto set = http(api, "PATCH", "/api/devices/mcs0/channels/0", R"({"position_si": 0.002, "referenced": true})");
    CHECK(set.status == 200);
    CHECK(has(set.body, "\"referenced\":true"));
    CHECK(mcs.request(":GPPK0\n") == ":PPK0,1\n");
    CHECK(http(api, "PATCH", "/api/devices/mcs0/channels/0", R"({"colour": 1})").status == 400);
    CHECK(http(api, "PATCH", "/api/devices/mcs0/channels/9", "{}").status == 404);
    CHECK(http(api, "GET", "/api/devices/nope").status == 404);

    const auto apt = http(api, "GET", "/api/devices/tdc001");
    CHECK(has(apt.body, "\"protocol_unit\":\"counts\""));
    CHECK(has(apt.body, "\"hex\":\"0x"));
}

TEST_CASE("control: a stall stops an MCS client's move where it stands, the log notes the client's mistakes",
          "[e2e][control][devices]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0", "--paused"}});
    TcpClient api(control_endpoint(daemon));
    TcpClient mcs(daemon.endpoint("mcs0"));
    const auto stall = http(api, "POST", "/api/faults", R"({"device":"mcs0","channel":0,"kind":"stall"})");
    REQUIRE(stall.status == 201);
    CHECK(has(http(api, "GET", "/api/faults").body, "\"kind\":\"stall\""));
    CHECK(has(http(api, "GET", "/api/faults/1").body, "\"device\":\"mcs0\""));   // the daemon's first fault

    REQUIRE(mcs.request(":MPA0,1000000,0\n") == ":E0,0\n");
    CHECK(mcs.request(":GS0\n") == ":S0,0\n");   // blocked: ended at once, at rest
    CHECK(mcs.request(":GP0\n") == ":P0,0\n");
    CHECK(mcs.request(":GP7\n") == ":E-1,7\n");  // an error the log notes (no such channel)

    const auto log = http(api, "GET", "/api/devices/mcs0/log");
    REQUIRE(log.status == 200);
    CHECK(has(log.body, "\"command\":\"MPA\""));
    CHECK(has(log.body, "absolute move while the physical position is unknown"));
    CHECK(has(log.body, "answered with an error"));
    CHECK(has(http(api, "GET", "/api/devices/mcs0/log?last=1").body, "\"direction\":\"out\""));
    REQUIRE(http(api, "DELETE", "/api/devices/mcs0/log").status == 200);
    CHECK(has(http(api, "GET", "/api/devices/mcs0/log").body, "\"entries\":[]"));
    REQUIRE(mcs.request(":GS0\n") == ":S0,0\n");   // logged again: the reset below empties it

    // The reset ends the fault, powers the controller up again and empties the log.
    const auto reset = http(api, "POST", "/api/reset", "{}");
    CHECK(reset.status == 200);
    CHECK(has(reset.body, "\"reset\":[\"mcs0\""));
    CHECK(has(http(api, "GET", "/api/faults").body, "\"faults\":[]"));
    CHECK(has(http(api, "GET", "/api/devices/mcs0/log").body, "\"entries\":[]"));
    REQUIRE(mcs.request(":MPA0,1000000,0\n") == ":E0,0\n");
    REQUIRE(http(api, "POST", "/api/clock", R"({"run_until_idle": true, "max_ms": 60000})").status == 200);
    CHECK(mcs.request(":GP0\n") == ":P0,1000000\n");
}

TEST_CASE("control: the event stream shows a client's move start and end on the device it follows",
          "[e2e][control][events]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0", "--paused"}});
    const auto control = control_endpoint(daemon);
    TcpClient events(control);
    events.send("GET /api/events?device=mcs0 HTTP/1.1\r\nHost: localhost\r\n\r\n");
    REQUIRE(read_event_with(events, ": rigsim event stream"));
    TcpClient api(control);
    TcpClient apt(daemon.endpoint("tdc001"));
    TcpClient mcs(daemon.endpoint("mcs0"));
    // The first batch after someone listens only takes the baseline of the status codes.
    REQUIRE(mcs.request(":GS0\n") == ":S0,0\n");
    REQUIRE(mcs.request(":MPR0,100000,0\n") == ":E0,0\n");
    CHECK(read_event_with(events, "event: move_started"));
    REQUIRE(http(api, "POST", "/api/clock", R"({"run_until_idle": true, "max_ms": 60000})").status == 200);
    CHECK(read_event_with(events, "event: move_ended"));
    // The wire entries of the device come too; another device's do not.
    apt.send(std::string("\x05\x00\x00\x00\x50\x01", 6));   // MGMSG_HW_REQ_INFO
    REQUIRE(mcs.request(":GS0\n") == ":S0,0\n");
    std::string seen;
    while (const auto line = events.read_line(500ms))
        seen += *line;
    CHECK(has(seen, "\"device\":\"mcs0\""));
    CHECK_FALSE(has(seen, "\"device\":\"tdc001\""));
}

TEST_CASE("control: paused, a 100 ms step brings exactly one APT status update, run_until_idle ends a homing",
          "[e2e][control][apt]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0", "--paused"}});
    TcpClient api(control_endpoint(daemon));
    TcpClient apt(daemon.endpoint("tdc001"));
    apt.send(header(0x0011, 0, 0));   // MGMSG_HW_START_UPDATEMSGS
    CHECK_FALSE(read_frame(apt.fd(), 300ms));   // paused: no clock time, no update
    REQUIRE(http(api, "POST", "/api/clock", R"({"step_ms": 100})").status == 200);
    const auto update = read_frame(apt.fd());
    REQUIRE(update);
    CHECK(update->id == 0x0491);   // MGMSG_MOT_GET_DCSTATUSUPDATE
    CHECK_FALSE(read_frame(apt.fd(), 300ms));
    apt.send(header(0x0012, 0, 0));   // MGMSG_HW_STOP_UPDATEMSGS

    apt.send(header(0x0443, 1, 0));   // MGMSG_MOT_MOVE_HOME
    // The move has started once the daemon answered a later request on the same connection.
    apt.send(header(0x0411, 1, 0));   // MGMSG_MOT_REQ_POSCOUNTER
    REQUIRE(wait_for(apt.fd(), 0x0412, 5000ms));
    const auto idle = http(api, "POST", "/api/clock", R"({"run_until_idle": true, "max_ms": 120000})");
    REQUIRE(idle.status == 200);
    const auto homed = wait_for(apt.fd(), 0x0444, 5000ms);   // MGMSG_MOT_MOVE_HOMED
    CHECK(homed);
    CHECK(has(http(api, "GET", "/api/devices/tdc001/channels/0").body, "\"referenced\":true"));
}

} // namespace control_devices_test
