// The units made after the 2012 manual through the real daemon (docs/protocol/apt.md "Units of
// today"): a K10CR1, an LTS150, a KBD101 with a DDS100, an MFF101, an MPC320, a KIM101, a TIM101 and an MMR601 rack, each asked who it is over its
// pty and moved over TCP, the moves timed on the daemon's paused clock stepped through the control API.
#include "apt_support.hpp"
#include "control_support.hpp"
#include "e2e_support.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <string>

namespace apt_units_of_today_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {

constexpr const char* kRig = R"({"tick_hz": 1000, "devices": [
  {"name": "k10cr1", "protocol": "apt", "model": "K10CR1", "tcp_port": 0, "apt": {}},
  {"name": "lts150", "protocol": "apt", "model": "LTS150", "tcp_port": 0, "apt": {"serial_number": 45000777}},
  {"name": "kbd101", "protocol": "apt", "model": "KBD101", "tcp_port": 0, "apt": {"stage": "DDS100"}},
  {"name": "mff101", "protocol": "apt", "model": "MFF101", "tcp_port": 0, "apt": {"flipper": {"position": 1}}},
  {"name": "mpc320", "protocol": "apt", "model": "MPC320", "tcp_port": 0, "apt": {}},
  {"name": "kim101", "protocol": "apt", "model": "KIM101", "tcp_port": 0, "apt": {}},
  {"name": "tim101", "protocol": "apt", "model": "TIM101", "tcp_port": 0, "apt": {}},
  {"name": "mmr601", "protocol": "apt", "model": "MMR601", "tcp_port": 0, "apt": {"bays": [{}]}}]})";

void step(LineClient& api, int ms)
{
    REQUIRE(http(api, "POST", "/api/clock", "{\"step_ms\": " + std::to_string(ms) + "}").status == 200);
}

struct Unit {
    const char* name;
    const char* model;
    std::uint32_t serial;
    std::int32_t target;   ///< MOVE_ABSOLUTE counts
    int moving_ms;         ///< the move's duration at the power-up VELPARAMS
};

} // namespace

