// TcpEndpoint (emulator/transport/tcp_endpoint.hpp) on loopback sockets, driven by an
// io_context the test runs: answers larger than the socket buffers, a client that stops
// reading (dropped beyond kMaxQueuedBytes), clients that go away, and what the other clients
// and devices see meanwhile. The device behind the endpoint records its sessions and echoes.
#include "emulator/transport/tcp_endpoint.hpp"

#include "tests/unit/transport/endpoint_harness.hpp"

#include <catch2/catch.hpp>

#include <boost/asio/ip/address.hpp>

#include <memory>
#include <string>
#include <vector>

namespace test_tcp_endpoint {

using namespace rigsim;
using namespace rigsim::test;

namespace {

/// A receive buffer the kernel rounds up to a few KiB: the client's window stays small.
constexpr int kSmallReceiveBuffer = 4096;

/// Two devices of a rig on 127.0.0.1, each with its TCP endpoint, sharing one budget.
struct Fixture {
    explicit Fixture(TcpConnectionBudget limits = {}) : budget(limits)
    {
        endpoint.start();
        other_endpoint.start();
    }
    ~Fixture()
    {
        // As the daemon shuts down: stop, then let the cancelled handlers release what they hold.
        endpoint.stop();
        other_endpoint.stop();
        io.restart();
        io.poll();
    }

    /// The session of `client`'s connection, once the endpoint has accepted it.
    std::shared_ptr<SessionRecord> session_of(RecordingDevice& d, const ClientFd& client)
    {
        const auto peer = tcp_peer_of(client);
        std::shared_ptr<SessionRecord> found;
        run_until(io, [&] {
            for (const auto& s : d.sessions)
                if (s->peer == peer)
                    found = s;
            return found != nullptr;
        });
        REQUIRE(found);
        return found;
    }

    /// Sends `request` and reads until as many bytes have come back (the devices echo) or
    /// the stream has ended.
    std::string echo(ClientFd& client, const std::string& request)
    {
        client.write(request);
        std::string got;
        run_until(io, [&] {
            return client.read_some(got) == ClientFd::Read::End || got.size() >= request.size();
        });
        return got;
    }

