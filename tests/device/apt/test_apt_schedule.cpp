// APT devices on a clock that keeps its schedule, as the daemon's does (models/clock.hpp, "The
// schedule"): the clock asks a device for its next change only after its tick, any tick, or its
// announcement that a session's messages were handled. Every step goes to two harnesses of the
// same devices, one on such a clock, and both must send the same bytes: a timer a message starts
// and nobody announces (a status update, the end of a move, a closed loop noticing the feedback
// another device routes to it) would be missed by the one that keeps its schedule.
#include "gauge_pair.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace test_apt_schedule {

using namespace rigsim::test;
using namespace rigsim::test::gauge_pair;

namespace {

/// The same devices twice: `asked` on the tests' clock, `kept` on one that keeps its schedule.
class Twin {
public:
    explicit Twin(const std::vector<rigsim::DeviceConfig>& devices) : asked_(devices.at(0)), kept_(devices.at(0))
    {
        for (std::size_t d = 1; d < devices.size(); ++d) {
            asked_.add_device(devices[d]);
            kept_.add_device(devices[d]);
        }
        kept_.keep_schedule();
    }
    /// Hex to device `d` of both; what they answered (the same, checked), and both due next at the
    /// same tick.
    std::string send(const std::string& hex_in, std::size_t d = 0)
    {
        const auto a = asked_.send(hex_in, d);
        const auto k = kept_.send(hex_in, d);
        INFO("sent " << hex_in << " to device " << d);
        CHECK(k == a);
        CHECK(kept_.device().clock().next_wakeup() == asked_.device().clock().next_wakeup());
        return k;
    }
    /// Both clocks `ms` on; what every device of both sent meanwhile must be the same. Returns
    /// what device 0 sent.
    std::string advance_ms(std::int64_t ms)
    {
        asked_.advance_ms(ms);
        kept_.advance_ms(ms);
        std::string first;
        for (std::size_t d = 0; d < asked_.device_count(); ++d) {
            INFO("device " << d << " after " << ms << " ms");
            const auto k = kept_.take(d);
            CHECK(k == asked_.take(d));
            if (d == 0)
                first = k;
        }
        return first;
    }
    AptHarness& kept() { return kept_; }

private:
    AptHarness asked_;
    AptHarness kept_;
};

/// PZ_GET_OUTPUTVOLTS of the TPZ in volts of the 75 V limit (p.96).
double output_v(Twin& t)
{
    const auto b = bytes(t.send("44 06 01 00 50 01"));
    REQUIRE(b.size() == 10);
    return static_cast<std::int16_t>(get_u16(b, 8)) / 32767.0 * 75.0;
}

} // namespace

TEST_CASE("apt schedule: status updates a message starts, a move's end and a home, on a kept schedule",
          "[device][apt][clock]")
{
    Twin t({tdc001()});
    CHECK(t.send("11 00 00 00 50 01").empty());   // HW_START_UPDATEMSGS: every 100 ms from now
    CHECK(frames(t.advance_ms(350)).size() == 3);
    t.send("43 04 01 00 50 01");                  // MOT_MOVE_HOME
    CHECK(frames(t.advance_ms(30'000)).size() > 3);
    t.send("53 04 06 00 D0 01 01 00 00 0C 01 00");   // MOVE_ABSOLUTE 68,608 counts
    for (int i = 0; i < 40; ++i)
        t.advance_ms(100);
    t.send("12 00 00 00 50 01");                  // HW_STOP_UPDATEMSGS
    t.advance_ms(1000);
}

TEST_CASE("apt schedule: a TPZ001's closed loop notices the hub output its TSG001 switches, on a kept schedule",
          "[device][apt][piezo][gauge][clock]")
{
    // The reader's TSG_IOSETTINGS (another device) decides whether the driver's feedback input reads
    // a gauge, and so whether the driver's closed loop wakes: the gauge announces the driver.
    Twin t({tpz(), tsg()});
    t.send(kClosedLoop);
    REQUIRE(t.send(kReqMode) == kModeClosed);
    t.send("46 06 04 00 D0 01 01 00 66 26");   // 30 % (p.97)
    t.advance_ms(1000);
    REQUIRE(extension_um(t.kept()) == Approx(0.3 * kTravelUm).margin(0.02));
    t.send(kTsgOutput2, 1);                    // the reader's signal goes to hub B: the loop holds
    t.send("46 06 04 00 D0 01 01 00 CC 4C");   // 60 %, taken in closed loop
    t.advance_ms(5000);
    const double before_v = output_v(t);
    CHECK(extension_um(t.kept()) == Approx(0.3 * kTravelUm).margin(0.02));
    t.send(kTsgOutput1, 1);                    // and back: the next tick resumes the loop
    t.advance_ms(1);
    CHECK(std::abs(output_v(t) - before_v) < 2.0);
    t.advance_ms(2000);
    CHECK(extension_um(t.kept()) == Approx(0.6 * kTravelUm).margin(0.02));
}

} // namespace test_apt_schedule
