// Firmware generations (docs/protocol/mcs.md, "Firmware generations"): what a device whose
// rig "firmware" is "2.0.1" answers differently from the manual's 1.2.44, bytes in -> bytes
// out on the stepped clock. The rigs go through the loader, as rigsimd reads them.
#include "mcs_harness.hpp"

#include "emulator/daemon/rig_families.hpp"

#include <catch2/catch.hpp>

#include <memory>
#include <string>

namespace test_mcs_firmware {

using rigsim::test::McsHarness;

namespace {

/// One linear channel (travel ±10.5 mm, mark at 0, search at 1 mm/s) of `sensor` starting at
/// physical `start`, on a device of generation `firmware` ("" leaves the key out).
std::unique_ptr<McsHarness> device(const std::string& firmware, const char* sensor = "S",
                                   std::int64_t start = 3'000'000)
{
    std::string text = R"({"tick_hz":1000,"devices":[{"name":"m","protocol":"mcs",)";
    if (!firmware.empty())
        text += R"("firmware":")" + firmware + R"(",)";
    text += R"("mcs":{"channels":[{"sensor_type":")" + std::string(sensor) + R"(","start_position_nm":)"
            + std::to_string(start) + "}]}}]}";
    const auto rig = rigsim::parse_rig_config(text, "rig.json");
    return std::make_unique<McsHarness>(rig.devices.at(0), rig.tick_hz);
}

} // namespace

TEST_CASE("firmware: GIV answers the generation's version unless the rig names another", "[device][mcs][firmware]")
{
    CHECK(device("")->send(":GIV\n") == ":IV1,2,44\n");
    CHECK(device("1.2.44")->send(":GIV\n") == ":IV1,2,44\n");
    CHECK(device("2.0.1")->send(":GIV\n") == ":IV2,0,1\n");
}

TEST_CASE("firmware: FRM directions beyond 1 are error 7 under 1.2.44, beyond 7 under 2.0.1", "[device][mcs][firmware][frm]")
{
    auto manual = device("1.2.44");
    for (int d = 2; d <= 8; ++d) {
        INFO("direction " << d);
        CHECK(manual->send(":FRM0," + std::to_string(d) + ",0,1\n") == ":E0,7\n");
    }
    CHECK(manual->send(":GS0\n:GPPK0\n") == ":S0,0\n:PPK0,0\n");
    auto later = device("2.0.1");
    CHECK(later->send(":FRM0,8,0,1\n") == ":E0,7\n");
    CHECK(later->send(":GS0\n") == ":S0,0\n");
    CHECK(later->send(":FRM0,7,0,1\n") == ":E0,0\n");
    CHECK(later->send(":GS0\n") == ":S0,7\n");
}

TEST_CASE("firmware 2.0.1: forward-backward (2) and backward-forward (3) search as 0 and 1 do", "[device][mcs][firmware][frm]")
{
    // From +3 mm with the mark at 0 behind: forward to the end stop at +10.5 mm (7.5 s),
    // then back to the mark (10.5 s), as the manual's forward search (2.3.3).
    for (const char* d : {"0", "2"}) {
        INFO("direction " << d);
        auto h = device("2.0.1");
        CHECK(h->send(":FRM0," + std::string(d) + ",0,1\n") == ":E0,0\n");
        h->advance_ms(7499);
        CHECK(h->send(":GS0\n:GP0\n") == ":S0,7\n:P0,7499000\n");
        h->advance_ms(10'500);
        CHECK(h->send(":GS0\n:GPPK0\n") == ":S0,7\n:PPK0,0\n");
        h->advance_ms(1);
        CHECK(h->send(":GS0\n:GPPK0\n:GP0\n") == ":S0,0\n:PPK0,1\n:P0,0\n");
    }
    // From -3 mm backward first: to -10.5 mm (7.5 s), then forward to the mark (10.5 s).
    for (const char* d : {"1", "3"}) {
        INFO("direction " << d);
        auto h = device("2.0.1", "S", -3'000'000);
        CHECK(h->send(":FRM0," + std::string(d) + ",0,1\n") == ":E0,0\n");
        h->advance_ms(7499);
        CHECK(h->send(":GP0\n") == ":P0,-7499000\n");
        h->advance_ms(10'501);
        CHECK(h->send(":GS0\n:GPPK0\n:GP0\n") == ":S0,0\n:PPK0,1\n:P0,0\n");
    }
}

TEST_CASE("firmware 2.0.1: abort on end stop (4..7): the first end stop ends the search with 144", "[device][mcs][firmware][frm]")
{
    for (const char* d : {"4", "6"}) {   // forward first; the mark lies behind
        INFO("direction " << d);
        auto h = device("2.0.1");
        CHECK(h->send(":SCM1\n") == "");
        CHECK(h->send(":FRM0," + std::string(d) + ",0,1\n") == "");
        h->advance_ms(7499);                                 // +3 -> +10.5 mm
        CHECK(h->send(":GS0\n") == ":S0,7\n");
        h->advance_ms(1);
        CHECK(h->send(":GS0\n:GPPK0\n:GP0\n") == ":E0,144\n:S0,0\n:PPK0,0\n:P0,7500000\n");
        h->advance_ms(20'000);                                // it stays at the end stop
        CHECK(h->send(":GS0\n:GP0\n") == ":S0,0\n:P0,7500000\n");
    }
    for (const char* d : {"5", "7"}) {   // backward first, toward the mark: found
        INFO("direction " << d);
        auto h = device("2.0.1");
        CHECK(h->send(":FRM0," + std::string(d) + ",0,1\n") == ":E0,0\n");
        h->advance_ms(2999);
        CHECK(h->send(":GS0\n") == ":S0,7\n");
        h->advance_ms(1);
        CHECK(h->send(":GS0\n:GPPK0\n:GP0\n") == ":S0,0\n:PPK0,1\n:P0,0\n");
    }
    // Synchronous mode: no message, the channel stops at the end stop with the position unknown.
    auto h = device("2.0.1", "S", -3'000'000);
    CHECK(h->send(":FRM0,5,0,1\n") == ":E0,0\n");
    h->advance_ms(7500);
    CHECK(h->send(":GS0\n:GPPK0\n:GP0\n") == ":S0,0\n:PPK0,0\n:P0,-7500000\n");
}

TEST_CASE("firmware 2.0.1: a range limit boundary aborts the search like an end stop (2.3.4)", "[device][mcs][firmware][frm]")
{
    auto h = device("2.0.1", "S", 1'000'000);
    CHECK(h->send(":FRM0,5,0,0\n") == ":E0,0\n");            // mark 1 mm behind: backward
    h->advance_ms(1000);
    CHECK(h->send(":GPPK0\n:SPL0,500000,2000000\n:MPA0,1000000,0\n") == ":PPK0,1\n:E0,0\n:E0,0\n");
    h->advance_ms(100);
    CHECK(h->send(":SCM1\n:FRM0,5,0,1\n") == "");             // the mark at 0 lies outside
    h->advance_ms(499);                                       // 1 -> 0.5 mm
    CHECK(h->send(":GS0\n") == ":S0,7\n");
    h->advance_ms(1);
    CHECK(h->send(":GS0\n:GP0\n") == ":E0,144\n:S0,0\n:P0,500000\n");
}

TEST_CASE("firmware 2.0.1: abort on end stop with distance-coded marks needs both marks ahead", "[device][mcs][firmware][frm]")
{
    // Marks every 2 mm from 0; from 9.9 mm forward the second mark (12 mm) lies beyond the
    // end stop at 10.5 mm: direction 0 reverses there (the manual), direction 4 ends there.
    auto reversing = device("2.0.1", "SC", 9'900'000);
    CHECK(reversing->send(":FRM0,0,0,1\n") == ":E0,0\n");
    reversing->advance_ms(600 + 3900);                        // to +10.5, back past 8 to 6 mm
    CHECK(reversing->send(":GS0\n:GPPK0\n:GP0\n") == ":S0,0\n:PPK0,1\n:P0,0\n");
    auto aborting = device("2.0.1", "SC", 9'900'000);
    CHECK(aborting->send(":SCM1\n:FRM0,4,0,1\n") == "");
    aborting->advance_ms(600);
    CHECK(aborting->send(":GS0\n:GPPK0\n") == ":E0,144\n:S0,0\n:PPK0,0\n");
    // From -2.5 mm both marks (-2, 0) lie ahead: found at the second.
    auto found = device("2.0.1", "SC", -2'500'000);
    CHECK(found->send(":FRM0,4,0,0\n") == ":E0,0\n");
    found->advance_ms(2500);
    CHECK(found->send(":GS0\n:GPPK0\n:GP0\n") == ":S0,0\n:PPK0,1\n:P0,0\n");
}

TEST_CASE("firmware 2.0.1: end-stop types ignore every direction: the end stop is the reference", "[device][mcs][firmware][frm]")
{
    auto h = device("2.0.1", "M", 0);
    CHECK(h->send(":SSD0,1\n:CS0\n") == ":E-1,0\n:E0,0\n");
    h->advance_ms(3000);
    CHECK(h->send(":MPA0,0,0\n") == ":E0,0\n");
    h->advance_ms(2000);
    CHECK(h->send(":FRM0,4,0,1\n") == ":E0,0\n");             // forward aborting: ignored, backward
    h->advance_ms(10'499);
    CHECK(h->send(":GS0\n") == ":S0,7\n");
    h->advance_ms(1);
    CHECK(h->send(":GS0\n:GPPK0\n:GP0\n") == ":S0,0\n:PPK0,1\n:P0,0\n");
}

TEST_CASE("firmware 2.0.1: hold time and auto zero as in the manual", "[device][mcs][firmware][frm]")
{
    auto h = device("2.0.1");
    CHECK(h->send(":FRM0,2,0,2\n:FRM0,2,60001,0\n:FRM0,2,-1,0\n") == ":E0,7\n:E0,7\n:E0,7\n");
    // The scale offset in non-volatile memory applies when auto zero is off (2.3.3).
    CHECK(h->send(":SSC0,2000000,0\n") == ":E-1,0\n");
    CHECK(h->send(":FRM0,3,60000,0\n") == ":E0,0\n");          // backward first: mark 3 mm behind
    h->advance_ms(3000);
    CHECK(h->send(":GS0\n:GPPK0\n:GP0\n") == ":S0,3\n:PPK0,1\n:P0,2000000\n");
    h->advance_ms(120'000);                                   // 60,000 ms: held until stopped
    CHECK(h->send(":GS0\n") == ":S0,3\n");
    CHECK(h->send(":S0\n:GS0\n") == ":E0,0\n:S0,0\n");
    // Auto zero: the mark reads 0; a hold of 1000 ms ends after 1 s.
    CHECK(h->send(":MPA0,4000000,0\n") == ":E0,0\n");
    h->advance_ms(1000);
    CHECK(h->send(":FRM0,3,1000,1\n") == ":E0,0\n");
    h->advance_ms(2000);
    CHECK(h->send(":GS0\n:GP0\n") == ":S0,3\n:P0,0\n");
    h->advance_ms(1000);
    CHECK(h->send(":GS0\n") == ":S0,0\n");
}

} // namespace test_mcs_firmware
