// The wire faults that real links have (docs/control-api.md "Faults"), on the real rigsimd over
// TCP and the pty, injected through the control API: what a client observes (the bytes, end of
// stream, ECONNRESET, a hang-up) as the paused clock is stepped. Nothing here waits on wall-clock
// time for something to happen: a fault's effect comes with a step, and "nothing yet" is a read
// that finds nothing within a short poll.
#include "control_support.hpp"
#include "e2e_support.hpp"

#include <catch2/catch.hpp>

#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <string>

namespace wire_faults_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {

/// The "id" number of a fault record.
std::string id_of(const std::string& record)
{
    const auto at = record.find("\"id\":");
    REQUIRE(at != std::string::npos);
    return record.substr(at + 5, record.find_first_not_of("0123456789", at + 5) - (at + 5));
}

/// Reads until the stream ends (within a generous deadline: the end is due already).
Reads read_to_end(int fd)
{
    return read_fd(fd, std::size_t(-1), kAnswerTimeout);
}

/// A paused daemon on the default rig, with its control API.
struct Rig {
    Daemon daemon{Daemon::Options{{}, {}, {"--control", "127.0.0.1:0", "--paused"}}};
    TcpClient api{control_endpoint(daemon)};

    std::string fault(const std::string& body)
    {
        const auto a = http(api, "POST", "/api/faults", body);
        INFO(a.body);
        REQUIRE(a.status == 201);
        return id_of(a.body);
    }
    void step(int ms) { REQUIRE(http(api, "POST", "/api/clock", "{\"step_ms\": " + std::to_string(ms) + "}").status == 200); }
};

} // namespace

TEST_CASE("wire faults: slicer hands the answer out slice_bytes at a time, gap_ms of clock time apart",
          "[e2e][control][faults][wire]")
{
    Rig rig;
    rig.fault(R"({"device":"mcs0","kind":"slicer","slice_bytes":2,"gap_ms":10})");
    TcpClient mcs(rig.daemon.endpoint("mcs0"));
    mcs.send(":GS0\n");
    CHECK(read_fd(mcs.fd(), 6).bytes == ":S");
    rig.step(10);
    CHECK(read_fd(mcs.fd(), 6).bytes == "0,");
    rig.step(10);
    CHECK(read_fd(mcs.fd(), 6).bytes == "0\n");
}

TEST_CASE("wire faults: bandwidth lets bytes_per_s through on the clock, each way", "[e2e][control][faults][wire]")
{
    Rig rig;
    const auto id = rig.fault(R"({"device":"mcs0","kind":"bandwidth","bytes_per_s":100,"direction":"out"})");
    TcpClient mcs(rig.daemon.endpoint("mcs0"));
    mcs.send(":GS0\n");
    CHECK(read_fd(mcs.fd(), 6, 200ms).bytes.empty());
    rig.step(30);   // a byte each 10 ms
    CHECK(read_fd(mcs.fd(), 6).bytes == ":S0");
    rig.step(30);
    CHECK(read_fd(mcs.fd(), 6).bytes == ",0\n");
    REQUIRE(http(rig.api, "DELETE", "/api/faults/" + id).status == 200);
    rig.fault(R"({"device":"mcs0","kind":"bandwidth","bytes_per_s":100,"direction":"in"})");
    mcs.send(":GS0\n");   // the command reaches the controller 50 ms later
    CHECK(read_fd(mcs.fd(), 6, 200ms).bytes.empty());
    rig.step(40);
    CHECK(read_fd(mcs.fd(), 6, 200ms).bytes.empty());
    rig.step(10);
    CHECK(read_fd(mcs.fd(), 6).bytes == ":S0,0\n");
}

