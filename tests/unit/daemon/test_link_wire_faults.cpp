// The wire faults that real links have (emulator/daemon/link.hpp): answers sliced, a byte rate,
// connections reset or closed (fast, slow, after a hang, after N bytes, after garbage), a serial
// unit's receive buffer overrun, a client at the wrong baud rate; and the output bound that held
// bytes share with the transport's queue. The device behind the link echoes; the clock is
// stepped; the transport is a recording Connection.
#include "emulator/daemon/link.hpp"

#include <catch2/catch.hpp>

#include <spdlog/sinks/ostream_sink.h>

#include <sstream>
#include <string>
#include <vector>

namespace test_link_wire_faults {

using namespace rigsim;

namespace {

/// Echoes every batch of bytes back, and remembers what it received.
class EchoDevice : public Device {
public:
    std::uint32_t serial_baud() const override { return baud; }
    std::uint32_t line_baud() const override { return unit_baud; }
    std::uint32_t baud = 0;
    std::uint32_t unit_baud = 9600;
    std::unique_ptr<Session> open_session(SendFn send, std::string) override
    {
        return std::make_unique<EchoSession>(*this, std::move(send));
    }
    std::string received;
    bool echo = true;

private:
    class EchoSession : public Session {
    public:
        EchoSession(EchoDevice& d, SendFn send) : d_(d), send_(std::move(send)) {}
        void receive(std::string_view bytes) override
        {
            d_.received.append(bytes);
            if (d_.echo)
                send_(bytes);
        }

