// The MCS2 command tree (emulator/mcs2/command_tree.*; SmarAct MCS2 Programmer's Guide 1.0.6,
// 6.2.2-6.2.3) on paths of the guide's Table 6.3: exact long or short forms in any case, indices
// where the guide writes '#', the optional [:PROPerty] root and leaves, and a compound message's
// relative commands at the level of the command before them.
#include "emulator/mcs2/command_tree.hpp"
#include "emulator/mcs2/message.hpp"

#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace test_mcs2_command_tree {

using namespace rigsim::mcs2;

namespace {

const CommandTree& tree()
{
    static const CommandTree t({
        "[:PROPerty]:DEVice:NOCHannels",
        "[:PROPerty]:DEVice:NOBModules",
        "[:PROPerty]:DEVice:SNUMber",
        "[:PROPerty]:MODule#:PSUPply[:ENABled]",
        "[:PROPerty]:CHANnel#:MMODe",
        "[:PROPerty]:CHANnel#:VELocity",
        "[:PROPerty]:CHANnel#:ACCeleration",
        "[:PROPerty]:CHANnel#:PTYPe[:CODE]",
        "[:PROPerty]:CHANnel#:PTYPe:NAME",
        "[:PROPerty]:CHANnel#:POSition[:CURRent]",
        "[:PROPerty]:CHANnel#:POSition:TARGet",
        "[:PROPerty]:CHANnel#:STATe",
        "[:PROPerty]:CHANnel#:CALibration:OPTions",
        ":MOVE#",
        ":STOP#",
        ":CALibrate#",
        ":SYSTem:ERRor:COUNt",
        ":SYSTem:ERRor[:NEXT]",
        "*IDN",
        "*RST",
    });
    return t;
}

/// Each command of `message` resolved in turn: its name and indices, or "undefined".
std::vector<std::string> resolve_all(const std::string& message)
{
    std::vector<std::string> out;
    CommandTree::Level level;
    for (const auto& c : parse_message(message)) {
        const auto f = tree().resolve(c, level);
        if (!f) {
            out.emplace_back("undefined");
            continue;
        }
        std::string s = f->name;
        for (const auto i : f->indices)
            s += " " + std::to_string(i);
        out.push_back(s);
    }
    return out;
}

} // namespace

TEST_CASE("mcs2 command tree: the guide's forms of one property all name it", "[unit][mcs2]")
{
    for (const auto* m : {":PROPerty:DEVice:SNUMber?", ":property:device:snumber?", ":PROP:DEV:SNUM?", ":prop:dev:snum?",
                          ":DEVice:SNUMber?", ":DEV:SNUM?"})
        CHECK(resolve_all(m) == std::vector<std::string>{"PROPerty:DEVice:SNUMber"});
    // Only the exact long or short form (6.2.2): neither a prefix nor the guide's own typo (ERRATA).
    CHECK(resolve_all(":DEV:SNUMB?") == std::vector<std::string>{"undefined"});
    CHECK(resolve_all(":DEV:NOMO?") == std::vector<std::string>{"undefined"});
    CHECK(resolve_all(":DEV:NOBM?") == std::vector<std::string>{"PROPerty:DEVice:NOBModules"});
}

TEST_CASE("mcs2 command tree: indices where the guide writes '#', optional leaves, commands and common commands",
          "[unit][mcs2]")
{
    CHECK(resolve_all(":CHAN2:POS?") == std::vector<std::string>{"PROPerty:CHANnel#:POSition:CURRent 2"});
    CHECK(resolve_all(":CHAN2:POS:CURR?") == std::vector<std::string>{"PROPerty:CHANnel#:POSition:CURRent 2"});
    CHECK(resolve_all(":CHAN2:POS:TARG?") == std::vector<std::string>{"PROPerty:CHANnel#:POSition:TARGet 2"});
    CHECK(resolve_all(":CHAN0:PTYP 300") == std::vector<std::string>{"PROPerty:CHANnel#:PTYPe:CODE 0"});
    CHECK(resolve_all(":MOD1:PSUP 0") == std::vector<std::string>{"PROPerty:MODule#:PSUPply:ENABled 1"});
    CHECK(resolve_all(":MOVE0 500000000") == std::vector<std::string>{"MOVE# 0"});
    CHECK(resolve_all(":CAL0") == std::vector<std::string>{"CALibrate# 0"});
    CHECK(resolve_all(":SYST:ERR?") == std::vector<std::string>{"SYSTem:ERRor:NEXT"});
    CHECK(resolve_all(":SYST:ERR:COUN?") == std::vector<std::string>{"SYSTem:ERRor:COUNt"});
    CHECK(resolve_all("*idn?;*RST") == std::vector<std::string>{"*IDN", "*RST"});
    // An index where the guide has none, none where it has one: no such command (-113).
    CHECK(resolve_all(":CHAN:STAT?") == std::vector<std::string>{"undefined"});
    CHECK(resolve_all(":DEV0:SNUM?") == std::vector<std::string>{"undefined"});
    CHECK(resolve_all(":CHAN0?") == std::vector<std::string>{"undefined"});   // a node, not a command
}

TEST_CASE("mcs2 command tree: a compound message's commands after the first start at its level (6.2.3)",
          "[unit][mcs2]")
{
    CHECK(resolve_all(":CHANnel0:MMODe 1;VELocity 10000;ACCeleration 0")
          == std::vector<std::string>{"PROPerty:CHANnel#:MMODe 0", "PROPerty:CHANnel#:VELocity 0",
                                      "PROPerty:CHANnel#:ACCeleration 0"});
    CHECK(resolve_all(":CHAN0:PTYPe?;MMODe?")
          == std::vector<std::string>{"PROPerty:CHANnel#:PTYPe:CODE 0", "PROPerty:CHANnel#:MMODe 0"});
    // A ':' starts at the root again; a relative path may go down from the level.
    CHECK(resolve_all(":CHAN1:VEL 5;:DEV:SNUM?;NOCH?")
          == std::vector<std::string>{"PROPerty:CHANnel#:VELocity 1", "PROPerty:DEVice:SNUMber",
                                      "PROPerty:DEVice:NOCHannels"});
    CHECK(resolve_all(":CHAN1:POS:TARG?;CURR?")
          == std::vector<std::string>{"PROPerty:CHANnel#:POSition:TARGet 1", "PROPerty:CHANnel#:POSition:CURRent 1"});
    // Not found at that level: undefined (the guide: "referenced to the same tree level").
    CHECK(resolve_all(":CHAN0:VEL 5;SNUM?") == std::vector<std::string>{"PROPerty:CHANnel#:VELocity 0", "undefined"});
    // The first command of a message without ':' starts at the root (the streaming example).
    CHECK(resolve_all("CHAN0:STAT?") == std::vector<std::string>{"PROPerty:CHANnel#:STATe 0"});
    // A command with a syntax error resolves to nothing.
    CHECK(resolve_all(":CHAN0:STAT?!") == std::vector<std::string>{"undefined"});
}

TEST_CASE("mcs2 command tree: a malformed path is refused when the tree is built", "[unit][mcs2]")
{
    CHECK_THROWS_AS(CommandTree({"[:PROPerty:DEVice"}), std::invalid_argument);
    CHECK_THROWS_AS(CommandTree({":DEVice::STATe"}), std::invalid_argument);
    CHECK_THROWS_AS(CommandTree({"*"}), std::invalid_argument);
    CHECK(CommandTree({":A:B", ":A:C"}).size() == 2 + 3);   // the roots, A, B, C
}

} // namespace test_mcs2_command_tree
