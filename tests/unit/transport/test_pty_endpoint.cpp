// PtyEndpoint (emulator/transport/pty_endpoint.hpp) on real ptys (openpty, as the daemon makes
// them), driven by an io_context the test runs; the test opens the slave through the
// endpoint's symlink as a serial application does. Answers larger than the pty holds, a client
// that stops reading (output dropped beyond kMaxQueuedBytes, the port kept open), the last
// client closing the port (what it left unread is flushed), and closing and reopening the
// port. The devices behind the endpoints record their sessions and echo.
//
// The daemon holds its own descriptor of the slave, so the master never reads EIO however
// often clients close the port; the endpoint learns of opens and closes from inotify (one
// watcher for every pty, as in the daemon).
#include "emulator/transport/pty_endpoint.hpp"

#include "emulator/transport/inotify_watcher.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/unit/transport/endpoint_harness.hpp"

#include <catch2/catch.hpp>

#include <memory>
#include <string>

namespace test_pty_endpoint {

using namespace rigsim;
using namespace rigsim::test;

namespace {

/// Two devices of a rig, each with its pty endpoint, on one inotify watcher.
struct Fixture {
    Fixture()
    {
        watcher.start();
        endpoint.start();
        other_endpoint.start();
    }
    ~Fixture()
    {
        // As the daemon shuts down: stop, then let the cancelled handlers finish.
        endpoint.stop();
        other_endpoint.stop();
        watcher.stop();
        io.restart();
        io.poll();
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

    /// No pty error was logged: the master never failed (no EIO when a client closes).
    bool pty_never_failed() const { return log.count("failed") == 0; }

    boost::asio::io_context io;
    CapturedLog log;
    TempDir dir;
    RecordingDevice device;
    RecordingDevice other;
    InotifyWatcher watcher{io};
    PtyEndpoint endpoint{io, device, dir.file("dev0"), log.logger, watcher};
    PtyEndpoint other_endpoint{io, other, dir.file("dev1"), log.logger, watcher};
};

} // namespace

TEST_CASE("transport pty: a large answer read slowly in small pieces arrives whole and in order",
          "[unit][transport][pty]")
{
    Fixture f;
    // 16 frames of 16 KiB: many times what the pty holds, so every frame is written in parts
    // as the client makes room.
    constexpr std::size_t kFrameBytes = 16 * 1024;
    constexpr std::size_t kFrames = 16;
    f.device.answer = [&](SessionRecord& s, std::string_view) {
        if (s.received != "big\n")
            return;
        for (std::size_t i = 0; i < kFrames; ++i)
            s.send(stream_bytes(i * kFrameBytes, kFrameBytes));
    };
    auto client = open_pty(f.endpoint.symlink_path());
    client.write("big\n");

    const auto got = read_in_pieces(f.io, client, kFrames * kFrameBytes, 997);

    CHECK(difference(got, stream_bytes(0, kFrames * kFrameBytes)) == "");
    CHECK(f.log.count("dropping output") == 0);
    CHECK(f.pty_never_failed());
}

TEST_CASE("transport pty: an answer with nothing queued ahead of it is written at once, before the loop runs "
          "again, and one queued behind a partly written frame waits its turn",
          "[unit][transport][pty]")
{
    Fixture f;
    auto client = open_pty(f.endpoint.symlink_path());
    CHECK(f.echo(client, "hello\n") == "hello\n");
    const auto session = f.device.sessions.back();
    session->send("at once\n");   // outside the loop: no handler runs before the client reads
    std::string got;
    CHECK(client.read_some(got) == ClientFd::Read::Data);
    CHECK(got == "at once\n");

    constexpr std::size_t kBig = 64 * 1024;   // many times what the pty holds
    session->send(stream_bytes(0, kBig));
    session->send("after");
    got = read_in_pieces(f.io, client, kBig + 5, 997);
    CHECK(difference(got, stream_bytes(0, kBig) + "after") == "");
    CHECK(f.log.count("dropping output") == 0);
    CHECK(f.pty_never_failed());
}

TEST_CASE("transport pty: output a client does not read is dropped beyond kMaxQueuedBytes, whole "
          "frames at a time, while the port stays open and the other devices keep working",
          "[unit][transport][pty]")
{
    Fixture f;
    // A queued frame costs its bytes and kQueuedFrameOverhead until it has been written whole.
    // The pty holds a few KiB, so a frame of about kMaxQueuedBytes is still being written
    // while the client reads nothing.
    constexpr std::size_t kFits = PtyEndpoint::kMaxQueuedBytes - PtyEndpoint::kQueuedFrameOverhead;
    auto client = open_pty(f.endpoint.symlink_path());
    auto other_client = open_pty(f.other_endpoint.symlink_path());
    CHECK(f.echo(client, "hello\n") == "hello\n");
    const auto session = f.device.sessions.back();

    SECTION("a frame that fits is kept whole; what follows it is dropped until it has been read")
    {
        session->send(stream_bytes(0, kFits));
        f.io.restart();
        f.io.poll();
        session->send("lost 1\n");   // 1 MiB + 71: one byte over would do
        session->send("lost 2\n");
        CHECK(f.log.count("dropping output") == 1);   // once, however much is dropped
        CHECK(f.echo(other_client, "other device\n") == "other device\n");

        const auto got = read_in_pieces(f.io, client, kFits, 997);
        CHECK(difference(got, stream_bytes(0, kFits)) == "");
        // The frame left the queue in the pass of the loop that wrote its last bytes: there is
        // room again.
        session->send("after\n");
        std::string rest;
        CHECK(run_until(f.io, [&] {
            client.read_some(rest);
            return rest.size() >= 6;
        }));
        CHECK(rest == "after\n");
    }
    SECTION("a frame bigger than the bound is dropped whole, none of it cut into the stream")
    {
        session->send(stream_bytes(0, kFits + 8));
        CHECK(f.log.count("dropping output") == 1);
        session->send("after\n");
        std::string got;
        CHECK(run_until(f.io, [&] {
            client.read_some(got);
            return got.size() >= 6;
        }));
        CHECK(got == "after\n");
    }
    CHECK(session->open);   // a serial port: the client is never cut off
    CHECK(f.device.sessions.size() == 1);
    CHECK(f.pty_never_failed());
}

TEST_CASE("transport pty: when the last client closes the port, what it did not read is flushed "
          "and the next client starts afresh",
          "[unit][transport][pty]")
{
    Fixture f;
    // 512 KiB: the pty holds a few KiB of it, the endpoint's queue the rest.
    constexpr std::size_t kBigAnswerBytes = 512 * 1024;
    f.device.answer = [](SessionRecord& s, std::string_view bytes) {
        if (s.received == "big\n") {
            for (std::size_t at = 0; at < kBigAnswerBytes; at += 64 * 1024)
                s.send(stream_bytes(at, 64 * 1024));
            return;
        }
        s.send(bytes);
    };
    auto first = open_pty(f.endpoint.symlink_path());
    first.write("big\n");
    CHECK(run_until(f.io, [&] { return f.device.sessions.back()->received == "big\n"; }));
    f.io.restart();
    f.io.poll();
    const auto first_session = f.device.sessions.back();
    // An unfinished line, then gone: the bytes are still the first client's.
    first.write("unfinished");
    first.close();

    // The close seen: a new session for the next opener, the first one's released.
    CHECK(run_until(f.io, [&] { return !first_session->open && f.device.open_sessions() == 1; }));
    CHECK(first_session->received == "big\nunfinished");
    REQUIRE(f.device.sessions.size() == 2);
    const auto second_session = f.device.sessions.back();
    // Nobody has the port open: lost, as on a serial line.
    second_session->send("nobody hears this\n");

    auto next = open_pty(f.endpoint.symlink_path());
    next.write("two\n");
    std::string got;
    CHECK(run_until(f.io, [&] {
        next.read_some(got);
        return got.find("two\n") != std::string::npos;
    }));
    CHECK(got == "two\n");
    CHECK(second_session->received == "two\n");
    CHECK(f.pty_never_failed());
}

TEST_CASE("transport pty: a client that closes the port and opens it again is answered again",
          "[unit][transport][pty]")
{
    Fixture f;
    auto client = open_pty(f.endpoint.symlink_path());
    CHECK(f.echo(client, "one\n") == "one\n");
    const auto first_session = f.device.sessions.back();

    SECTION("after the endpoint has seen the close: a new session")
    {
        for (int cycle = 0; cycle < 5; ++cycle) {
            client.close();
            const auto sessions = static_cast<std::size_t>(2 + cycle);
            CHECK(run_until(f.io, [&] { return f.device.sessions.size() == sessions; }));
            client = open_pty(f.endpoint.symlink_path());
            const auto request = "again " + std::to_string(cycle) + "\n";
            CHECK(f.echo(client, request) == request);
            CHECK(f.device.sessions.back()->received == request);
            CHECK(f.device.open_sessions() == 1);
        }
        CHECK(first_session->received == "one\n");
    }
    SECTION("before the endpoint has seen the close: the line carries on")
    {
        // Closed and opened again with the loop not run in between: the endpoint reads both
        // events in one batch, and the port never counted as closed.
        client.close();
        client = open_pty(f.endpoint.symlink_path());
        CHECK(f.echo(client, "two\n") == "two\n");
        CHECK(f.device.sessions.size() == 1);
        CHECK(first_session->received == "one\ntwo\n");
    }
    CHECK(f.pty_never_failed());
}

/// What a read of the slave gives now: bytes appended to `into` (-1), end of file (0), an error
/// (errno), -1 while nothing has come.
int read_result(ClientFd& client, std::string& into)
{
    char buf[4096];
    const auto n = ::read(client.get(), buf, sizeof buf);
    if (n > 0) {
        into.append(buf, static_cast<std::size_t>(n));
        return -1;
    }
    if (n == 0)
        return 0;
    return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR ? -1 : errno;
}

TEST_CASE("transport pty: a hang-up the wire asks for ends the client's line (end of file, EIO on "
          "write) and puts a new pty with a new session behind the symlink",
          "[unit][transport][pty]")
{
    Fixture f;
    auto client = open_pty(f.endpoint.symlink_path());
    CHECK(f.echo(client, "one\n") == "one\n");
    REQUIRE(f.device.sessions.size() == 1);
    const auto first = f.device.sessions[0];
    REQUIRE(first->connection.hangup);
    CHECK(first->connection.max_queued_bytes == PtyEndpoint::kMaxQueuedBytes);
    CHECK(first->connection.client_baud() == 115200);
    termios tio{};
    REQUIRE(::tcgetattr(client.get(), &tio) == 0);
    ::cfsetospeed(&tio, B9600);
    ::cfsetispeed(&tio, B9600);
    REQUIRE(::tcsetattr(client.get(), TCSANOW, &tio) == 0);
    CHECK(first->connection.client_baud() == 9600);   // the client's termios, as the link reads it
    const auto old_device = f.endpoint.device_path();

    SECTION("reset: at once")
    {
        first->send("unread\n");   // lost with the line
        first->connection.hangup(Hangup::Reset);
        CHECK(first->open);   // once the loop runs
        std::string got;
        int result = -1;
        CHECK(run_until(f.io, [&] { return (result = read_result(client, got)) >= 0; }));
        CHECK(result == 0);
        CHECK(got.empty());
    }
    SECTION("close: once the client has read what was written")
    {
        first->send("last words\n");
        first->connection.hangup(Hangup::Close);
        std::string got;
        int result = -1;
        CHECK(run_until(f.io, [&] { return (result = read_result(client, got)) >= 0; }));
        CHECK(result == 0);
        CHECK(got == "last words\n");
    }
    CHECK_FALSE(first->open);
    CHECK(::write(client.get(), "x", 1) == -1);
    CHECK(errno == EIO);
    CHECK(f.log.count("hung up by a wire fault") == 1);
    CHECK(f.endpoint.device_path() != old_device);
    REQUIRE(f.device.sessions.size() == 2);
    CHECK(f.device.sessions[1]->open);
    CHECK(f.device.sessions[1]->received.empty());

    auto again = open_pty(f.endpoint.symlink_path());
    CHECK(f.echo(again, "two\n") == "two\n");
    CHECK(f.device.sessions[1]->received == "two\n");
    // A hang-up asked for by the old session does nothing to the new line.
    first->connection.hangup(Hangup::Reset);
    CHECK(f.echo(again, "three\n") == "three\n");
    auto other = open_pty(f.other_endpoint.symlink_path());
    CHECK(f.echo(other, "other\n") == "other\n");
    CHECK(f.pty_never_failed());
}

} // namespace test_pty_endpoint
