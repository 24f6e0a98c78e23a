// The event bus: each subscriber takes what its filter passes, an event is built once for all of
// them, and only when some subscriber (or the follow-up, for what it makes) takes its kind.

#include "emulator/core/event_bus.hpp"
#include "emulator/core/wire_log.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace test_event_bus {

using namespace rigsim;
using nlohmann::json;

TEST_CASE("event bus: wants() only the kinds a subscriber's filter passes, nothing else is built", "[unit][core]")
{
    EventBus bus;
    CHECK_FALSE(bus.wants("mcs0", "wire"));
    std::vector<std::string> got;
    const auto h = bus.subscribe([&](const Event& e) { got.push_back(e.type + "@" + e.device); },
                                 EventFilter{{"mcs0"}, {"status", "clock"}});
    CHECK(bus.active());
    CHECK(bus.wants("mcs0", "status"));
    CHECK_FALSE(bus.wants("mcs0", "wire"));
    CHECK_FALSE(bus.wants("tdc001", "status"));
    CHECK(bus.wants("", "clock"));   // a rig-wide event passes any device list
    CHECK_FALSE(bus.wants("", "reset"));

    // A wire log on a bus whose stream asked for status only builds no wire event.
    WireLog log("mcs0", 1000, &bus);
    log.add(1, true, "tcp 127.0.0.1:1", ":GP0\n");
    bus.publish("tdc001", "status", 0, json::object());
    CHECK(bus.built() == 0);
    bus.publish("mcs0", "status", 1, json{{"channel", 0}});
    bus.publish("", "clock", 2, json::object());
    CHECK(bus.built() == 2);
    CHECK(got == std::vector<std::string>{"status@mcs0", "clock@"});

    // Another subscriber that takes everything: the wire log's entries are built, once each.
    int all = 0;
    const auto h2 = bus.subscribe([&](const Event&) { ++all; });
    log.add(2, true, "tcp 127.0.0.1:1", ":GP0\n");
    CHECK(bus.built() == 3);
    CHECK(all == 1);
    CHECK(got.size() == 2);
    bus.unsubscribe(h2);
    bus.unsubscribe(h);
    CHECK_FALSE(bus.active());
}

TEST_CASE("event bus: the data's keys win, seq and time_ms are added, a subscriber may leave while called",
          "[unit][core]")
{
    EventBus bus;
    std::vector<std::string> texts;
    std::uint64_t h = 0;
    h = bus.subscribe([&](const Event& e) {
        texts.push_back(e.json);
        bus.unsubscribe(h);   // its connection failed while it was being written to
    });
    int second = 0;
    bus.subscribe([&](const Event&) { ++second; });
    bus.publish("dev", "wire", 5, json{{"seq", 77}, {"channel", 1}});
    REQUIRE(texts.size() == 1);
    CHECK(texts[0] == R"({"channel":1,"device":"dev","seq":77,"time_ms":5.0,"type":"wire"})");
    bus.publish("dev", "wire", 6, json::object());
    CHECK(texts.size() == 1);
    CHECK(second == 2);
}

TEST_CASE("event bus: the follow-up's reads are built while a subscriber takes what it makes", "[unit][core]")
{
    EventBus bus;
    std::vector<std::string> seen;
    bus.set_follow_up(
        [&](const Event& e) {
            seen.push_back(e.type);
            if (e.type == "move_ended")
                bus.publish("", "frames", 1, json::object());
        },
        {"move_ended"}, {"frames"});
    std::vector<std::string> got;
    bus.subscribe([&](const Event& e) { got.push_back(e.type); }, EventFilter{{}, {"frames"}});
    CHECK(bus.wants("mcs0", "move_ended"));   // read to make "frames"
    CHECK_FALSE(bus.wants("mcs0", "status"));
    bus.publish("mcs0", "move_ended", 1, json::object());
    CHECK(got == std::vector<std::string>{"frames"});   // the move itself not sent: not asked for
    CHECK(seen == std::vector<std::string>{"move_ended", "frames"});
}

} // namespace test_event_bus
