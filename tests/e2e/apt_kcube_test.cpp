// One K-Cube session through the real daemon with the later firmware generation's scaling
// ("firmware": "issue-44.1", docs/protocol/apt.md "Firmware generations"): a KST101 with a
// ZST225B over its pty, as a Kinesis-era driver talks to it. The clock is paused and stepped
// through the control API, so the move's duration is measured on the daemon's clock, not the
// wall clock.
#include "apt_support.hpp"
#include "control_support.hpp"
#include "e2e_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <string>

namespace apt_kcube_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {

constexpr const char* kRig = R"({"tick_hz": 1000, "devices": [
  {"name": "kst", "protocol": "apt", "model": "KST101", "firmware": "issue-44.1", "tcp_port": 0,
   "apt": {"stage": "ZST225B"}}]})";

// ZST225B on the later KST101: 2,008,645.63 microsteps per mm; 53.68 per microstep/s and
// 53.68 × 204.94e-6 per microstep/s² (pyLabLib's KST101 figures, which a driver sends: 1 mm is
// 2,008,646 microsteps, 1 mm/s 107,824,097, 4 mm/s² 88,390).
constexpr double kPerMmExact = 2'008'645.63;
const std::int32_t kPerMm = static_cast<std::int32_t>(std::lround(kPerMmExact));
const std::int32_t kOneMmPerS = static_cast<std::int32_t>(std::lround(kPerMmExact * 53.68));
const std::int32_t kTwoMmPerS = static_cast<std::int32_t>(std::lround(2.0 * kPerMmExact * 53.68));
const std::int32_t kFourMmPerS2 = static_cast<std::int32_t>(std::lround(4.0 * kPerMmExact * 53.68 * 204.94e-6));

std::string chan1()
{
    return std::string("\x01\x00", 2);
}

bool has(const std::string& text, const std::string& needle)
{
    return text.find(needle) != std::string::npos;
}

/// Steps the paused clock by `ms`.
void step(LineClient& api, int ms)
{
    REQUIRE(http(api, "POST", "/api/clock", "{\"step_ms\": " + std::to_string(ms) + "}").status == 200);
}

} // namespace

TEST_CASE("apt K-Cube at issue-44.1: a KST101 session over the pty with the later scaling, timed on the daemon's "
          "clock",
          "[e2e][apt]")
{
    Daemon daemon(Daemon::Options{kRig, {}, {"--control", "127.0.0.1:0", "--paused"}});
    TcpClient api(control_endpoint(daemon));
    CHECK(has(http(api, "GET", "/api/devices/kst").body, "\"firmware\":\"issue-44.1\""));
    PtyClient c(daemon.endpoint("kst").pty);
    const int fd = c.fd();

    // HW_GET_INFO: the KST101, with the later fields (hardware version 1 at data 78).
    c.send(header(0x0005, 0, 0));
    const auto info = wait_for(fd, 0x0006);
    REQUIRE(info);
    REQUIRE(info->data.size() == 84);
    CHECK(get32(info->data, 0) == 26'000'001);
    CHECK(info->data.substr(4, 6) == "KST101");
    CHECK(info->data[78] == 1);

    // Power-up VELPARAMS in the later units: 2 mm/s, 4 mm/s².
    c.send(header(0x0414, 1, 0));
    auto vel = wait_for(fd, 0x0415);
    REQUIRE(vel);
    CHECK(get32(vel->data, 6) == kFourMmPerS2);
    CHECK(get32(vel->data, 10) == kTwoMmPerS);

    // Set 1 mm/s and 4 mm/s² in the later units; they read back as set.
    c.send(with_data(0x0413, chan1() + le32(0) + le32(kFourMmPerS2) + le32(kOneMmPerS)));
    c.send(header(0x0414, 1, 0));
    vel = wait_for(fd, 0x0415);
    REQUIRE(vel);
    CHECK(get32(vel->data, 6) == kFourMmPerS2);
    CHECK(get32(vel->data, 10) == kOneMmPerS);

    // MOVE_RELATIVE 1 mm: 1 mm at 1 mm/s plus v/a = 1.25 s of the daemon's clock. The request
    // is handled once a later one on the same connection is answered.
    c.send(with_data(0x0448, chan1() + le32(kPerMm)));
    c.send(header(0x0411, 1, 0));
    const auto start = wait_for(fd, 0x0412);
    REQUIRE(start);
    CHECK(get32(start->data, 2) == 0);
    step(api, 625);
    c.send(header(0x0411, 1, 0));
    const auto half = wait_for(fd, 0x0412);
    REQUIRE(half);
    CHECK(std::abs(get32(half->data, 2) - kPerMm / 2) < kPerMm / 100);   // half way at half time
    step(api, 615);
    CHECK_FALSE(read_frame(fd, 300ms));   // 1.24 s: still moving, no MOVE_COMPLETED
    step(api, 20);
    const auto done = wait_for(fd, 0x0464, 5000ms);
    REQUIRE(done);
    REQUIRE(done->data.size() == 14);
    CHECK(get32(done->data, 2) == kPerMm);   // MOTSTATUS: position, then the encoder count
    CHECK(get32(done->data, 6) == kPerMm);

    // The carriage is 1 mm from where it started (the ZST225B stands mid-travel at power-up).
    const auto channel = http(api, "GET", "/api/devices/kst/channels/0").body;
    INFO(channel);
    const auto at = channel.find("\"position_si\":");
    REQUIRE(at != std::string::npos);
    CHECK(std::abs(std::stod(channel.substr(at + 14)) - 0.0135) < 1e-9);

    // Status updates: MOT_GET_STATUSUPDATE with the position in the later microsteps.
    c.send(header(0x0011, 0, 0));
    c.send(header(0x0411, 1, 0));
    REQUIRE(wait_for(fd, 0x0412));
    step(api, 100);
    const auto update = wait_for(fd, 0x0481, 5000ms);
    REQUIRE(update);
    CHECK(get32(update->data, 2) == kPerMm);
    c.send(header(0x0012, 0, 0));
}

} // namespace apt_kcube_test
