// APT jog and status-update timing on the stepped clock: what the e2e APT session used to
// count against the wall clock through the daemon (--time-scale 10); the serial line's pace
// with the rig's faithful_timing.
#include "apt_harness.hpp"
#include "emulator/daemon/link.hpp"

#include <string>
#include <vector>

namespace test_apt_timing {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;

namespace {

/// MOVE_ABSOLUTE for channel 1 of a TDC001 to `counts`.
std::string move_absolute(std::int32_t counts)
{
    std::string d;
    put_i32(d, counts);
    return "53 04 06 00 D0 01 01 00 " + hex(d);
}

constexpr std::int32_t kTwoMm = 68'608;      // MTS50-Z8: 34,304 counts/mm
constexpr std::int32_t kJogStep = 3'430;     // the power-up jog step, 0.1 mm

} // namespace

TEST_CASE("MOVE_JOG forward: one jog step on the clock, the counter rising, then MOVE_COMPLETED with the position",
          "[device][apt][timing]")
{
    AptHarness h;
    CHECK(h.send(move_absolute(kTwoMm)) == "");
    h.advance_ms(5000);
    REQUIRE(frames(h.take()).size() == 1);                         // MOVE_COMPLETED
    REQUIRE(position_of(h.send("11 04 01 00 50 01")) == kTwoMm);

    CHECK(h.send("6A 04 01 01 50 01") == "");                      // MOVE_JOG channel 1 forward
    std::int32_t last = kTwoMm;
    bool seen_on_the_way = false;
    std::string completed;
    int ms = 0;
    for (; ms < 5000 && completed.empty(); ++ms) {
        h.advance_ms(1);
        completed = h.take();
        if (!completed.empty())
            break;
        const auto p = position_of(h.send("11 04 01 00 50 01"));
        CHECK(p >= last);                                          // never backwards
        CHECK(p <= kTwoMm + kJogStep);                             // never past the step
        seen_on_the_way = seen_on_the_way || (p > kTwoMm && p < kTwoMm + kJogStep);
        last = p;
    }
    INFO("MOVE_COMPLETED after " << ms + 1 << " ms");
    CHECK(seen_on_the_way);                                        // the step took clock time
    const auto out = frames(completed);
    REQUIRE(out.size() == 1);
    CHECK(out[0].substr(0, 17) == "64 04 0E 00 81 50");            // MOVE_COMPLETED
    CHECK(position_of(out[0]) == kTwoMm + kJogStep);
    CHECK(position_of(h.send("11 04 01 00 50 01")) == kTwoMm + kJogStep);
}

TEST_CASE("status updates during a move: ten per second of clock, the position in each rising to the target",
          "[device][apt][timing]")
{
    AptHarness h;
    CHECK(h.send("11 00 00 00 50 01") == "");                      // HW_START_UPDATEMSGS
    CHECK(h.send(move_absolute(kTwoMm)) == "");
    std::vector<std::string> updates;
    for (int ms = 0; ms < 1000; ++ms) {
        h.advance_ms(1);
        for (const auto& f : frames(h.take()))
            if (f.substr(0, 5) == "91 04")                         // MOT_GET_DCSTATUSUPDATE
                updates.push_back(f);
    }
    REQUIRE(updates.size() == 10);
    std::int32_t last = -1;
    for (const auto& u : updates) {
        CHECK(position_of(u) > last);
        last = position_of(u);
    }
    CHECK(last <= kTwoMm);
    CHECK(h.send("12 00 00 00 50 01") == "");                      // HW_STOP_UPDATEMSGS
    h.advance_ms(1000);
    for (const auto& f : frames(h.take()))
        CHECK(f.substr(0, 5) != "91 04");
}

TEST_CASE("faithful_timing: the pty's line runs at 115200 baud 8N1, a 90-byte HW_GET_INFO arrives after 7.8 ms of clock",
          "[device][apt][timing]")
{
    auto config = tdc001();
    CHECK(AptHarness(config).device().serial_baud() == 0);   // unpaced without faithful_timing
    config.faithful_timing = true;
    Clock clock;   // 1 kHz
    models::World world{clock};
    AptDevice device(config, world, std::make_shared<spdlog::logger>("apt", std::make_shared<spdlog::sinks::null_sink_st>()));
    world.link_all();
    device.power_up();
    CHECK(device.serial_baud() == AptDevice::kBaudRate);
    // The daemon's link paces the pty (MCS's mechanism): 90 bytes x 10 bits / 115200 baud = 7.8125 ms.
    Link link{device, clock};
    std::string pty_out, tcp_out;
    auto pty = link.open_session([&](std::string_view b) { pty_out.append(b); }, "pty /tmp/x/tdc001");
    auto tcp = link.open_session([&](std::string_view b) { tcp_out.append(b); }, "tcp 127.0.0.1:5000");
    tcp->receive(bytes("05 00 00 00 50 01"));
    CHECK(tcp_out.size() == 90);   // TCP is never paced
    pty->receive(bytes("05 00 00 00 50 01"));
    clock.advance(7);
    CHECK(pty_out.empty());
    clock.advance(1);              // the first tick past 7.8125 ms
    REQUIRE(pty_out.size() == 90);
    CHECK(pty_out == tcp_out);
    // Two answers in one read leave one after the other: 12 + 12 bytes, 2.08 ms -> 3 ticks.
    pty_out.clear();
    pty->receive(bytes("11 04 01 00 50 01 11 04 01 00 50 01"));
    clock.advance(2);
    CHECK(pty_out.size() < 24);
    clock.advance(1);
    CHECK(pty_out.size() == 24);
}

namespace {

/// A TDC001 powered up on `clock`, behind a link with `model`.
struct ModelledTdc001 {
    ModelledTdc001(Clock& clock, LinkModel model, bool faithful = false)
        : world(clock), device(config(faithful), world, std::make_shared<spdlog::logger>("apt", std::make_shared<spdlog::sinks::null_sink_st>())),
          link(device, clock)
    {
        world.link_all();
        device.power_up();
        link.set_model(model);
    }
    static DeviceConfig config(bool faithful)
    {
        auto c = tdc001();
        c.faithful_timing = faithful;
        return c;
    }
    models::World world;
    AptDevice device;
    Link link;
};

/// What a client reads: (tick, bytes) per write the link hands the transport.
using Reads = std::vector<std::pair<Ticks, std::size_t>>;

/// Steps `clock` tick by tick to `until`.
void run_to(Clock& clock, Ticks until)
{
    while (clock.now() < until)
        clock.advance(1);
}

} // namespace

TEST_CASE("link model: a 12-byte answer comes at the USB-serial chip's latency timer, a 90-byte one in two USB packets",
          "[device][apt][timing][link]")
{
    Clock clock;   // 1 kHz: a tick is a USB frame
    ModelledTdc001 unit(clock, LinkModel{});   // 16 ms timer, 62-byte packets, 1 ms frames
    Reads pty_reads;
    std::string tcp_out;
    auto pty = unit.link.open_session([&](std::string_view b) { pty_reads.emplace_back(clock.now(), b.size()); },
                                      "pty /tmp/x/tdc001");
    auto tcp = unit.link.open_session([&](std::string_view b) { tcp_out.append(b); }, "tcp 127.0.0.1:5000");

    SECTION("12 bytes: held until the timer expires at 16 ms")
    {
        pty->receive(bytes("11 04 01 00 50 01"));   // MOT_REQ_POSCOUNTER: reaches the unit in frame 1
        run_to(clock, 40);
        CHECK(pty_reads == Reads{{16, 12}});
        tcp->receive(bytes("11 04 01 00 50 01"));   // TCP has no chip unless the model says so
        CHECK(tcp_out.size() == 12);
    }
    SECTION("90 bytes: 62 in the next frame, 28 when the restarted timer expires")
    {
        pty->receive(bytes("05 00 00 00 50 01"));   // HW_REQ_INFO, reaches the unit at 1 ms
        run_to(clock, 40);
        CHECK(pty_reads == Reads{{1, 62}, {17, 28}});
    }
    SECTION("the timer keeps its phase between answers")
    {
        run_to(clock, 20);
        pty->receive(bytes("11 04 01 00 50 01"));   // status packets at 16, 32: the answer at 32
        run_to(clock, 60);
        CHECK(pty_reads == Reads{{32, 12}});
    }
}

TEST_CASE("link model: with faithful_timing the chip's UART carries both ways at 115200 baud", "[device][apt][timing][link]")
{
    Clock clock;
    ModelledTdc001 unit(clock, LinkModel{}, true);
    Reads reads;
    auto pty = unit.link.open_session([&](std::string_view b) { reads.emplace_back(clock.now(), b.size()); },
                                      "pty /tmp/x/tdc001");
    // The request: frame 1, then 6 bytes (0.52 ms) on the line: at the unit in tick 2. The
    // answer's 62nd byte is at the chip at 2 + 62 x 0.0868 = 7.38 ms: frame 8; the last 28 go at
    // 8 + 16.
    pty->receive(bytes("05 00 00 00 50 01"));
    run_to(clock, 40);
    CHECK(reads == Reads{{8, 62}, {24, 28}});
}

TEST_CASE("link model: on TCP on request, and the unit's processing time per answer", "[device][apt][timing][link]")
{
    Clock clock;
    LinkModel model;
    model.latency_timer_ms = 1;
    model.processing_us = 2000;
    model.tcp = true;
    ModelledTdc001 unit(clock, model);
    Reads reads;
    auto tcp = unit.link.open_session([&](std::string_view b) { reads.emplace_back(clock.now(), b.size()); },
                                      "tcp 127.0.0.1:5000");
    // Two requests in one write reach the unit at 1 ms; it answers the first at 3 ms, the second
    // at 5 ms; a 1 ms timer sends each at once.
    tcp->receive(bytes("11 04 01 00 50 01 11 04 01 00 50 01"));
    run_to(clock, 20);
    CHECK(reads == Reads{{3, 12}, {5, 12}});
}

TEST_CASE("link model: what a client wrote before it closed the port still reaches the unit", "[device][apt][timing][link]")
{
    Clock clock;
    ModelledTdc001 unit(clock, LinkModel{});
    {
        auto pty = unit.link.open_session([](std::string_view) {}, "pty /tmp/x/tdc001");
        pty->receive(bytes(move_absolute(kTwoMm)));   // held for the next USB frame...
    }                                                 // ...when the client closes the port
    CHECK(unit.link.held_requests() == 0);
    run_to(clock, 5000);
    std::string answer;
    auto again = unit.link.open_session([&](std::string_view b) { answer.append(b); }, "pty /tmp/x/tdc001");
    again->receive(bytes("11 04 01 00 50 01"));
    run_to(clock, 5100);
    REQUIRE(answer.size() == 12);
    CHECK(position_of(hex(answer)) == kTwoMm);        // the move was made
}

} // namespace test_apt_timing
