// models::PiezoScanner: a 12-bit level swept at a constant speed, a function of clock time.

#include "models/piezo_scanner.hpp"

#include <catch2/catch.hpp>

namespace test_piezo_scanner {

using namespace rigsim;
using namespace rigsim::models;

TEST_CASE("piezo scanner: the level follows the clock and the end tick is the first at the target",
          "[unit][models][piezo]")
{
    Clock clock;
    PiezoScanner s(clock, 1500);
    s.start(0, 100, 300);   // 100 levels at 300 levels/s: 333.3 ms
    CHECK(s.end_tick() == 334);
    CHECK(s.level_at(150) == Approx(45.0));
    CHECK(s.displacement_nm(150) == Approx(45.0 * 1500 / 4095));
    CHECK(s.level_at(333) < 100.0);
    CHECK(s.level_at(334) == 100.0);
    s.settle(200);
    CHECK(s.level() == Approx(60.0));
    CHECK_FALSE(s.scanning());
    s.start(200, 0, 60);    // down again, 1 s
    CHECK(s.end_tick() == 1200);
    CHECK(s.level_at(2000) == 0.0);
    s.start(300, s.level_at(300), 5);   // no span: over at its start
    CHECK(s.end_tick() == 300);
}

} // namespace test_piezo_scanner
