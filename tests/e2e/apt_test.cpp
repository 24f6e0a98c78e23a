// APT through the real daemon: a standard-library client over TCP and over the pty homes,
// moves, jogs and starts status updates, at --time-scale 100 (the 25 mm homing run takes
// 0.25 s). How long each takes on the clock is tested on the stepped clock (tests/device/apt).
#include <catch2/catch.hpp>

#include <poll.h>
#include <csignal>
#include <unistd.h>

#include <cstdint>
#include <string>
#include <vector>

#include "apt_support.hpp"
#include "e2e_support.hpp"

namespace apt_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {

void session(LineClient& c)
{
    const int fd = c.fd();
    // Nothing arrives unasked: the first frame is the answer to HW_REQ_INFO.
    c.send(header(0x0005, 0, 0));
    auto info = read_frame(fd);
    REQUIRE(info);
    CHECK(info->id == 0x0006);
    REQUIRE(info->data.size() == 84);
    CHECK(get32(info->data, 0) == 83'000'001);
    CHECK(info->data.substr(4, 6) == "TDC001");

    // Home: MOVE_HOMED follows, and the counter reads 0.
    c.send(header(0x0443, 1, 0));
    REQUIRE(wait_for(fd, 0x0444, 20'000ms));
    c.send(header(0x0411, 1, 0));
    auto pos = wait_for(fd, 0x0412);
    REQUIRE(pos);
    CHECK(get32(pos->data, 2) == 0);

    // Move absolute to 2 mm (68608 counts): MOVE_COMPLETED with the status, then the position.
    c.send(with_data(0x0453, std::string("\x01\x00", 2) + le32(68'608)));
    auto done = wait_for(fd, 0x0464);
    REQUIRE(done);
    CHECK(done->data.size() == 14);
    CHECK(get32(done->data, 2) == 68'608);

    // Jog one step (0.1 mm) forward.
    c.send(header(0x046A, 1, 1));
    auto jogged = wait_for(fd, 0x0464);
    REQUIRE(jogged);
    CHECK(get32(jogged->data, 2) == 68'608 + 3'430);

    // Status updates flow once started (their cadence, 10 per second of clock, is the
    // device test "status updates during a move: ten per second of clock, ...").
    c.send(header(0x0011, 0, 0));
    CHECK(wait_for(fd, 0x0491));
    c.send(header(0x0012, 0, 0));
}

} // namespace

TEST_CASE("APT over TCP: info, home, move, jog, status updates", "[e2e][apt]")
{
    Daemon::Options options;
    options.extra_args = {"--time-scale", "100"};
    Daemon daemon(options);
    TcpClient c(daemon.endpoint("tdc001"));
    session(c);
}

TEST_CASE("APT over the pty: info, home, move, jog, status updates", "[e2e][apt]")
{
    Daemon::Options options;
    options.extra_args = {"--time-scale", "100"};
    Daemon daemon(options);
    PtyClient c(daemon.endpoint("tdc001").pty);
    session(c);
}

TEST_CASE("APT: what MOT_SET_EEPROMPARAMS saves survives a daemon restart (--state-file)", "[e2e][apt]")
{
    TempDir state_dir;
    const auto state = state_dir.file("state.json");
    Daemon::Options options;
    options.extra_args = {"--state-file", state};
    {
        Daemon daemon(options);
        TcpClient c(daemon.endpoint("kdc101"));
        // VELPARAMS: acceleration 16, max 4096 (APT units); then save them.
        c.send(with_data(0x0413, std::string("\x01\x00\x00\x00\x00\x00\x10\x00\x00\x00\x00\x10\x00\x00", 14)));
        c.send(with_data(0x04B9, std::string("\x01\x00\x13\x04", 4)));
        c.send(header(0x0414, 1, 0));
        auto vel = wait_for(c.fd(), 0x0415);
        REQUIRE(vel);
        CHECK(get32(vel->data, 10) == 4096);
        REQUIRE(wait_until([&] { return read_file(state).has_value(); }, 5000ms));
        REQUIRE(daemon.stop(SIGTERM) == std::optional<int>(0));
    }
    Daemon daemon(options);
    TcpClient c(daemon.endpoint("kdc101"));
    c.send(header(0x0414, 1, 0));
    auto vel = wait_for(c.fd(), 0x0415);
    REQUIRE(vel);
    CHECK(get32(vel->data, 6) == 16);
    CHECK(get32(vel->data, 10) == 4096);
}

} // namespace apt_test
