// The motor messages of later protocol issues (kcube_params.hpp) on the units that take them:
// under the "issue-44.1" generation a SET is answered back by its REQ, a SET out of the
// documented range is ignored (the REQ still answers the old block), a model that does not
// take the block ignores it; under the manual's "issue-3" generation (the default) every one
// of them is ignored. MOT_SET_EEPROMPARAMS saves their SETs as it saves the manual's.
#include "apt_harness.hpp"

#include <spdlog/sinks/ostream_sink.h>

#include <fstream>
#include <sstream>
#include <stdlib.h>
#include <unistd.h>

namespace test_apt_kcube_params {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;

namespace {

/// `c` following the later protocol issue's generation.
DeviceConfig later(DeviceConfig c)
{
    c.firmware = "issue-44.1";
    config_of(c).firmware = Firmware::Issue44_1;
    return c;
}

/// `c` following the manual's generation, named as the rig would name it.
DeviceConfig manual(DeviceConfig c)
{
    c.firmware = "issue-3";
    config_of(c).firmware = Firmware::Issue3;
    return c;
}

const std::string kTwelveZeros = " 00 00 00 00 00 00 00 00 00 00 00 00";

/// A state store on a fresh file holding `json`, removed afterwards.
class StoreFixture {
public:
    explicit StoreFixture(const std::string& json)
    {
        char dir_template[] = "/tmp/rigsim-kcube-XXXXXX";
        REQUIRE(::mkdtemp(dir_template));
        dir_ = dir_template;
        path_ = dir_ + "/state.json";
        std::ofstream(path_) << json;
        log_ = std::make_shared<spdlog::logger>("state", std::make_shared<spdlog::sinks::ostream_sink_mt>(log_text_));
        store_ = std::make_unique<StateStore>(path_, log_);
    }
    ~StoreFixture()
    {
        store_.reset();
        for (const auto* suffix : {"", ".damaged", ".damaged.1"})
            std::remove((path_ + suffix).c_str());
        ::rmdir(dir_.c_str());
    }
    StateStore& store() { return *store_; }
    std::string log() const { return log_text_.str(); }

private:
    std::string dir_;
    std::string path_;
    std::ostringstream log_text_;
    std::shared_ptr<spdlog::logger> log_;
    std::unique_ptr<StateStore> store_;
};

/// A device (not powered up: no stage moves here) whose log is captured.
class LoggedDevice {
public:
    explicit LoggedDevice(const DeviceConfig& config)
        : log_(std::make_shared<spdlog::logger>("apt", std::make_shared<spdlog::sinks::ostream_sink_st>(log_text_))),
          device_(config, world_, log_, nullptr),
          session_(device_.open_session([this](std::string_view b) { out_.append(b); }, "test"))
    {
    }
    /// Hex in; hex of everything sent since the last call out.
    std::string send(const std::string& hex_in)
    {
        session_->receive(bytes(hex_in));
        std::string r;
        r.swap(out_);
        return hex(r);
    }
    /// The log written since the last call.
    std::string take_log()
    {
        std::string r = log_text_.str();
        log_text_.str("");
        return r;
    }

private:
    std::ostringstream log_text_;
    std::shared_ptr<spdlog::logger> log_;
    Clock clock_;
    models::World world_{clock_};
    AptDevice device_;
    std::string out_;
    std::unique_ptr<Session> session_;
};

} // namespace

TEST_CASE("the later-issue motor messages are ignored with a warning that says why", "[device][apt][kcube]")
{
    LoggedDevice old_unit(apt_cube("KST101", "DRV014"));
    CHECK(old_unit.send("26 04 06 00 D0 01 01 00 0A 00 64 00") == "");
    auto log = old_unit.take_log();
    CHECK(log.find("[warning]") != std::string::npos);
    CHECK(log.find("test: MGMSG_MOT_SET_POWERPARAMS is a message of later protocol issues: a KST101 of the "
                   "issue-3 generation (the 2012 manual) does not know it: ignored")
          != std::string::npos);

    LoggedDevice kst(later(apt_cube("KST101", "DRV014")));
    CHECK(kst.send("26 04 06 00 D0 01 01 00 00 00 64 00") == "");
    CHECK(kst.take_log().find("MGMSG_MOT_SET_POWERPARAMS with RestFactor 0 (1..100): ignored") != std::string::npos);
    CHECK(kst.send("FE 04 99 00 50 01") == "");
    CHECK(kst.take_log().find("MGMSG_MOT_SET_TSTACTUATORTYPE with actuator 0x99 (not a documented actuator): ignored")
          != std::string::npos);

    LoggedDevice kdc(later(apt_cube("KDC101", "Z825B")));
    CHECK(kdc.send("2A 05 01 00 50 01") == "");
    CHECK(kdc.take_log().find("MGMSG_MOT_REQ_KCUBEKSTLOOPPARAMS is not a message a KDC101 acts on: ignored")
          != std::string::npos);
}

TEST_CASE("issue-44.1: MOT_SET/REQ_POWERPARAMS on the steppers, ranges 1..100 %", "[device][apt][kcube]")
{
    AptHarness h(later(apt_cube("KST101", "DRV014")));
    // Issue 16 p. 44: APTServer's rest 5 %, move 30 % until a client sets them.
    CHECK(h.send("27 04 01 00 50 01") == "28 04 06 00 81 50 01 00 05 00 1E 00");
    CHECK(h.send("26 04 06 00 D0 01 01 00 0A 00 64 00") == "");
    CHECK(h.send("27 04 01 00 50 01") == "28 04 06 00 81 50 01 00 0A 00 64 00");
    // Out of 1..100: ignored, the block unchanged.
    CHECK(h.send("26 04 06 00 D0 01 01 00 00 00 64 00") == "");
    CHECK(h.send("26 04 06 00 D0 01 01 00 0A 00 65 00") == "");
    CHECK(h.send("27 04 01 00 50 01") == "28 04 06 00 81 50 01 00 0A 00 64 00");
    // A channel-0 REQ is the cube's channel 1, as for the manual's messages.
    CHECK(h.send("27 04 00 00 50 01") == "28 04 06 00 81 50 01 00 0A 00 64 00");

    AptHarness tst(later(apt_cube("TST001", "DRV001")));
    CHECK(tst.send("26 04 06 00 D0 01 01 00 0F 00 1E 00") == "");
    CHECK(tst.send("27 04 01 00 50 01") == "28 04 06 00 81 50 01 00 0F 00 1E 00");

    AptHarness rack(later(apt_rack("BSC203", {"DRV014", "ZST225B"})));
    CHECK(rack.send("26 04 06 00 A2 01 01 00 0F 00 1E 00") == "");   // bay 1 (0x22)
    CHECK(rack.send("27 04 01 00 22 01") == "28 04 06 00 81 22 01 00 0F 00 1E 00");
    CHECK(rack.send("27 04 01 00 21 01") == "28 04 06 00 81 21 01 00 05 00 1E 00");

    // A DC servo has no phase power: the KDC101 ignores the block.
    AptHarness kdc(later(apt_cube("KDC101", "Z825B")));
    CHECK(kdc.send("26 04 06 00 D0 01 01 00 0A 00 64 00") == "");
    CHECK(kdc.send("27 04 01 00 50 01") == "");
}

TEST_CASE("issue-44.1: MOT_SET/REQ_TRIGGER on the racks keep any mode byte", "[device][apt][kcube]")
{
    AptHarness bsc(later(apt_rack("BSC203", {"DRV014"})));
    CHECK(bsc.send("01 05 01 00 21 01") == "02 05 01 00 01 21");
    CHECK(bsc.send("00 05 01 53 21 01") == "");   // issue 16 p. 103's example mode
    CHECK(bsc.send("01 05 01 00 21 01") == "02 05 01 53 01 21");
    CHECK(bsc.send("00 05 01 FF 21 01") == "");
    CHECK(bsc.send("01 05 01 00 21 01") == "02 05 01 FF 01 21");

    AptHarness bbd(later(apt_rack("BBD203", {"MLS203-X"})));
    CHECK(bbd.send("00 05 01 53 21 01") == "");
    CHECK(bbd.send("01 05 01 00 21 01") == "02 05 01 53 01 21");

    AptHarness kst(later(apt_cube("KST101", "DRV014")));
    CHECK(kst.send("00 05 01 53 50 01") == "");
    CHECK(kst.send("01 05 01 00 50 01") == "");
}

TEST_CASE("issue-44.1: MOT_SET/REQ_KCUBEMMIPARAMS on the K-Cubes, with the wheel and display ranges",
          "[device][apt][kcube]")
{
    AptHarness h(later(apt_cube("KDC101", "Z825B")));
    const std::string zeros32 = " 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00";
    CHECK(h.send("21 05 01 00 50 01") == "22 05 24 00 81 50 01 00 01 00" + zeros32);
    const std::string block = "01 00 02 00 00 00 01 00 00 08 00 00 01 00 E8 03 00 00 18 FC FF FF 3C 00 0A 00 02 00 "
                              "FF FF FF 7F 03 00 00 00";
    CHECK(h.send("20 05 24 00 D0 01 " + block) == "");
    CHECK(h.send("21 05 01 00 50 01") == "22 05 24 00 81 50 " + block);
    // JSMode 0 (the KSC101's msl-equipment SET: a motor cube has a wheel), 4, DirSense 3,
    // DispBrightness 101, DispTimeout 481, DispDimLevel 11: each ignored.
    for (const auto* bad : {"01 00 00 00 00 00 01 00 00 08 00 00 01 00 E8 03 00 00 18 FC FF FF 3C 00 0A 00 02 00 ",
                            "01 00 04 00 00 00 01 00 00 08 00 00 01 00 E8 03 00 00 18 FC FF FF 3C 00 0A 00 02 00 ",
                            "01 00 02 00 00 00 01 00 00 08 00 00 03 00 E8 03 00 00 18 FC FF FF 3C 00 0A 00 02 00 ",
                            "01 00 02 00 00 00 01 00 00 08 00 00 01 00 E8 03 00 00 18 FC FF FF 65 00 0A 00 02 00 ",
                            "01 00 02 00 00 00 01 00 00 08 00 00 01 00 E8 03 00 00 18 FC FF FF 3C 00 E1 01 02 00 ",
                            "01 00 02 00 00 00 01 00 00 08 00 00 01 00 E8 03 00 00 18 FC FF FF 3C 00 0A 00 0B 00 "}) {
        INFO(bad);
        CHECK(h.send(std::string("20 05 24 00 D0 01 ") + bad + "00 00 00 00 00 00 00 00") == "");
        CHECK(h.send("21 05 01 00 50 01") == "22 05 24 00 81 50 " + block);
    }

    AptHarness kst(later(apt_cube("KST101", "DRV014")));
    CHECK(kst.send("20 05 24 00 D0 01 " + block) == "");
    CHECK(kst.send("21 05 01 00 50 01") == "22 05 24 00 81 50 " + block);
}

TEST_CASE("issue-44.1: MOT_SET/REQ_KCUBETRIGIOCONFIG keeps documented modes, one position-pulse port",
          "[device][apt][kcube]")
{
    AptHarness h(later(apt_cube("KDC101", "Z825B")));
    CHECK(h.send("24 05 01 00 50 01") == "25 05 16 00 81 50 01 00 00 00 01 00 00 00 01 00" + kTwelveZeros);
    // Thorlabs' example: TRIG1 relative-move input, TRIG2 in-motion output, both active high.
    CHECK(h.send("23 05 16 00 D0 01 01 00 02 00 01 00 0B 00 01 00" + kTwelveZeros) == "");
    const std::string example = "25 05 16 00 81 50 01 00 02 00 01 00 0B 00 01 00" + kTwelveZeros;
    CHECK(h.send("24 05 01 00 50 01") == example);
    // Mode 5 (not a mode), polarity 3, both ports pulsing at positions (0x0D, 0x0F): ignored.
    CHECK(h.send("23 05 16 00 D0 01 01 00 05 00 01 00 0B 00 01 00" + kTwelveZeros) == "");
    CHECK(h.send("23 05 16 00 D0 01 01 00 02 00 03 00 0B 00 01 00" + kTwelveZeros) == "");
    CHECK(h.send("23 05 16 00 D0 01 01 00 0D 00 01 00 0F 00 01 00" + kTwelveZeros) == "");
    CHECK(h.send("24 05 01 00 50 01") == example);
    // One position-pulse port, active low: kept.
    CHECK(h.send("23 05 16 00 D0 01 01 00 0D 00 02 00 12 00 01 00" + kTwelveZeros) == "");
    CHECK(h.send("24 05 01 00 50 01") == "25 05 16 00 81 50 01 00 0D 00 02 00 12 00 01 00" + kTwelveZeros);
}

TEST_CASE("issue-44.1: MOT_SET/REQ_KCUBEPOSTRIGPARAMS, pulse width 1..1,000,000 us", "[device][apt][kcube]")
{
    AptHarness h(later(apt_cube("KST101", "DRV014")));
    const std::string head = "28 05 2E 00 81 50 ";
    // Power-up: Thorlabs' example's start-up values.
    CHECK(h.send("27 05 01 00 50 01")
          == head + "01 00 00 00 00 00 00 00 00 00 01 00 00 00 00 00 00 00 00 00 00 00 01 00 00 00 32 00 00 00 01 00 00 00"
                 + kTwelveZeros);
    // From 1000 every 200 counts, 5 pulses forward; from 2000 every 100, 3 back; 10 us; 2 cycles.
    const std::string block = "01 00 E8 03 00 00 C8 00 00 00 05 00 00 00 D0 07 00 00 64 00 00 00 03 00 00 00 "
                              "0A 00 00 00 02 00 00 00" + kTwelveZeros;
    CHECK(h.send("26 05 2E 00 D0 01 " + block) == "");
    CHECK(h.send("27 05 01 00 50 01") == head + block);
    // Pulse width 0 and 1,000,001 us: ignored.
    CHECK(h.send("26 05 2E 00 D0 01 01 00 E8 03 00 00 C8 00 00 00 05 00 00 00 D0 07 00 00 64 00 00 00 03 00 00 00 "
                 "00 00 00 00 02 00 00 00" + kTwelveZeros) == "");
    CHECK(h.send("26 05 2E 00 D0 01 01 00 E8 03 00 00 C8 00 00 00 05 00 00 00 D0 07 00 00 64 00 00 00 03 00 00 00 "
                 "41 42 0F 00 02 00 00 00" + kTwelveZeros) == "");
    CHECK(h.send("27 05 01 00 50 01") == head + block);
}

TEST_CASE("issue-44.1: MOT_SET/REQ_KCUBEKSTLOOPPARAMS on the KST101, loop mode 1 or 2", "[device][apt][kcube]")
{
    AptHarness h(later(apt_cube("KST101", "DRV014")));
    const std::string head = "2B 05 1C 00 81 50 ";
    CHECK(h.send("2A 05 01 00 50 01")
          == head + "01 00 01 00 40 0D 03 00 E8 03 00 00 64 00 00 00 00 E1 F5 05 C8 00 00 00 00 00 00 00");
    const std::string closed = "01 00 02 00 10 27 00 00 64 00 00 00 0A 00 00 00 40 42 0F 00 14 00 00 00 00 10 00 00";
    CHECK(h.send("29 05 1C 00 D0 01 " + closed) == "");
    CHECK(h.send("2A 05 01 00 50 01") == head + closed);
    CHECK(h.send("29 05 1C 00 D0 01 01 00 03 00 10 27 00 00 64 00 00 00 0A 00 00 00 40 42 0F 00 14 00 00 00 00 10 00 00")
          == "");
    CHECK(h.send("2A 05 01 00 50 01") == head + closed);

    AptHarness kdc(later(apt_cube("KDC101", "Z825B")));
    CHECK(kdc.send("2A 05 01 00 50 01") == "");
}

TEST_CASE("issue-3 (the default): a unit of the manual ignores every later-issue motor message",
          "[device][apt][kcube]")
{
    for (const auto& config : {apt_cube("KST101", "DRV014"), manual(apt_cube("KST101", "DRV014"))}) {
        AptHarness h(config);
        CHECK(h.send("26 04 06 00 D0 01 01 00 0A 00 64 00") == "");
        CHECK(h.send("27 04 01 00 50 01") == "");
        CHECK(h.send("21 05 01 00 50 01") == "");
        CHECK(h.send("24 05 01 00 50 01") == "");
        CHECK(h.send("27 05 01 00 50 01") == "");
        CHECK(h.send("2A 05 01 00 50 01") == "");
        CHECK(h.send("FE 04 41 00 50 01") == "");
        // The unit goes on answering the manual's messages.
        CHECK(h.send("11 04 01 00 50 01") == "12 04 06 00 81 50 01 00 00 00 00 00");
    }
    AptHarness bsc(apt_rack("BSC203", {"DRV014"}));
    CHECK(bsc.send("00 05 01 53 21 01") == "");
    CHECK(bsc.send("01 05 01 00 21 01") == "");
    AptHarness kdc(apt_cube("KDC101", "Z825B"));
    CHECK(kdc.send("20 05 24 00 D0 01 01 00 01 00" + kTwelveZeros + kTwelveZeros + " 00 00 00 00 00 00 00 00") == "");
    CHECK(kdc.send("21 05 01 00 50 01") == "");
}

TEST_CASE("issue-44.1: MOT_SET_EEPROMPARAMS saves the later-issue SETs and a power-up restores them",
          "[device][apt][kcube][eeprom]")
{
    StoreFixture f("{}");
    const std::string block = "01 00 02 00 00 00 01 00 00 08 00 00 01 00 E8 03 00 00 18 FC FF FF 3C 00 0A 00 02 00 "
                              "FF FF FF 7F 03 00 00 00";
    {
        AptHarness h(later(apt_cube("KST101", "DRV014")), &f.store());
        CHECK(h.send("20 05 24 00 D0 01 " + block) == "");
        CHECK(h.send("B9 04 04 00 D0 01 01 00 20 05") == "");
        CHECK(h.send("26 04 06 00 D0 01 01 00 0A 00 64 00") == "");
        CHECK(h.send("B9 04 04 00 D0 01 01 00 26 04") == "");
        // TSTACTUATORTYPE has no GET: what is saved is the last actuator the unit took.
        CHECK(h.send("FE 04 41 00 50 01") == "");
        CHECK(h.send("FE 04 99 00 50 01") == "");   // no such actuator: ignored
        CHECK(h.send("B9 04 04 00 D0 01 01 00 FE 04") == "");
    }
    REQUIRE(f.store().get("cube", "bay0/0x0520"));
    CHECK(*f.store().get("cube", "bay0/0x0520") == "01000200000001000008000001"
                                                   "00e803000018fcffff3c000a000200ffffff7f03000000");
    REQUIRE(f.store().get("cube", "bay0/0x0426"));
    CHECK(*f.store().get("cube", "bay0/0x0426") == "01000a006400");
    REQUIRE(f.store().get("cube", "bay0/0x04fe"));
    CHECK(*f.store().get("cube", "bay0/0x04fe") == "4100");

    AptHarness again(later(apt_cube("KST101", "DRV014")), &f.store());
    CHECK(again.send("21 05 01 00 50 01") == "22 05 24 00 81 50 " + block);
    CHECK(again.send("27 04 01 00 50 01") == "28 04 06 00 81 50 01 00 0A 00 64 00");
    CHECK(f.log().find("skipped") == std::string::npos);
}

TEST_CASE("issue-3: MOT_SET_EEPROMPARAMS saves no later-issue SET and a stored one is skipped",
          "[device][apt][kcube][eeprom]")
{
    StoreFixture f(R"({"cube": {"bay0/0x0426": "01000a006400"}})");
    AptHarness h(apt_cube("KST101", "DRV014"), &f.store());
    CHECK(f.log().find("bay0/0x0426\": skipped: MGMSG_MOT_SET_POWERPARAMS is not a parameter SET that "
                       "MOT_SET_EEPROMPARAMS saves")
          != std::string::npos);
    CHECK(h.send("FE 04 41 00 50 01") == "");
    CHECK(h.send("B9 04 04 00 D0 01 01 00 FE 04") == "");
    CHECK(f.store().get("cube", "bay0/0x04fe") == nullptr);
}

} // namespace test_apt_kcube_params
