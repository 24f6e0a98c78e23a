// The daemon under resource pressure: connection limits, running out of descriptors, many
// ptys. Assertions count things (log lines, descriptors, answers), never wall time.

#include <catch2/catch.hpp>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "e2e_support.hpp"

namespace resource_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {


/// The local port of a connected socket.
int local_port(int fd)
{
    sockaddr_in addr{};
    socklen_t len = sizeof addr;
    if (::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0)
        return -1;
    return ntohs(addr.sin_port);
}

/// Opens a connection and checks that the daemon serves it (an MCS device answers GNC).
bool served(const Endpoint& ep)
{
    TcpClient c(ep);
    return c.request(":GNC\n").rfind(":N", 0) == 0;
}

} // namespace

TEST_CASE("resources: a connection beyond the per-device limit is closed, the others keep working",
          "[e2e][tcp][resources]")
{
    Daemon daemon;   // default --max-connections-per-device 32
    const Endpoint ep = daemon.endpoint("mcs0");
    std::vector<std::unique_ptr<TcpClient>> clients;
    for (int i = 0; i < 32; ++i) {
        clients.push_back(std::make_unique<TcpClient>(ep));
        REQUIRE(clients.back()->request(":GNC\n") == ":N3\n");
    }
    TcpClient extra(ep);
    const int extra_port = local_port(extra.fd());
    CHECK(extra.wait_for_eof(kAnswerTimeout));
    for (auto& c : clients)
        CHECK(c->request(":GSI\n") == ":ID3118100\n");
    // Another device has its own allowance.
    TcpClient apt(daemon.endpoint("tdc001"));
    CHECK_FALSE(apt.wait_for_eof(200ms));
    const std::string line = "connection refused: 32 open, the limit (--max-connections-per-device 32)";
    CHECK(wait_until([&] { return count_of(daemon.log(), line) == 1; }, kAnswerTimeout));
    const std::string log = daemon.log();
    INFO("log:\n" << log.substr(log.size() > 3000 ? log.size() - 3000 : 0));
    CHECK(log.find("[mcs0] tcp 127.0.0.1:" + std::to_string(extra_port) + ": " + line) != std::string::npos);

    // Once one closes, a new connection is accepted.
    clients.front()->close();
    CHECK(wait_until([&] { return served(ep); }, 5000ms));
}

TEST_CASE("resources: refused connections are logged once per second, not once each",
          "[e2e][tcp][resources]")
{
    Daemon::Options options;
    options.extra_args = {"--max-connections-per-device", "2"};
    Daemon daemon(options);
    const Endpoint ep = daemon.endpoint("mcs0");
    TcpClient a(ep), b(ep);
    REQUIRE(a.request(":GNC\n") == ":N3\n");
    REQUIRE(b.request(":GNC\n") == ":N3\n");
    for (int i = 0; i < 200; ++i) {
        TcpClient refused(ep);
        REQUIRE(refused.wait_for_eof(kAnswerTimeout));
    }
    // The summary line of the first second may still be due: wait for all 200 to be counted.
    const auto reported = [&] {
        const std::string log = daemon.log();
        std::size_t total = count_of(log, "connection refused:");
        for (auto at = log.find("refused "); at != std::string::npos; at = log.find("refused ", at + 1)) {
            const auto more = log.find(" more connection(s)", at);
            if (more != std::string::npos && more < log.find('\n', at))
                total += std::stoul(log.substr(at + 8, more - at - 8));
        }
        return total;
    };
    CHECK(wait_until([&] { return reported() == 200; }, 5000ms));
    INFO("log:\n" << daemon.log());
    CHECK(count_of(daemon.log(), "connection refused:") == 1);
    CHECK(a.request(":GSI\n") == ":ID3118100\n");
}

TEST_CASE("resources: --max-connections bounds the connections of all devices together",
          "[e2e][tcp][resources]")
{
    Daemon::Options options;
    options.extra_args = {"--max-connections", "3"};
    Daemon daemon(options);
    TcpClient a(daemon.endpoint("mcs0")), b(daemon.endpoint("mcs0"));
    TcpClient c(daemon.endpoint("tdc001"));
    REQUIRE(a.request(":GNC\n") == ":N3\n");
    REQUIRE(b.request(":GNC\n") == ":N3\n");
    REQUIRE_FALSE(c.wait_for_eof(200ms));
    TcpClient d(daemon.endpoint("kdc101"));
    CHECK(d.wait_for_eof(kAnswerTimeout));
    CHECK(wait_until([&] { return count_of(daemon.log(), "the limit (--max-connections 3)") == 1; },
                     kAnswerTimeout));
    CHECK(count_of(daemon.log(), "[kdc101] tcp 127.0.0.1:") == 1);
    b.close();
    CHECK(wait_until([&] { return served(daemon.endpoint("mcs0")); }, 5000ms));
}

