// APT piezo waveform output (PZ_SET_OUTPUTLUT, OUTPUTLUTPARAMS, START/STOP_LUTOUTPUT; manual
// p.106-112) on a BPC303 bay: the output follows the table on the clock (1 ms base samples,
// p.109), GET_OUTPUTVOLTS reads the instant value. Timing: models/lut_player.hpp.
#include "apt_harness.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace test_apt_lut {

using namespace rigsim::test;

namespace {

rigsim::DeviceConfig bpc303()
{
    rigsim::DeviceConfig c;
    c.name = "rack";
    c.protocol = "apt";
    c.model = "BPC303";
    PiezoBayConfig bay;
    bay.actuator.max_voltage_v = 150;
    bay.actuator.hysteresis = 0;
    bay.actuator.creep = 0;
    config_of(c).piezo_bays.assign(3, bay);
    return c;
}

std::string le16(int v)
{
    char b[8];
    std::snprintf(b, sizeof b, "%02X %02X", v & 0xFF, (v >> 8) & 0xFF);
    return b;
}

std::string le32(std::int64_t v)
{
    return le16(static_cast<int>(v & 0xFFFF)) + " " + le16(static_cast<int>((v >> 16) & 0xFFFF));
}

/// The 30 data bytes of OUTPUTLUTPARAMS (p.108), channel 1, no trigger fields.
std::string lut_data(int mode, int length, std::int64_t cycles)
{
    return "01 00 " + le16(mode) + " " + le16(length) + " " + le32(cycles) + " " + le32(1) + " " + le32(0) + " "
           + le32(0) + " 00 00 00 00 00 00 00 00";
}

/// PZ_SET_OUTPUTLUTPARAMS to bay 0x21: DelayTime 1, no rests.
std::string lut_params(int mode, int length, std::int64_t cycles)
{
    return "03 07 1E 00 A1 01 " + lut_data(mode, length, cycles);
}

/// The plan's 1,000-sample sine: 16384 + 16000 sin(2 pi k / 1000).
std::vector<int> sine_table()
{
    std::vector<int> t(1000);
    for (int k = 0; k < 1000; ++k)
        t[k] = static_cast<int>(std::lround(16384 + 16000 * std::sin(2 * M_PI * k / 1000)));
    return t;
}

void load(AptHarness& h, const std::vector<int>& table)
{
    for (std::size_t k = 0; k < table.size(); ++k)
        REQUIRE(h.send("00 07 06 00 A1 01 01 00 " + le16(static_cast<int>(k)) + " " + le16(table[k])).empty());
}

int output_code(AptHarness& h)
{
    const auto b = bytes(h.send("44 06 01 00 21 01"));
    REQUIRE(b.size() == 10);
    return static_cast<std::int16_t>(get_u16(b, 8));
}

} // namespace

TEST_CASE("apt BPC303 LUT: a 1,000-sample sine is output on the clock, fixed cycles end and hold",
          "[device][apt][piezo][lut]")
{
    AptHarness h(bpc303());
    const auto table = sine_table();
    load(h, table);
    h.send(lut_params(0x02, 1000, 3));
    CHECK(h.send("04 07 01 00 21 01") == "05 07 1E 00 81 21 " + lut_data(0x02, 1000, 3));
    h.send("06 07 01 00 21 01");
    CHECK(output_code(h) == table[0]);
    std::int64_t at = 0;
    for (int t : {1, 250, 500, 999, 1000, 1250, 2999}) {
        h.advance_ms(t - at);
        at = t;
        CHECK(output_code(h) == table[t % 1000]);
    }
    // After the third cycle the last sample holds (p.110).
    h.advance_ms(1);
    CHECK(output_code(h) == table[999]);
    h.advance_ms(1000);
    CHECK(output_code(h) == table[999]);
}

TEST_CASE("apt BPC303 LUT: STOP holds the output of the stop instant", "[device][apt][piezo][lut]")
{
    AptHarness h(bpc303());
    const auto table = sine_table();
    load(h, table);
    h.send(lut_params(0x01, 1000, 1));
    h.send("06 07 01 00 21 01");
    h.advance_ms(1250);
    h.send("07 07 01 00 21 01");
    CHECK(output_code(h) == table[250]);
    h.advance_ms(500);
    CHECK(output_code(h) == table[250]);
    // Open-loop SET_OUTPUTVOLTS takes over once the LUT is stopped.
    h.send("43 06 04 00 A1 01 01 00 00 10");
    CHECK(output_code(h) == 0x1000);
}

TEST_CASE("apt BPC303 LUT: a bad index or bad parameters are ignored and logged", "[device][apt][piezo][lut]")
{
    AptHarness h(bpc303());
    CHECK(h.send("00 07 06 00 A1 01 01 00 05 00 88 08").empty());
    CHECK(h.send("01 07 01 00 21 01") == "02 07 06 00 81 21 01 00 05 00 88 08");
    // Index 8000 is past 0..7999 (p.106): ignored, REQ still answers the last good SET (D-9).
    CHECK(h.send("00 07 06 00 A1 01 01 00 40 1F 00 01").empty());
    CHECK(h.send("01 07 01 00 21 01") == "02 07 06 00 81 21 01 00 05 00 88 08");
    // Mode with neither continuous nor fixed, CycleLength 0: ignored; the previous params stay.
    h.send(lut_params(0x02, 6, 2));
    const auto good = h.send("04 07 01 00 21 01");
    h.send(lut_params(0x00, 6, 2));
    h.send(lut_params(0x02, 0, 2));
    CHECK(h.send("04 07 01 00 21 01") == good);
    // START with a CycleLength beyond the 6 samples loaded (indices 0..5, p.109): ignored.
    h.send(lut_params(0x02, 7, 2));
    h.send("06 07 01 00 21 01");
    CHECK(output_code(h) == 0);
}

TEST_CASE("apt BPC303 LUT: the unit is busy while the LUT runs, idle once it holds, and status updates alone are not busy",
          "[device][apt][piezo][lut]")
{
    AptHarness h(bpc303());
    h.send("11 00 00 00 11 01");   // HW_START_UPDATEMSGS: a periodic report only
    h.advance_ms(250);
    CHECK_FALSE(h.take().empty());  // the updates come
    CHECK_FALSE(h.device().busy());
    load(h, {1000, 2000, 3000, 4000});
    h.send(lut_params(0x02, 4, 2));
    h.send("06 07 01 00 21 01");
    CHECK(h.device().busy());
    h.advance_ms(7);
    CHECK(h.device().busy());      // the last sample of the second cycle is still out
    h.advance_ms(2);
    CHECK(output_code(h) == 4000);   // the run is over: the last sample holds
    CHECK_FALSE(h.device().busy());
}

} // namespace test_apt_lut
