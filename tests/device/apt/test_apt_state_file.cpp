// The APT non-volatile memory (--state-file): what MOT_SET_EEPROMPARAMS may save, and a
// power-up that restores only well-formed, accepted parameter SETs of the device's own bays.
#include "apt_harness.hpp"

#include <spdlog/sinks/ostream_sink.h>

#include <fstream>
#include <sstream>
#include <stdlib.h>
#include <unistd.h>

namespace test_apt_state_file {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;

namespace {

/// A state file with `json` in a fresh directory, and a store on it whose log is captured.
class StateFileFixture {
public:
    explicit StateFileFixture(const std::string& json)
    {
        char dir_template[] = "/tmp/rigsim-state-XXXXXX";
        REQUIRE(::mkdtemp(dir_template));
        dir_ = dir_template;
        path_ = dir_ + "/state.json";
        std::ofstream(path_) << json;
        log_ = std::make_shared<spdlog::logger>("state", std::make_shared<spdlog::sinks::ostream_sink_mt>(log_text_));
        store_ = std::make_unique<StateStore>(path_, log_);
    }
    ~StateFileFixture()
    {
        store_.reset();
        for (const auto* suffix : {"", ".damaged", ".damaged.1"})
            std::remove((path_ + suffix).c_str());
        ::rmdir(dir_.c_str());
    }

    StateStore& store() { return *store_; }
    const std::string& path() const { return path_; }
    std::string log() const { return log_text_.str(); }

private:
    std::string dir_;
    std::string path_;
    std::ostringstream log_text_;
    std::shared_ptr<spdlog::logger> log_;
    std::unique_ptr<StateStore> store_;
};

/// The skip line StateStore::reject writes for `key` of device `device`.
std::string skipped(const StateFileFixture& f, const std::string& device, const std::string& key)
{
    return "state file " + f.path() + ": device \"" + device + "\", key \"" + key + "\": skipped: ";
}

/// What the log says after the skip line of `key`, to the end of that line.
std::string why_skipped(const StateFileFixture& f, const std::string& device, const std::string& key)
{
    const auto log = f.log();
    const auto head = skipped(f, device, key);
    const auto at = log.find(head);
    if (at == std::string::npos)
        return "<not skipped>";
    const auto from = at + head.size();
    return log.substr(from, log.find('\n', from) - from);
}

constexpr const char* kVelParams_acc16_max4096 = "01000000000010000000" "00100000";   // chan 1, min 0, acc 16, max 4096

} // namespace

TEST_CASE("state file: good MOT_SET_EEPROMPARAMS entries still restore", "[device][apt][eeprom][state]")
{
    StateFileFixture f(std::string(R"({"cube": {"bay0/0x0413": ")") + kVelParams_acc16_max4096
                       + R"(", "bay0/0x043a": "010000000d00"}})");
    AptHarness h(tdc001(), &f.store());
    CHECK(h.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 01 00 00 00 00 00 10 00 00 00 00 10 00 00");
    CHECK(h.send("3B 04 01 00 50 01") == "3C 04 06 00 81 50 01 00 00 00 0D 00");   // backlash 0x000D0000
    CHECK(f.log().find("skipped") == std::string::npos);
    // A restored SET is the bay's last accepted one: saving it again keeps it.
    CHECK(h.send("B9 04 04 00 D0 01 01 00 13 04") == "");
    REQUIRE(f.store().get("cube", "bay0/0x0413"));
    CHECK(*f.store().get("cube", "bay0/0x0413") == kVelParams_acc16_max4096);
}

TEST_CASE("state file: a short MOT_SET_PMDSTAGEAXISPARAMS entry is skipped, not read past its end",
          "[device][apt][eeprom][state]")
{
    StateFileFixture f(R"({"rack": {"bay0/0x04f0": "01000000"}})");
    AptHarness h(apt_rack("BBD203", {"MLS203-X", "MLS203-Y"}), &f.store());
    CHECK(why_skipped(f, "rack", "bay0/0x04f0")
          == "4 data bytes, MGMSG_MOT_SET_PMDSTAGEAXISPARAMS has 74");
    CHECK(get_i32(bytes(h.send("F1 04 01 00 21 01")), 40) == 2'200'000);   // travel unchanged: MaxPos 110 mm
    CHECK(f.store().get("rack", "bay0/0x04f0") == nullptr);
}

