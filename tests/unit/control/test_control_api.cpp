// The control API's routes over a clock, its ticker and a stand-in for the world's motion,
// without sockets: each route, each error. The clock is paused and stepped, so no
// assertion depends on wall time.
#include "emulator/control/control_api.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <boost/asio/io_context.hpp>

#include <string>

namespace test_control_api {

using namespace rigsim;
using rigsim::control::ControlApi;
using nlohmann::json;

namespace {

/// Moves (wants a tick every tick) until tick `until`; then rests.
class Motion : public Tickable {
public:
    Ticks next_change(Ticks now) const override { return now < until ? now + 1 : kNever; }
    void tick(Ticks now) override { last = now; }

    Ticks until = 0;
    Ticks last = 0;
};

/// A clock at 1 kHz, its ticker (started paused: tick 0 until a test steps or resumes it), one
/// motion and two devices.
struct Fixture {
    Fixture()
    {
        clock.add(&motion);
    }
    ~Fixture() { clock.remove(&motion); }

    /// The reply's status and parsed body.
    std::pair<unsigned, json> call(const std::string& method, const std::string& target, const std::string& body = {})
    {
        auto reply = api.handle(method, target, body);
        if (reply.later) {
            // A clock step runs in slices on the loop; its answer comes when it is done.
            bool answered = false;
            control::HttpReply answer;
            reply.later([&](control::HttpReply r) {
                answer = std::move(r);
                answered = true;
            });
            io.restart();
            io.run();
            REQUIRE(answered);
            reply = std::move(answer);
        }
        INFO(method << " " << target << " " << body << " -> " << reply.status << " " << reply.body);
        const auto parsed = json::parse(reply.body, nullptr, false);
        REQUIRE_FALSE(parsed.is_discarded());
        return {reply.status, parsed};
    }
    /// The error message of a request that must fail with `status`.
    std::string error_of(const std::string& method, const std::string& target, const std::string& body,
                         unsigned status)
    {
        const auto [got, answer] = call(method, target, body);
        CHECK(got == status);
        REQUIRE(answer.contains("error"));
        return answer["error"].get<std::string>();
    }