    boost::asio::io_context io;
    CapturedLog log;
    RecordingDevice device;
    RecordingDevice other;
    TcpConnectionBudget budget;
    TcpEndpoint endpoint{io, device, boost::asio::ip::make_address("127.0.0.1"), 0, log.logger, budget};
    TcpEndpoint other_endpoint{io, other, boost::asio::ip::make_address("127.0.0.1"), 0, log.logger, budget};
};

} // namespace

TEST_CASE("transport tcp: a large answer read slowly in small pieces arrives whole and in order",
          "[unit][transport][tcp]")
{
    Fixture f;
    // Three rounds of a 1 MiB frame, a 13-byte one and one of 4 KiB + 1: 3 MiB in all, under
    // the 4 MiB a connection may have queued. A frame of 1 MiB is more than a small receive
    // window and the socket's send buffer hold, so the endpoint writes it in parts as the
    // client makes room; the small frames behind it must wait their turn.
    const std::vector<std::size_t> sizes{1 << 20, 13, 4097, 1 << 20, 13, 4097, 1 << 20, 13, 4097};
    std::size_t total = 0;
    for (const auto size : sizes)
        total += size;
    REQUIRE(total + sizes.size() * TcpEndpoint::kQueuedFrameOverhead <= TcpEndpoint::kMaxQueuedBytes);
    f.device.answer = [&](SessionRecord& s, std::string_view) {
        if (s.received != "big\n")
            return;
        std::size_t at = 0;
        for (const auto size : sizes) {
            s.send(stream_bytes(at, size));
            at += size;
        }
    };
    auto client = connect_tcp(f.endpoint.port(), kSmallReceiveBuffer);
    client.write("big\n");

    const auto got = read_in_pieces(f.io, client, total, 997);

    CHECK(difference(got, stream_bytes(0, total)) == "");
    CHECK(f.device.open_sessions() == 1);   // the connection is still open
    CHECK(f.log.count("reads nothing") == 0);
}

TEST_CASE("transport tcp: an answer with nothing queued ahead of it is written at once, before the loop runs "
          "again, and one queued behind a partly written frame waits its turn",
          "[unit][transport][tcp]")
{
    Fixture f;
    auto client = connect_tcp(f.endpoint.port(), kSmallReceiveBuffer);
    const auto session = f.session_of(f.device, client);
    session->send("at once\n");   // outside the loop: no handler runs before the client reads
    std::string got;
    CHECK(client.read_some(got) == ClientFd::Read::Data);
    CHECK(got == "at once\n");

    // More than the socket takes: the rest of it is queued, and so is what follows it.
    constexpr std::size_t kBig = 1 << 20;
    static_assert(kBig + 5 + 2 * TcpEndpoint::kQueuedFrameOverhead <= TcpEndpoint::kMaxQueuedBytes);
    session->send(stream_bytes(0, kBig));
    session->send("after");
    got = read_in_pieces(f.io, client, kBig + 5, 65536);
    CHECK(difference(got, stream_bytes(0, kBig) + "after") == "");
    CHECK(f.log.count("reads nothing") == 0);
}

TEST_CASE("transport tcp: a client that stops reading is dropped once its queue passes "
          "kMaxQueuedBytes, and the other clients and devices keep working",
          "[unit][transport][tcp]")
{
    Fixture f;
    // A queued frame costs its bytes and kQueuedFrameOverhead until it has been written
    // whole; the frame that takes the total past kMaxQueuedBytes ends the connection. Frames
    // of 64 KiB (+ 64): 63 fit in 4 MiB, the 64th not yet written tips it over.
    constexpr std::size_t kFrameBytes = 64 * 1024;
    constexpr std::size_t kFrameCost = kFrameBytes + TcpEndpoint::kQueuedFrameOverhead;
    constexpr std::size_t kUnwrittenAtDrop = TcpEndpoint::kMaxQueuedBytes / kFrameCost + 1;
    static_assert(kUnwrittenAtDrop == 64);

    auto slow = connect_tcp(f.endpoint.port(), kSmallReceiveBuffer);
    auto bystander = connect_tcp(f.endpoint.port());
    auto other_client = connect_tcp(f.other_endpoint.port());
    const auto slow_session = f.session_of(f.device, slow);
    f.session_of(f.device, bystander);
    f.session_of(f.other, other_client);
    REQUIRE(f.budget.open_total == 3);

    // The device sends on its own (as APT status updates do), one frame at a time, the loop
    // run after each so that the endpoint writes what the kernel takes, until the connection
    // is dropped.
    std::size_t sent = 0;
    while (f.log.count("reads nothing") == 0 && sent < 4 * kUnwrittenAtDrop + 1000) {
        slow_session->send(stream_bytes(sent * kFrameBytes, kFrameBytes));
        ++sent;
        f.io.restart();
        f.io.poll();
    }
    REQUIRE(f.log.count("reads nothing") == 1);
    CHECK(run_until(f.io, [&] { return !slow_session->open; }));
    CHECK(f.budget.open_total == 2);

    // What the kernel had taken still arrives, in order, then the end of the stream: those
    // whole frames had been written; the rest (the frame in the middle of its write and the
    // ones behind it, the last one included) were what the endpoint held.
    std::string got;
    ClientFd::Read last = ClientFd::Read::Nothing;
    CHECK(run_until(f.io, [&] {
        while ((last = slow.read_some(got)) == ClientFd::Read::Data) {
        }
        return last == ClientFd::Read::End;
    }));
    CHECK(difference(got, stream_bytes(0, got.size())) == "");
    const std::size_t written = got.size() / kFrameBytes;
    INFO(sent << " frames sent; the kernel took " << got.size() << " bytes");
    CHECK(sent - written == kUnwrittenAtDrop);

    // Nobody else noticed.
    CHECK(f.echo(bystander, "still here\n") == "still here\n");
    CHECK(f.echo(other_client, "me too\n") == "me too\n");
    CHECK(f.device.open_sessions() == 1);
    CHECK(f.other.open_sessions() == 1);
}

TEST_CASE("transport tcp: a client that goes away is noticed, its session released and its "
          "place given to the next client",
          "[unit][transport][tcp]")
{
    // One connection per device: the next client is refused unless the first one's place
    // has been given back.
    Fixture f(TcpConnectionBudget{256, 1, 0});
    // 3.5 MiB: more than the kernel took in the test above, so the endpoint most likely still
    // holds part of it when the client goes (the 4 MiB bound is not reached).
    constexpr std::size_t kBigAnswerBytes = 56 * 64 * 1024;
    f.device.answer = [](SessionRecord& s, std::string_view bytes) {
        if (s.received == "big\n") {
            for (std::size_t at = 0; at < kBigAnswerBytes; at += 64 * 1024)
                s.send(stream_bytes(at, 64 * 1024));
            return;
        }
        s.send(bytes);
    };
    auto first = connect_tcp(f.endpoint.port(), kSmallReceiveBuffer);
    const auto first_session = f.session_of(f.device, first);

    SECTION("a close with nothing pending (end of stream)")
    {
        CHECK(f.echo(first, "one\n") == "one\n");
        first.close();
        CHECK(run_until(f.io, [&] { return !first_session->open; }));
        CHECK(f.log.count("disconnected") == 1);
        CHECK(first_session->received == "one\n");
    }
    SECTION("a close with answers unread (reset)")
    {
        first.write("big\n");
        // The answer has begun to arrive: the endpoint is writing it.
        std::string some;
        CHECK(run_until(f.io, [&] {
            first.read_some(some, 1);
            return !some.empty();
        }));
        first.close();
        CHECK(run_until(f.io, [&] { return !first_session->open; }));
        CHECK(first_session->received == "big\n");
    }
    CHECK(f.budget.open_total == 0);

    auto next = connect_tcp(f.endpoint.port());
    CHECK(f.echo(next, "two\n") == "two\n");
    REQUIRE(f.device.sessions.size() == 2);
    CHECK(f.device.sessions[1]->received == "two\n");
    CHECK(f.device.open_sessions() == 1);
    CHECK(f.log.count("refused") == 0);
}

/// What the client's next read gives: bytes appended to `into` (0), end of stream (0, returned as
/// 0), or the error (errno); -1 while nothing has come.
int read_result(ClientFd& client, std::string& into)
{
    char buf[1 << 16];
    const auto n = ::read(client.get(), buf, sizeof buf);
    if (n > 0) {
        into.append(buf, static_cast<std::size_t>(n));
        return -1;
    }
    if (n == 0)
        return 0;
    return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR ? -1 : errno;
}

TEST_CASE("transport tcp: a reset the wire asks for reaches the client as ECONNRESET, its session "
          "released, its place given back",
          "[unit][transport][tcp]")
{
    Fixture f(TcpConnectionBudget{256, 1, 0});
    auto client = connect_tcp(f.endpoint.port());
    auto other = connect_tcp(f.other_endpoint.port());
    const auto session = f.session_of(f.device, client);
    CHECK(f.echo(client, "one\n") == "one\n");
    REQUIRE(session->connection.hangup);
    CHECK(session->connection.max_queued_bytes == TcpEndpoint::kMaxQueuedBytes);
    CHECK(session->connection.frame_overhead == TcpEndpoint::kQueuedFrameOverhead);
    CHECK(session->connection.queued_bytes() == 0);
    CHECK_FALSE(session->connection.client_baud);   // no serial line

    session->connection.hangup(Hangup::Reset);
    CHECK(session->open);   // never inside the call that asked: once the loop runs
    std::string got;
    int result = -1;
    CHECK(run_until(f.io, [&] { return (result = read_result(client, got)) >= 0; }));
    CHECK(result == ECONNRESET);
    CHECK(got.empty());
    CHECK_FALSE(session->open);
    CHECK(f.log.count("reset by a wire fault") == 1);
    CHECK(f.budget.open_total == 1);   // the other device's client
    CHECK(f.echo(other, "still\n") == "still\n");
    auto next = connect_tcp(f.endpoint.port());
    CHECK(f.echo(next, "two\n") == "two\n");
}

TEST_CASE("transport tcp: a close the wire asks for delivers what was queued, then end of stream, "
          "the client's later bytes go nowhere until it closes",
          "[unit][transport][tcp]")
{
    Fixture f;
    // More than the kernel takes at once for a small window: most of it is queued when the
    // close is asked for.
    constexpr std::size_t kAnswerBytes = 16 * 64 * 1024;
    f.device.answer = [&](SessionRecord& s, std::string_view) {
        for (std::size_t at = 0; at < kAnswerBytes; at += 64 * 1024)
            s.send(stream_bytes(at, 64 * 1024));
        s.connection.hangup(Hangup::Close);
    };
    auto client = connect_tcp(f.endpoint.port(), kSmallReceiveBuffer);
    const auto session = f.session_of(f.device, client);
    client.write("go\n");
    std::string got;
    int result = -1;
    CHECK(run_until(f.io, [&] { return (result = read_result(client, got)) >= 0; }));
    CHECK(result == 0);   // end of stream, not a reset
    CHECK(difference(got, stream_bytes(0, kAnswerBytes)).empty());
    CHECK_FALSE(session->open);
    CHECK(f.log.count("closed by a wire fault") == 1);
    // Half-closed: the client may still send; nothing reaches a session, and the connection
    // ends when the client closes its side.
    client.write("after\n");
    run_until(f.io, [] { return false; }, std::chrono::milliseconds(20));
    CHECK(session->received == "go\n");
    CHECK(f.device.sessions.size() == 1);
    CHECK(f.budget.open_total == 1);
    client.close();
    CHECK(run_until(f.io, [&] { return f.budget.open_total == 0; }));
}

} // namespace test_tcp_endpoint
