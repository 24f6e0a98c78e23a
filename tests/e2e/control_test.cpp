// The HTTP control API of the real rigsimd (--control): found through the endpoints file,
// it pauses and steps the clock that the devices' protocols see, and survives bad requests.
// The HTTP client is a LineClient on a TCP socket: status line and headers are lines, and
// every body the daemon sends is one line of JSON.
#include "control_support.hpp"
#include "e2e_support.hpp"

#include <catch2/catch.hpp>

#include <csignal>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace control_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

TEST_CASE("control: pause holds an MCS move, step_ms finishes it, a bad request gets 400", "[e2e][control]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0"}});
    const auto control = control_endpoint(daemon);
    CHECK(control.host == "127.0.0.1");
    TcpClient api(control);

    const auto rig = http(api, "GET", "/api/rig");
    CHECK(rig.status == 200);
    CHECK(rig.body.find("\"name\":\"mcs0\"") != std::string::npos);
    CHECK(rig.body.find("\"clock\":{") != std::string::npos);

    const auto paused = http(api, "POST", "/api/clock", R"({"pause": true})");
    CHECK(paused.status == 200);
    CHECK(paused.body.find("\"paused\":true") != std::string::npos);

    TcpClient mcs(daemon.endpoint("mcs0"));
    REQUIRE(mcs.request(":MPA0,1000000,0\n") == ":E0,0\n");
    // While paused the device answers at once, from the paused state: still moving. The move
    // takes well under 3 s of clock time when running, so this wait would see it end.
    std::vector<std::string> seen;
    CHECK_FALSE(poll_status_until(mcs, 0, 0, 1000ms, &seen));
    REQUIRE_FALSE(seen.empty());
    CHECK(seen.back() != ":S0,0\n");

    const auto stepped = http(api, "POST", "/api/clock", R"({"step_ms": 10000})");
    CHECK(stepped.status == 200);
    CHECK(stepped.body.find("\"paused\":true") != std::string::npos);
    CHECK(mcs.request(":GS0\n") == ":S0,0\n");
    CHECK(mcs.request(":GP0\n") == ":P0,1000000\n");

    // run_until_idle ends the next move without the test knowing how long it takes.
    REQUIRE(mcs.request(":MPA0,0,0\n") == ":E0,0\n");
    CHECK(mcs.request(":GS0\n") != ":S0,0\n");
    const auto idle = http(api, "POST", "/api/clock", R"({"run_until_idle": true, "max_ms": 60000})");
    CHECK(idle.status == 200);
    CHECK(idle.body.find("\"reached_ms\":") != std::string::npos);
    CHECK(mcs.request(":GS0\n") == ":S0,0\n");
    CHECK(mcs.request(":GP0\n") == ":P0,0\n");

    // A request that is not HTTP: 400 with a JSON body, that connection closed, the daemon
    // serving on.
    TcpClient bad(control);
    bad.send("HELLO THERE\r\n\r\n");
    const auto refused = read_answer(bad);
    CHECK(refused.status == 400);
    CHECK(refused.body.rfind("{\"error\":", 0) == 0);
    CHECK(bad.wait_for_eof(kAnswerTimeout));

    const auto bad_body = http(api, "POST", "/api/clock", R"({"pause": true, "resume": true})");
    CHECK(bad_body.status == 400);
    CHECK(http(api, "GET", "/api/nothing").status == 404);
    const auto clock = http(api, "GET", "/api/clock");
    CHECK(clock.status == 200);
    CHECK(clock.body.find("\"now_ticks\":") != std::string::npos);
    CHECK(daemon.running());
}

TEST_CASE("control: off for a rig without \"control\", the endpoints file has no control key", "[e2e][control]")
{
    Daemon daemon(Daemon::Options{{}, fixture("two_channel_rig.json"), {}});
    CHECK(daemon.endpoints_json().find("\"control\"") == std::string::npos);
}

TEST_CASE("control: the built-in default rig serves it (on an ephemeral port under --ephemeral-ports)",
          "[e2e][control]")
{
    Daemon daemon;   // config/default.json: "control": {"port": 40200}, made ephemeral here
    const auto control = control_endpoint(daemon);
    CHECK(control.host == "127.0.0.1");
    CHECK(control.port != 40200);
    TcpClient api(control);
    CHECK(http(api, "GET", "/api/clock").status == 200);
}

