// The shipped stages' scales pinned against their published figures (docs/protocol/errata.md,
// "Stage scales"), independently of config/stages: a driver that commands one unit
// (1 mm, 10 degrees) in the counts Thorlabs' tables give for that stage on that controller moves
// the emulated carriage by that unit, and velocities set from the published per-mm/s figures
// run the carriage at the speed they mean, on the stepped clock.
#include "apt_harness.hpp"
#include "emulator/control/body_state.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <string>

namespace test_apt_stage_scales {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A controller driving `stage` (in bay 0 of a rack), following firmware generation `fw`.
DeviceConfig unit(const std::string& model, const std::string& stage, Firmware fw)
{
    auto c = model == "BSC203" || model == "BBD203" ? apt_rack(model, {stage}) : apt_cube(model, stage);
    c.firmware = std::string(firmware_name(fw));
    config_of(c).firmware = fw;
    return c;
}

/// Where the carriage of channel 0 (bay 0) stands, in m or rad (the control API's position_si).
double carriage_si(AptHarness& h)
{
    nlohmann::json out = nlohmann::json::object();
    rigsim::control::describe_device(h.device(), &h.world(), out);   // as the control API does
    return out["channels"].at(0)["position_si"].get<double>();
}

/// The header of a message `id` ("48 04") with `length` (< 256) data bytes from the host to the
/// unit (0x50) or to bay 0 of a rack (0x21), with the data flag.
std::string header_to(const std::string& model, const char* id, int length)
{
    const bool rack = model == "BSC203" || model == "BBD203";
    char size[8];
    std::snprintf(size, sizeof size, "%02X 00", length);
    return std::string(id) + " " + size + (rack ? " A1 01 " : " D0 01 ");
}

/// One stage on one controller, and the counts a driver sends for `unit` of it.
struct Scale {
    const char* model;
    Firmware fw;
    const char* stage;
    std::int32_t counts;   ///< the published counts per unit, rounded as a driver sends them
    double unit;           ///< 1 mm, or 10 degrees on the rotation stage
    double published;      ///< the published counts per mm (per degree)
};

// Counts per mm as Thorlabs tabulates them per controller (AlexShkarin/pyLabLib,
// pylablib/devices/Thorlabs/kinesis.py, KinesisMotor._get_step_scale; manual 7.1 for the MLS203,
// p. 55 for the Z8; the Z8's later 34,554.96 is the disagreement docs/protocol/errata.md records).
constexpr Scale kScales[]{
    {"TST001", Firmware::Issue3, "DRV001", 51'200, 1, 51'200},
    {"KST101", Firmware::Issue44_1, "DRV001", 819'200, 1, 819'200},
    {"BSC203", Firmware::Issue44_1, "DRV001", 819'200, 1, 819'200},
    {"TST001", Firmware::Issue3, "DRV014", 25'600, 1, 25'600},
    {"KST101", Firmware::Issue44_1, "DRV014", 409'600, 1, 409'600},
    {"TST001", Firmware::Issue3, "ZST225B", 125'540, 1, 125'540.35},
    {"BSC203", Firmware::Issue3, "ZST225B", 125'540, 1, 125'540.35},
    {"KST101", Firmware::Issue44_1, "ZST225B", 2'008'646, 1, 2'008'645.63},
    {"TDC001", Firmware::Issue3, "MTS50-Z8", 34'304, 1, 34'304},
    {"KDC101", Firmware::Issue44_1, "MTS25-Z8", 34'304, 1, 34'304},
    {"KDC101", Firmware::Issue3, "Z812B", 34'304, 1, 34'304},
    {"TDC001", Firmware::Issue44_1, "Z825B", 34'304, 1, 34'304},
    {"KDC101", Firmware::Issue3, "PRM1-Z8", 19'196, 10, 1'919.6418578623391},
    {"BBD203", Firmware::Issue3, "MLS203-X", 20'000, 1, 20'000},
    {"BBD203", Firmware::Issue44_1, "MLS203-Y", 20'000, 1, 20'000},
    {"BBD203", Firmware::Issue3, "DDSM100", 2'000, 1, 2'000},
};

/// `mm` (degrees on the rotation stage) in the control API's SI unit.
double si(const Scale& s, double units)
{
    return std::string(s.stage) == "PRM1-Z8" ? units * kPi / 180.0 : units * 1e-3;
}

} // namespace

