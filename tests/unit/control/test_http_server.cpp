// The control API's HTTP server on loopback, on an io_context the test runs (no daemon): the
// request deadlines (mod_reqtimeout's rule, ReadDeadline, checked on stepped time points), slow
// clients dropped by the configured limits while a normal client is served, a full server
// making room for a new client, and the event streams' queues (shared chunks, batched writes,
// released when their clients go).

#include "emulator/control/http_server.hpp"

#include "tests/unit/transport/endpoint_harness.hpp"

#include <catch2/catch.hpp>

#include <boost/asio/ip/address.hpp>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

namespace test_http_server {

using namespace rigsim;
using namespace rigsim::test;
using control::HttpReply;
using control::HttpServer;
using control::HttpServerLimits;
using control::ReadDeadline;
using control::ReadTimeout;
using control::StreamChunk;
using control::StreamWriter;
using std::chrono::milliseconds;
using std::chrono::seconds;

namespace {

const std::string kGet = "GET /api/clock HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n";

/// A server whose router answers every request {"ok":true}, and GET /api/events with a stream
/// whose writer the test keeps (so that it publishes by hand).
struct Server {
    explicit Server(HttpServerLimits limits)
        : server(io, boost::asio::ip::make_address("127.0.0.1"), 0,
                 [this](std::string_view, std::string_view target, std::string_view) {
                     ++requests;
                     HttpReply reply;
                     if (target == "/api/events")
                         reply.stream = [this](StreamWriter w) -> std::function<void()> {
                             writers.push_back(std::move(w));
                             return [this] { ++streams_ended; };
                         };
                     else
                         reply.body = "{\"ok\":true}\n";
                     return reply;
                 },
                 log.logger, limits)
    {
        server.start();
    }

    std::uint16_t port() const { return server.local_endpoint().port(); }

    /// A request on a fresh connection, answered: its status line.
    std::string ask(ClientFd& client, const std::string& request = kGet)
    {
        client.write(request);
        std::string got;
        run_until(io, [&] {
            client.read_some(got);
            return got.find("\r\n\r\n") != std::string::npos && got.find("\"ok\"") != std::string::npos;
        });
        return got.substr(0, got.find("\r\n"));
    }

