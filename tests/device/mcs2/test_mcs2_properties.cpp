// MCS2 property tree over the wire (MCS2 Programmer's Guide 1.0.6, chapter 4 and Table 6.3): every
// row of the table answers its query in long and short form, stored properties take their range and
// read back, and the grammar's and the table's errors reach the error queue with their codes.

#include "mcs2_harness.hpp"

#include "emulator/mcs2/properties.hpp"

#include <catch2/catch.hpp>

#include <cctype>
#include <string>

using rigsim::test::Mcs2Harness;
namespace mcs2 = rigsim::mcs2;

namespace {

/// A row's path as a client writes it: optional keywords left out, `#` -> 0; `short_form`: each
/// keyword's upper-case letters only.
std::string spelled(std::string_view path, bool short_form)
{
    std::string out;
    std::size_t i = 0;
    while (i < path.size()) {
        if (path[i] == '[') {
            i = path.find(']', i) + 1;
            continue;
        }
        const char c = path[i++];
        if (c == '#')
            out += '0';
        else if (!short_form || !std::islower(static_cast<unsigned char>(c)))
            out += c;
    }
    return out;
}

} // namespace

TEST_CASE("MCS2: every readable row of the table answers in long and short form, or queues its unit's error",
          "[device][mcs2]")
{
    Mcs2Harness h;
    int answered = 0, refused = 0;
    for (const auto& p : mcs2::table()) {
        if (p.access == mcs2::Access::W)
            continue;
        for (const bool short_form : {false, true}) {
            const auto query = spelled(p.path, short_form) + "?";
            CAPTURE(query);
            const auto answer = h.send(query);   // a line, CR LF ended (empty values: just CR LF)
            const auto errors = h.errors();
            if (p.id == mcs2::Id::ErrNext || p.id == mcs2::Id::ErrCount) {
                CHECK(!answer.empty());
                continue;
            }
            if (answer.empty()) {
                // Only what this unit lacks: no I/O module (257), no hand control module (256), no open stream.
                REQUIRE(errors.size() == 1);
                const bool lacking = errors[0].rfind("257,", 0) == 0 || errors[0].rfind("256,", 0) == 0 ||
                                     errors[0].rfind("768,", 0) == 0;
                CHECK(lacking);
                ++refused;
            } else {
                CHECK(answer.size() >= 2);
                CHECK(answer.substr(answer.size() - 2) == "\r\n");
                CHECK(errors.empty());
                ++answered;
            }
        }
    }
    CHECK(answered == 2 * 94);
    CHECK(refused == 2 * 14);
}

TEST_CASE("MCS2: stored properties take their range and read back, past it 19 Invalid parameter", "[device][mcs2]")
{
    Mcs2Harness h;
    for (const auto& p : mcs2::table()) {
        if (p.kind != mcs2::Kind::Stored || p.access != mcs2::Access::RW || p.scope == mcs2::Scope::Common)
            continue;
        const auto path = spelled(p.path, false);
        CAPTURE(path);
        for (const auto v : {p.min, p.max}) {
            CHECK(h.send(path + " " + std::to_string(v)).empty());   // a setting is never answered
            CHECK(h.errors().empty());
            CHECK(h.number(path + "?") == v);   // Pulse Width's 4×10^9 too: read unsigned
        }
        h.send(path + " " + std::to_string(p.max + 1));
        CHECK(h.errors() == std::vector<std::string>{"19,\"Invalid parameter\""});
    }
}