    private:
        EchoDevice& d_;
        SendFn send_;
    };
};

/// The transport's side of one connection: every write kept apart, the hang-ups asked for.
struct Transport {
    std::vector<std::string> writes;
    std::vector<Hangup> hangups;
    std::size_t queued = 0;
    std::uint32_t client_baud = 9600;
    std::string all() const
    {
        std::string s;
        for (const auto& w : writes)
            s += w;
        return s;
    }
    Connection connection(std::size_t bound = 4096)
    {
        Connection c;
        c.hangup = [this](Hangup how) { hangups.push_back(how); };
        c.queued_bytes = [this] { return queued; };
        c.max_queued_bytes = bound;
        c.frame_overhead = 64;
        c.client_baud = [this] { return client_baud; };
        return c;
    }
};

struct Fixture {
    explicit Fixture(std::string peer = "tcp 127.0.0.1:5000", std::size_t bound = 4096)
    {
        session = link.open_connection([this](std::string_view b) { t.writes.emplace_back(b); },
                                       t.connection(bound), std::move(peer));
    }
    std::ostringstream log_text;
    Clock clock{1000};
    EchoDevice echo;
    Link link{echo, clock,
              std::make_shared<spdlog::logger>("link", std::make_shared<spdlog::sinks::ostream_sink_st>(log_text))};
    Transport t;
    std::unique_ptr<Session> session;
};

} // namespace

TEST_CASE("slicer: answers go out in slices of slice_bytes, gap_ms apart on the clock", "[link]")
{
    Fixture f;
    SliceFault s;
    s.id = 1;
    s.slice_bytes = 3;
    s.gap = 10;
    f.link.add(s);
    f.session->receive("abcdefgh");
    CHECK(f.echo.received == "abcdefgh");   // the client's bytes are not sliced
    CHECK(f.t.writes == std::vector<std::string>{"abc"});
    f.clock.advance(9);
    CHECK(f.t.writes.size() == 1);
    f.clock.advance(1);
    CHECK(f.t.writes == std::vector<std::string>{"abc", "def"});
    f.clock.advance(10);
    CHECK(f.t.writes == std::vector<std::string>{"abc", "def", "gh"});
    // The next answer's first slice keeps the gap after the last one.
    f.session->receive("ij");
    CHECK(f.t.writes.size() == 3);
    f.clock.advance(10);
    CHECK(f.t.writes.back() == "ij");
    REQUIRE(f.link.remove(1));
    f.session->receive("klmnop");
    CHECK(f.t.writes.back() == "klmnop");
}

TEST_CASE("slicer without a gap: one write per slice, all at once", "[link]")
{
    Fixture f;
    SliceFault s;
    s.id = 1;
    s.slice_bytes = 1;
    f.link.add(s);
    f.session->receive("xyz");
    CHECK(f.t.writes == std::vector<std::string>{"x", "y", "z"});
}

TEST_CASE("bandwidth: answers trickle out at bytes_per_s of clock time, held while the clock stands", "[link]")
{
    Fixture f;
    BandwidthFault b;
    b.id = 2;
    b.bytes_per_s = 100;   // a byte each 10 ms
    b.inbound = false;
    f.link.add(b);
    f.session->receive("12345");
    CHECK(f.echo.received == "12345");   // in: not limited
    CHECK(f.t.all().empty());
    f.clock.advance(10);
    CHECK(f.t.all() == "1");
    f.clock.advance(25);
    CHECK(f.t.all() == "123");
    f.clock.advance(15);
    CHECK(f.t.all() == "12345");
    CHECK(f.link.next_change(f.clock.now()) == kNever);
}

TEST_CASE("bandwidth in: the client's bytes reach the device at bytes_per_s", "[link]")
{
    Fixture f;
    BandwidthFault b;
    b.id = 2;
    b.bytes_per_s = 1000;   // a byte a tick
    b.outbound = false;
    f.link.add(b);
    f.session->receive("abcd");
    CHECK(f.echo.received.empty());
    f.clock.advance(2);
    CHECK(f.echo.received == "ab");
    CHECK(f.t.all() == "ab");   // answered as it arrives; out is not limited
    f.clock.advance(2);
    CHECK(f.echo.received == "abcd");
}

TEST_CASE("reset: after after_ms from the first client byte the transport is asked to reset, held answers lost",
          "[link]")
{
    Fixture f;
    LatencyFault late;
    late.id = 1;
    late.latency = 100;
    f.link.add(late);
    CloseFault r;
    r.id = 2;
    r.kind = CloseKind::Reset;
    r.delay = 50;
    f.link.add(r);
    f.clock.advance(20);
    CHECK(f.link.next_change(f.clock.now()) == kNever);   // no client byte yet: nothing runs
    f.session->receive("q");
    CHECK(f.link.held() == 1);
    f.clock.advance(49);
    CHECK(f.t.hangups.empty());
    f.clock.advance(1);
    CHECK(f.t.hangups == std::vector<Hangup>{Hangup::Reset});
    CHECK(f.link.held() == 0);
    f.clock.advance(200);
    CHECK(f.t.writes.empty());   // the late answer never comes
    f.session->receive("more");
    CHECK(f.echo.received == "q");   // a closed connection carries nothing
    CHECK(f.t.hangups.size() == 1);
}

TEST_CASE("reset with after_ms 0 on a used connection acts at once, a paused clock or not", "[link]")
{
    Fixture f;
    f.session->receive("a");
    CloseFault r;
    r.id = 2;
    r.kind = CloseKind::Reset;
    f.link.add(r);
    CHECK(f.t.hangups == std::vector<Hangup>{Hangup::Reset});
}

TEST_CASE("slow_close: answers flow until delay_ms, then held ones go out and the connection closes", "[link]")
{
    Fixture f;
    f.session->receive("a");
    CloseFault c;
    c.id = 3;
    c.kind = CloseKind::SlowClose;
    c.delay = 100;
    f.link.add(c);
    BandwidthFault b;
    b.id = 4;
    b.bytes_per_s = 100;
    b.inbound = false;
    f.link.add(b);
    f.clock.advance(95);
    f.session->receive("bcd");   // out at 105, 115, 125
    f.clock.advance(5);
    CHECK(f.t.hangups.empty());   // closing: the held answer goes out first
    CHECK(f.t.all() == "a");
    f.session->receive("lost");   // nothing more reaches the device
    CHECK(f.echo.received == "abcd");
    f.clock.advance(25);
    CHECK(f.t.all() == "abcd");
    CHECK(f.t.hangups == std::vector<Hangup>{Hangup::Close});
}

TEST_CASE("hang_close: nothing more passes at once, the connection closes close_after_ms later", "[link]")
{
    Fixture f;
    f.session->receive("a");
    CloseFault h;
    h.id = 5;
    h.kind = CloseKind::HangClose;
    h.delay = 30;
    f.link.add(h);
    f.session->receive("b");
    CHECK(f.echo.received == "a");
    CHECK(f.t.all() == "a");
    f.clock.advance(29);
    CHECK(f.t.hangups.empty());
    f.clock.advance(1);
    CHECK(f.t.hangups == std::vector<Hangup>{Hangup::Close});
}

TEST_CASE("hang_close on a connection opened while it lasts: silent, closed close_after_ms after its first byte",
          "[link]")
{
    Fixture f;
    CloseFault h;
    h.id = 5;
    h.kind = CloseKind::HangClose;
    h.delay = 30;
    f.link.add(h);
    f.clock.advance(100);
    Transport late;
    auto s = f.link.open_connection([&](std::string_view b) { late.writes.emplace_back(b); }, late.connection(),
                                    "tcp 127.0.0.1:5001");
    s->receive("x");
    CHECK(late.writes.empty());
    f.clock.advance(29);
    CHECK(late.hangups.empty());
    f.clock.advance(1);
    CHECK(late.hangups == std::vector<Hangup>{Hangup::Close});
}

TEST_CASE("cut_after out: exactly N more answer bytes, then the connection closes", "[link]")
{
    Fixture f;
    f.session->receive("ab");
    CloseFault c;
    c.id = 6;
    c.kind = CloseKind::CutAfter;
    c.bytes = 5;
    f.link.add(c);
    f.session->receive("cde");
    CHECK(f.t.hangups.empty());
    f.session->receive("fghij");
    CHECK(f.t.all() == "abcdefg");
    CHECK(f.t.hangups == std::vector<Hangup>{Hangup::Close});
    f.session->receive("k");
    CHECK(f.echo.received == "abcdefghij");
}

TEST_CASE("cut_after in: N client bytes reach the device, are answered, then the connection closes", "[link]")
{
    Fixture f;
    CloseFault c;
    c.id = 6;
    c.kind = CloseKind::CutAfter;
    c.bytes = 3;
    c.inbound = true;
    f.link.add(c);
    f.session->receive("12345");
    CHECK(f.echo.received == "123");
    CHECK(f.t.all() == "123");
    CHECK(f.t.hangups == std::vector<Hangup>{Hangup::Close});
}

TEST_CASE("cut_after 0 closes every connection at once", "[link]")
{
    Fixture f;
    CloseFault c;
    c.id = 6;
    c.kind = CloseKind::CutAfter;
    f.link.add(c);
    CHECK(f.t.hangups == std::vector<Hangup>{Hangup::Close});
}

TEST_CASE("garbage_close: N seeded random bytes replace held answers, then the connection closes", "[link]")
{
    std::string first;
    for (int run = 0; run < 2; ++run) {
        Fixture f;
        LatencyFault late;
        late.id = 1;
        late.latency = 1000;
        f.link.add(late);
        f.session->receive("held");
        CloseFault g;
        g.id = 7;
        g.kind = CloseKind::GarbageClose;
        g.bytes = 16;
        g.seed = 99;
        g.delay = 10;
        f.link.add(g);
        f.clock.advance(10);
        REQUIRE(f.t.writes.size() == 1);
        CHECK(f.t.writes[0].size() == 16);
        CHECK(f.t.hangups == std::vector<Hangup>{Hangup::Close});
        f.clock.advance(2000);
        CHECK(f.t.writes.size() == 1);
        if (run == 0)
            first = f.t.writes[0];
        else
            CHECK(f.t.writes[0] == first);
    }
}

TEST_CASE("a closing fault ended before it acts closes nothing", "[link]")
{
    Fixture f;
    f.session->receive("a");
    CloseFault r;
    r.id = 2;
    r.kind = CloseKind::Reset;
    r.delay = 50;
    f.link.add(r);
    f.clock.advance(10);
    REQUIRE(f.link.remove(2));
    f.clock.advance(100);
    CHECK(f.t.hangups.empty());
    CHECK(f.link.next_change(f.clock.now()) == kNever);
}

TEST_CASE("a clock that keeps its schedule wakes for a pending close", "[link][clock]")
{
    Fixture f;
    f.clock.keep_schedule();
    CloseFault r;
    r.id = 2;
    r.kind = CloseKind::Reset;
    r.delay = 40;
    f.link.add(r);
    CHECK(f.clock.next_wakeup() == kNever);
    f.clock.advance(5);
    f.session->receive("a");   // the delay runs from here
    CHECK(f.clock.next_wakeup() == 45);
    f.clock.advance(40);
    CHECK(f.t.hangups.size() == 1);
    CHECK(f.clock.next_wakeup() == kNever);
}

TEST_CASE("overrun: a serial unit's receive buffer loses the bytes beyond it and drains on the clock", "[link]")
{
    Fixture f("pty /tmp/x/mcs0");
    Transport tcp;
    auto socket = f.link.open_connection([&](std::string_view b) { tcp.writes.emplace_back(b); }, tcp.connection(),
                                         "tcp 127.0.0.1:5001");
    OverrunFault o;
    o.id = 8;
    o.buffer_bytes = 4;
    o.drain_bytes_per_s = 100;   // a byte each 10 ms
    f.link.add(o);
    f.session->receive("abcdefg");
    CHECK(f.echo.received == "abcd");
    CHECK(f.link.dropped() == 3);
    f.clock.advance(20);   // two bytes drained
    f.session->receive("hij");
    CHECK(f.echo.received == "abcdhi");
    f.clock.advance(1000);   // a paused clock would keep it full; this one drains it
    f.session->receive("klmn");
    CHECK(f.echo.received == "abcdhiklmn");
    f.echo.received.clear();
    socket->receive("not a serial line: never overruns");
    CHECK(f.echo.received == "not a serial line: never overruns");
}

TEST_CASE("uart_resample: the same rate reads the bytes back, another reads garbage, deterministically",
          "[link]")
{
    const std::string sent = ":GS0\n";
    CHECK(uart_resample(sent, 9600, 9600) == sent);
    const auto slow_reader = uart_resample(sent, 115200, 9600);   // 12 sent bits per read bit
    const auto fast_reader = uart_resample(sent, 9600, 115200);
    CHECK(slow_reader != sent);
    CHECK(fast_reader != sent);
    CHECK(slow_reader.size() <= 1);   // five bytes in less than one read byte time
    CHECK(fast_reader.size() >= sent.size());   // each sent start bit reads as a byte of zeros at least
    CHECK(fast_reader[0] == '\0');
    CHECK(uart_resample(sent, 9600, 115200) == fast_reader);
    CHECK(uart_resample("", 9600, 115200).empty());
    // Twice as fast a sender: one read bit spans two sent bits, so a 0x00 (nine bits low) reads
    // as its low half and the idle line after it.
    CHECK(uart_resample(std::string(1, '\0'), 19200, 9600) == "\xF8");
}

TEST_CASE("baud_mismatch: a serial client at another rate than the unit's is garbled both ways", "[link]")
{
    Fixture f("pty /tmp/x/mcs0");
    BaudMismatchFault b;
    b.id = 9;
    f.link.add(b);
    f.t.client_baud = 9600;   // the unit's too: nothing changes
    f.session->receive(":GS0\n");
    CHECK(f.echo.received == ":GS0\n");
    CHECK(f.t.all() == ":GS0\n");
    f.echo.received.clear();
    f.t.writes.clear();
    f.t.client_baud = 115200;
    f.session->receive(":GS0\n");
    CHECK(f.echo.received == uart_resample(":GS0\n", 115200, 9600));
    CHECK(f.t.all() == uart_resample(f.echo.received, 9600, 115200));
    CHECK(f.link.corrupted() == 5 + f.echo.received.size());
    REQUIRE(f.link.remove(9));
    f.echo.received.clear();
    f.session->receive(":GS0\n");
    CHECK(f.echo.received == ":GS0\n");
}

TEST_CASE("held answers count in the connection's output bound with what the transport has queued", "[link]")
{
    Fixture f("tcp 127.0.0.1:5000", 1000);
    LatencyFault late;
    late.id = 1;
    late.latency = 10;
    f.link.add(late);
    f.t.queued = 500;
    f.session->receive(std::string(200, 'a'));   // 264 held + 500 queued: fits
    f.session->receive(std::string(200, 'b'));   // 528 + 500: beyond 1000, dropped
    CHECK(f.link.held() == 1);
    CHECK(f.link.dropped() == 200);
    CHECK(f.log_text.str().find("dropping answers beyond the connection's bound (1000 bytes)") != std::string::npos);
    f.session->receive(std::string(200, 'c'));   // dropped too: one warning for the run
    CHECK(f.log_text.str().find("dropping answers", f.log_text.str().find("dropping answers") + 1) == std::string::npos);
    f.t.queued = 0;
    f.session->receive(std::string(10, 'd'));
    CHECK(f.log_text.str().find("dropped 400 bytes of answers") != std::string::npos);
    f.clock.advance(10);
    CHECK(f.t.all() == std::string(200, 'a') + std::string(10, 'd'));
}

TEST_CASE("a session whose connection has no bound of its own holds at most kMaxHeldBytes", "[link]")
{
    Clock clock{1000};
    EchoDevice echo;
    Link link{echo, clock};
    std::string out;
    auto s = link.open_session([&](std::string_view b) { out.append(b); }, "test");
    LatencyFault late;
    late.id = 1;
    late.latency = 10;
    link.add(late);
    const std::string chunk(64 * 1024, 'x');
    for (int i = 0; i < 20; ++i)
        s->receive(chunk);
    CHECK(link.held() == 15);   // 15 x (64 KiB + 64) fit in 1 MiB; the 16th would not
    CHECK(link.dropped() == 5 * chunk.size());
}

TEST_CASE("reset ends the new faults and forgets pending closes", "[link]")
{
    Fixture f;
    f.session->receive("a");
    CloseFault r;
    r.id = 2;
    r.kind = CloseKind::Reset;
    r.delay = 50;
    f.link.add(r);
    SliceFault s;
    s.id = 3;
    s.slice_bytes = 1;
    f.link.add(s);
    f.link.reset();
    f.clock.advance(100);
    CHECK(f.t.hangups.empty());
    f.session->receive("bc");
    CHECK(f.t.writes.back() == "bc");
}

} // namespace test_link_wire_faults