    boost::asio::io_context io;
    CapturedLog log;
    int requests = 0;
    int streams_ended = 0;
    std::vector<StreamWriter> writers;
    HttpServer server;
};

/// True once `client`'s connection has been closed by the server (whatever it sent before).
bool closed_by_server(ClientFd& client)
{
    std::string ignored;
    return client.read_some(ignored) == ClientFd::Read::End;
}

} // namespace

TEST_CASE("ReadDeadline: the initial time, one second per MinRate bytes, never past the cap", "[unit][control]")
{
    using T = std::chrono::steady_clock::time_point;
    const T t0{};
    ReadDeadline d;
    d.start(ReadTimeout{seconds(5), seconds(20), 500}, t0);
    CHECK(d.deadline() == t0 + seconds(5));
    CHECK_FALSE(d.expired(t0 + milliseconds(4999)));
    CHECK(d.expired(t0 + seconds(5)));
    // A slowloris: a byte a second moves the deadline 2 ms a byte; it falls behind.
    for (int s = 1; s <= 4; ++s)
        d.received(1);
    CHECK(d.deadline() == t0 + seconds(5) + milliseconds(8));
    CHECK(d.expired(t0 + seconds(6)));
    CHECK(d.bytes() == 4);
    // At the rate or faster: up to the cap, then no further.
    d.start(ReadTimeout{seconds(5), seconds(20), 500}, t0);
    d.received(500);
    CHECK(d.deadline() == t0 + seconds(6));
    d.received(100'000);
    CHECK(d.deadline() == t0 + seconds(20));
    // No rate: a fixed deadline (the idle time between requests).
    d.start(ReadTimeout{seconds(60), seconds(60), 0}, t0 + seconds(1));
    d.received(1'000'000);
    CHECK(d.deadline() == t0 + seconds(61));
}

TEST_CASE("http server: a client that sends its header a byte at a time is closed by the header deadline, "
          "while a normal client is served",
          "[unit][control]")
{
    HttpServerLimits limits;
    limits.header_timeout = ReadTimeout{milliseconds(300), seconds(2), 500};
    Server s(limits);
    auto slow = connect_tcp(s.port());
    const auto opened = SteadyClock::now();
    slow.write("GET /api/clock HTTP/1.1\r\n");
    auto next_byte = SteadyClock::now();
    bool closed = false;
    int served = 0;
    REQUIRE(run_until(s.io, [&] {
        if (!closed && SteadyClock::now() >= next_byte) {
            ::send(slow.get(), "a", 1, MSG_NOSIGNAL);   // one header byte every 20 ms: 50 bytes/s
            next_byte = SteadyClock::now() + milliseconds(20);
        }
        closed = closed || closed_by_server(slow);
        if (!closed) {
            auto normal = connect_tcp(s.port());
            CHECK(s.ask(normal) == "HTTP/1.1 200 OK");
            ++served;
        }
        return closed;
    }));
    // Never before its first deadline (300 ms, moved on 2 ms per byte), whatever the machine's speed.
    CHECK(SteadyClock::now() - opened >= milliseconds(300));
    CHECK(served > 0);
    CHECK(s.log.count("request header too slow") == 1);
    CHECK(s.log.count("limits: 300 ms, then 500 bytes/s, at most 2000 ms") == 1);
    CHECK(run_until(s.io, [&] { return s.server.connections() == 0; }));
}

TEST_CASE("http server: a body that comes too slowly is closed by the body deadline", "[unit][control]")
{
    HttpServerLimits limits;
    limits.body_timeout = ReadTimeout{milliseconds(200), seconds(2), 500};
    Server s(limits);
    auto slow_body = connect_tcp(s.port());
    slow_body.write("POST /api/faults HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
                    "Content-Length: 1000\r\n\r\n{");
    REQUIRE(run_until(s.io, [&] { return closed_by_server(slow_body); }));
    CHECK(s.requests == 0);
    CHECK(s.log.count("request body too slow (") == 1);
}

TEST_CASE("http server: a connection that sends nothing is closed by the header deadline", "[unit][control]")
{
    HttpServerLimits limits;
    limits.header_timeout = ReadTimeout{milliseconds(200), seconds(2), 500};
    Server s(limits);
    auto silent = connect_tcp(s.port());
    REQUIRE(run_until(s.io, [&] { return closed_by_server(silent); }));
    CHECK(s.log.count("request header too slow (0 bytes in") == 1);
    CHECK(run_until(s.io, [&] { return s.server.connections() == 0; }));
}

TEST_CASE("http server: with every connection taken, a new client replaces the one that waited longest for "
          "a request",
          "[unit][control]")
{
    HttpServerLimits limits;
    limits.max_connections = 2;
    Server s(limits);
    auto first = connect_tcp(s.port());
    first.write("GET /api/clock HTTP/1.1\r\n");   // a header that never ends
    REQUIRE(run_until(s.io, [&] { return s.server.connections() == 1; }));
    auto second = connect_tcp(s.port());
    second.write("GET");
    REQUIRE(run_until(s.io, [&] { return s.server.connections() == 2; }));
    auto third = connect_tcp(s.port());
    CHECK(s.ask(third) == "HTTP/1.1 200 OK");
    CHECK(run_until(s.io, [&] { return closed_by_server(first); }));
    std::string got;
    CHECK(second.read_some(got) == ClientFd::Read::Nothing);   // still open
    CHECK(s.log.count("which waited") == 1);
}

TEST_CASE("http server: every stream's events are copied into its own queue and written in batches, a stream "
          "that falls behind is closed and its queue released",
          "[unit][control]")
{
    HttpServerLimits limits;
    limits.max_stream_backlog_bytes = 64 * 1024;
    Server s(limits);
    auto reader = connect_tcp(s.port());
    auto deaf = connect_tcp(s.port(), 4096);
    const std::string open = "GET /api/events HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n";
    reader.write(open);
    deaf.write(open);
    REQUIRE(run_until(s.io, [&] { return s.writers.size() == 2 && s.server.streams() == 2; }));
    const auto chunk = std::make_shared<const std::string>("event: x\nid: 1\ndata: {}\n\n");
    for (int i = 0; i < 100; ++i)
        for (auto& w : s.writers)
            w(chunk);
    // 100 events each, copied into each stream's queue (pages of its own, emulator/core/frame_queue.hpp):
    // the chunk is nobody's but the caller's, and each copy counts against the bound.
    CHECK(chunk.use_count() == 1);
    CHECK(s.server.stream_backlog_bytes() >= 2 * 100 * (chunk->size() + 32));
    std::string got;
    REQUIRE(run_until(s.io, [&] {
        reader.read_some(got);
        return got.size() >= 100 * chunk->size();
    }));
    CHECK(got.find("HTTP/1.1 200 OK\r\n") == 0);
    // The deaf stream falls 64 KiB behind: closed, its queue and its place released.
    const auto big = std::make_shared<const std::string>(std::string(8192, 'x'));
    REQUIRE(run_until(s.io, [&] {
        for (auto& w : s.writers)
            w(big);
        reader.read_some(got);
        return s.server.streams() == 1;
    }));
    CHECK(s.log.count("an event stream's client is") == 1);
    CHECK(s.streams_ended == 1);
    reader.close();
    CHECK(run_until(s.io, [&] { return s.server.connections() == 0; }));
    CHECK(s.server.stream_backlog_bytes() == 0);
    CHECK(s.streams_ended == 2);
}

TEST_CASE("http server: a kept-alive client is served request after request, the hook runs when a connection "
          "has gone",
          "[unit][control]")
{
    Server s(HttpServerLimits{});
    int closed = 0;
    s.server.on_connection_closed([&] { ++closed; });
    {
        auto client = connect_tcp(s.port());
        for (int i = 0; i < 3; ++i)
            CHECK(s.ask(client) == "HTTP/1.1 200 OK");
        // Two requests in one write: both answered, in order.
        client.write(kGet + kGet);
        std::string got;
        REQUIRE(run_until(s.io, [&] {
            client.read_some(got);
            return s.requests == 5 && got.find("\"ok\"", got.find("\"ok\"") + 1) != std::string::npos;
        }));
    }
    CHECK(run_until(s.io, [&] { return s.server.connections() == 0 && closed == 1; }));
}

} // namespace test_http_server
