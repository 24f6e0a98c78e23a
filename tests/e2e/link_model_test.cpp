// The link model (docs/config.md "The link model") on the real rigsimd: a USB-serial chip between
// the unit and its clients, on the pty and, with "tcp", on TCP, as the paused clock is stepped
// through the control API. The chip's batching itself is tested on the stepped clock in
// tests/unit/daemon/test_usb_serial.cpp and tests/device/apt/test_apt_timing.cpp; here, that the
// daemon builds it from the rig JSON and releases its packets with the clock's steps. "Nothing
// yet" is a read that finds nothing within a short poll.
#include "control_support.hpp"
#include "e2e_support.hpp"

#include <catch2/catch.hpp>

#include <poll.h>
#include <unistd.h>

#include <string>

namespace link_model_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {

/// What `fd` has to read within `timeout` (up to `want` bytes; nothing more is waited for once
/// they have come).
std::string read_some(int fd, std::size_t want, Millis timeout = 200ms)
{
    return read_fd(fd, want, timeout).bytes;
}

struct Rig {
    // mcs0: the chip on the pty and TCP, 4-byte packets (":P0,0\n" goes in two); mcs1: on the pty
    // only.
    Daemon daemon{Daemon::Options{
        R"({"devices":[
              {"name":"mcs0","protocol":"mcs","link":{"packet_bytes":4,"tcp":true},"mcs":{"channels":[{},{}]}},
              {"name":"mcs1","protocol":"mcs","link":{},"mcs":{"channels":[{}]}}]})",
        {},
        {"--control", "127.0.0.1:0", "--paused"}}};
    TcpClient api{control_endpoint(daemon)};

    void step(int ms)
    {
        REQUIRE(http(api, "POST", "/api/clock", "{\"step_ms\": " + std::to_string(ms) + "}").status == 200);
    }
    /// Waits until the daemon has read a client's write, which the link holds for the next USB
    /// frame (a step sent sooner could come first).
    void wait_held_request(const std::string& device)
    {
        CHECK(wait_until([&] {
            return http(api, "GET", "/api/devices/" + device).body.find("\"held_requests\":1") != std::string::npos;
        }, 5000ms));
    }
};

} // namespace

TEST_CASE("link model: a USB-serial chip's packets on TCP and the pty, released by the clock's steps",
          "[e2e][control][link]")
{
    Rig rig;
    TcpClient tcp(rig.daemon.endpoint("mcs0"));
    PtyClient pty(rig.daemon.endpoint("mcs0").pty);
    TcpClient direct(rig.daemon.endpoint("mcs1"));
    // The clock is paused at 0: each connection's latency timer runs from there (16 ms).
    tcp.send(":GP0\n");                                  // reaches the unit in the frame at 1 ms
    rig.wait_held_request("mcs0");
    CHECK(read_some(tcp.fd(), 6).empty());
    rig.step(1);                                         // a full packet in that frame
    CHECK(read_some(tcp.fd(), 4, 2000ms) == ":P0,");
    rig.step(15);
    CHECK(read_some(tcp.fd(), 6).empty());               // the rest waits for the timer
    rig.step(1);                                         // 17 ms: 16 after the full packet
    CHECK(read_some(tcp.fd(), 2, 2000ms) == "0\n");

    pty.send(":GP1\n");                                  // at 17 ms: in the unit at 18
    rig.wait_held_request("mcs0");
    rig.step(1);
    CHECK(read_some(pty.fd(), 4, 2000ms) == ":P1,");
    rig.step(15);
    CHECK(read_some(pty.fd(), 6).empty());
    rig.step(1);                                         // 34 ms
    CHECK(read_some(pty.fd(), 2, 2000ms) == "0\n");

    CHECK(direct.request(":GNC\n") == ":N1\n");          // mcs1's chip is on its pty only
}

} // namespace link_model_test