TEST_CASE("MCS2: answers: numbers bare, strings quoted, a compound query's answers joined by semicolon and space", "[device][mcs2]")
{
    Mcs2Harness h;
    CHECK(h.send(":DEV:SNUM?") == "\"MCS2-00001234\"\r\n");
    CHECK(h.send(":DEVICE:NOCHANNELS?") == "3\r\n");
    CHECK(h.send(":dev:nobm?") == "1\r\n");
    CHECK(h.send(":CHANnel0:PTYPe?;PTYPe:NAME?") == "300; \"SL...S1SS\"\r\n");
    // Relative commands start at the level of the one before (6.2.3): channel 0's three settings.
    CHECK(h.send(":CHAN0:MMOD 1;VEL 10000;ACC 0").empty());
    CHECK(h.send(":CHAN0:MMOD?;VEL?;ACC?;:CHAN1:MMOD?") == "1; 10000; 0; 0\r\n");
    // The first command may lack its ':' (EPICS motorSmarAct sends "CHAN%d:AMPL %d").
    CHECK(h.send("CHAN1:AMPL 0").empty());
    CHECK(h.ask(":CHAN1:AMPL?") == "0");
    // A fraction (EPICS prints every value with %f) is rounded.
    CHECK(h.send(":CHAN0:VEL 1000000000.500000").empty());
    CHECK(h.number(":CHAN0:VEL?") == 1'000'000'001);
    // Device Name: written as a string, read quoted (4.2.5); its default is the serial number.
    CHECK(h.ask(":DEV:NAME?") == "\"MCS2-00001234\"");
    CHECK(h.send(":DEV:NAME \"left stage\"").empty());
    CHECK(h.ask(":DEV:NAME?") == "\"left stage\"");
    CHECK(h.errors().empty());
}

TEST_CASE("MCS2: Hold Time's infinite reads -1 whether written -1 or 4294967295 (errata)", "[device][mcs2]")
{
    Mcs2Harness h;
    CHECK(h.ask(":CHAN0:HOLD?") == "-1");   // SA_CTL_INFINITE by default (4.4.14)
    h.send(":CHAN0:HOLD 250");
    CHECK(h.ask(":CHAN0:HOLD?") == "250");
    h.send(":CHAN0:HOLD 4294967295");
    CHECK(h.ask(":CHAN0:HOLD?") == "-1");
    h.send(":CHAN0:HOLD 4294967296");
    CHECK(h.errors() == std::vector<std::string>{"19,\"Invalid parameter\""});
}

TEST_CASE("MCS2: errors go to the queue with their codes, never answered, and the queue reads 0,\"No Error\" empty",
          "[device][mcs2]")
{
    Mcs2Harness h;
    CHECK(h.send(":CHAN0:STAT?!").empty());    // the guide's own example (6.3.8)
    CHECK(h.send(":CHAN7:POS?").empty());      // 3 channels
    CHECK(h.send(":MOD4:STAT?").empty());      // 1 module
    CHECK(h.send(":CHAN0:NOPE?").empty());
    CHECK(h.send(":CHAN0:STAT 1").empty());    // read-only: no setting form
    CHECK(h.send(":CHAN0:POS? 5").empty());
    CHECK(h.send(":CHAN0:VEL").empty());
    CHECK(h.send(":CHAN0:VEL fast").empty());
    CHECK(h.send(":DEV:NOMO?").empty());       // the guide's typo for NOBModules (errata)
    CHECK(h.send(":STOP0 1").empty());
    CHECK(h.number(":SYST:ERR:COUN?") == 10);
    CHECK(h.errors() == std::vector<std::string>{
                            "-101,\"Invalid character\"", "34,\"Invalid channel index\"", "33,\"Invalid module index\"",
                            "-113,\"Undefined header\"", "-113,\"Undefined header\"", "-108,\"Parameter not allowed\"",
                            "-109,\"Missing parameter\"", "-104,\"Data type error\"", "-113,\"Undefined header\"",
                            "-108,\"Parameter not allowed\""});
    CHECK(h.ask(":SYST:ERR?") == "0,\"No Error\"");
    CHECK(h.ask(":SYSTEM:ERROR:NEXT?") == "0,\"No Error\"");
}

TEST_CASE("MCS2: the error queue holds 32, one more makes the newest -350 Queue overflow, *CLS empties it",
          "[device][mcs2]")
{
    Mcs2Harness h;
    for (int i = 0; i < 40; ++i)
        h.send(":CHAN9:POS?");
    CHECK(h.number(":SYST:ERR:COUN?") == 32);
    CHECK(h.ask("*STB?") == "4");   // the error queue bit
    const auto e = h.errors();
    REQUIRE(e.size() == 32);
    CHECK(e.front() == "34,\"Invalid channel index\"");
    CHECK(e.back() == "-350,\"Queue overflow\"");
    h.send(":CHAN9:POS?");
    h.send("*CLS");
    CHECK(h.number(":SYST:ERR:COUN?") == 0);
    CHECK(h.ask("*STB?") == "0");
}

TEST_CASE("MCS2: each connection has its own error queue", "[device][mcs2]")
{
    Mcs2Harness h;
    std::string other_out;
    auto other = h.open(other_out);
    h.send_to(*other, other_out, ":CHAN9:POS?");
    CHECK(h.number(":SYST:ERR:COUN?") == 0);
    CHECK(h.send_to(*other, other_out, ":SYST:ERR:COUN?") == "1\r\n");
}

TEST_CASE("MCS2: common commands (Table 6.1)", "[device][mcs2]")
{
    Mcs2Harness h;
    CHECK(h.ask("*IDN?") == "SmarAct GmbH,MCS2,MCS2-00001234,current");
    CHECK(h.ask("*OPC?") == "1");
    CHECK(h.ask("*TST?") == "0");
    CHECK(h.ask("*ESR?") == "0");
    h.send("*ESE 32;*SRE 16");
    CHECK(h.ask("*ESE?;*SRE?") == "32; 16");
    CHECK(h.send("*WAI;*OPC").empty());
    CHECK(h.errors().empty());
    // *RST resets the device and the connection must be made again (Table 6.1).
    h.send(":CHAN0:VEL 5000;:CHAN0:TUN:WPR 1397571922");
    h.send("*RST");
    CHECK(h.hangups() == 1);
    std::string sink;
    auto again = h.open(sink);
    CHECK(h.send_to(*again, sink, ":CHAN0:VEL?;:CHAN0:TUN:WPR?") == "0; 1\r\n");
}

TEST_CASE("MCS2 firmware 1.0.6: the keywords of later firmware are undefined", "[device][mcs2]")
{
    auto config = rigsim::test::mcs2_device_config();
    rigsim::mcs2::config_of(config).firmware = rigsim::mcs2::Firmware::Guide106;
    Mcs2Harness old(config);
    CHECK(old.ask(":CHAN0:SENS:MODE?").empty());
    CHECK(old.ask(":MOD:STAT?").empty());
    CHECK(old.errors().size() == 2);
    CHECK(old.ask(":CHAN0:SENS:PMOD?") == "1");
    // Sensor present, calibrated, on the reference mark (at 0): no AMPLIFIER_ENABLED bit.
    CHECK(old.number(":CHAN0:STAT?") == 0x8060);
    Mcs2Harness current;
    CHECK(current.ask(":CHAN0:SENS:MODE?") == "1");
    CHECK(current.ask(":CHAN0:SENS:DEL?") == "100");
    CHECK(current.ask(":MOD:STAT?") == "1");
    CHECK(current.number(":CHAN0:STAT?") == (0x8060 | (1 << 18)));
}

TEST_CASE("MCS2 defaults of the live rows: Signal Correction Options 15, and a power-up keeps what is non-volatile",
          "[device][mcs2]")
{
    Mcs2Harness h;
    CHECK(h.ask(":CHAN0:SCOR:OPT?") == "15");   // 4.6.2: 0x0f
    h.send(":CHAN0:SCOR:OPT 2;:CHAN0:LSC:OFF 7;:CHAN0:SDIR 1;:CHAN0:MMOD 4;:CHAN0:RLIM:MIN 5");
    CHECK(h.ask(":CHAN0:SCOR:OPT?") == "7");    // bits 0 and 2 read 1
    h.device().power_cycle({});
    CHECK(h.ask(":CHAN0:SCOR:OPT?;:CHAN0:LSC:OFF?;:CHAN0:SDIR?") == "7; 7; 1");   // non-volatile
    CHECK(h.ask(":CHAN0:MMOD?;:CHAN0:RLIM:MIN?") == "0; 0");                     // volatile
    rigsim::PowerCycle erase;
    erase.keep_saved = false;
    h.device().power_cycle(erase);
    CHECK(h.ask(":CHAN0:SCOR:OPT?;:CHAN0:LSC:OFF?;:CHAN0:SDIR?") == "15; 0; 0");
}

TEST_CASE("MCS2 bounds: a 20-digit number is -104, one message's answer at most 64 KiB", "[device][mcs2]")
{
    Mcs2Harness h;
    h.send(":CHAN0:VEL 92233720368547758080");   // wraps uint64 if checked after the multiply
    CHECK(h.errors() == std::vector<std::string>{"-104,\"Data type error\""});
    CHECK(h.ask(":CHAN0:VEL?") == "0");
    h.send(":CHAN0:POS 99999999999999");   // a long number to read: 14 digits
    h.send(":CGR:OPEN 0");
    for (int i = 0; i < 256; ++i)
        h.send(":CHAN0:POS:TARG?");
    h.send(":CGR:CLOS");
    std::string many;
    for (int i = 0; i < 64; ++i)
        many += ":CGR:VAL?;";
    const auto answer = h.send(many);
    CHECK(answer.size() <= rigsim::mcs2::kMaxAnswer + 2);
    CHECK(answer.size() > 60'000);
    const auto e = h.errors();
    REQUIRE(!e.empty());
    CHECK(e[0] == "13,\"Buffer overflow\"");
}

TEST_CASE("MCS2 tuning: written only with the key, the type then reads 0 \"modified\" until saved to a slot",
          "[device][mcs2]")
{
    Mcs2Harness h;
    CHECK(h.ask(":CHAN0:TUN:GAIN:SHIF?") == "10");
    h.send(":CHAN0:TUN:GAIN:SHIF 12");
    CHECK(h.errors() == std::vector<std::string>{"35,\"Permission denied\""});
    h.send(":CHAN0:TUN:WPR 1397572946");   // the decimal printed beside the key is not 0x534D4152 (errata)
    CHECK(h.ask(":CHAN0:TUN:WPR?") == "1");
    h.send(":CHAN0:TUN:WPR 1397571922");   // 0x534D4152, "SMAR" (4.8.17)
    CHECK(h.ask(":CHAN0:TUN:WPR?") == "0");
    h.send(":CHAN0:TUN:GAIN:SHIF 12");
    CHECK(h.ask(":CHAN0:PTYP?;PTYP:NAME?;:CHAN0:TUN:CUST?") == "0; \"modified\"; 1");
    h.send(":CHAN0:TUN:SAVE 251");
    CHECK(h.ask(":CHAN0:PTYP?;PTYP:NAME?;:CHAN0:TUN:GAIN:SHIF?") == "251; \"CUSTOM1\"; 12");
    h.send(":CHAN0:PTYP 300");
    CHECK(h.ask(":CHAN0:TUN:GAIN:SHIF?") == "10");
    h.send(":CHAN0:PTYP 251");   // the saved slot brings its tuning back
    CHECK(h.ask(":CHAN0:TUN:GAIN:SHIF?") == "12");
    h.send(":CHAN0:PTYP 252");   // an empty slot
    h.send(":CHAN0:PTYP 305");   // no such type
    CHECK(h.errors() == std::vector<std::string>{"19,\"Invalid parameter\"", "19,\"Invalid parameter\""});
}
