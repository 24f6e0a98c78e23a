// A TPZ001 piezo driver and the TSG001 strain gauge reader mounted on its actuator, described in
// a rig JSON and run by the real daemon: a client over TCP closes the loop on the TPZ001 and
// reads the gauge on the TSG001. The loop's accuracy against creep is tested on the stepped
// clock (tests/device/apt/test_apt_closed_loop.cpp).
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstdlib>
#include <string>

#include "apt_support.hpp"
#include "e2e_support.hpp"

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {

std::int16_t word_at(const AptFrame& f, std::size_t at)
{
    return static_cast<std::int16_t>(static_cast<std::uint8_t>(f.data[at]) | static_cast<std::uint8_t>(f.data[at + 1]) << 8);
}

/// TSG_READING's Reading (p.129).
std::int16_t gauge_reading(LineClient& tsg)
{
    tsg.send(header(0x07DD, 1, 0));
    auto f = wait_for(tsg.fd(), 0x07DE);
    REQUIRE(f);
    REQUIRE(f->data.size() == 6);
    return word_at(*f, 2);
}

} // namespace

TEST_CASE("apt gauge pair: rigsimd --config runs a TPZ001 in closed loop on its TSG001", "[e2e][apt]")
{
    Daemon daemon({"", fixture("piezo_gauge_rig.json"), {}});
    TcpClient tpz(daemon.endpoint("tpz"));
    TcpClient tsg(daemon.endpoint("tsg"));

    CHECK(std::abs(gauge_reading(tsg)) < 100);   // 0 V: the gauge reads about 0 (noise 0.002 um)
    tpz.send(header(0x0640, 1, 2));              // PZ_SET_POSCONTROLMODE closed loop (p.94)
    tpz.send(header(0x0641, 1, 0));
    REQUIRE(wait_for(tpz.fd(), 0x0642));   // the mode change is handled before the set point
    tpz.send(with_data(0x0646, std::string("\x01\x00\x00\x40", 4)));   // PZ_SET_OUTPUTPOS 50 % (p.97)

    // Poll with a deadline until the gauge reads the set point within 0.5 % of the travel.
    const auto deadline = SteadyClock::now() + 10s;
    std::int16_t reading = 0;
    while (SteadyClock::now() < deadline) {
        reading = gauge_reading(tsg);
        if (std::abs(reading - 16384) < 164)
            break;
    }
    INFO("gauge reading " << reading);
    CHECK(std::abs(reading - 16384) < 164);
    tpz.send(header(0x0647, 1, 0));
    auto pos = wait_for(tpz.fd(), 0x0648);
    REQUIRE(pos);
    CHECK(std::abs(word_at(*pos, 2) - 16384) < 164);
}
