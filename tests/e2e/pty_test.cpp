// The MCS protocol over the daemon's pseudo-terminal, as a serial-port client sees it:
// open the symlink, raw mode, close, reopen, change the baud rate.

#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "e2e_support.hpp"

namespace pty_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

TEST_CASE("pty: a session survives close, reopen and baud changes", "[e2e][pty]")
{
    Daemon daemon;
    const Endpoint ep = daemon.endpoint();
    INFO("endpoints: " << daemon.endpoints_json());
    // --pty-dir DIR puts the symlink at DIR/<device name>.
    CHECK(ep.pty == daemon.dir().file("mcs0"));
    REQUIRE(path_exists(ep.pty));

    {
        PtyClient p(ep.pty);
        CHECK(p.request(":GNC\n") == ":N3\n");
        CHECK(p.request(":GSI\n") == ":ID3118100\n");
        // A command split across writes is reassembled.
        p.send(":G");
        p.send("S");
        CHECK(p.request("T0\n") == ":ST0,1\n");

        REQUIRE(p.request(":SCLS0,4000000\n") == ":E-1,0\n");
        REQUIRE(p.request(":MPA0,2000000,0\n") == ":E0,0\n");
        REQUIRE(poll_status_until(p, 0, 0, 5000ms));
        CHECK(p.request(":GP0\n") == ":P0,2000000\n");
    }

    {
        PtyClient p(ep.pty, B9600);
        CHECK(p.baud() == B9600);
        CHECK(p.request(":GP0\n") == ":P0,2000000\n");
        p.set_baud(B115200);
        CHECK(p.baud() == B115200);
        CHECK(p.request(":GP0\n") == ":P0,2000000\n");
        CHECK(p.request(":GCLS0\n") == ":CLS0,4000000\n");
        REQUIRE(p.request(":MPR0,-500000,0\n") == ":E0,0\n");
        REQUIRE(poll_status_until(p, 0, 0, 5000ms));
        CHECK(p.request(":GP0\n") == ":P0,1500000\n");
    }

    // A third open, and the TCP endpoint of the same device, see the same state.
    PtyClient p(ep.pty);
    CHECK(p.request(":GP0\n") == ":P0,1500000\n");
    TcpClient t(ep);
    CHECK(t.request(":GP0\n") == ":P0,1500000\n");
    CHECK(p.request(":GNC\n") == ":N3\n");
}

TEST_CASE("pty: --pty-group gives the pty to the group, mode 0660, as a serial port", "[e2e][pty]")
{
    Daemon::Options options;
    options.extra_args = {"--pty-group", std::to_string(::getegid())};
    Daemon daemon(options);
    const Endpoint ep = daemon.endpoint();
    struct stat st {};
    REQUIRE(::stat(ep.pty.c_str(), &st) == 0);   // the pty device behind the link
    CHECK(S_ISCHR(st.st_mode));
    CHECK(st.st_gid == ::getegid());
    CHECK((st.st_mode & 07777) == 0660);
    PtyClient p(ep.pty);
    CHECK(p.request(":GNC\n") == ":N3\n");
}

TEST_CASE("pty: answers unread when the client closes the port are not read by the next opener",
          "[e2e][pty]")
{
    Daemon daemon;
    const Endpoint ep = daemon.endpoint();
    TcpClient t(ep);
    {
        PtyClient p(ep.pty);
        p.send(":MPA0,1000,0\n:GSI\n:GNC\n");   // three answers this client never reads
        // Once the move shows over TCP, the daemon has handled the line and answered it.
        REQUIRE(wait_until([&] { return t.request(":GP0\n") == ":P0,1000\n"; }, 5000ms));
    }
    // The daemon learns of the close asynchronously (inotify) and logs it; a client that
    // reopens within microseconds of closing may still see the old answers
    // (docs/architecture.md), so wait for the daemon to have seen the close.
    REQUIRE(wait_until([&] { return daemon.log().find(": closed") != std::string::npos; }, 5000ms));
    PtyClient p(ep.pty);
    CHECK(p.request(":GP0\n") == ":P0,1000\n");   // the first answer read is its own
    CHECK(p.request(":GNC\n") == ":N3\n");
}

TEST_CASE("pty: faithful timing paces answers at the controller's baud rate", "[e2e][pty]")
{
    // The rate the device asks for (9600 baud from the factory, CB + R) is tested on the
    // device (tests/device/mcs/test_mcs_timing.cpp "faithful_timing: ..."). The pacing itself
    // is the link's (emulator/daemon/link.hpp), in clock time at scale 1: only lower bounds, which a
    // busy machine cannot break.
    Daemon::Options options;
    options.config_json = R"({"devices":[{"name":"mcs0","protocol":"mcs","faithful_timing":true,
        "mcs":{"channels":[{},{},{}]}}]})";
    Daemon daemon(options);
    const Endpoint ep = daemon.endpoint();
    PtyClient p(ep.pty);
    // 100 answers ":N3\n" = 400 bytes = 4000 bits: at the factory 9600 baud (1.2) they
    // cannot arrive in less than 0.41 s; at 115200 baud (CB, effective after R) in 34 ms.
    auto burst = [&] {
        std::string commands;
        for (int i = 0; i < 100; ++i)
            commands += ":GNC\n";
        const auto start = SteadyClock::now();
        p.send(commands);
        for (int i = 0; i < 100; ++i)
            REQUIRE(p.read_line() == std::optional<std::string>(":N3\n"));
        return elapsed_ms(start);
    };
    CHECK(burst() >= 410);
    CHECK(p.request(":CB115200\n") == ":BR114285\n");
    CHECK(p.request(":R\n") == ":E-1,0\n");
    CHECK(burst() >= 34);                                     // still paced
    TcpClient t(ep);                                          // TCP is not a serial line
    CHECK(t.request(":GNC\n") == ":N3\n");
}

