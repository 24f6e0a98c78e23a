// Faults on the wire (emulator/daemon/link.hpp): unplugged, dropped and corrupted bytes, late
// answers. The device behind the link echoes; the clock is stepped.
#include "emulator/daemon/link.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

namespace test_link {

using namespace rigsim;

namespace {

/// Echoes every batch of bytes back, and remembers what it received.
class EchoDevice : public Device {
public:
    std::uint32_t serial_baud() const override { return baud; }
    std::uint32_t baud = 0;
    std::unique_ptr<Session> open_session(SendFn send, std::string) override
    {
        return std::make_unique<EchoSession>(*this, std::move(send));
    }
    std::string received;

private:
    class EchoSession : public Session {
    public:
        EchoSession(EchoDevice& d, SendFn send) : d_(d), send_(std::move(send)) {}
        void receive(std::string_view bytes) override
        {
            d_.received.append(bytes);
            send_(bytes);
        }

    private:
        EchoDevice& d_;
        SendFn send_;
    };
};

struct Fixture {
    Clock clock{1000};
    EchoDevice echo;
    Link link{echo, clock};
    std::string out;
    std::unique_ptr<Session> session = link.open_session([this](std::string_view b) { out.append(b); }, "test");
};

} // namespace

TEST_CASE("a link without faults passes bytes both ways at once", "[link]")
{
    Fixture f;
    f.session->receive("abc");
    CHECK(f.echo.received == "abc");
    CHECK(f.out == "abc");
    CHECK(f.link.next_change(0) == kNever);
}

TEST_CASE("an unplugged link loses bytes both ways until it is plugged in again", "[link]")
{
    Fixture f;
    f.link.set_unplugged(7, true);
    f.session->receive("lost");
    CHECK(f.echo.received.empty());
    CHECK(f.out.empty());
    CHECK(f.link.unplugged());
    CHECK_FALSE(f.link.remove(8));
    CHECK(f.link.remove(7));
    f.session->receive("back");
    CHECK(f.out == "back");
}

TEST_CASE("dropped bytes: with probability 1 every byte of the chosen direction is lost", "[link]")
{
    Fixture f;
    ByteFault drop;
    drop.id = 3;
    drop.inbound = false;   // answers only
    f.link.add(drop);
    f.session->receive("12345");
    CHECK(f.echo.received == "12345");
    CHECK(f.out.empty());
    CHECK(f.link.dropped() == 5);
    REQUIRE(f.link.remove(3));
    f.session->receive("6");
    CHECK(f.out == "6");
}

TEST_CASE("corrupted bytes: each chosen byte has exactly one bit flipped, the same with the same seed", "[link]")
{
    const std::string sent = "hello, world";
    std::string first;
    for (int run = 0; run < 2; ++run) {
        Fixture f;
        ByteFault c;
        c.id = 1;
        c.corrupt = true;
        c.outbound = false;
        c.seed = 42;
        f.link.add(c);
        f.session->receive(sent);
        REQUIRE(f.echo.received.size() == sent.size());
        for (std::size_t i = 0; i < sent.size(); ++i) {
            const unsigned diff = static_cast<unsigned char>(sent[i] ^ f.echo.received[i]);
            CHECK(diff != 0);
            CHECK((diff & (diff - 1)) == 0);   // one bit
        }
        CHECK(f.link.corrupted() == sent.size());
        if (run == 0)
            first = f.echo.received;
        else
            CHECK(f.echo.received == first);
    }
}

TEST_CASE("a probability of 0.5 drops about half of the bytes, deterministically per seed", "[link]")
{
    Fixture f;
    ByteFault drop;
    drop.id = 1;
    drop.outbound = false;
    drop.probability = 0.5;
    f.link.add(drop);
    f.session->receive(std::string(10000, 'x'));
    CHECK(f.echo.received.size() > 4500);
    CHECK(f.echo.received.size() < 5500);
}

TEST_CASE("latency holds answers for clock time, in order, and a step releases them", "[link]")
{
    Fixture f;
    LatencyFault late;
    late.id = 9;
    late.latency = 50;
    late.jitter = 20;
    f.link.add(late);
    f.session->receive("a");
    f.clock.advance(1);
    f.session->receive("b");
    CHECK(f.out.empty());
    CHECK(f.link.held() == 2);
    CHECK(f.link.next_change(f.clock.now()) >= 50);
    f.clock.advance(49);   // tick 50: not yet past the shortest possible delay of "b"
    f.clock.advance(21);   // tick 71: both due (50 + 20 at most, "b" no earlier than "a")
    CHECK(f.out == "ab");
    CHECK(f.link.held() == 0);
    CHECK(f.link.remove(9));
    f.session->receive("c");
    CHECK(f.out == "abc");
}

TEST_CASE("a clock that keeps its schedule sees every answer the link holds, and when the last goes",
          "[link][clock]")
{
    // The daemon's clock asks the link again only when the link announces a change
    // (models/clock.hpp, "The schedule"): an answer held and not announced would never go out.
    Fixture f;
    f.clock.keep_schedule();
    CHECK(f.clock.next_wakeup() == kNever);
    LatencyFault late;
    late.id = 4;
    late.latency = 30;
    f.link.add(late);
    f.session->receive("a");
    CHECK(f.clock.next_wakeup() == 30);
    f.clock.advance(10);
    f.session->receive("b");
    CHECK(f.clock.next_wakeup() == 30);   // "b" goes out after "a", at 40
    f.clock.advance(20);
    CHECK(f.out == "a");
    CHECK(f.clock.next_wakeup() == 40);
    f.clock.advance(10);
    CHECK(f.out == "ab");
    CHECK(f.clock.next_wakeup() == kNever);
    f.session->receive("c");
    f.link.reset();   // held answers dropped: the link is idle again
    CHECK(f.clock.next_wakeup() == kNever);
    f.clock.advance(100);
    CHECK(f.out == "ab");
}

TEST_CASE("a paused clock holds late answers: nothing goes out without clock time", "[link]")
{
    Fixture f;
    LatencyFault late;
    late.id = 2;
    late.latency = 10;
    f.link.add(late);
    f.session->receive("x");
    f.clock.advance(9);
    CHECK(f.out.empty());
    f.clock.advance(1);
    CHECK(f.out == "x");
}

TEST_CASE("faithful timing: a serial line's answers arrive when the line has carried them, in clock time",
          "[link]")
{
    Clock clock{1000};
    EchoDevice echo;
    echo.baud = 9600;
    Link link{echo, clock};
    CHECK(link.serial_baud() == 0);   // the transport must not pace a second time
    std::string pty_out, tcp_out;
    auto pty = link.open_session([&](std::string_view b) { pty_out.append(b); }, "pty /tmp/x/mcs0");
    auto tcp = link.open_session([&](std::string_view b) { tcp_out.append(b); }, "tcp 127.0.0.1:5000");
    tcp->receive(std::string(96, 't'));
    CHECK(tcp_out.size() == 96);   // TCP is not a serial line
    pty->receive(std::string(96, 'a'));   // 960 bits at 9600 baud: 100 ms
    pty->receive(std::string(48, 'b'));   // 50 ms more, after the first
    CHECK(pty_out.empty());
    clock.advance(99);
    CHECK(pty_out.empty());
    clock.advance(1);
    CHECK(pty_out == std::string(96, 'a'));
    clock.advance(49);
    CHECK(pty_out.size() == 96);
    clock.advance(1);
    CHECK(pty_out.size() == 144);
    // The line idle since: the next answer starts now.
    clock.advance(1000);
    pty->receive(std::string(10, 'c'));   // 100 bits: 10.4 ms -> 11 ticks
    clock.advance(10);
    CHECK(pty_out.size() == 144);
    clock.advance(1);
    CHECK(pty_out.size() == 154);
}

TEST_CASE("a reset link has no fault, holds no answer, its line idle and its counters at 0", "[link]")
{
    Fixture f;
    LatencyFault late;
    late.id = 4;
    late.latency = 1000;
    f.link.add(late);
    ByteFault drop;
    drop.id = 5;
    drop.inbound = false;
    drop.probability = 0.5;
    f.link.add(drop);
    f.session->receive(std::string(100, 'x'));
    REQUIRE(f.link.held() > 0);
    REQUIRE(f.link.dropped() > 0);
    f.link.set_unplugged(6, true);
    f.link.reset();
    CHECK(f.link.held() == 0);
    CHECK(f.link.dropped() == 0);
    CHECK_FALSE(f.link.unplugged());
    CHECK(f.link.latency_id() == 0);
    f.clock.advance(2000);
    CHECK(f.out.empty());   // the held answer of before the reset never comes
    f.session->receive("y");
    CHECK(f.out == "y");
}

} // namespace test_link
