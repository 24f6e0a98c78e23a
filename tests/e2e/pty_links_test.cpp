// Two daemons on one pty directory: the links belong to the daemon that holds their lock
// files (<dir>/.<name>.lock). A second daemon is refused while the first runs, takes links
// over that a killed daemon left, and replaces a running daemon's only when told to.

#include <catch2/catch.hpp>

#include <csignal>
#include <climits>
#include <unistd.h>

#include <string>

#include "e2e_support.hpp"

namespace pty_links_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

/// Where the symlink at `path` points, or "" if it is none.
std::string link_target(const std::string& path)
{
    char target[PATH_MAX] = {};
    const auto n = ::readlink(path.c_str(), target, sizeof target - 1);
    return n > 0 ? std::string(target, static_cast<std::size_t>(n)) : std::string();
}

/// A daemon whose links go to `pty_dir` (another daemon's directory), with `more` flags.
Daemon::Options on_links_of(const Daemon& other, std::vector<std::string> more = {})
{
    Daemon::Options o;
    o.extra_args = {"--pty-dir", other.dir().path()};   // the last --pty-dir wins
    o.extra_args.insert(o.extra_args.end(), more.begin(), more.end());
    return o;
}

TEST_CASE("pty links: a second daemon on a running daemon's links is refused with exit 2 and leaves them "
          "alone",
          "[e2e][pty]")
{
    Daemon first;
    const Endpoint ep = first.endpoint("mcs0");
    const auto target = link_target(ep.pty);
    REQUIRE(!target.empty());
    CHECK(path_exists(first.dir().file(".mcs0.lock")));

    const auto second = run_rigsimd({"--ephemeral-ports", "--pty-dir", first.dir().path()});
    INFO("stderr: " << second.err);
    CHECK(second.exited);
    CHECK(second.exit_code == 2);
    CHECK(second.err.find("pty link " + ep.pty + " ") != std::string::npos);
    CHECK(second.err.find("(pid " + std::to_string(first.pid()) + ")") != std::string::npos);
    CHECK(second.err.find("--replace-links") != std::string::npos);

    // The first daemon's links are its own still, and answer.
    CHECK(link_target(ep.pty) == target);
    CHECK(link_target(first.dir().file("tdc001")) == link_target(first.endpoint("tdc001").pty));
    PtyClient p(ep.pty);
    CHECK(p.request(":GNC\n") == ":N3\n");
    p.close();

    // A clean exit takes the links and their lock files away.
    REQUIRE(first.stop(SIGTERM) == std::optional<int>(0));
    CHECK_FALSE(path_exists(ep.pty));
    CHECK_FALSE(path_exists(first.dir().file(".mcs0.lock")));
}

TEST_CASE("pty links: the links of a daemon killed with SIGKILL are taken over without a flag", "[e2e][pty]")
{
    Daemon killed;
    const auto pty = killed.endpoint("mcs0").pty;
    const auto old_target = link_target(pty);
    REQUIRE(killed.stop(SIGKILL).has_value());
    REQUIRE(path_exists(pty));                                 // left behind, as its lock file
    REQUIRE(path_exists(killed.dir().file(".mcs0.lock")));

    Daemon next(on_links_of(killed));
    INFO("log: " << next.log());
    CHECK(next.endpoint("mcs0").pty == pty);
    PtyClient p(pty);
    CHECK(p.request(":GSI\n") == ":ID3118100\n");
    CHECK(next.log().find("taken over") == std::string::npos);
}

TEST_CASE("pty links: --replace-links takes a running daemon's links over", "[e2e][pty]")
{
    Daemon first;
    const Endpoint ep = first.endpoint("mcs0");
    TcpClient first_tcp(ep);
    REQUIRE(first_tcp.request(":SCLS0,1111\n") == ":E-1,0\n");

    Daemon second(on_links_of(first, {"--replace-links"}));
    INFO("log: " << second.log());
    CHECK(second.log().find("pty link " + ep.pty + " taken over from the running rigsimd pid "
                            + std::to_string(first.pid()))
          != std::string::npos);
    TcpClient second_tcp(second.endpoint("mcs0"));
    REQUIRE(second_tcp.request(":SCLS0,2222\n") == ":E-1,0\n");
    {
        PtyClient p(ep.pty);   // the second daemon's device now
        CHECK(p.request(":GCLS0\n") == ":CLS0,2222\n");
    }
    CHECK(first_tcp.request(":GCLS0\n") == ":CLS0,1111\n");   // the first one runs on

    // A third daemon is refused naming the second, whose lock replaced the first one's.
    const auto third = run_rigsimd({"--ephemeral-ports", "--pty-dir", first.dir().path()});
    INFO("third's stderr: " << third.err);
    CHECK(third.exit_code == 2);
    CHECK(third.err.find("(pid " + std::to_string(second.pid()) + ")") != std::string::npos);

    // When the first exits, it removes neither the links nor the lock files it no longer holds.
    REQUIRE(first.stop(SIGTERM) == std::optional<int>(0));
    CHECK(path_exists(first.dir().file(".mcs0.lock")));
    PtyClient p(ep.pty);
    CHECK(p.request(":GCLS0\n") == ":CLS0,2222\n");
}

} // namespace pty_links_test
