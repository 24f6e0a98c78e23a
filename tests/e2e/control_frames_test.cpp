// The rig's frames on the real rigsimd: a client moves an MCS stage over its pty while the test
// reads the tool point through the control API (GET /api/frames, /api/frames/{name}, the
// "frames" event). The rig: a rotation stage (stage/1) 30 mm above the table, a linear stage
// (stage/0) on it, a tip 20 mm above the linear stage's carriage (kinematics_rig.json).
#include "control_support.hpp"
#include "e2e_support.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <string>
#include <vector>

namespace control_frames_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {

/// The three numbers after `key` (`"position_mm":[`) from `from` on in `text`.
std::vector<double> triple_after(const std::string& text, const std::string& key, std::size_t from = 0)
{
    const auto at = text.find(key, from);
    REQUIRE(at != std::string::npos);
    std::vector<double> out;
    const char* p = text.c_str() + at + key.size();
    for (int i = 0; i < 3; ++i) {
        char* end = nullptr;
        out.push_back(std::strtod(p, &end));
        REQUIRE(end != p);
        p = end + 1;   // the ',' or ']'
    }
    return out;
}

void check_near(const std::vector<double>& got, double x, double y, double z)
{
    REQUIRE(got.size() == 3);
    CHECK(got[0] == Approx(x).margin(1e-6));
    CHECK(got[1] == Approx(y).margin(1e-6));
    CHECK(got[2] == Approx(z).margin(1e-6));
}

std::string rig_path()
{
    return std::string(RIGSIM_E2E_DIR) + "/kinematics_rig.json";
}

/// Reads SSE lines until an event of `type`; its data line.
std::string next_event(LineClient& stream, const std::string& type)
{
    for (int lines = 0; lines < 200; ++lines) {
        const auto line = stream.read_line(5000ms);
        REQUIRE(line);
        if (*line != "event: " + type + "\n")
            continue;
        stream.read_line();   // id:
        const auto data = stream.read_line();
        REQUIRE(data);
        REQUIRE(data->rfind("data: ", 0) == 0);
        return *data;
    }
    FAIL("no " << type << " event");
    return {};
}

} // namespace

TEST_CASE("control: the tip's pose follows the MCS stages a client moves over the pty", "[e2e][control][frames]")
{
    Daemon daemon(Daemon::Options{{}, rig_path(), {"--control", "127.0.0.1:0", "--paused"}});
    const auto control = control_endpoint(daemon);
    TcpClient api(control);

    // The start: x at its start position (0.5 mm), the rotation stage at 0.
    const auto all = http(api, "GET", "/api/frames");
    REQUIRE(all.status == 200);
    CHECK(all.body.find("\"name\":\"table\"") != std::string::npos);
    const auto x = http(api, "GET", "/api/frames/x");
    REQUIRE(x.status == 200);
    CHECK(x.body.rfind(R"({"joint":{"channel":0,"device":"stage","position":)", 0) == 0);
    CHECK(std::strtod(x.body.c_str() + x.body.find("\"position\":") + 11, nullptr) == Approx(0.5).margin(1e-9));
    CHECK(x.body.find(R"("type":"prismatic"},"name":"x","parent":"turn",)") != std::string::npos);
    const auto tip = http(api, "GET", "/api/frames/tip");
    REQUIRE(tip.status == 200);
    check_near(triple_after(tip.body, "\"world\":{\"position_mm\":["), 0.5, 0, 50);
    check_near(triple_after(tip.body, "\"parent_relative\":{\"position_mm\":["), 0, 0, 20);
    CHECK(tip.body.find("\"tool\":true") != std::string::npos);
    const auto missing = http(api, "GET", "/api/frames/nope");
    CHECK(missing.status == 404);
    CHECK(missing.body == R"({"error":"no frame named \"nope\""})" "\n");

    TcpClient events(control);
    events.send("GET /api/events?type=frames HTTP/1.1\r\nHost: localhost\r\n\r\n");
    while (auto line = events.read_line())
        if (*line == ": rigsim event stream\n")
            break;

    // x 2 mm on (the unreferenced counter starts at 0 where the stage powered up: physically to
    // 2.5 mm) and the rotation stage to 90 degrees, over the pty; the clock runs them out.
    PtyClient mcs(daemon.endpoint("stage").pty);
    REQUIRE(mcs.request(":MPA0,2000000,0\n") == ":E0,0\n");
    REQUIRE(http(api, "POST", "/api/clock", R"({"run_until_idle": true, "max_ms": 60000})").status == 200);
    const auto moved = next_event(events, "frames");
    CHECK(moved.find(R"("after":{"device":"stage","type":"move_ended"})") != std::string::npos);
    CHECK(moved.find("\"name\":\"table\"") == std::string::npos);   // the table did not move
    CHECK(moved.find("\"name\":\"turn\"") == std::string::npos);
    check_near(triple_after(moved, "\"world\":{\"position_mm\":[", moved.find("\"name\":\"tip\"")), 2.5, 0, 50);

    REQUIRE(mcs.request(":MAA1,90000000,0,0\n") == ":E1,0\n");
    REQUIRE(http(api, "POST", "/api/clock", R"({"run_until_idle": true, "max_ms": 60000})").status == 200);
    const auto turned = next_event(events, "frames");
    CHECK(turned.find("\"name\":\"turn\"") != std::string::npos);
    const auto now = http(api, "GET", "/api/frames/tip");
    check_near(triple_after(now.body, "\"world\":{\"position_mm\":["), 0, 2.5, 50);
    const auto at = now.body.find("\"world\":");
    check_near(triple_after(now.body, "\"rpy_deg\":[", at), 0, 0, 90);
}

TEST_CASE("control: a rig without kinematics has no frames", "[e2e][control][frames]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0"}});
    TcpClient api(control_endpoint(daemon));
    const auto all = http(api, "GET", "/api/frames");
    CHECK(all.status == 200);
    CHECK(all.body == R"({"collisions":[],"frames":[],"tools":[]})" "\n");
    CHECK(http(api, "GET", "/api/frames/table").status == 404);
}

} // namespace control_frames_test
