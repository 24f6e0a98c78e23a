// The daemon as a process: shutdown on signals, time scaling, several daemons side by
// side, a rig from a config file.

#include <catch2/catch.hpp>

#include <csignal>
#include <string>

#include "e2e_support.hpp"

namespace lifecycle_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

TEST_CASE("lifecycle: SIGTERM or SIGINT with clients connected exits 0 and removes the pty",
          "[e2e][lifecycle]")
{
    const int sig = GENERATE(SIGTERM, SIGINT);
    INFO("signal " << sig);
    Daemon daemon;
    const Endpoint ep = daemon.endpoint();
    REQUIRE(path_exists(ep.pty));

    TcpClient t(ep);
    PtyClient p(ep.pty);
    REQUIRE(t.request(":GNC\n") == ":N3\n");
    REQUIRE(p.request(":GNC\n") == ":N3\n");
    // A move in progress (5 s at 1 mm/s) must not delay the shutdown.
    REQUIRE(t.request(":SCLS0,1000000\n") == ":E-1,0\n");
    REQUIRE(t.request(":MPA0,5000000,0\n") == ":E0,0\n");

    const auto start = SteadyClock::now();
    const auto status = daemon.stop(sig, kShutdownTimeout);
    INFO("daemon log:\n" << daemon.log());
    REQUIRE(status.has_value());
    INFO("shutdown took " << elapsed_ms(start) << " ms");
    CHECK(describe_wait_status(*status) == "exited 0");
    CHECK_FALSE(path_exists(ep.pty));
    CHECK(t.wait_for_eof(2000ms));
}

TEST_CASE("lifecycle: --time-scale 10 is accepted and the clock runs: a move completes",
          "[e2e][lifecycle]")
{
    // How fast the scaled clock runs is unit-tested on the Ticker (tests/unit/daemon/test_ticker.cpp)
    // and the move's timing on the stepped clock (tests/device/mcs/test_mcs_timing.cpp): here
    // only that the daemon takes the flag and its clock carries a move to the end.
    Daemon daemon({"", fixture("long_travel_rig.json"), {"--time-scale", "10"}});
    TcpClient c(daemon.endpoint());
    REQUIRE(c.request(":GP0\n") == ":P0,0\n");
    REQUIRE(c.request(":MPA0,10000000,0\n") == ":E0,0\n");
    REQUIRE(poll_status_until(c, 0, 0, 5000ms));
    CHECK(c.request(":GP0\n") == ":P0,10000000\n");
}

TEST_CASE("lifecycle: two daemons with ephemeral ports and their own pty dirs coexist",
          "[e2e][lifecycle]")
{
    Daemon first;
    Daemon second;
    const Endpoint a = first.endpoint();
    const Endpoint b = second.endpoint();
    INFO("first: " << first.endpoints_json() << "\nsecond: " << second.endpoints_json());
    CHECK(a.port != 0);
    CHECK(b.port != 0);
    CHECK(a.port != b.port);
    CHECK(a.pty != b.pty);
    CHECK(a.pty == first.dir().file("mcs0"));
    CHECK(b.pty == second.dir().file("mcs0"));

    TcpClient ta(a), tb(b);
    PtyClient pa(a.pty), pb(b.pty);
    CHECK(ta.request(":GNC\n") == ":N3\n");
    CHECK(tb.request(":GNC\n") == ":N3\n");
    CHECK(pa.request(":GNC\n") == ":N3\n");
    CHECK(pb.request(":GNC\n") == ":N3\n");

    // They are separate rigs: a move on the first leaves the second where it was.
    const std::string second_before = tb.request(":GP0\n");
    REQUIRE(ta.request(":MPA0,1000000,0\n") == ":E0,0\n");
    REQUIRE(poll_status_until(pa, 0, 0, 3000ms));
    CHECK(ta.request(":GP0\n") == ":P0,1000000\n");
    CHECK(pb.request(":GP0\n") == second_before);
    CHECK(tb.request(":GS0\n") == ":S0,0\n");
}

TEST_CASE("lifecycle: --config builds the rig the file describes", "[e2e][lifecycle]")
{
    Daemon daemon({"", fixture("two_channel_rig.json"), {}});
    INFO("endpoints: " << daemon.endpoints_json());
    CHECK_FALSE(find_endpoint(daemon.endpoints_json(), "mcs0").has_value());
    const Endpoint ep = daemon.endpoint("stage");
    CHECK(ep.pty == daemon.dir().file("stage"));
    CHECK(json_string_value(daemon.endpoints_json(), "model") == "MCS-2D");
    CHECK(json_string_value(daemon.endpoints_json(), "protocol") == "mcs");

    TcpClient c(ep);
    CHECK(c.request(":GNC\n") == ":N2\n");
    CHECK(c.request(":GSI\n") == ":ID1234567\n");
    CHECK(c.request(":GST0\n") == ":ST0,1\n");
    CHECK(c.request(":GST1\n") == ":ST1,2\n");
    // start_position_nm is the physical position at power-up; like the real controller
    // the position reads 0 until referenced.
    CHECK(c.request(":GP0\n") == ":P0,0\n");
    CHECK(c.request(":GP2\n") == ":E-1,7\n");
}

TEST_CASE(
    "lifecycle: --bind, --tick-hz and --log-level are honoured and the log goes to stderr",
    "[e2e][lifecycle]")
{
    const std::string level = GENERATE(std::string("debug"), std::string("mcs0=debug"));
    INFO("--log-level " << level);
    Daemon daemon({"", "", {"--bind", "127.0.0.1", "--tick-hz", "200", "--log-level", level}});
    const Endpoint ep = daemon.endpoint();
    CHECK(ep.host == "127.0.0.1");

    TcpClient c(ep);
    CHECK(c.request(":GNC\n") == ":N3\n");
    // The clock runs at 200 Hz: a move completes (its timing at 200 Hz: device test "at a
    // 200 Hz tick a move ends on its target, ...").
    REQUIRE(c.request(":MPA0,1000000,0\n") == ":E0,0\n");
    REQUIRE(poll_status_until(c, 0, 0, 3000ms));
    CHECK(c.request(":GP0\n") == ":P0,1000000\n");

    // A client mistake is logged (warn) to stderr.
    CHECK(c.request(":FOO\n") == ":E-1,2\n");
    const bool logged = wait_until(
        [&] { return daemon.log().find("FOO") != std::string::npos; }, 2000ms);
    INFO("daemon log:\n" << daemon.log());
    CHECK(logged);
}

} // namespace lifecycle_test