TEST_CASE("resources: out of descriptors, accept backs off instead of spinning",
          "[e2e][tcp][resources]")
{
    Daemon::Options options;
    options.config_json = R"({"devices":[{"name":"mcs0","protocol":"mcs","mcs":{"channels":[{}]}}]})";
    options.extra_args = {"--max-connections-per-device", "1000", "--max-connections", "1000"};
    constexpr unsigned long kMaxFiles = 32;
    Daemon daemon(options, Daemon::Limits{kMaxFiles});
    const Endpoint ep = daemon.endpoint("mcs0");
    // One connection and disconnect first: a sanitizer build's run-time checks open a pipe
    // the first time they meet a type, which they could not do once descriptors run out.
    REQUIRE(served(ep));
    const std::size_t at_start = open_fds(daemon.pid()).size();
    INFO("descriptors open at start: " << at_start);
    REQUIRE(at_start < kMaxFiles);

    // More clients than the daemon has descriptors left: the rest wait in the backlog, and
    // every accept fails with EMFILE until a descriptor frees.
    std::vector<std::unique_ptr<TcpClient>> clients;
    for (std::size_t i = 0; i < kMaxFiles - at_start + 4; ++i)
        clients.push_back(std::make_unique<TcpClient>(ep));
    REQUIRE(wait_until([&] { return daemon.log().find("accept failed") != std::string::npos; }, 5000ms));

    // A polling window of 1.5 s: with the back-off (100 ms doubling to 1 s) at most a handful
    // of failures are logged; a loop that re-arms at once logs thousands.
    const auto window_end = SteadyClock::now() + 1500ms;
    wait_until([&] { return SteadyClock::now() >= window_end; }, 2000ms);
    const std::string log = daemon.log();
    const std::size_t failures = count_of(log, "accept failed");
    INFO("accept failures logged: " << failures << "; log tail:\n"
                                    << log.substr(log.size() > 2000 ? log.size() - 2000 : 0));
    CHECK(failures <= 10);
    CHECK(log.find("Too many open files") != std::string::npos);
    CHECK(daemon.running());

    // Descriptors free up: the daemon accepts again and serves new clients.
    clients.clear();
    CHECK(wait_until([&] { return served(ep); }, 5000ms));
    CHECK(daemon.log().find("accepting again") != std::string::npos);
}

TEST_CASE("resources: a rig of 200 ptys starts, on one inotify instance", "[e2e][pty][resources]")
{
    // More ptys than the default per-user limit of inotify instances (128).
    std::string devices;
    for (int i = 0; i < 200; ++i)
        devices += std::string(i ? "," : "") + R"({"name":"m)" + std::to_string(i)
                   + R"(","protocol":"mcs","mcs":{"channels":[{}]}})";
    Daemon::Options options;
    options.config_json = R"({"devices":[)" + devices + "]}";
    Daemon daemon(options);
    const auto fds = open_fds(daemon.pid());
    CHECK(std::count(fds.begin(), fds.end(), "anon_inode:inotify") == 1);

    // Opens and closes are still told apart per pty.
    for (const char* name : {"m0", "m199"}) {
        const Endpoint ep = daemon.endpoint(name);
        {
            PtyClient p(ep.pty);
            CHECK(p.request(":GNC\n") == ":N1\n");
        }
        CHECK(wait_until([&] { return daemon.log().find("pty " + ep.pty + ": closed") != std::string::npos; },
                         5000ms));
    }
}

TEST_CASE("resources: the connection limits are flags, listed by --help and checked",
          "[e2e][cli][resources]")
{
    const auto help = run_rigsimd({"--help"});
    CHECK(help.exit_code == 0);
    CHECK(help.out.find("--max-connections N") != std::string::npos);
    CHECK(help.out.find("--max-connections-per-device N") != std::string::npos);
    for (const char* flag : {"--max-connections", "--max-connections-per-device"}) {
        const auto r = run_rigsimd({flag, "0"});
        CHECK(r.exit_code == 2);
        CHECK(r.err == "rigsimd: " + std::string(flag) + ": expected an integer 1..65536, got \"0\"\n");
    }
}

} // namespace resource_test