TEST_CASE("control: --control refuses a host name and a missing port", "[e2e][control][cli]")
{
    for (const std::string bad : {"localhost:0", "127.0.0.1", "127.0.0.1:65536", "::1:80", ""}) {
        const auto r = run_rigsimd({"--control", bad});
        INFO(bad << ": " << r.err);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find("--control: expected") != std::string::npos);
    }
}

TEST_CASE("control: the rig's control port becomes ephemeral under --ephemeral-ports", "[e2e][control]")
{
    // Port 1 is privileged: the daemon could not bind it, so a control URL proves the port
    // was replaced by an ephemeral one.
    Daemon daemon(Daemon::Options{
        R"({"control": {"port": 1}, "devices": [{"name": "mcs0", "protocol": "mcs", "mcs": {"channels": [{}]}}]})",
        {}, {}});
    const auto control = control_endpoint(daemon);
    CHECK(control.host == "127.0.0.1");
    CHECK(control.port != 1);
    TcpClient api(control);
    CHECK(http(api, "GET", "/api/clock").status == 200);
}

TEST_CASE("control: a control port in use stops start-up with exit 1 naming it", "[e2e][control]")
{
    Daemon first(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0"}});
    const auto taken = control_endpoint(first);
    TempDir dir;
    const auto r = run_rigsimd({"--control", taken.tcp, "--ephemeral-ports", "--pty-dir", dir.path()});
    INFO(r.err);
    CHECK(r.exited);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("control API: cannot listen on tcp " + taken.tcp) != std::string::npos);
    CHECK(first.running());
}

TEST_CASE("control: SIGTERM closes open control connections and the daemon exits 0", "[e2e][control]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0"}});
    const auto control = control_endpoint(daemon);
    TcpClient idle(control);
    CHECK(http(idle, "GET", "/api/clock").status == 200);   // kept alive, now waiting
    TcpClient half(control);
    half.send("GET /api/cl");                                // a request cut in the middle
    const auto status = daemon.stop(SIGTERM);
    REQUIRE(status);
    CHECK(describe_wait_status(*status) == "exited 0");
    CHECK(idle.wait_for_eof(kAnswerTimeout));
    CHECK(half.wait_for_eof(kAnswerTimeout));
}

TEST_CASE("control: out of descriptors, the control API's accept backs off instead of spinning",
          "[e2e][control][resources]")
{
    Daemon::Options options;
    options.config_json = R"({"devices":[{"name":"mcs0","protocol":"mcs","mcs":{"channels":[{}]}}]})";
    options.extra_args = {"--control", "127.0.0.1:0"};
    constexpr unsigned long kMaxFiles = 32;
    Daemon daemon(options, Daemon::Limits{kMaxFiles});
    const auto control = control_endpoint(daemon);
    {
        // One request first: a sanitizer build's run-time checks open a pipe the first time
        // they meet a type, which they could not do once descriptors run out.
        TcpClient api(control);
        REQUIRE(http(api, "GET", "/api/clock").status == 200);
    }
    const std::size_t at_start = open_fds(daemon.pid()).size();
    REQUIRE(at_start < kMaxFiles);

    // More clients than the daemon has descriptors left: every accept fails with EMFILE.
    std::vector<std::unique_ptr<TcpClient>> clients;
    for (std::size_t i = 0; i < kMaxFiles - at_start + 4; ++i)
        clients.push_back(std::make_unique<TcpClient>(control));
    REQUIRE(wait_until([&] { return daemon.log().find("control: accept failed") != std::string::npos; }, 5000ms));

    // A polling window of 1.5 s: with the back-off (100 ms doubling to 1 s) at most a handful
    // of failures are logged; a loop that re-arms at once logs thousands.
    const auto window_end = SteadyClock::now() + 1500ms;
    wait_until([&] { return SteadyClock::now() >= window_end; }, 2000ms);
    const std::string log = daemon.log();
    INFO("log tail:\n" << log.substr(log.size() > 2000 ? log.size() - 2000 : 0));
    CHECK(count_of(log, "control: accept failed") <= 10);
    CHECK(daemon.running());

    // Descriptors free up: the control API accepts and answers again.
    clients.clear();
    CHECK(wait_until(
        [&] {
            TcpClient api(control);
            return http(api, "GET", "/api/clock").status == 200;
        },
        5000ms));
    CHECK(daemon.log().find("control: accepting again") != std::string::npos);
}

} // namespace control_test