TEST_CASE("apt units of today: K10CR1, LTS150 and KBD101 tell who they are over the pty and move over TCP on the "
          "daemon's clock",
          "[e2e][apt]")
{
    Daemon daemon(Daemon::Options{kRig, {}, {"--control", "127.0.0.1:0", "--paused"}});
    TcpClient api(control_endpoint(daemon));
    CHECK(http(api, "GET", "/api/devices/k10cr1").body.find("\"firmware\":\"issue-44.1\"") != std::string::npos);
    // K10CR1: 90° at 10 °/s and 10 °/s² (10 s); LTS150: 10 mm at 20 mm/s² peaking below 20 mm/s
    // (2 × sqrt(10 / 20) = 1.414 s); KBD101 + DDS100: 10 mm at 5,000 mm/s² (2 × sqrt(10 / 5000) = 89 ms).
    for (const auto& u : {Unit{"k10cr1", "K10CR1", 55'000'001, 12'288'000, 10'000},
                          Unit{"lts150", "LTS150", 45'000'777, 4'096'000, 1'414},
                          Unit{"kbd101", "KBD101", 28'000'001, 20'000, 89}}) {
        INFO(u.name);
        PtyClient pty(daemon.endpoint(u.name).pty);
        pty.send(header(0x0005, 0, 0));
        const auto info = wait_for(pty.fd(), 0x0006);
        REQUIRE(info);
        REQUIRE(info->data.size() == 84);
        CHECK(static_cast<std::uint32_t>(get32(info->data, 0)) == u.serial);
        CHECK(info->data.substr(4, std::string(u.model).size()) == u.model);

        TcpClient tcp(daemon.endpoint(u.name));
        tcp.send(with_data(0x0453, std::string("\x01\x00", 2) + le32(u.target)));
        tcp.send(header(0x0411, 1, 0));   // answered once the move has been taken
        REQUIRE(wait_for(tcp.fd(), 0x0412));
        step(api, u.moving_ms - 5);
        CHECK_FALSE(read_frame(tcp.fd(), 300ms));   // still moving
        step(api, 10);
        const auto done = wait_for(tcp.fd(), 0x0464, 5000ms);
        REQUIRE(done);
        REQUIRE(done->data.size() == 14);
        CHECK(get32(done->data, 2) == u.target);
    }
}

TEST_CASE("apt units of today: an MFF101 names itself MFF002 over the pty and flips over TCP in its transit time",
          "[e2e][apt]")
{
    Daemon daemon(Daemon::Options{kRig, {}, {"--control", "127.0.0.1:0", "--paused"}});
    TcpClient api(control_endpoint(daemon));
    PtyClient pty(daemon.endpoint("mff101").pty);
    pty.send(header(0x0005, 0, 0));
    const auto info = wait_for(pty.fd(), 0x0006);
    REQUIRE(info);
    CHECK(info->data.substr(4, 6) == "MFF002");
    CHECK(get32(info->data, 0) == 37'000'001);

    TcpClient tcp(daemon.endpoint("mff101"));
    tcp.send(header(0x046A, 1, 2));   // MOVE_JOG to position 2
    tcp.send(header(0x0429, 1, 0));   // REQ_STATUSBITS: on the way to 2
    auto bits = wait_for(tcp.fd(), 0x042A);
    REQUIRE(bits);
    CHECK(get32(bits->data, 2) == 0x20);
    step(api, 495);
    CHECK_FALSE(read_frame(tcp.fd(), 300ms));
    step(api, 10);   // 500 ms: issue 37's transit time
    const auto done = wait_for(tcp.fd(), 0x0464, 5000ms);
    REQUIRE(done);
    REQUIRE(done->data.size() == 14);
    CHECK(get32(done->data, 10) == 0x02);
    CHECK(http(api, "GET", "/api/devices/mff101/channels/0").body.find("\"position\":2") != std::string::npos);
}

TEST_CASE("apt units of today: an MPC320 tells who it is over the pty and turns paddle 3 (bit 0x04) over TCP",
          "[e2e][apt]")
{
    Daemon daemon(Daemon::Options{kRig, {}, {"--control", "127.0.0.1:0", "--paused"}});
    TcpClient api(control_endpoint(daemon));
    PtyClient pty(daemon.endpoint("mpc320").pty);
    pty.send(header(0x0005, 0, 0));
    const auto info = wait_for(pty.fd(), 0x0006);
    REQUIRE(info);
    CHECK(info->data.substr(4, 6) == "MPC320");

    TcpClient tcp(daemon.endpoint("mpc320"));
    tcp.send(with_data(0x0453, std::string("\x04\x00", 2) + le32(685)));   // paddle 3 to 85 deg: 425 ms
    tcp.send(header(0x0411, 4, 0));
    REQUIRE(wait_for(tcp.fd(), 0x0412));
    step(api, 420);
    CHECK_FALSE(read_frame(tcp.fd(), 300ms));
    step(api, 10);
    const auto done = wait_for(tcp.fd(), 0x0464, 5000ms);
    REQUIRE(done);
    CHECK(done->data.empty());   // the 6-byte form
    tcp.send(header(0x0411, 4, 0));
    const auto at = wait_for(tcp.fd(), 0x0412);
    REQUIRE(at);
    CHECK(get32(at->data, 2) == 685);
}

TEST_CASE("apt units of today: a KIM101 tells who it is over the pty and drives channel 1 (bit 0x01) over TCP",
          "[e2e][apt]")
{
    Daemon daemon(Daemon::Options{kRig, {}, {"--control", "127.0.0.1:0", "--paused"}});
    TcpClient api(control_endpoint(daemon));
    PtyClient pty(daemon.endpoint("kim101").pty);
    pty.send(header(0x0005, 0, 0));
    const auto info = wait_for(pty.fd(), 0x0006);
    REQUIRE(info);
    CHECK(info->data.substr(4, 6) == "KIM101");

    TcpClient tcp(daemon.endpoint("kim101"));
    // PZMOT_MOVE_ABSOLUTE, channel 1 to 1000 steps: 500 steps/s after a 5 ms ramp, 2005 ms.
    tcp.send(with_data(0x08D4, std::string("\x01\x00", 2) + le32(1000)));
    tcp.send(header(0x08C1, 0x07, 0x01));   // PZMOT_REQ_PARAMS DriveOPParams, channel 1
    const auto drive = wait_for(tcp.fd(), 0x08C2);
    REQUIRE(drive);
    CHECK(drive->data.size() == 14);
    step(api, 2000);
    CHECK_FALSE(read_frame(tcp.fd(), 300ms));
    step(api, 10);
    const auto done = wait_for(tcp.fd(), 0x08D6, 5000ms);
    REQUIRE(done);
    REQUIRE(done->data.size() == 14);
    CHECK(get32(done->data, 2) == 1000);
    const auto channel = http(api, "GET", "/api/devices/kim101/channels/0").body;
    CHECK(channel.find("\"unit\":\"piezo_motor\"") != std::string::npos);
    CHECK(channel.find("\"position\":1000") != std::string::npos);
}

TEST_CASE("apt units of today: a TIM101 tells who it is over the pty and jogs the channel MOD_SET_CHANENABLESTATE "
          "selects over TCP",
          "[e2e][apt]")
{
    Daemon daemon(Daemon::Options{kRig, {}, {"--control", "127.0.0.1:0", "--paused"}});
    TcpClient api(control_endpoint(daemon));
    PtyClient pty(daemon.endpoint("tim101").pty);
    pty.send(header(0x0005, 0, 0));
    const auto info = wait_for(pty.fd(), 0x0006);
    REQUIRE(info);
    CHECK(info->data.substr(4, 6) == "TIM101");

    TcpClient tcp(daemon.endpoint("tim101"));
    // Channel 1 is the selected one at power-up: channel 2 jogs only once MOD_SET_CHANENABLESTATE
    // selects it (bit 0x02).
    tcp.send(header(0x08D9, 0x02, 0x02));
    step(api, 1000);
    CHECK_FALSE(read_frame(tcp.fd(), 300ms));
    tcp.send(header(0x0210, 0x02, 0x01));
    tcp.send(header(0x08D9, 0x02, 0x02));   // PZMOT_MOVE_JOG channel 2 reverse: 250 steps, 505 ms
    step(api, 500);
    CHECK_FALSE(read_frame(tcp.fd(), 300ms));
    step(api, 5);
    const auto done = wait_for(tcp.fd(), 0x08D6, 5000ms);
    REQUIRE(done);
    REQUIRE(done->data.size() == 14);
    CHECK(get32(done->data, 2) == -250);
}

TEST_CASE("apt units of today: an MMR601 rack tells who it is over the pty, its MPZ601 card answers for channel 2 "
          "over TCP, and a client that addresses it as a single unit freezes it until a power cycle",
          "[e2e][apt]")
{
    Daemon daemon(Daemon::Options{kRig, {}, {"--control", "127.0.0.1:0", "--paused"}});
    TcpClient api(control_endpoint(daemon));
    PtyClient pty(daemon.endpoint("mmr601").pty);
    auto to_rack = header(0x0005, 0, 0);
    to_rack[4] = 0x11;   // the motherboard
    pty.send(to_rack);
    const auto info = wait_for(pty.fd(), 0x0006);
    REQUIRE(info);
    CHECK(info->data.substr(4, 6) == "MMR601");

    TcpClient tcp(daemon.endpoint("mmr601"));
    auto volts = with_data(0x0643, std::string("\x02\x00\xFF\x3F", 4));   // PZ_SET_OUTPUTVOLTS, channel 2
    volts[4] = static_cast<char>(0x21 | 0x80);   // bay 0's card
    tcp.send(volts);
    auto req = header(0x0644, 2, 0);
    req[4] = 0x21;
    tcp.send(req);
    const auto got = wait_for(tcp.fd(), 0x0645);
    REQUIRE(got);
    CHECK(got->data == std::string("\x02\x00\xFF\x3F", 4));
    // pyLabLib with is_rack_system=False: to 0x50. The rack answers nothing more ...
    tcp.send(header(0x0005, 0, 0));
    tcp.send(req);
    CHECK_FALSE(read_frame(tcp.fd(), 300ms));
    CHECK(http(api, "GET", "/api/devices/mmr601").body.find("\"frozen\":true") != std::string::npos);
    // ... until it is power cycled.
    const auto cycled = http(api, "POST", "/api/faults", R"({"device":"mmr601","kind":"power_cycle"})").status;
    CHECK((cycled == 200 || cycled == 201));
    tcp.send(req);
    REQUIRE(wait_for(tcp.fd(), 0x0645));
}

} // namespace apt_units_of_today_test
