// MCS move timing on the stepped clock, tick by tick (manual 2.4 GS, 3.3 MPA/MPR, 3.2 SCLS):
// what the e2e tests used to check against the wall clock through the daemon.
#include "mcs_harness.hpp"
#include "emulator/daemon/link.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <utility>
#include <vector>

namespace test_mcs_timing {

using rigsim::Ticks;
using rigsim::test::McsHarness;
using rigsim::test::mcs_device_config;

namespace {

/// One status answer and for how many consecutive ticks it was given.
using Run = std::pair<std::string, Ticks>;

/// `query` asked now and after each of the next `ticks` ticks, as runs of equal answers.
std::vector<Run> answers_per_tick(McsHarness& h, const std::string& query, Ticks ticks)
{
    std::vector<Run> runs;
    for (Ticks t = 0; t <= ticks; ++t) {
        if (t > 0)
            h.advance_ticks(1);
        auto answer = h.send(query);
        if (!runs.empty() && runs.back().first == answer)
            ++runs.back().second;
        else
            runs.emplace_back(std::move(answer), 1);
    }
    return runs;
}

} // namespace

TEST_CASE("MPA with hold time 0: targeting (4) at every tick of the move, then stopped (0), nothing else",
          "[device][mcs][timing]")
{
    McsHarness h;
    CHECK(h.send(":SCLS0,4000000\n") == ":E-1,0\n");          // 4 mm/s
    CHECK(h.send(":MPA0,2000000,0\n") == ":E0,0\n");          // 2 mm: 500 ms
    // Ticks 0..499 targeting; from tick 500 on stopped.
    CHECK(answers_per_tick(h, ":GS0\n", 600) == std::vector<Run>{{":S0,4\n", 500}, {":S0,0\n", 101}});
    CHECK(h.send(":GP0\n") == ":P0,2000000\n");
}

TEST_CASE("MPA with hold time 60000: targeting until the target, then holding (3) until S",
          "[device][mcs][timing]")
{
    McsHarness h;
    CHECK(h.send(":MPA2,100000,60000\n") == ":E2,0\n");       // 0.1 mm at 10 mm/s: 10 ms
    CHECK(answers_per_tick(h, ":GS2\n", 2000) == std::vector<Run>{{":S2,4\n", 10}, {":S2,3\n", 1991}});
    CHECK(h.send(":GP2\n") == ":P2,100000\n");
    CHECK(h.send(":S2\n") == ":E2,0\n");
    CHECK(h.send(":GS2\n") == ":S2,0\n");
    CHECK(h.send(":GP2\n") == ":P2,100000\n");
}

TEST_CASE("the long-travel rig's first channel: 10 mm at 10 mm/s take 1 s of clock from its start at -5 mm",
          "[device][mcs][timing]")
{
    // tests/e2e/long_travel_rig.json, channel 0.
    auto config = mcs_device_config();
    rigsim::mcs::config_of(config).channels[0].start_position_nm = -5'000'000;
    rigsim::mcs::config_of(config).channels[0].max_speed_nm_per_s = 10'000'000;
    McsHarness h(config);
    CHECK(h.send(":GP0\n") == ":P0,0\n");                     // unreferenced: reads 0
    CHECK(h.send(":MPA0,10000000,0\n") == ":E0,0\n");
    CHECK(answers_per_tick(h, ":GS0\n", 1100) == std::vector<Run>{{":S0,4\n", 1000}, {":S0,0\n", 101}});
    CHECK(h.send(":GP0\n") == ":P0,10000000\n");
}

TEST_CASE("at a 200 Hz tick a move ends on its target, at the first tick after the arrival time",
          "[device][mcs][timing]")
{
    McsHarness h(mcs_device_config(), 200);
    CHECK(h.send(":MPA0,1000000,0\n") == ":E0,0\n");          // 1 mm at 10 mm/s: 100 ms = 20 ticks
    CHECK(answers_per_tick(h, ":GS0\n", 30) == std::vector<Run>{{":S0,4\n", 20}, {":S0,0\n", 11}});
    CHECK(h.send(":GP0\n") == ":P0,1000000\n");
    CHECK(h.send(":MPR0,1234567,0\n") == ":E0,0\n");          // 123.4567 ms: arrives in tick 25
    CHECK(answers_per_tick(h, ":GS0\n", 30) == std::vector<Run>{{":S0,4\n", 25}, {":S0,0\n", 6}});
    CHECK(h.send(":GP0\n") == ":P0,2234567\n");
}

TEST_CASE("a rejected MPA starts no move", "[device][mcs][timing]")
{
    McsHarness h;
    CHECK(h.send(":MPA0,1000000,70000\n") == ":E0,7\n");      // hold time beyond 60000
    h.advance_ms(1000);
    CHECK(h.send(":GS0\n:GP0\n") == ":S0,0\n:P0,0\n");
}

TEST_CASE("faithful_timing: the serial line runs at 9600 baud until CB and R change it, unpaced without it",
          "[device][mcs][timing]")
{
    auto config = mcs_device_config();
    SECTION("faithful_timing on")
    {
        config.faithful_timing = true;
        McsHarness h(config);
        CHECK(h.device().serial_baud() == 9600);               // factory rate (1.2)
        CHECK(h.send(":CB115200\n") == ":BR114285\n");
        CHECK(h.device().serial_baud() == 9600);               // CB takes effect at the next reset
        CHECK(h.send(":R\n") == ":E-1,0\n");
        CHECK(h.device().serial_baud() == 115200);
    }
    SECTION("faithful_timing off")
    {
        McsHarness h(config);
        CHECK(h.device().serial_baud() == 0);
        CHECK(h.send(":CB115200\n:R\n") == ":BR114285\n:E-1,0\n");
        CHECK(h.device().serial_baud() == 0);
    }
}

TEST_CASE("link model: :GP0 and its answer at 9600 baud through a USB-serial chip", "[device][mcs][timing][link]")
{
    auto config = mcs_device_config();
    config.faithful_timing = true;
    McsHarness h(config);
    CHECK(h.send(":MPA0,1000000,0\n") == ":E0,0\n");
    h.advance_ms(2000);
    REQUIRE(h.send(":GP0\n") == ":P0,1000000\n");
    rigsim::Link link{h.device(), h.clock()};
    std::vector<std::pair<Ticks, std::string>> reads;
    const auto read = [&](std::string_view b) { reads.emplace_back(h.clock().now(), std::string(b)); };
    const auto t0 = h.clock().now();
    SECTION("the line alone: 12 bytes of answer, 12.5 ms")
    {
        auto pty = link.open_session(read, "pty /tmp/x/mcs");
        pty->receive(":GP0\n");
        h.advance_ms(40);
        REQUIRE(reads.size() == 1);
        CHECK(reads[0] == std::make_pair(t0 + 13, std::string(":P0,1000000\n")));
    }
    SECTION("the chip: the request in frame 1 and 5.2 ms on the line, the answer's first 8 bytes at the timer")
    {
        link.set_model(rigsim::LinkModel{});
        auto pty = link.open_session(read, "pty /tmp/x/mcs");
        pty->receive(":GP0\n");
        h.advance_ms(40);
        // At the unit at 1 + 5.2 -> 7 ms; its bytes reach the chip at 8.04, 9.08, ... 19.5 ms:
        // 8 of them by the timer at 16 ms, the last 4 at 32 ms.
        REQUIRE(reads.size() == 2);
        CHECK(reads[0] == std::make_pair(t0 + 16, std::string(":P0,1000")));
        CHECK(reads[1] == std::make_pair(t0 + 32, std::string("000\n")));
    }
}

} // namespace test_mcs_timing
