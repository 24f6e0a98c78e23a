// The MMR601 modular rack with MPZ601 piezo cards (docs/protocol/apt.md "Units of today"): the rack's
// identity as read from a unit (pyLabLib issue 97), bays at 0x21.. as on the BSC203, two piezo channels
// a card addressed by the channel word, their status updates, and the freeze of a rack addressed as a
// single unit (the wrong rack flag, pyLabLib issue 81) until a power cycle. Bytes in -> bytes out on
// the stepped clock.
#include "apt_harness.hpp"

#include "models/piezo_actuator.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace test_apt_mmr601 {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;
using nlohmann::json;

namespace {

json rack(json apt = json::object())
{
    return json{{"name", "mmr"}, {"protocol", "apt"}, {"model", "MMR601"}, {"apt", std::move(apt)}};
}


} // namespace

TEST_CASE("MMR601: the rack's identity, MPZ601 cards in its bays, two channels a card", "[device][apt][today][mmr601]")
{
    AptHarness h(loaded_apt_device(rack({{"bays", json::array({json::object(), json::object()})}})));
    const auto info = bytes(h.send("05 00 00 00 11 01"));
    REQUIRE(info.size() == 90);
    CHECK(get_u32(info, 6) == 75'000'001);
    CHECK(hex(info.substr(10, 8)) == "4D 4D 52 36 30 31 00 00");   // "MMR601"
    CHECK(get_u16(info, 18) == 3);                                  // type 3 (pyLabLib issue 97)
    CHECK(hex(info.substr(20, 4)) == "02 00 01 00");               // firmware 1.0.2
    CHECK(info.substr(24, 47) == std::string("MMR601 Rack USB Communications Board (Issue 3)", 47));
    CHECK(get_u16(info, 84) == 3);   // hardware version
    CHECK(get_u16(info, 88) == 2);   // the two cards (six in the default rig, as issue 97's unit reports)
    const auto card = bytes(h.send("05 00 00 00 22 01"));
    REQUIRE(card.size() == 90);
    CHECK(get_u32(card, 6) / 1'000'000 == 51);
    CHECK(hex(card.substr(10, 8)) == "4D 50 5A 36 30 31 00 00");   // "MPZ601"
    // RACK_REQ_BAYUSED: bays 0 and 1 hold a card, bay 2 does not; a message to it is ignored.
    CHECK(h.send("60 00 00 00 11 01") == "61 00 00 01 01 11");
    CHECK(h.send("60 00 02 00 11 01") == "61 00 02 02 01 11");
    CHECK(h.send("05 00 00 00 23 01") == "");
    // PZ_SET_OUTPUTVOLTS on card 0's channel 2: channel 1 keeps 0.
    CHECK(h.send("43 06 04 00 A1 01 02 00 FF 3F") == "");
    CHECK(h.send("44 06 02 00 21 01") == "45 06 04 00 81 21 02 00 FF 3F");
    CHECK(h.send("44 06 01 00 21 01") == "45 06 04 00 81 21 01 00 00 00");
    h.advance_ms(100);
    const auto* ch2 = h.world().find_as<models::PiezoActuator>("mmr/1.2");
    const auto* ch1 = h.world().find_as<models::PiezoActuator>("mmr/1.1");
    REQUIRE(ch2 != nullptr);
    REQUIRE(ch1 != nullptr);
    CHECK(ch2->extension_um() > 4.0);
    CHECK(ch1->extension_um() == 0.0);
    // Channel 3 is no channel of an MPZ601; channel 0 neither (a rack keeps the manual's rule).
    CHECK(h.send("44 06 03 00 21 01") == "");
    CHECK(h.send("44 06 00 00 21 01") == "");
    // The status updates: one PZ_GET_PZSTATUSUPDATE per channel of each card, from its bay.
    CHECK(h.send("11 00 00 00 11 01") == "");
    h.advance_ms(100);
    const auto updates = frames(h.take());
    REQUIRE(updates.size() == 4);
    CHECK(updates[0].substr(0, 23) == "61 06 0A 00 81 21 01 00");
    CHECK(updates[1].substr(0, 23) == "61 06 0A 00 81 21 02 00");
    CHECK(updates[2].substr(0, 23) == "61 06 0A 00 81 22 01 00");
    CHECK(updates[3].substr(0, 23) == "61 06 0A 00 81 22 02 00");
}

