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

#include "e2e_support.hpp"

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {

struct AptFrame {
    std::uint16_t id = 0;
    std::string data;   ///< empty for header-only frames
};

std::string header(std::uint16_t id, std::uint8_t p1, std::uint8_t p2)
{
    return {static_cast<char>(id & 0xff), static_cast<char>(id >> 8), static_cast<char>(p1),
            static_cast<char>(p2), '\x50', '\x01'};
}

std::string with_data(std::uint16_t id, const std::string& data)
{
    std::string h{static_cast<char>(id & 0xff), static_cast<char>(id >> 8),
                  static_cast<char>(data.size() & 0xff), static_cast<char>(data.size() >> 8),
                  static_cast<char>(0x50 | 0x80), '\x01'};
    return h + data;
}

std::string le32(std::int32_t v)
{
    const auto u = static_cast<std::uint32_t>(v);
    return {static_cast<char>(u), static_cast<char>(u >> 8), static_cast<char>(u >> 16), static_cast<char>(u >> 24)};
}

std::int32_t get32(const std::string& s, std::size_t at)
{
    return static_cast<std::int32_t>(static_cast<std::uint8_t>(s[at]) | static_cast<std::uint8_t>(s[at + 1]) << 8
                                     | static_cast<std::uint8_t>(s[at + 2]) << 16
                                     | static_cast<std::uint32_t>(static_cast<std::uint8_t>(s[at + 3])) << 24);
}

/// Reads exactly n bytes from fd within the deadline (polling, no fixed sleep).
bool read_exact(int fd, std::string& out, std::size_t n, Millis timeout)
{
    const auto deadline = SteadyClock::now() + timeout;
    while (out.size() < n) {
        const auto left = std::chrono::duration_cast<Millis>(deadline - SteadyClock::now()).count();
        if (left <= 0)
            return false;
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, static_cast<int>(left)) <= 0)
            continue;
        char buf[512];
        const auto got = ::read(fd, buf, std::min(sizeof buf, n - out.size()));
        if (got <= 0)
            return false;
        out.append(buf, static_cast<std::size_t>(got));
    }
    return true;
}

/// The next whole frame: a 6-byte header, then the data packet if the data flag is set.
std::optional<AptFrame> read_frame(int fd, Millis timeout = 5000ms)
{
    std::string h;
    if (!read_exact(fd, h, 6, timeout))
        return std::nullopt;
    AptFrame f;
    f.id = static_cast<std::uint16_t>(static_cast<std::uint8_t>(h[0]) | static_cast<std::uint8_t>(h[1]) << 8);
    if (static_cast<std::uint8_t>(h[4]) & 0x80) {
        const std::size_t len = static_cast<std::uint8_t>(h[2]) | static_cast<std::uint8_t>(h[3]) << 8;
        if (!read_exact(fd, f.data, len, timeout))
            return std::nullopt;
    }
    return f;
}

/// Frames until one with `id` arrives (status updates may come in between).
std::optional<AptFrame> wait_for(int fd, std::uint16_t id, Millis timeout = 10'000ms)
{
    const auto deadline = SteadyClock::now() + timeout;
    while (SteadyClock::now() < deadline) {
        auto f = read_frame(fd, std::chrono::duration_cast<Millis>(deadline - SteadyClock::now()));
        if (!f)
            return std::nullopt;
        if (f->id == id)
            return f;
    }
    return std::nullopt;
}

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