    boost::asio::io_context io;
    Clock clock{1000};
    Motion motion;
    Ticker ticker{io, clock, 1.0, Ticker::Start::Paused};
    ControlApi api{clock, ticker, [this] { return clock.next_wakeup() != kNever; },
                   {DeviceEndpoints{"mcs0", "mcs", "MCS-3D", "127.0.0.1:40100", "/tmp/rigsim/mcs0", "1.2.44", ""},
                    DeviceEndpoints{"tdc0", "apt", "TDC001", "127.0.0.1:40101", "/tmp/rigsim/tdc0", "issue-44.1", ""}}};
};

} // namespace

TEST_CASE("control api: GET /api/clock is the clock's state", "[unit][control]")
{
    Fixture f;
    f.clock.advance(250);
    const auto [status, body] = f.call("GET", "/api/clock");
    CHECK(status == 200);
    CHECK(body == json{{"now_ticks", 250}, {"now_ms", 250.0}, {"tick_hz", 1000}, {"time_scale", 1.0},
                       {"paused", true}});
}

TEST_CASE("control api: GET /api/rig lists the devices and the clock", "[unit][control]")
{
    Fixture f;
    const auto [status, body] = f.call("GET", "/api/rig?verbose=1");
    CHECK(status == 200);
    CHECK(body["clock"] == f.call("GET", "/api/clock").second);
    REQUIRE(body["devices"].size() == 2);
    CHECK(body["devices"][0] == json{{"name", "mcs0"},   {"protocol", "mcs"},        {"model", "MCS-3D"},
                                     {"firmware", "1.2.44"}, {"tcp", "127.0.0.1:40100"}, {"pty", "/tmp/rigsim/mcs0"}});
    CHECK(body["devices"][1]["name"] == "tdc0");
    CHECK(body["devices"][1]["firmware"] == "issue-44.1");
}

TEST_CASE("control api: POST /api/clock pauses, resumes and scales", "[unit][control]")
{
    Fixture f;
    auto [status, body] = f.call("POST", "/api/clock", R"({"resume": true})");
    CHECK(status == 200);
    CHECK(body["paused"] == false);
    CHECK_FALSE(f.ticker.paused());

    std::tie(status, body) = f.call("POST", "/api/clock", R"({"pause": true})");
    CHECK(status == 200);
    CHECK(body["paused"] == true);
    CHECK(f.ticker.paused());

    std::tie(status, body) = f.call("POST", "/api/clock", R"({"scale": 2.5})");
    CHECK(status == 200);
    CHECK(body["time_scale"] == 2.5);
    CHECK(f.ticker.time_scale() == 2.5);
    CHECK(body["paused"] == true);
}

TEST_CASE("control api: POST step_ms advances the paused clock by exactly that", "[unit][control]")
{
    Fixture f;
    f.motion.until = 10'000;
    auto [status, body] = f.call("POST", "/api/clock", R"({"step_ms": 100})");
    CHECK(status == 200);
    CHECK(body["now_ticks"] == 100);
    CHECK(body["now_ms"] == 100.0);
    CHECK(f.motion.last == 100);
    CHECK_FALSE(body.contains("reached_ms"));

    std::tie(status, body) = f.call("POST", "/api/clock", R"({"step_ms": 0})");
    CHECK(status == 200);
    CHECK(body["now_ticks"] == 100);
}

TEST_CASE("control api: POST run_until_idle stops when nothing moves, or at max_ms", "[unit][control]")
{
    Fixture f;
    f.motion.until = 1234;
    auto [status, body] = f.call("POST", "/api/clock", R"({"run_until_idle": true, "max_ms": 60000})");
    CHECK(status == 200);
    CHECK(body["now_ticks"] == 1234);
    CHECK(body["reached_ms"] == 1234.0);
    CHECK(body["idle"] == true);
    CHECK(f.motion.last == 1234);

    f.motion.until = 100'000;
    std::tie(status, body) = f.call("POST", "/api/clock", R"({"run_until_idle": true, "max_ms": 500})");
    CHECK(status == 200);
    CHECK(body["reached_ms"] == 1734.0);
    CHECK(body["idle"] == false);   // max_ms came first: the motion goes on
    CHECK(f.clock.now() == 1734);
}

TEST_CASE("control api: an unknown route is 404, a wrong method 405", "[unit][control]")
{
    Fixture f;
    CHECK(f.error_of("GET", "/api/nothing", "", 404) == "no route \"/api/nothing\"");
    CHECK(f.error_of("GET", "/index.html", "", 404) == "no route \"/index.html\"");
    CHECK(f.error_of("GET", "/ui/", "", 404) == "no route \"/ui/\"");
    CHECK(f.error_of("GET", "/api/\xff\xfe", "", 404) == "no route \"/api/\xef\xbf\xbd\xef\xbf\xbd\"");
    CHECK(f.error_of("POST", "/api/rig", "{}", 405) == "POST /api/rig: method not allowed (GET)");
    CHECK(f.error_of("DELETE", "/api/clock", "", 405) == "DELETE /api/clock: method not allowed (GET, POST)");
}

TEST_CASE("control api: the live view's page and files at /, /ui/app.js, /ui/style.css, GET only", "[unit][control]")
{
    Fixture f;
    const struct {
        const char* target;
        const char* type;
        const char* start;
    } files[] = {{"/", "text/html; charset=utf-8", "<!doctype html>"},
                 {"/?token=ignored", "text/html; charset=utf-8", "<!doctype html>"},
                 {"/ui/app.js", "text/javascript; charset=utf-8", "// rigsim live view"},
                 {"/ui/style.css", "text/css; charset=utf-8", ":root"}};
    for (const auto& file : files) {
        INFO(file.target);
        const auto reply = f.api.handle("GET", file.target, "");
        CHECK(reply.status == 200);
        CHECK(reply.body.rfind(file.start, 0) == 0);
        const auto header = [&](const std::string& name) {
            for (const auto& [n, v] : reply.headers)
                if (n == name)
                    return v;
            return std::string();
        };
        CHECK(header("Content-Type") == file.type);
        CHECK(header("Content-Security-Policy").rfind("default-src 'none'; script-src 'self';", 0) == 0);
        CHECK(header("X-Frame-Options") == "DENY");
    }
    CHECK(f.error_of("POST", "/", "{}", 405) == "POST /: method not allowed (GET)");
    CHECK(f.error_of("DELETE", "/ui/app.js", "", 405) == "DELETE /ui/app.js: method not allowed (GET)");
}

TEST_CASE("control api: a bad POST /api/clock body is 400 naming the key", "[unit][control]")
{
    Fixture f;
    const auto bad = [&](const std::string& body) { return f.error_of("POST", "/api/clock", body, 400); };
    CHECK(bad("") == "body: expected a JSON object, got invalid JSON (at byte 1)");
    CHECK(bad("{\"pause\": tru") == "body: expected a JSON object, got invalid JSON (at byte 14)");
    CHECK(bad("[1]") == "body: expected a JSON object, got array");
    CHECK(bad("{}") == "expected exactly one of pause, resume, step_ms, scale, run_until_idle");
    CHECK(bad(R"({"speed": 2})")
          == "unknown key \"speed\" (expected one of pause, resume, step_ms, scale, run_until_idle)");
    CHECK(bad(R"({"pause": true, "resume": true})") == "\"pause\" and \"resume\": expected exactly one action");
    CHECK(bad(R"({"pause": false})") == "\"pause\": expected true, got false");
    CHECK(bad(R"({"resume": 1})") == "\"resume\": expected true, got 1");
    CHECK(bad(R"({"step_ms": -1})") == "\"step_ms\": expected an integer 0..86400000, got -1");
    CHECK(bad(R"({"step_ms": 1.5})") == "\"step_ms\": expected an integer 0..86400000, got 1.5");
    CHECK(bad(R"({"step_ms": "10"})") == "\"step_ms\": expected an integer 0..86400000, got \"10\"");
    CHECK(bad(R"({"step_ms": 18446744073709551615})")
          == "\"step_ms\": expected an integer 0..86400000, got 18446744073709551615");
    CHECK(bad(R"({"scale": 0})") == "\"scale\": expected a number 0.001..1000.0, got 0");
    CHECK(bad(R"({"scale": -2})") == "\"scale\": expected a number 0.001..1000.0, got -2");
    CHECK(bad(R"({"scale": 1e15})") == "\"scale\": expected a number 0.001..1000.0, got 1e+15");
    CHECK(bad(R"({"scale": 1e999})") == "body: expected a JSON object, got a number too large for a double");
    CHECK(bad(R"({"scale": "fast"})") == "\"scale\": expected a number 0.001..1000.0, got \"fast\"");
    CHECK(bad(R"({"run_until_idle": true})") == "\"max_ms\": required with run_until_idle");
    CHECK(bad(R"({"run_until_idle": true, "max_ms": 0})") == "\"max_ms\": expected an integer 1..86400000, got 0");
    CHECK(bad(R"({"step_ms": 5, "max_ms": 10})") == "\"max_ms\": only with run_until_idle");
    CHECK(bad(R"({"run_until_idle": false, "max_ms": 10})") == "\"run_until_idle\": expected true, got false");
    // Nothing changed on the way.
    CHECK(f.clock.now() == 0);
    CHECK(f.ticker.paused());
    CHECK(f.ticker.time_scale() == 1.0);
}

TEST_CASE("control api: a deeply nested or binary body is refused, not a crash", "[unit][control]")
{
    Fixture f;
    CHECK(f.error_of("POST", "/api/clock", std::string(64 * 1024, '['), 400) == "body: nested deeper than 32 levels");
    static const char binary[] = "{\"pause\x00\xff\": true}";
    CHECK(f.error_of("POST", "/api/clock", std::string(binary, sizeof binary - 1), 400)
          .rfind("body: expected a JSON object, got invalid JSON", 0) == 0);
}

} // namespace test_control_api
