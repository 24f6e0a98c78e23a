// APT jog and status-update timing on the stepped clock: what the e2e APT session used to
// count against the wall clock through the daemon (--time-scale 10).
#include "apt_harness.hpp"

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

} // namespace test_apt_timing
