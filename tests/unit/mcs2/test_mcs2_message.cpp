// MCS2 ASCII messages (emulator/mcs2/line_framer.*, message.*; SmarAct MCS2 Programmer's Guide
// 1.0.6, 6.1-6.3): lines end at LF with an optional CR, an overlong line is one overrun; a
// message's commands, keywords with their indices, queries and parameters, and each syntax error
// with its SCPI code of Table 6.4. The messages quoted here are the guide's own examples.
#include "emulator/mcs2/line_framer.hpp"
#include "emulator/mcs2/message.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace test_mcs2_message {

using namespace rigsim::mcs2;

namespace {

/// The lines of `bytes` fed in pieces of `piece` bytes ("!overrun" for an overrun).
std::vector<std::string> lines(const std::string& bytes, std::size_t piece, std::size_t max_line = 64)
{
    LineFramer framer(max_line);
    std::vector<std::string> out;
    for (std::size_t at = 0; at < bytes.size(); at += piece) {
        std::string_view in = std::string_view(bytes).substr(at, piece);
        while (!in.empty()) {
            const auto r = framer.parse(in);
            REQUIRE(r.consumed > 0);
            in.remove_prefix(r.consumed);
            if (r.status == LineFramer::Status::Line)
                out.emplace_back(r.line);
            else if (r.status == LineFramer::Status::Overrun)
                out.emplace_back("!overrun");
        }
    }
    return out;
}

std::vector<std::string> keywords(const Command& c)
{
    std::vector<std::string> out;
    for (const auto& k : c.path)
        out.push_back(k.name + (k.index ? "#" + std::to_string(*k.index) : ""));
    return out;
}

} // namespace

TEST_CASE("mcs2 line framer: CR LF or LF ends a message, however the bytes come, an overlong one is one overrun",
          "[unit][mcs2]")
{
    const std::string wire = ":DEV:SNUM?\r\n:CHAN0:MMOD 4\n\r\n" + std::string(100, 'x') + "\n:STOP0\r\n:CAL0";
    const std::vector<std::string> expected{":DEV:SNUM?", ":CHAN0:MMOD 4", "", "!overrun", ":STOP0"};
    for (std::size_t piece : {std::size_t{1}, std::size_t{3}, std::size_t{7}, wire.size()})
        CHECK(lines(wire, piece) == expected);
    LineFramer framer(64);
    CHECK(framer.parse(std::string(1'000'000, 'y')).status == LineFramer::Status::NeedMore);
    CHECK(framer.buffered() == 0);   // discarding: nothing kept
    CHECK(framer.parse("\n").status == LineFramer::Status::Overrun);
}