TEST_CASE("MMR601: addressed as a single unit (0x50), it freezes until a power cycle", "[device][apt][today][mmr601]")
{
    AptHarness h(loaded_apt_device(rack()));
    CHECK(frames(h.send("05 00 00 00 11 01")).size() == 1);
    CHECK(h.send("11 00 00 00 11 01") == "");   // status updates on: 12 a period (6 cards, 2 channels)
    h.advance_ms(100);
    CHECK(frames(h.take()).size() == 12);
    CHECK(h.send("05 00 00 00 50 01") == "");   // pyLabLib with is_rack_system=False
    CHECK(h.send("05 00 00 00 11 01") == "");
    CHECK(h.send("44 06 01 00 21 01") == "");
    json d;
    h.device().describe(d);
    CHECK(d["frozen"] == true);
    // Frozen, it sends nothing by itself either: no status updates.
    h.advance_ms(1000);
    CHECK(h.take() == "");
    h.device().power_cycle(PowerCycle{});
    CHECK(frames(h.send("05 00 00 00 11 01")).size() == 1);
    CHECK(h.send("44 06 01 00 21 01") == "45 06 04 00 81 21 01 00 00 00");
}

TEST_CASE("MMR601: the rig's cards, refused with the JSON pointer", "[device][apt][today][mmr601]")
{
    CHECK(apt_load_error(rack({{"bays", json::array({{{"channels", json::array({json::object()})}}})}}))
          == "rig.json: /devices/0/apt/bays/0/channels: expected an array of 2 channel objects, got an array of 1 "
             "element");
    CHECK(apt_load_error(rack({{"bays", json::array({{{"travel_um", 30}}})}}))
          == "rig.json: /devices/0/apt/bays/0: unknown key \"travel_um\" (allowed: channels)");
    CHECK(apt_load_error(rack({{"bays", json::array({{{"channels", json::array({{{"travel_um", 30}}, {{"creep", 0.01}}})}}})}}))
          == "");
    CHECK(apt_load_error(rack({{"bays", json::array({json::object(), json::object(), json::object(), json::object(),
                                                 json::object(), json::object(), json::object()})}}))
              .find("1..6 bays")
          != std::string::npos);
    CHECK(apt_load_error(json{{"name", "mmr"}, {"protocol", "apt"}, {"model", "MMR601"}, {"firmware", "issue-3"}, {"apt", json::object()}})
              .find("firmware")
          != std::string::npos);
}

TEST_CASE("MMR601: an MPZ601 card takes PZ_SET_IOSETTINGS per channel and PZ_SET_LUTVALUETYPE for both",
          "[device][apt][today][mmr601]")
{
    AptHarness h(loaded_apt_device(rack({{"bays", json::array({json::object()})}})));
    CHECK(h.send("71 06 02 00 21 01") == "72 06 0A 00 81 21 02 00 00 00 00 00 00 00 00 00");
    CHECK(h.send("70 06 0A 00 A1 01 02 00 02 00 03 00 00 00 FF FF") == "");
    CHECK(h.send("71 06 02 00 21 01") == "72 06 0A 00 81 21 02 00 02 00 03 00 00 00 FF FF");
    CHECK(h.send("71 06 01 00 21 01") == "72 06 0A 00 81 21 01 00 00 00 00 00 00 00 00 00");
    CHECK(h.send("70 06 0A 00 A1 01 01 00 03 00 00 00 00 00 00 00") == "");   // current limit 3: out of range
    CHECK(h.send("71 06 01 00 21 01") == "72 06 0A 00 81 21 01 00 00 00 00 00 00 00 00 00");
    // LUTVALUETYPE 2 (positions): param1 is the type, not a channel; both channels take it.
    CHECK(h.send("08 07 02 00 21 01") == "");
    json d;
    h.device().describe(d);
    CHECK(d["channels"][0]["card_channels"][0]["lut_value_type"] == "position");
    CHECK(d["channels"][0]["card_channels"][1]["lut_value_type"] == "position");
    CHECK(h.send("08 07 03 00 21 01") == "");   // no type 3: ignored
    h.device().describe(d);
    CHECK(d["channels"][0]["card_channels"][1]["lut_value_type"] == "position");
}

} // namespace test_apt_mmr601
