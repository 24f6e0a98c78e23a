// The daemon's TCP endpoint: sessions, several clients, disconnects, and oversize input that
// must not hurt the daemon or a bystander. What the MCS protocol answers is tested on the
// stepped clock (tests/device/mcs) and replayed over TCP by transcript_test.cpp.

#include <catch2/catch.hpp>

#include <algorithm>
#include <regex>
#include <string>
#include <vector>

#include "e2e_support.hpp"

namespace tcp_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {

bool all_match(const std::vector<std::string>& answers, const std::string& pattern)
{
    const std::regex re(pattern);
    return std::all_of(answers.begin(), answers.end(),
                       [&](const std::string& a) { return std::regex_match(a, re); });
}

} // namespace

TEST_CASE("TCP: two clients at once each get only their own answers, in order", "[e2e][tcp]")
{
    Daemon daemon;
    TcpClient a(daemon.endpoint());
    TcpClient b(daemon.endpoint());

    SECTION("one request each, alternating")
    {
        a.send(":GNC\n");
        b.send(":GSI\n");
        CHECK(b.read_line() == ":ID3118100\n");
        CHECK(a.read_line() == ":N3\n");
        b.send(":GCT0\n");
        a.send(":GP7\n");
        CHECK(a.read_line() == ":E-1,7\n");
        CHECK(b.read_line() == ":CT0,0\n");
    }

    SECTION("pipelined requests whose bytes interleave on the wire")
    {
        REQUIRE(a.request(":SCLS1,2000000\n") == ":E-1,0\n");
        REQUIRE(b.request(":SCLS2,3000000\n") == ":E-1,0\n");
        const std::string to_a = ":GNC\n:GCLS1\n:GP7\n:GST0\n";
        const std::string to_b = ":GSI\n:GCLS2\n:FOO\n:GCT2\n";
        // One byte at a time from each client in turn: each session reassembles its own
        // commands however they are split.
        for (std::size_t i = 0; i < std::max(to_a.size(), to_b.size()); ++i) {
            if (i < to_a.size())
                a.send(to_a.substr(i, 1));
            if (i < to_b.size())
                b.send(to_b.substr(i, 1));
        }
        CHECK(a.read_line() == ":N3\n");
        CHECK(a.read_line() == ":CLS1,2000000\n");
        CHECK(a.read_line() == ":E-1,7\n");
        CHECK(a.read_line() == ":ST0,1\n");
        CHECK(b.read_line() == ":ID3118100\n");
        CHECK(b.read_line() == ":CLS2,3000000\n");
        CHECK(b.read_line() == ":E-1,2\n");
        CHECK(b.read_line() == ":CT2,0\n");
    }

    SECTION("a move by one client is seen by the other")
    {
        REQUIRE(a.request(":MPA1,1000000,0\n") == ":E1,0\n");
        CHECK(poll_status_until(b, 1, 0, 3000ms));
        CHECK(b.request(":GP1\n") == ":P1,1000000\n");
        CHECK(a.request(":GP1\n") == ":P1,1000000\n");
    }

    // Nothing stray is left queued for either client: the next answer is its own.
    CHECK(a.request(":GNC\n") == ":N3\n");
    CHECK(b.request(":GNC\n") == ":N3\n");
}

TEST_CASE("TCP: a client that disconnects mid-move does not lose the move", "[e2e][tcp]")
{
    Daemon daemon;
    {
        TcpClient a(daemon.endpoint());
        // 1 mm/s: the 0.8 mm move takes about 0.8 s.
        REQUIRE(a.request(":SCLS0,1000000\n") == ":E-1,0\n");
        REQUIRE(a.request(":MPA0,800000,0\n") == ":E0,0\n");
        REQUIRE(a.request(":GS0\n") == ":S0,4\n");

        SECTION("closed with a FIN")
        {
            a.close();
        }
        SECTION("reset with an RST while answers are pending")
        {
            // Unread answers plus an abortive close: the daemon's writes to this session
            // fail (ECONNRESET/EPIPE); that must end the session only.
            for (int i = 0; i < 50; ++i)
                a.send(":GP0\n");
            a.abort();
        }
    }

    TcpClient b(daemon.endpoint());
    const std::string first = b.request(":GS0\n");
    INFO("first status after the disconnect: " << first);
    CHECK((first == ":S0,4\n" || first == ":S0,0\n"));
    std::vector<std::string> seen;
    CHECK(poll_status_until(b, 0, 0, 5000ms, &seen));
    CHECK(all_match(seen, ":S0,[04]\n"));
    CHECK(b.request(":GP0\n") == ":P0,800000\n");
    CHECK(b.request(":GCLS0\n") == ":CLS0,1000000\n");
    CHECK(b.request(":GNC\n") == ":N3\n");
    CHECK(daemon.running());
}

TEST_CASE("TCP: an oversize line is answered E-1,1 and leaves the daemon and a bystander working", "[e2e][tcp]")
{
    Daemon daemon;
    TcpClient a(daemon.endpoint());
    TcpClient b(daemon.endpoint()); // a bystander that must keep working throughout

    SECTION("an oversize line is discarded and answered E-1,1 at its newline")
    {
        const std::string body(300, 'A');
        a.send(":" + body.substr(0, 150));
        CHECK(b.request(":GNC\n") == ":N3\n");
        a.send(body.substr(150) + "\n");
        CHECK(a.read_line() == ":E-1,1\n");
        CHECK(a.request(":GNC\n") == ":N3\n");
    }

    SECTION("a 10 MB line without a newline does not hurt the daemon")
    {
        constexpr std::size_t kTotal = 10u * 1024u * 1024u;
        constexpr std::size_t kChunk = 256u * 1024u;
        const std::string chunk(kChunk, 'A');
        a.send(":");
        const auto start = SteadyClock::now();
        for (std::size_t sent = 0; sent < kTotal; sent += kChunk) {
            // A send that cannot complete means the daemon stopped reading this client.
            a.send(chunk, 10000ms);
            if ((sent / kChunk) % 8 == 0)
                REQUIRE(b.request(":GNC\n") == ":N3\n");
        }
        INFO("10 MB sent in " << elapsed_ms(start) << " ms");
        CHECK(b.request(":GSI\n") == ":ID3118100\n");
        a.send("\n:GNC\n");
        CHECK(a.read_line() == ":E-1,1\n");
        CHECK(a.read_line() == ":N3\n");
        CHECK(a.request(":GSI\n") == ":ID3118100\n");
    }

    CHECK(b.request(":GNC\n") == ":N3\n");
    CHECK(a.request(":GNC\n") == ":N3\n");
    CHECK(daemon.running());
}

} // namespace tcp_test
