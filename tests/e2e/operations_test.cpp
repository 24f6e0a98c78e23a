// The daemon as an operator sees it: every shutdown signal cleans up, clients connected at
// shutdown do not outlive their devices, errors name the thing, bad input does not flood the
// log. Run under AddressSanitizer too (scripts/test.sh), where a use-after-free aborts.

#include <catch2/catch.hpp>

#include <csignal>
#include <fstream>
#include <string>
#include <vector>

#include "e2e_support.hpp"

namespace operations_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {

const std::vector<std::string> kDefaultRigDevices{"mcs0",   "tdc001", "kdc101", "bbd203", "tst001",
                                                  "kst101", "bsc203", "tsc001", "ksc101", "tpz001",
                                                  "tsg001", "kpz101", "ksg101", "bpc303"};

/// What a sanitizer or a crash leaves in the log.
bool log_is_clean(const std::string& log)
{
    return log.find("AddressSanitizer") == std::string::npos && log.find("runtime error") == std::string::npos
           && log.find("LeakSanitizer") == std::string::npos;
}

bool ipv6_loopback_available()
{
    std::ifstream in("/proc/net/if_inet6");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("00000000000000000000000000000001", 0) == 0)
            return true;
    return false;
}

} // namespace

TEST_CASE("operations: shutdown with a TCP client on every device of the default rig exits 0 cleanly",
          "[e2e][operations]")
{
    const int sig = GENERATE(SIGTERM, SIGINT);
    INFO("signal " << sig);
    Daemon daemon;
    std::vector<std::unique_ptr<TcpClient>> clients;
    for (const auto& name : kDefaultRigDevices) {
        clients.push_back(std::make_unique<TcpClient>(daemon.endpoint(name)));
        // MCS: a command; APT: HW_REQ_INFO (0x0005) to the unit (0x50) from the host (0x01).
        clients.back()->send(name == "mcs0" ? std::string(":GNC\n") : std::string("\x05\x00\x00\x00\x50\x01", 6));
    }
    REQUIRE(clients.front()->read_line() == std::string(":N3\n"));
    const auto status = daemon.stop(sig, kShutdownTimeout);
    INFO("daemon log:\n" << daemon.log());
    REQUIRE(status.has_value());
    CHECK(describe_wait_status(*status) == "exited 0");
    CHECK(log_is_clean(daemon.log()));
}

TEST_CASE("operations: every signal that would end the daemon cleans up its ptys and endpoints file",
          "[e2e][operations]")
{
    const int sig = GENERATE(SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGTERM);
    INFO("signal " << sig);
    Daemon daemon;
    std::vector<std::string> ptys;
    for (const auto& name : kDefaultRigDevices)
        ptys.push_back(daemon.endpoint(name).pty);
    const auto endpoints_file = daemon.dir().file("endpoints.json");
    REQUIRE(path_exists(endpoints_file));
    TcpClient client(daemon.endpoint());
    REQUIRE(client.request(":GNC\n") == ":N3\n");

    const auto status = daemon.stop(sig, kShutdownTimeout);
    INFO("daemon log:\n" << daemon.log());
    REQUIRE(status.has_value());
    CHECK(describe_wait_status(*status) == "exited 0");
    for (const auto& pty : ptys) {
        INFO(pty);
        CHECK_FALSE(path_exists(pty));
    }
    CHECK_FALSE(path_exists(endpoints_file));
    CHECK(daemon.log().find("shutting down") != std::string::npos);
}

TEST_CASE("operations: a TCP port in use names the device and the port", "[e2e][operations]")
{
    Daemon first;
    const auto taken = first.endpoint();
    TempDir dir;
    const auto rig = dir.file("rig.json");
    write_file(rig, R"({"devices": [{"name": "stage", "protocol": "mcs", "tcp_port": )" + std::to_string(taken.port)
                        + R"(, "mcs": {"channels": [{}]}}]})");
    const auto r = run_rigsimd({"--config", rig, "--pty-dir", dir.path()});
    INFO("stderr: " << r.err);
    REQUIRE(r.exited);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("rigsimd: device \"stage\": cannot listen on tcp 127.0.0.1:" + std::to_string(taken.port)
                     + ": bind: Address already in use")
          != std::string::npos);
    CHECK_FALSE(path_exists(dir.file("stage")));
}

TEST_CASE("operations: --bind :: writes an address a local client can connect to", "[e2e][operations]")
{
    if (!ipv6_loopback_available()) {
        WARN("no IPv6 loopback on this machine: not tested");
        return;
    }
    Daemon daemon({"", "", {"--bind", "::"}});
    const auto ep = daemon.endpoint();
    INFO("endpoints: " << daemon.endpoints_json());
    CHECK(ep.tcp == "[::1]:" + std::to_string(ep.port));
    TcpClient client(ep);
    CHECK(client.request(":GNC\n") == ":N3\n");
}

TEST_CASE("operations: a config that is no regular file, or a device named \"..\", is refused at once",
          "[e2e][operations]")
{
    SECTION("/dev/zero")
    {
        const auto r = run_rigsimd({"--config", "/dev/zero"}, 5000ms);
        INFO("stderr: " << r.err);
        REQUIRE(r.exited);
        CHECK(r.exit_code == 2);
        CHECK(r.err == "/dev/zero: not a regular file (a character device): a rig is read from a JSON file\n");
    }
    SECTION("device named \"..\"")
    {
        TempDir dir;
        const auto rig = dir.file("rig.json");
        write_file(rig, R"({"devices": [{"name": "..", "protocol": "mcs", "mcs": {"channels": [{}]}}]})");
        const auto r = run_rigsimd({"--check-config", rig});
        INFO("stderr: " << r.err);
        REQUIRE(r.exited);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find("/devices/0/name: expected a device name, got \"..\"") != std::string::npos);
    }
}

TEST_CASE("operations: a flood of bad commands gets every error answer but a bounded log", "[e2e][operations]")
{
    Daemon daemon;
    TcpClient client(daemon.endpoint());
    // 20,000 bad commands (100 kB): each is answered, and used to cost a 100-byte log line.
    constexpr int kChunks = 20;
    constexpr int kPerChunk = 1000;
    std::string chunk;
    for (int i = 0; i < kPerChunk; ++i)
        chunk += ":FOO\n";
    int answers = 0;
    for (int c = 0; c < kChunks; ++c) {
        client.send(chunk);
        for (int i = 0; i < kPerChunk; ++i)
            if (client.read_line() == std::string(":E-1,2\n"))
                ++answers;
    }
    CHECK(answers == kChunks * kPerChunk);
    // The summary of the last window comes within a second or two (periodic flush).
    const bool summarised = wait_until(
        [&] { return daemon.log().find("more warning(s) suppressed") != std::string::npos; }, 5000ms);
    const auto log = daemon.log();
    INFO("log size " << log.size() << " bytes; head:\n" << log.substr(0, 2000));
    CHECK(summarised);
    CHECK(log.size() < 100'000);
    // Another connection's warnings are not swallowed by the first one's flood.
    TcpClient other(daemon.endpoint());
    CHECK(other.request(":BAR\n") == ":E-1,2\n");
    CHECK(wait_until([&] { return daemon.log().find("\"BAR\"") != std::string::npos; }, 3000ms));
}

} // namespace operations_test
