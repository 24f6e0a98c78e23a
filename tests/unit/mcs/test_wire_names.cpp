// The MCS wire log's decoder: command and answer strings with the manual's names.
#include "emulator/mcs/wire_names.hpp"

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

namespace test_wire_names {

using nlohmann::json;
using namespace rigsim::mcs;

namespace {

json decoded(std::string_view line, bool inbound)
{
    json out = json::object();
    decode_line(line, inbound, out);
    return out;
}

} // namespace

TEST_CASE("MCS wire names: a command string with chapter 3's parameter names", "[unit][mcs][wirelog]")
{
    CHECK(decoded(":MPA0,1000,0\n", true)
          == json{{"text", "MPA0,1000,0"}, {"command", "MPA"}, {"name", "Move to Position Absolute"},
                  {"fields", {{"channelIndex", 0}, {"position", 1000}, {"holdTime", 0}}}});
    CHECK(decoded(":GNC\n", true)["fields"] == json::object());
    const auto unknown = decoded(":FOO1,x\n", true);
    CHECK(unknown["name"] == "unknown");
    CHECK(unknown["fields"] == json{{"param1", 1}, {"param2", "x"}});
}

TEST_CASE("MCS wire names: answers, acknowledges and errors with appendix 4.2's meaning", "[unit][mcs][wirelog]")
{
    CHECK(decoded(":P0,-25\n", false)["fields"] == json{{"channelIndex", 0}, {"position", -25}});
    CHECK(decoded(":E-1,0\n", false)["name"] == "Acknowledge");
    const auto err = decoded(":E0,142\n", false);
    CHECK(err["name"] == "Error");
    CHECK(err["fields"] == json{{"sourceChannel", 0}, {"errorCode", 142}, {"meaning", "End Stop Reached Error"}});
    CHECK(error_name(999) == "Unknown Error");
    CHECK(command_name("FRM") == "Find Reference Mark");
}

TEST_CASE("MCS wire names: a queued command as its command string", "[unit][mcs][wirelog]")
{
    CHECK(command_text(MovePositionAbsolute{1, -500, 60000}) == "MPA1,-500,60000");
    CHECK(command_text(MoveStep{0, -30000, 4095, 18500}) == "MST0,-30000,4095,18500");
    CHECK(command_text(FindReferenceMark{2, 1, 0, 1}) == "FRM2,1,0,1");
}

} // namespace test_wire_names
