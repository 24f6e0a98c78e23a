// The control API's fault, event, reset, device and log routes on the real rigsimd: what a
// client on the device's own port sees while a test steers the rig over HTTP.
#include "control_support.hpp"
#include "e2e_support.hpp"

#include <catch2/catch.hpp>

#include <string>

namespace control_routes_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {

/// The "id" number of a fault record.
std::string id_of(const std::string& record)
{
    const auto at = record.find("\"id\":");
    REQUIRE(at != std::string::npos);
    return record.substr(at + 5, record.find_first_not_of("0123456789", at + 5) - (at + 5));
}

} // namespace

TEST_CASE("control: an unplugged MCS device answers nothing until the fault ends, the pty and port stay",
          "[e2e][control][faults]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0"}});
    TcpClient api(control_endpoint(daemon));
    TcpClient mcs(daemon.endpoint("mcs0"));
    REQUIRE(mcs.request(":GS0\n") == ":S0,0\n");

    const auto added = http(api, "POST", "/api/faults", R"({"device":"mcs0","kind":"unplugged"})");
    REQUIRE(added.status == 201);
    mcs.send(":GS0\n");
    CHECK_FALSE(mcs.read_line(300ms));
    PtyClient pty(daemon.endpoint("mcs0").pty);
    pty.send(":GS0\n");
    CHECK_FALSE(pty.read_line(300ms));
    CHECK(http(api, "GET", "/api/devices/mcs0").body.find("\"unplugged\":true") != std::string::npos);

    CHECK(http(api, "DELETE", "/api/faults/" + id_of(added.body)).status == 200);
    CHECK(mcs.request(":GS0\n") == ":S0,0\n");   // the lost commands got no late answer
    CHECK(pty.request(":GS0\n") == ":S0,0\n");
    CHECK(http(api, "DELETE", "/api/faults/" + id_of(added.body)).status == 404);
}

TEST_CASE("control: answer latency runs on the clock: paused, the answer waits, a step releases it",
          "[e2e][control][faults]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0", "--paused"}});
    TcpClient api(control_endpoint(daemon));
    CHECK(http(api, "GET", "/api/clock").body.find("\"paused\":true") != std::string::npos);
    REQUIRE(http(api, "POST", "/api/faults", R"({"device":"mcs0","kind":"latency","latency_ms":100})").status == 201);
    TcpClient mcs(daemon.endpoint("mcs0"));
    mcs.send(":GS0\n");
    CHECK_FALSE(mcs.read_line(300ms));
    REQUIRE(http(api, "POST", "/api/clock", R"({"step_ms": 99})").status == 200);
    CHECK_FALSE(mcs.read_line(100ms));
    REQUIRE(http(api, "POST", "/api/clock", R"({"step_ms": 1})").status == 200);
    CHECK(mcs.read_line() == std::optional<std::string>(":S0,0\n"));
}

TEST_CASE("control: dropped bytes lose the command, corrupted ones change it", "[e2e][control][faults]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0"}});
    TcpClient api(control_endpoint(daemon));
    TcpClient mcs(daemon.endpoint("mcs0"));
    const auto drop = http(api, "POST", "/api/faults", R"({"device":"mcs0","kind":"drop_bytes","direction":"in"})");
    REQUIRE(drop.status == 201);
    mcs.send(":GS0\n");
    CHECK_FALSE(mcs.read_line(300ms));
    CHECK(http(api, "GET", "/api/devices/mcs0").body.find("\"dropped_bytes\":5") != std::string::npos);
    REQUIRE(http(api, "DELETE", "/api/faults/" + id_of(drop.body)).status == 200);

    REQUIRE(http(api, "POST", "/api/faults", R"({"device":"mcs0","kind":"corrupt_bytes","direction":"out"})").status
            == 201);
    mcs.send(":GS0\n");
    const auto garbled = mcs.read_line(300ms);
    // Every byte has one bit flipped: the '\n' may be gone too, so the answer is not ":S0,0\n".
    CHECK(garbled != std::optional<std::string>(":S0,0\n"));
    REQUIRE(http(api, "DELETE", "/api/faults").status == 200);
    mcs.close();
    TcpClient again(daemon.endpoint("mcs0"));
    CHECK(again.request(":GS0\n") == ":S0,0\n");
}

TEST_CASE("control: the event stream carries clock and fault events, filtered by type", "[e2e][control][events]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0"}});
    const auto control = control_endpoint(daemon);
    TcpClient events(control);
    events.send("GET /api/events?type=clock,fault_added HTTP/1.1\r\nHost: localhost\r\n\r\n");
    REQUIRE(events.read_line() == std::optional<std::string>("HTTP/1.1 200 OK\r\n"));
    std::string head;
    while (auto line = events.read_line()) {
        head += *line;
        if (*line == "\r\n")
            break;
    }
    CHECK(head.find("Content-Type: text/event-stream") != std::string::npos);
    CHECK(events.read_line() == std::optional<std::string>(": rigsim event stream\n"));
    CHECK(events.read_line() == std::optional<std::string>("\n"));

    TcpClient api(control);
    REQUIRE(http(api, "POST", "/api/clock", R"({"pause": true})").status == 200);
    REQUIRE(http(api, "POST", "/api/faults", R"({"device":"mcs0","kind":"unplugged"})").status == 201);
    REQUIRE(http(api, "DELETE", "/api/faults").status == 200);   // fault_removed: filtered out
    REQUIRE(http(api, "POST", "/api/clock", R"({"resume": true})").status == 200);
    CHECK(events.read_line() == std::optional<std::string>("event: clock\n"));
    CHECK(events.read_line().value_or("").rfind("id: ", 0) == 0);
    const auto data = events.read_line();
    REQUIRE(data);
    CHECK(data->find("\"paused\":true") != std::string::npos);
    CHECK(events.read_line() == std::optional<std::string>("\n"));
    CHECK(events.read_line() == std::optional<std::string>("event: fault_added\n"));
    events.read_line();
    CHECK(events.read_line()->find("\"kind\":\"unplugged\"") != std::string::npos);
    events.read_line();
    CHECK(events.read_line() == std::optional<std::string>("event: clock\n"));
    // The stream is not closed for idleness, and a closed stream leaves the daemon serving.
    events.close();
    CHECK(http(api, "GET", "/api/clock").status == 200);
    CHECK(daemon.running());
}

} // namespace control_routes_test