TEST_CASE("state file: a stored MOVE_ABSOLUTE is not replayed (the stage does not move at power-up)",
          "[device][apt][eeprom][state]")
{
    StateFileFixture f(R"({"cube": {"bay0/0x0453": "0100a0860100"}})");
    AptHarness h(tdc001(), &f.store());
    h.advance_ms(10'000);
    CHECK(why_skipped(f, "cube", "bay0/0x0453")
          == "MGMSG_MOT_MOVE_ABSOLUTE is not a parameter SET that MOT_SET_EEPROMPARAMS saves");
    CHECK(position_of(h.send("11 04 01 00 50 01")) == 0);
    CHECK(h.take() == "");   // no MOVE_COMPLETED either
}

TEST_CASE("state file: data that is not even-length hex is skipped and named", "[device][apt][eeprom][state]")
{
    StateFileFixture f(R"({"cube": {"bay0/0x0413": "01zz000000001000000000100000", "bay0/0x043a": "010000000d0",
                                    "bay0/0x0445": "+1000000000d", "bay0/0x0450": 42}})");
    AptHarness h(tdc001(), &f.store());
    CHECK(why_skipped(f, "cube", "bay0/0x0413") == "data is not hex (character 3 is 'z')");
    CHECK(why_skipped(f, "cube", "bay0/0x043a") == "data has an odd number of hex digits (11)");
    CHECK(why_skipped(f, "cube", "bay0/0x0445") == "data is not hex (character 1 is '+')");
    CHECK(why_skipped(f, "cube", "bay0/0x0450") == "expected a string of hex digits, got number");
    CHECK(h.send("3B 04 01 00 50 01") == "3C 04 06 00 81 50 01 00 00 00 00 00");   // backlash unchanged
}

TEST_CASE("state file: an entry out of range is skipped as the bay ignores it", "[device][apt][eeprom][state]")
{
    // VELPARAMS with acceleration 0; LIMSWITCHPARAMS with hardware mode 9.
    StateFileFixture f(R"({"cube": {"bay0/0x0413": "0100000000000000000000100000",
                                    "bay0/0x0423": "01000900020000000000000000000100"}})");
    AptHarness h(tdc001(), &f.store());
    const auto defaults = AptHarness().send("14 04 01 00 50 01");
    CHECK(why_skipped(f, "cube", "bay0/0x0413") == "the bay ignores this MGMSG_MOT_SET_VELPARAMS (its warning says why)");
    CHECK(why_skipped(f, "cube", "bay0/0x0423") == "the bay ignores this MGMSG_MOT_SET_LIMSWITCHPARAMS (its warning says why)");
    CHECK(h.send("14 04 01 00 50 01") == defaults);
    // Not the bay's last accepted SET either: MOT_SET_EEPROMPARAMS has nothing to save.
    CHECK(h.send("B9 04 04 00 D0 01 01 00 13 04") == "");
    CHECK(f.store().get("cube", "bay0/0x0413") == nullptr);
}