TEST_CASE("mcs2 message: the guide's commands, long and short forms, indices, queries and parameters",
          "[unit][mcs2]")
{
    auto c = parse_message(":PROPerty:DEVice:SNUMber?");
    REQUIRE(c.size() == 1);
    CHECK(c[0].error == ScpiError::None);
    CHECK(c[0].absolute);
    CHECK(c[0].query);
    CHECK(keywords(c[0]) == std::vector<std::string>{"PROPerty", "DEVice", "SNUMber"});

    c = parse_message(":prop:dev:snum?");
    REQUIRE(c.size() == 1);
    CHECK(keywords(c[0]) == std::vector<std::string>{"prop", "dev", "snum"});

    c = parse_message(":PROPerty:CHANnel0:VELocity 1000000000");
    REQUIRE(c.size() == 1);
    CHECK_FALSE(c[0].query);
    CHECK(keywords(c[0]) == std::vector<std::string>{"PROPerty", "CHANnel#0", "VELocity"});
    REQUIRE(c[0].params.size() == 1);
    CHECK(c[0].params[0].kind == Param::Kind::Integer);
    CHECK(c[0].params[0].integer == 1'000'000'000);

    c = parse_message(":MOVE0 -500000000");
    REQUIRE(c.size() == 1);
    CHECK(keywords(c[0]) == std::vector<std::string>{"MOVE#0"});
    CHECK(c[0].params[0].integer == -500'000'000);

    // A compound message (6.2.3): the commands after the first are relative, no leading ':'.
    c = parse_message(":CHANnel0:MMODe 1;VELocity 10000;ACCeleration 0");
    REQUIRE(c.size() == 3);
    CHECK(keywords(c[1]) == std::vector<std::string>{"VELocity"});
    CHECK_FALSE(c[1].absolute);
    CHECK(c[1].text == "VELocity 10000");
    CHECK(c[2].params[0].integer == 0);

    c = parse_message(":CHAN0:PTYPe?;MMODe?");
    REQUIRE(c.size() == 2);
    CHECK((c[0].query && c[1].query));

    // The streaming frame (6.5.2) has no leading ':' and a parameter list.
    c = parse_message("STR:FRAM 0,1000000,1,100000");
    REQUIRE(c.size() == 1);
    CHECK_FALSE(c[0].absolute);
    REQUIRE(c[0].params.size() == 4);
    CHECK(c[0].params[3].integer == 100'000);

    c = parse_message("*IDN?");
    REQUIRE(c.size() == 1);
    CHECK(c[0].common);
    CHECK(keywords(c[0]) == std::vector<std::string>{"IDN"});

    // Strings: quoted (a ';' inside is the string's, "" one quote), or a bare word.
    c = parse_message(R"(:DEV:NAME "stage; ""left""" ; :DEV:NAME?)");
    REQUIRE(c.size() == 2);
    REQUIRE(c[0].params.size() == 1);
    CHECK(c[0].params[0].kind == Param::Kind::String);
    CHECK(c[0].params[0].text == "stage; \"left\"");
    c = parse_message(":DEV:NAME rig_left , 12 ,  +7");
    REQUIRE(c[0].params.size() == 3);
    CHECK(c[0].params[0].text == "rig_left");
    CHECK(c[0].params[2].integer == 7);
    CHECK(parse_message(":MOVE0 -9223372036854775808")[0].params[0].integer == INT64_MIN);

    CHECK(parse_message("").empty());
    CHECK(parse_message(" ; ;").empty());
}

TEST_CASE("mcs2 message: each syntax error has its SCPI code (Table 6.4) and its place, the other commands stand",
          "[unit][mcs2]")
{
    const auto error = [](const std::string& m) {
        const auto c = parse_message(m);
        REQUIRE(c.size() == 1);
        return std::make_pair(c[0].error, c[0].error_at);
    };
    // The guide's own (4): an invalid character, no response.
    CHECK(error(":CHAN0:STAT?!") == std::make_pair(ScpiError::InvalidCharacter, std::size_t{12}));
    CHECK(error(":CHAN0::STAT?").first == ScpiError::InvalidSeparator);
    CHECK(error(":CHAN0:STAT:?").first == ScpiError::InvalidSeparator);
    CHECK(error(":").first == ScpiError::UndefinedHeader);
    CHECK(error("?").first == ScpiError::UndefinedHeader);
    CHECK(error("*").first == ScpiError::UndefinedHeader);
    CHECK(error("*RST5").first == ScpiError::InvalidCharacter);
    CHECK(error(":CHAN0A:STAT?").first == ScpiError::InvalidCharacter);
    CHECK(error(":CHAN0:VEL 12ab").first == ScpiError::DataTypeError);
    CHECK(error(":CHAN0:VEL 99999999999999999999").first == ScpiError::DataTypeError);
    CHECK(error(":CHAN0:VEL 9223372036854775808").first == ScpiError::DataTypeError);
    CHECK(error(":CHAN0:VEL 92233720368547758080").first == ScpiError::DataTypeError);   // would wrap uint64
    CHECK(error(":STR:FRAM 0,1,").first == ScpiError::MissingParameter);
    CHECK(error(":STR:FRAM 0,,1").first == ScpiError::MissingParameter);
    CHECK(error(":CHAN0:VEL 1 2").first == ScpiError::InvalidSeparator);
    CHECK(error(R"(:DEV:NAME "left)").first == ScpiError::InvalidStringData);
    CHECK(error(":CHAN123456789012:STAT?").first == ScpiError::InvalidCharacter);
    CHECK(error(":A:B:C:D:E:F:G:H:I:J:K:L:M:N:O:P:Q").first == ScpiError::UndefinedHeader);
    // One bad command of a compound message: the others are read.
    const auto c = parse_message(":CHAN0:MMOD 1;VEL 1x;ACC 0");
    REQUIRE(c.size() == 3);
    CHECK(c[0].error == ScpiError::None);
    CHECK(c[1].error == ScpiError::DataTypeError);
    CHECK(c[2].error == ScpiError::None);
    // More than 64 commands: the rest is one overrun, not executed.
    std::string many;
    for (int i = 0; i < 70; ++i)
        many += ":STOP0;";
    const auto all = parse_message(many);
    REQUIRE(all.size() == kMaxCommandsPerMessage + 1);
    CHECK(all.back().error == ScpiError::InputBufferOverrun);
    CHECK(scpi_error_text(ScpiError::InvalidCharacter) == "Invalid character");
}

TEST_CASE("mcs2 message: a decimal fraction is taken and rounded (EPICS motorSmarAct prints values with %f)",
          "[unit][mcs2]")
{
    const auto value = [](const std::string& m) {
        const auto c = parse_message(m);
        REQUIRE(c.size() == 1);
        REQUIRE(c[0].error == ScpiError::None);
        REQUIRE(c[0].params.size() == 1);
        return c[0].params[0].integer;
    };
    CHECK(value(":CHAN0:VEL 1000000000.000000") == 1'000'000'000);
    CHECK(value(":MOVE0 -1000000.000000") == -1'000'000);
    CHECK(value(":MOVE0 12.5") == 13);
    CHECK(value(":MOVE0 -12.5") == -13);
    CHECK(value(":MOVE0 12.4999") == 12);
    CHECK(value(":MOVE0 9223372036854775806.5") == 9'223'372'036'854'775'807);
    const auto c = parse_message(":MOVE0 9223372036854775807.5");
    REQUIRE(c.size() == 1);
    CHECK(c[0].error == ScpiError::DataTypeError);   // rounds past int64
    CHECK(parse_message(":MOVE0 1.")[0].error == ScpiError::DataTypeError);
    CHECK(parse_message(":MOVE0 1.5e3")[0].error == ScpiError::DataTypeError);
}

} // namespace test_mcs2_message