TEST_CASE("stage scales: the published counts for one unit move every shipped stage's carriage by that unit",
          "[device][apt][stages]")
{
    for (const auto& s : kScales) {
        INFO(s.model << " (" << firmware_name(s.fw) << ") + " << s.stage);
        AptHarness h(unit(s.model, s.stage, s.fw));
        const double before = carriage_si(h);
        CHECK(h.send(header_to(s.model, "48 04", 6) + "01 00 " + le32(s.counts)) == "");   // MOVE_RELATIVE
        h.advance_ms(10'000);
        const auto done = frames(h.take());
        REQUIRE(done.size() == 1);
        CHECK(done[0].substr(0, 5) == "64 04");                                          // MOVE_COMPLETED
        CHECK(position_of(done[0]) == s.counts);
        // The carriage moved what the published figure says those counts are, to within a count.
        const double expected_units = s.counts / s.published;
        CHECK(carriage_si(h) - before == Approx(si(s, expected_units)).margin(si(s, 1.0 / s.published)));
        CHECK(expected_units == Approx(s.unit).margin(1.0 / s.published));
    }
}

TEST_CASE("stage scales: VELPARAMS from the published per-mm/s figures run 1 mm at 1 mm/s (4 mm/s^2): 1.25 s",
          "[device][apt][stages]")
{
    // A stepper counts microsteps/s (p. 29) on the TST001; the later Trinamic units 53.68 per
    // microstep/s and 53.68 x 204.94e-6 per microstep/s^2; the DC cubes T = 2048 / 6e6 s,
    // velocity = counts/s x T x 65536, acceleration = counts/s^2 x T^2 x 65536 (pyLabLib
    // _calculate_scale; POSICS-II/thorlabs-apt-device BSC201_DRV250: 21,987,328 per mm/s and
    // 4,506 per mm/s^2 at 409,600 per mm).
    struct Speed {
        const char* model;
        Firmware fw;
        const char* stage;
        double per_mm, velocity_per_count, acceleration_per_count;
    };
    constexpr double kT = 2048.0 / 6e6;
    constexpr Speed kSpeeds[]{
        {"TST001", Firmware::Issue3, "DRV001", 51'200, 1, 1},
        {"KST101", Firmware::Issue44_1, "DRV001", 819'200, 53.68, 53.68 * 204.94e-6},
        {"TST001", Firmware::Issue3, "ZST225B", 125'540.35, 1, 1},
        {"KST101", Firmware::Issue44_1, "ZST225B", 2'008'645.63, 53.68, 53.68 * 204.94e-6},
        {"KST101", Firmware::Issue44_1, "DRV014", 409'600, 53.68, 53.68 * 204.94e-6},
        {"KDC101", Firmware::Issue44_1, "MTS50-Z8", 34'304, kT * 65536, kT * kT * 65536},
    };
    for (const auto& s : kSpeeds) {
        INFO(s.model << " (" << firmware_name(s.fw) << ") + " << s.stage);
        AptHarness h(unit(s.model, s.stage, s.fw));
        const auto velocity = static_cast<std::int32_t>(std::lround(s.per_mm * s.velocity_per_count));
        const auto acceleration = static_cast<std::int32_t>(std::lround(4 * s.per_mm * s.acceleration_per_count));
        CHECK(h.send(header_to(s.model, "13 04", 14) + "01 00 " + le32(0) + " " + le32(acceleration) + " "
                     + le32(velocity))
              == "");
        const double before = carriage_si(h);
        CHECK(h.send(header_to(s.model, "48 04", 6) + "01 00 " + le32(static_cast<std::int32_t>(std::lround(s.per_mm))))
              == "");
        int ms = 0;
        std::string done;
        while (done.empty() && ms < 5000) {
            h.advance_ms(1);
            ++ms;
            done = h.take();
        }
        CHECK(ms >= 1245);   // 1 mm at 1 mm/s, plus v/a = 0.25 s of ramps
        CHECK(ms <= 1255);
        CHECK(carriage_si(h) - before == Approx(1e-3).margin(1e-8));
    }
}

} // namespace test_apt_stage_scales