TEST_CASE("state file: entries of a bay the device lacks, of another channel or with a bad key are skipped",
          "[device][apt][eeprom][state]")
{
    StateFileFixture f(std::string(R"({"cube": {"bay1/0x0413": ")") + kVelParams_acc16_max4096 + R"(",
                                                "bay0/0x0414": "0200000000001000000000100000",
                                                "bay0/0x413": "x", "bay00/0x0413": "x", "bay0/0x0413 ": "x",
                                                "bay0/0x0413": "0200000000001000000000100000"},
                                       "rack": {"bay0/0x0413": "x"}})");
    AptHarness h(tdc001(), &f.store());
    CHECK(why_skipped(f, "cube", "bay1/0x0413") == "no bay 1 (the TDC001 has bay 0 only)");
    CHECK(why_skipped(f, "cube", "bay0/0x0414") == "MGMSG_MOT_REQ_VELPARAMS is not a parameter SET that MOT_SET_EEPROMPARAMS saves");
    CHECK(why_skipped(f, "cube", "bay0/0x413") == "the key is not bay<N>/0x<4 lower-case hex digits>");
    CHECK(why_skipped(f, "cube", "bay00/0x0413") == "the key is not bay<N>/0x<4 lower-case hex digits>");
    CHECK(why_skipped(f, "cube", "bay0/0x0413 ") == "the key is not bay<N>/0x<4 lower-case hex digits>");
    CHECK(why_skipped(f, "cube", "bay0/0x0413") == "channel 2 in the data; bay 0 is channel 1");
    CHECK(f.log().find("\"rack\"") == std::string::npos);   // another device's entries: not this device's business
    CHECK(h.send("14 04 01 00 50 01") == AptHarness().send("14 04 01 00 50 01"));
    CHECK(f.store().get("rack", "bay0/0x0413") != nullptr);
}