TEST_CASE("wire faults: reset: a TCP client reads ECONNRESET, a pty client a hang-up, after after_ms",
          "[e2e][control][faults][wire]")
{
    Rig rig;
    TcpClient mcs(rig.daemon.endpoint("mcs0"));
    REQUIRE(mcs.request(":GS0\n") == ":S0,0\n");
    rig.fault(R"({"device":"mcs0","kind":"reset","after_ms":50})");
    REQUIRE(mcs.request(":GS0\n") == ":S0,0\n");   // until after_ms has passed
    rig.step(50);
    auto r = read_to_end(mcs.fd());
    CHECK(r.end == Reads::End::Error);
    CHECK(r.error == ECONNRESET);

    // A connection opened while it lasts is reset after_ms after its first byte.
    TcpClient next(rig.daemon.endpoint("mcs0"));
    CHECK(next.request(":GS0\n") == ":S0,0\n");
    rig.step(50);
    CHECK(read_to_end(next.fd()).error == ECONNRESET);

    PtyClient pty(rig.daemon.endpoint("mcs0").pty, B9600);
    REQUIRE(pty.request(":GS0\n") == ":S0,0\n");
    rig.step(50);
    r = read_to_end(pty.fd());
    CHECK(r.end == Reads::End::Eof);   // the slave is hung up: read gives end of file
    CHECK(::write(pty.fd(), "x", 1) == -1);
    CHECK(errno == EIO);
    REQUIRE(http(rig.api, "DELETE", "/api/faults").status == 200);
    PtyClient again(rig.daemon.endpoint("mcs0").pty, B9600);   // a new pty behind the symlink
    CHECK(again.request(":GS0\n") == ":S0,0\n");
    CHECK(rig.daemon.log().find("hung up by a wire fault") != std::string::npos);
}

TEST_CASE("wire faults: slow_close answers until delay_ms, then the client reads end of stream (FIN)",
          "[e2e][control][faults][wire]")
{
    Rig rig;
    TcpClient mcs(rig.daemon.endpoint("mcs0"));
    PtyClient pty(rig.daemon.endpoint("mcs0").pty, B9600);
    REQUIRE(mcs.request(":GS0\n") == ":S0,0\n");
    REQUIRE(pty.request(":GS0\n") == ":S0,0\n");
    rig.fault(R"({"device":"mcs0","kind":"slow_close","delay_ms":100})");
    rig.step(99);
    CHECK(mcs.request(":GS0\n") == ":S0,0\n");
    CHECK(pty.request(":GS0\n") == ":S0,0\n");
    rig.step(1);
    auto r = read_to_end(mcs.fd());
    CHECK(r.end == Reads::End::Eof);
    CHECK(r.bytes.empty());
    mcs.send(":GS0\n");   // half-closed: the client may still write; nothing answers
    // A hung-up pty ends as end of stream or, when the hang-up overtakes the read, EIO: either
    // is the end (one CI run under load read EIO).
    const auto pty_end = read_to_end(pty.fd());
    CHECK((pty_end.end == Reads::End::Eof || (pty_end.end == Reads::End::Error && pty_end.error == EIO)));
    CHECK(rig.daemon.running());
}

TEST_CASE("wire faults: hang_close answers nothing more, then closes after close_after_ms",
          "[e2e][control][faults][wire]")
{
    Rig rig;
    TcpClient mcs(rig.daemon.endpoint("mcs0"));
    REQUIRE(mcs.request(":GS0\n") == ":S0,0\n");
    rig.fault(R"({"device":"mcs0","kind":"hang_close","close_after_ms":1000})");
    mcs.send(":GS0\n");
    CHECK(read_fd(mcs.fd(), 6, 300ms).bytes.empty());
    rig.step(999);
    CHECK(read_fd(mcs.fd(), 6, 100ms).end == Reads::End::Open);
    rig.step(1);
    auto r = read_to_end(mcs.fd());
    CHECK(r.end == Reads::End::Eof);
    CHECK(r.bytes.empty());
}

TEST_CASE("wire faults: cut_after lets N more bytes through, then closes", "[e2e][control][faults][wire]")
{
    Rig rig;
    TcpClient mcs(rig.daemon.endpoint("mcs0"));
    rig.fault(R"({"device":"mcs0","kind":"cut_after","bytes":9})");
    CHECK(mcs.request(":GS0\n") == ":S0,0\n");
    mcs.send(":GS1\n");
    auto r = read_to_end(mcs.fd());
    CHECK(r.bytes == ":S1");
    CHECK(r.end == Reads::End::Eof);

    PtyClient pty(rig.daemon.endpoint("mcs0").pty, B9600);
    pty.send(":GS0\n");   // the pty counts its own 9 bytes
    r = read_fd(pty.fd(), 7);
    CHECK(r.bytes == ":S0,0\n");   // 6 of 9: the line stays
    CHECK(r.end == Reads::End::Open);
}

