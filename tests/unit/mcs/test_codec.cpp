// MCS codec: command strings to typed commands, and the errors of appendix 4.2.
#include "emulator/mcs/codec.hpp"
#include "emulator/mcs/handler_replies.hpp"

#include <fstream>
#include <iterator>
#include <limits>
#include <regex>
#include <string>
#include <variant>
#include <vector>

#include <catch2/catch.hpp>

namespace test_mcs_codec {

using namespace rigsim::mcs;

namespace {

int error_of(std::string_view line)
{
    const auto d = decode(line);
    REQUIRE_FALSE(d.command);
    CHECK(d.error.channel == kSystem);
    return static_cast<int>(d.error.code);
}

} // namespace

TEST_CASE("codec decodes the commands with their parameters", "[unit][mcs][codec]")
{
    auto d = decode("MPA0,-2000000,60000");
    REQUIRE(d.command);
    const auto& mpa = std::get<MovePositionAbsolute>(*d.command);
    CHECK(mpa.channel == 0);
    CHECK(mpa.position_nm == -2000000);
    CHECK(mpa.hold_ms == 60000);

    d = decode("S");
    REQUIRE(d.command);
    CHECK_FALSE(std::get<Stop>(*d.command).channel);
    d = decode("S2");
    REQUIRE(d.command);
    CHECK(std::get<Stop>(*d.command).channel == 2);

    d = decode("SCLA1,+1000");
    REQUIRE(d.command);
    CHECK(std::get<SetClosedLoopAcceleration>(*d.command).acceleration == 1000);

    CHECK(std::holds_alternative<GetNumberOfChannels>(*decode("GNC").command));
    CHECK(std::holds_alternative<GetPosition>(*decode("GP1").command));
}

TEST_CASE("codec answers unknown commands with error 2", "[unit][mcs][codec]")
{
    CHECK(error_of("FOO") == 2);
    CHECK(error_of("FOO1,2") == 2);
    CHECK(error_of("GPX0") == 2);
    CHECK(error_of("SZPP0") == 2);
}

TEST_CASE("codec knows every command of chapter 3", "[unit][mcs][codec]")
{
    // One valid command string per command of the manual's chapter 3 (67 commands).
    const char* all[] = {
        "GCM", "GCT0", "GIV", "GNC", "GSI", "R", "SCM0", "SHE1", "GAL0", "GCLA0", "GCLS0",
        "GCP0,16842753", "GEET0", "GESM", "GPL0", "GSC0", "GSD0", "GSE", "GST0", "SARP0,1",
        "SAL0,0,0,0,0", "SCLA0,1", "SCLF0,100", "SCLS0,1", "SCP0,16842753,0", "SEET0,1,100,0",
        "SESM0", "SP0,0", "SPL0,0,0", "SRC0,1", "SRT0,1", "SSC0,0,0", "SSD0,0", "SSE1", "SST0,1",
        "SSWS0,1", "SZF0", "SZP0", "ATC0,1792", "CS0", "CTCQ0", "FRM0,0,0,0", "MAA0,0,0,0",
        "MAR0,0,0,0", "MGFA0,0,1,0", "MGOA0,0,1", "MGOR0,0,1", "MPA0,0,0", "MPR0,0,0",
        "MSCA0,0,1", "MSCR0,0,1", "MST0,1,1,1", "S", "TC0", "GA0", "GB0,0", "GF0", "GGO0", "GP0",
        "GPPK0", "GS0", "GVL0", "CB9600", "GSN0", "GFV0", "GFP0,255", "K",
    };
    CHECK(std::size(all) == 67);
    for (const char* line : all) {
        INFO(line);
        CHECK(decode(line).command);
    }
}

TEST_CASE("codec answers syntax, parse, count and overflow errors", "[unit][mcs][codec]")
{
    CHECK(error_of("") == 1);
    CHECK(error_of("123") == 1);
    CHECK(error_of("gnc") == 1);
    CHECK(error_of("GP 0") == 1);     // white space is not allowed (1.1)
    CHECK(error_of("GP0\r") == 1);
    CHECK(error_of("GP0.5") == 1);
    CHECK(error_of("GP,") == 4);
    CHECK(error_of("MPA0,,0") == 4);
    CHECK(error_of("GP1-2") == 4);
    CHECK(error_of("GP-") == 4);
    CHECK(error_of("GP") == 5);
    CHECK(error_of("MPA0,1") == 5);
    CHECK(error_of("GP0,1") == 6);
    CHECK(error_of("GNC0") == 6);
    CHECK(error_of("S0,1") == 6);
    CHECK(error_of("GP2147483648") == 3);
    CHECK(error_of("MPA0,-2147483649,0") == 3);
    CHECK(error_of("GP99999999999999999999999") == 3);
    CHECK(decode("MPA0,-2147483648,0").command);
    // MSCA/MSCR speeds reach 4,095,000,000: wider than 32 bits signed, within unsigned.
    CHECK(std::get<MoveScanAbsolute>(*decode("MSCA0,1,4095000000").command).speed == 4'095'000'000);
    CHECK(error_of("MSCA0,1,4294967296") == 3);
    CHECK(error_of("MSCA0,2147483648,1") == 3);
}

TEST_CASE("codec encodes answers without spaces", "[unit][mcs][codec]")
{
    CHECK(encode(Ack{0}) == ":E0,0\n");
    CHECK(encode(Ack{kSystem}) == ":E-1,0\n");
    CHECK(encode(Error{2, ErrorCode::WrongSensorType}) == ":E2,143\n");
    CHECK(encode(Answer{"P0,2000000"}) == ":P0,2000000\n");
    CHECK(encode(Silent{}).empty());
    CHECK(encode(Error{std::numeric_limits<int>::min(), ErrorCode::Syntax}) == ":E-2147483648,1\n");
    std::string out = ":S0,0\n";   // appended after what is there
    encode(Ack{255}, out);
    CHECK(out == ":S0,0\n:E255,0\n");
}

TEST_CASE("the handler's answer texts: a prefix and one or two numbers, the widest included", "[unit][mcs][codec]")
{
    CHECK(replies::join("P", 0, 2'000'000) == "P0,2000000");
    CHECK(replies::join("N", 3) == "N3");
    CHECK(replies::join("MSCA", -1, std::numeric_limits<std::int64_t>::min())
          == "MSCA-1,-9223372036854775808");
    CHECK(replies::join(std::string(40, 'X'), std::numeric_limits<std::int64_t>::min(),
                        std::numeric_limits<std::int64_t>::max())
          == std::string(40, 'X') + "-9223372036854775808,9223372036854775807");
}

TEST_CASE("every command of the codec's table is found by its mnemonic, and nothing else is", "[unit][mcs][codec]")
{
    // The mnemonics as codec.cpp's table lists them.
    std::ifstream source(RIGSIM_SOURCE_DIR "/emulator/mcs/codec.cpp");
    REQUIRE(source);
    const std::string text{std::istreambuf_iterator<char>(source), std::istreambuf_iterator<char>()};
    const std::regex entry(R"re(\{\{"([A-Z]+)", ")re");
    std::vector<std::string> mnemonics;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), entry); it != std::sregex_iterator(); ++it)
        mnemonics.push_back((*it)[1]);
    CHECK(mnemonics.size() == std::variant_size_v<Command>);
    for (const auto& m : mnemonics) {
        INFO(m);
        const auto* info = find_command(m);
        REQUIRE(info != nullptr);
        CHECK(info->mnemonic == m);
        const auto d = decode(m);   // a command, or too few parameters: never an unknown command
        CHECK((d.command || d.error.code == ErrorCode::TooFewParameters));
        CHECK_FALSE(find_command(m + "X"));
        CHECK(error_of(m + "Q0") == static_cast<int>(ErrorCode::InvalidCommand));
    }
    for (const char* unknown : {"", "X", "GPP", "ABCDEFGH", "ABCDEFGHIJ", "gp", "G P"})
        CHECK_FALSE(find_command(unknown));
    CHECK(error_of("ABCDEFGHIJ0") == static_cast<int>(ErrorCode::InvalidCommand));
}

TEST_CASE("find_command: each command's table entry, with the manual's names", "[unit][mcs][codec]")
{
    const auto* mpa = find_command("MPA");
    REQUIRE(mpa != nullptr);
    CHECK(mpa->name == "Move to Position Absolute");
    CHECK(mpa->params == "channelIndex,position,holdTime");
    CHECK(find_command("GNC")->params.empty());
    CHECK(find_command("XYZ") == nullptr);
    // The parameter count comes from the names: three for MPA, one optional for S.
    CHECK(decode("MPA0,1,2,3").error.code == ErrorCode::TooManyParameters);
    CHECK(decode("MPA0,1").error.code == ErrorCode::TooFewParameters);
    CHECK(decode("S").command.has_value());
    CHECK(decode("S0").command.has_value());
    CHECK(decode("S0,1").error.code == ErrorCode::TooManyParameters);
}

} // namespace test_mcs_codec