TEST_CASE("rig eeprom: apt.eeprom holds the unit's power-up parameters, under what the state file saved",
          "[device][apt][eeprom][state]")
{
    auto config = tdc001();
    config.source = "rig.json";
    config.pointer = "/devices/0";
    config_of(config).eeprom = {{"bay0/0x0413", kVelParams_acc16_max4096}, {"bay0/0x043a", "010000000d00"}};
    {
        AptHarness h(config);
        CHECK(h.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 01 00 00 00 00 00 10 00 00 00 00 10 00 00");
        CHECK(h.send("3B 04 01 00 50 01") == "3C 04 06 00 81 50 01 00 00 00 0D 00");   // backlash 851,968: the rig's
    }
    {
        // What a client saved since (the state file) is laid over the rig's memory.
        StateFileFixture f(R"({"cube": {"bay0/0x0413": "0100000000002000000000200000"}})");
        AptHarness h(config, &f.store());
        CHECK(h.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 01 00 00 00 00 00 20 00 00 00 00 20 00 00");
        CHECK(h.send("3B 04 01 00 50 01") == "3C 04 06 00 81 50 01 00 00 00 0D 00");
    }
}

TEST_CASE("rig eeprom: a power cycle brings the rig's memory back, with or without what was saved",
          "[device][apt][eeprom][state]")
{
    auto config = tdc001();
    config_of(config).eeprom = {{"bay0/0x0413", kVelParams_acc16_max4096}};
    StateFileFixture f(R"({"cube": {"bay0/0x043a": "010000000d00"}})");
    AptHarness h(config, &f.store());
    const std::string rig_velparams = "15 04 0E 00 81 50 01 00 00 00 00 00 10 00 00 00 00 10 00 00";
    CHECK(h.send("13 04 0E 00 D0 01 01 00 00 00 00 00 20 00 00 00 00 20 00 00") == "");   // a client's VELPARAMS
    CHECK(h.send("14 04 01 00 50 01") != rig_velparams);
    h.device().power_cycle(PowerCycle{true, false});
    CHECK(h.send("14 04 01 00 50 01") == rig_velparams);                                   // the unsaved SET is gone
    CHECK(h.send("3B 04 01 00 50 01") == "3C 04 06 00 81 50 01 00 00 00 0D 00");           // the saved one stays
    h.device().power_cycle(PowerCycle{false, false});
    CHECK(h.send("14 04 01 00 50 01") == rig_velparams);                                   // the unit's own memory
    CHECK(h.send("3B 04 01 00 50 01") == "3C 04 06 00 81 50 01 00 00 00 00 00");           // what was saved: erased
}

TEST_CASE("rig eeprom: an entry the unit does not save or take is a config error naming its pointer",
          "[device][apt][eeprom][state]")
{
    const std::pair<std::pair<const char*, const char*>, const char*> cases[] = {
        {{"bay0/0x0453", "0100a0860100"},
         "rig.json: /devices/0/apt/eeprom/bay0~10x0453: MGMSG_MOT_MOVE_ABSOLUTE is not a parameter SET that MOT_SET_EEPROMPARAMS saves"},
        {{"bay1/0x0413", kVelParams_acc16_max4096},
         "rig.json: /devices/0/apt/eeprom/bay1~10x0413: no bay 1 (the TDC001 has bay 0 only)"},
        {{"bay0/0x0413", "0100"},
         "rig.json: /devices/0/apt/eeprom/bay0~10x0413: 2 data bytes, MGMSG_MOT_SET_VELPARAMS has 14"},
        {{"bay0/0x0413", "0100000000000000000000100000"},   // acceleration 0
         "rig.json: /devices/0/apt/eeprom/bay0~10x0413: the bay ignores this MGMSG_MOT_SET_VELPARAMS (its warning says why)"},
        {{"bay0/0x0413", "0200000000001000000000100000"},
         "rig.json: /devices/0/apt/eeprom/bay0~10x0413: channel 2 in the data; bay 0 is channel 1"},
    };
    for (const auto& [entry, message] : cases) {
        INFO(entry.first << " " << entry.second);
        auto config = tdc001();
        config.source = "rig.json";
        config.pointer = "/devices/0";
        config_of(config).eeprom = {{entry.first, entry.second}};
        AptHarness h(config);
        CHECK_THROWS_WITH(h.device(), message);
    }
}

TEST_CASE("MOT_SET_EEPROMPARAMS saves only the parameter SETs of the manual, never the live position",
          "[device][apt][eeprom][state]")
{
    StateFileFixture f("{}");
    AptHarness h(tdc001(), &f.store());
    // p. 28: SET_POSCOUNTER sets the 'live' position count, not a setting.
    CHECK(h.send("10 04 06 00 D0 01 01 00 40 0D 03 00") == "");
    CHECK(h.send("B9 04 04 00 D0 01 01 00 10 04") == "");
    CHECK(f.store().get("cube", "bay0/0x0410") == nullptr);
    CHECK(f.log().empty());
    // A parameter SET is saved as sent.
    CHECK(h.send("3A 04 06 00 D0 01 01 00 00 0D 00 00") == "");
    CHECK(h.send("B9 04 04 00 D0 01 01 00 3A 04") == "");
    REQUIRE(f.store().get("cube", "bay0/0x043a"));
    CHECK(*f.store().get("cube", "bay0/0x043a") == "0100000d0000");
}

namespace {

/// Issue 12's units for the EEPROM case: a TPZ001, a BPC303 with three 150 V bays, a TSG001.
DeviceConfig pz_unit(const std::string& name, const std::string& model)
{
    DeviceConfig c;
    c.name = name;
    c.protocol = "apt";
    c.model = model;
    auto& apt = config_of(c);
    if (model == "BPC303") {
        PiezoBayConfig bay;
        bay.actuator.max_voltage_v = 150;
        bay.strain_gauge = true;
        apt.piezo_bays = {bay, bay, bay};
    }
    return c;
}

} // namespace

TEST_CASE("state file: PZ_SET_EEPROMPARAMS saves TPZ001 and TSG001 settings across a power cycle, a BPC303 bay ignores it",
          "[device][apt][eeprom][state][piezo]")
{
    StateFileFixture f("{}");
    {
        AptHarness h(pz_unit("tpz", "TPZ001"), &f.store());
        const auto bpc = h.add_device(pz_unit("bpc", "BPC303"), &f.store());
        const auto tsg = h.add_device(pz_unit("tsg", "TSG001"), &f.store());
        // TPZ001: PICONSTS 50/5 (p.100), display intensity 100 (p.114, no channel word), slew rates
        // 1266/1266 (p.123), each saved with PZ_SET_EEPROMPARAMS (p.113) naming it.
        CHECK(h.send("55 06 06 00 D0 01 01 00 32 00 05 00") == "");
        CHECK(h.send("D0 07 04 00 D0 01 01 00 55 06") == "");
        CHECK(h.send("D1 07 02 00 D0 01 64 00") == "");
        CHECK(h.send("D0 07 04 00 D0 01 01 00 D1 07") == "");
        CHECK(h.send("83 06 06 00 D0 01 01 00 F2 04 F2 04") == "");
        CHECK(h.send("D0 07 04 00 D0 01 01 00 83 06") == "");
        // Changed after the save: not what the EEPROM holds.
        CHECK(h.send("55 06 06 00 D0 01 01 00 3C 00 06 00") == "");
        // BPC303 bay 1 (0x22): OUTPUTMAXVOLTS 100 V (p.121 answers with the new maximum and travel).
        // The BPC30x table (p.132) has no PZ_SET_EEPROMPARAMS: the bay ignores it, nothing is saved.
        CHECK(frames(h.send("80 06 06 00 A2 01 01 00 E8 03 00 00", bpc)).size() == 2);
        CHECK(h.send("D0 07 04 00 A2 01 01 00 80 06", bpc) == "");
        // TSG001: TSG_IOSETTINGS display mode 2 (volts), force calibration 30000 (p.128).
        CHECK(h.send("DA 07 0E 00 D0 01 01 00 01 00 02 00 30 75 00 00 00 00 00 00", tsg) == "");
        CHECK(h.send("D0 07 04 00 D0 01 01 00 DA 07", tsg) == "");
        REQUIRE(f.store().get("tpz", "bay0/0x0655"));
        CHECK(*f.store().get("tpz", "bay0/0x0655") == "010032000500");
        CHECK(f.store().device_state("bpc").empty());
        REQUIRE(f.store().get("tsg", "bay0/0x07da"));
        CHECK(*f.store().get("tsg", "bay0/0x07da") == "0100010002003075000000000000");
        f.store().flush();
    }
    // Power cycle: the daemon restarts on the state file it wrote.
    StateStore reloaded(f.path());
    AptHarness h(pz_unit("tpz", "TPZ001"), &reloaded);
    const auto bpc = h.add_device(pz_unit("bpc", "BPC303"), &reloaded);
    const auto tsg = h.add_device(pz_unit("tsg", "TSG001"), &reloaded);
    CHECK(h.take() == "");   // restoring answers nobody
    CHECK(h.take(bpc) == "");
    CHECK(h.send("56 06 01 00 50 01") == "57 06 06 00 81 50 01 00 32 00 05 00");
    CHECK(h.send("D2 07 01 00 50 01") == "D3 07 02 00 81 50 64 00");
    CHECK(h.send("84 06 01 00 50 01") == "85 06 06 00 81 50 01 00 F2 04 F2 04");
    CHECK(h.send("81 06 01 00 22 01", bpc) == "82 06 06 00 81 22 01 00 DC 05 08 00");   // power-up 150 V
    CHECK(h.send("DB 07 01 00 50 01", tsg) == "DC 07 0E 00 81 50 01 00 01 00 02 00 30 75 00 00 00 00 00 00");
    CHECK(f.log().find("skipped") == std::string::npos);
}

TEST_CASE("state file: an MFF101's saved MFF_OPERPARAMS are its transit time at the next power-up",
          "[device][apt][eeprom][state][flipper]")
{
    // 1500 ms, I/O 1 an at-position output: saved by MOT_SET_EEPROMPARAMS, restored by a new unit.
    const std::string block = "01 00 DC 05 00 00 57 00 00 00 03 00 10 00 64 00 00 00 01 00 01 00 C8 00 00 00 "
                              "00 00 00 00 00 00 00 00";
    DeviceConfig mff;
    mff.name = "mff";
    mff.protocol = "apt";
    mff.model = "MFF101";
    mff.firmware = "issue-44.1";
    config_of(mff).firmware = Firmware::Issue44_1;
    StateFileFixture f("{}");
    {
        AptHarness h(mff, &f.store());
        CHECK(h.send("10 05 22 00 D0 01 " + block) == "");
        CHECK(h.send("B9 04 04 00 D0 01 01 00 10 05") == "");
        REQUIRE(f.store().get("mff", "bay0/0x0510"));
    }
    AptHarness again(mff, &f.store());
    CHECK(again.send("11 05 01 00 50 01") == "12 05 22 00 81 50 " + block);
    CHECK(again.send("6A 04 01 02 50 01") == "");
    std::string done;
    CHECK(ms_until_reply(again, done, 3'000) == 1'500);
}

} // namespace test_apt_state_file