TEST_CASE("wire faults: garbage_close sends N random bytes, then closes", "[e2e][control][faults][wire]")
{
    Rig rig;
    rig.fault(R"({"device":"mcs0","kind":"garbage_close","bytes":32,"seed":7})");
    TcpClient mcs(rig.daemon.endpoint("mcs0"));
    mcs.send(":GS0\n");   // its first byte starts the delay (after_ms 0): the command is lost
    auto r = read_to_end(mcs.fd());
    CHECK(r.bytes.size() == 32);
    CHECK(r.end == Reads::End::Eof);
    TcpClient next(rig.daemon.endpoint("mcs0"));
    next.send(":GS0\n");
    CHECK(read_to_end(next.fd()).bytes == r.bytes);   // the same seed, the same garbage
}

TEST_CASE("wire faults: overrun loses what the unit's receive buffer cannot hold, on the pty only",
          "[e2e][control][faults][wire]")
{
    Rig rig;
    rig.fault(R"({"device":"mcs0","kind":"overrun","buffer_bytes":8,"drain_bytes_per_s":1000})");
    PtyClient pty(rig.daemon.endpoint("mcs0").pty, B9600);
    pty.send(":GS0\n:GS1\n:GS2\n");   // 15 bytes into 8: ":GS0\n:GS" kept
    CHECK(pty.read_line() == std::optional<std::string>(":S0,0\n"));
    CHECK_FALSE(pty.read_line(300ms));
    CHECK(http(rig.api, "GET", "/api/devices/mcs0").body.find("\"dropped_bytes\":7") != std::string::npos);
    rig.step(100);   // drained
    CHECK(pty.request(":GS1\n") == ":S1,0\n");   // the controller resyncs on ':'
    TcpClient mcs(rig.daemon.endpoint("mcs0"));
    mcs.send(":GS0\n:GS1\n:GS2\n");
    CHECK(mcs.read_line() == std::optional<std::string>(":S0,0\n"));
    CHECK(mcs.read_line() == std::optional<std::string>(":S1,0\n"));
    CHECK(mcs.read_line() == std::optional<std::string>(":S2,0\n"));
}

TEST_CASE("wire faults: baud_mismatch garbles a pty client whose termios rate is not the controller's",
          "[e2e][control][faults][wire]")
{
    Rig rig;
    rig.fault(R"({"device":"mcs0","kind":"baud_mismatch"})");
    PtyClient pty(rig.daemon.endpoint("mcs0").pty, B115200);   // the MCS runs at 9600 (CB)
    pty.send(":GS0\n");
    CHECK_FALSE(pty.read_line(300ms));
    CHECK(http(rig.api, "GET", "/api/devices/mcs0").body.find("\"corrupted_bytes\":5") != std::string::npos);
    pty.set_baud(B9600);
    CHECK(pty.request(":GS0\n") == ":S0,0\n");
}

TEST_CASE("wire faults: a latency fault's held answers count in the pty's 1 MiB bound, the drops logged",
          "[e2e][control][faults][wire]")
{
    Rig rig;
    rig.fault(R"({"device":"mcs0","kind":"latency","latency_ms":1000})");
    PtyClient pty(rig.daemon.endpoint("mcs0").pty, B9600);
    // 200,000 answers of 6 bytes (the controller answers each read of commands in one piece,
    // so the bookkeeping is small): more than 1 MiB held.
    std::string commands;
    for (int i = 0; i < 1000; ++i)
        commands += ":GS0\n";
    for (int i = 0; i < 200; ++i)
        pty.send(commands);
    const auto deadline = SteadyClock::now() + kAnswerTimeout;
    while (rig.daemon.log().find("dropping answers beyond the connection's bound (1048576 bytes)") == std::string::npos
           && SteadyClock::now() < deadline)
        CHECK_FALSE(pty.read_line(20ms));
    CHECK(rig.daemon.log().find("dropping answers beyond the connection's bound (1048576 bytes)") != std::string::npos);
    rig.step(1000);
    CHECK(pty.read_line() == std::optional<std::string>(":S0,0\n"));
    CHECK(rig.daemon.running());
}

} // namespace wire_faults_test