namespace {

/// Waits until the daemon has logged the close of `pty` for the `nth` time.
bool wait_for_close(const Daemon& daemon, const std::string& pty, std::size_t nth)
{
    return wait_until([&] { return count_of(daemon.log(), "pty " + pty + ": closed") >= nth; },
                      5000ms);
}

} // namespace

TEST_CASE("pty: a client that floods the port and exits without reading leaves the next one "
          "its whole output allowance",
          "[e2e][pty]")
{
    Daemon daemon;
    const Endpoint ep = daemon.endpoint();
    {
        // More answers than the 1 MiB the daemon keeps for an unread port plus what the pty
        // itself buffers.
        PtyClient flood(ep.pty);
        std::string commands;
        for (int i = 0; i < 350000; ++i)
            commands += ":GNC\n";
        commands += ":SCLS0,1234\n";
        flood.send(commands, 30000ms);
        // Once the last command shows over TCP, the daemon has handled the whole flood.
        TcpClient t(ep);
        REQUIRE(wait_until([&] { return t.request(":GCLS0\n") == ":CLS0,1234\n"; }, 30000ms));
        REQUIRE(daemon.log().find("dropping output") != std::string::npos);
    }
    REQUIRE(wait_for_close(daemon, ep.pty, 1));
    // The queue was cut to the frame being written: the allowance must be whole again. A
    // burst of requests sent before reading any answer needs most of it (12000 answers of
    // 11 bytes: more than the pty buffers, less than 1 MiB with the per-frame overhead).
    PtyClient p(ep.pty);
    CHECK(p.request(":GSI\n") == ":ID3118100\n");
    std::string burst;
    for (int i = 0; i < 12000; ++i)
        burst += ":GSI\n";
    p.send(burst);
    int answers = 0;
    while (auto line = p.read_line()) {
        if (*line != ":ID3118100\n")
            break;
        if (++answers == 12000)
            break;
    }
    CHECK(answers == 12000);
    CHECK(p.request(":GP0\n") == ":P0,0\n");
    CHECK(p.request(":GNC\n") == ":N3\n");
}

TEST_CASE("pty: a process that opens the closed port starts from an empty framer", "[e2e][pty]")
{
    Daemon daemon;

    SECTION("APT: a frame cut short by the last process does not swallow the next request")
    {
        const Endpoint ep = daemon.endpoint("tdc001");
        {
            // MOT_SET_VELPARAMS (0x0413, 14 data bytes): the header and 2 bytes of data.
            PtyClient a(ep.pty);
            a.send(std::string("\x13\x04\x0e\x00\xd0\x01\x01\x00", 8));
        }
        REQUIRE(wait_for_close(daemon, ep.pty, 1));
        PtyClient b(ep.pty);
        // HW_REQ_INFO (0x0005) is answered with HW_GET_INFO (0x0006, 84 data bytes).
        b.send(std::string("\x05\x00\x00\x00\x50\x01", 6));
        std::string answer;
        REQUIRE(wait_until(
            [&] {
                char buf[256];
                const auto n = ::read(b.fd(), buf, sizeof buf);
                if (n > 0)
                    answer.append(buf, static_cast<std::size_t>(n));
                return answer.size() >= 90;
            },
            kAnswerTimeout));
        CHECK(answer.substr(0, 2) == std::string("\x06\x00", 2));
        CHECK(answer.size() == 90);
    }

    SECTION("MCS: a line without its newline is not the start of the next process's line")
    {
        const Endpoint ep = daemon.endpoint("mcs0");
        {
            PtyClient a(ep.pty);
            a.send(":GN");
        }
        REQUIRE(wait_for_close(daemon, ep.pty, 1));
        PtyClient b(ep.pty);
        CHECK(b.request("C\n:GSI\n") == ":ID3118100\n");   // "C\n" alone is no command
        CHECK(b.request(":GNC\n") == ":N3\n");
    }
}

TEST_CASE("pty: a client that leaves ECHO on gets each answer once, with no echo storm",
          "[e2e][pty]")
{
    Daemon daemon;
    const Endpoint ep = daemon.endpoint();
    PtyClient p(ep.pty);
    // A naive client: canonical mode with echo, as a terminal leaves the line.
    termios t{};
    REQUIRE(::tcgetattr(p.fd(), &t) == 0);
    t.c_lflag |= ECHO | ICANON;
    REQUIRE(::tcsetattr(p.fd(), TCSANOW, &t) == 0);

    CHECK(p.request(":GNC\n") == ":N3\n");
    // An echoed answer would come back to the device as a command, and its error answer
    // would be echoed in turn: every further line read here would be one of those.
    std::vector<std::string> extra;
    const auto deadline = SteadyClock::now() + 500ms;
    while (SteadyClock::now() < deadline)
        if (auto line = p.read_line(50ms))
            extra.push_back(*line);
    INFO("first extra line: " << (extra.empty() ? std::string("none") : extra.front()));
    CHECK(extra.empty());
    CHECK(p.request(":GSI\n") == ":ID3118100\n");
    CHECK(daemon.log().find("error 2") == std::string::npos);
}

} // namespace pty_test
