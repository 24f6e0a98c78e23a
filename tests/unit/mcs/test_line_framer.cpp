// MCS line framer (manual 1.1): arbitrary splits and coalescing, garbage, oversize.
#include "emulator/mcs/line_framer.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

namespace test_line_framer {

using rigsim::mcs::LineFramer;

namespace {

/// Feed `input` in pieces of `chunk` bytes; collect "C:<line>", "O", "I:<line>" events.
std::vector<std::string> frame(LineFramer& f, const std::string& input, std::size_t chunk,
                               std::size_t* ignored = nullptr)
{
    std::vector<std::string> events;
    for (std::size_t pos = 0; pos < input.size(); pos += chunk) {
        std::string_view piece = std::string_view(input).substr(pos, chunk);
        while (!piece.empty()) {
            const auto r = f.parse(piece);
            REQUIRE(r.consumed > 0);
            REQUIRE(r.consumed <= piece.size());
            piece.remove_prefix(r.consumed);
            if (ignored)
                *ignored += r.ignored;
            switch (r.status) {
            case LineFramer::Status::NeedMore:
                REQUIRE(piece.empty());
                break;
            case LineFramer::Status::Command:
                // The command as it crossed the wire, when all of it came in this piece.
                if (!r.frame.empty())
                    CHECK(r.frame == ":" + std::string(r.line) + "\n");
                events.push_back("C:" + std::string(r.line));
                break;
            case LineFramer::Status::Oversize:
                events.emplace_back("O");
                break;
            case LineFramer::Status::Interrupted:
                events.push_back("I:" + std::string(r.line));
                break;
            }
        }
    }
    return events;
}

std::vector<std::string> frame(const std::string& input, std::size_t chunk)
{
    LineFramer f;
    return frame(f, input, chunk);
}

} // namespace

TEST_CASE("framer yields one command per ':' ... newline", "[unit][mcs][framer]")
{
    CHECK(frame(":GNC\n", 100) == std::vector<std::string>{"C:GNC"});
    CHECK(frame(":GNC\n:GP0\n:MPA0,1,0\n", 100)
          == std::vector<std::string>{"C:GNC", "C:GP0", "C:MPA0,1,0"});
}

TEST_CASE("framer gives the same commands for every split of the input", "[unit][mcs][framer]")
{
    const std::string input = "junk:GNC\n\n:GP0\n::MPA0,2000000,0\nxx:\n:S\n";
    const std::vector<std::string> expected{"C:GNC", "C:GP0", "C:MPA0,2000000,0", "C:S"};
    for (std::size_t chunk = 1; chunk <= input.size(); ++chunk) {
        INFO("chunk " << chunk);
        CHECK(frame(input, chunk) == expected);
    }
    // Every two-piece split, Beast's parsegrind style.
    for (std::size_t cut = 0; cut <= input.size(); ++cut) {
        LineFramer f;
        auto events = frame(f, input.substr(0, cut), input.size() + 1);
        auto rest = frame(f, input.substr(cut), input.size() + 1);
        events.insert(events.end(), rest.begin(), rest.end());
        INFO("cut " << cut);
        CHECK(events == expected);
    }
}

TEST_CASE("framer gives a command's bytes as they came when they came in one input, none otherwise",
          "[unit][mcs][framer]")
{
    LineFramer f;
    std::string_view in = "x:GP0\n::GS1\n:GN";
    auto r = f.parse(in);
    CHECK(r.status == LineFramer::Status::Command);
    CHECK(r.frame == ":GP0\n");
    in.remove_prefix(r.consumed);
    r = f.parse(in);   // "::" : the second ':' starts the command
    CHECK(r.status == LineFramer::Status::Command);
    CHECK(r.line == "GS1");
    CHECK(r.frame == ":GS1\n");
    in.remove_prefix(r.consumed);
    r = f.parse(in);
    CHECK(r.status == LineFramer::Status::NeedMore);
    r = f.parse("C\n");   // its start came in the input before
    CHECK(r.status == LineFramer::Status::Command);
    CHECK(r.line == "GNC");
    CHECK(r.frame.empty());
    r = f.parse(":");
    r = f.parse("GP2\n");   // the ':' came alone
    CHECK(r.line == "GP2");
    CHECK(r.frame.empty());
}

TEST_CASE("framer ignores bytes between a newline and ':' and empty commands", "[unit][mcs][framer]")
{
    LineFramer f;
    std::size_t ignored = 0;
    CHECK(frame(f, "hello\r\n\x01\xff:\n:GNC\n", 3, &ignored) == std::vector<std::string>{"C:GNC"});
    CHECK(ignored == 9);
}

TEST_CASE("framer starts over at a ':' inside a command", "[unit][mcs][framer]")
{
    CHECK(frame(":GP0:GNC\n", 100) == std::vector<std::string>{"I:GP0", "C:GNC"});
    for (std::size_t chunk = 1; chunk < 10; ++chunk)
        CHECK(frame(":GP0:GNC\n", chunk) == std::vector<std::string>{"I:GP0", "C:GNC"});
}

TEST_CASE("framer discards an oversize command up to its newline", "[unit][mcs][framer]")
{
    const std::string longline = ":" + std::string(LineFramer::kDefaultMaxLine + 1, 'A') + "\n:GNC\n";
    for (std::size_t chunk : {1u, 7u, 256u, 4096u})
        CHECK(frame(longline, chunk) == std::vector<std::string>{"O", "C:GNC"});
    const std::string fits = ":" + std::string(LineFramer::kDefaultMaxLine, 'A') + "\n";
    CHECK(frame(fits, 5) == std::vector<std::string>{"C:" + std::string(LineFramer::kDefaultMaxLine, 'A')});
}

TEST_CASE("framer survives 10 MB without a newline", "[unit][mcs][framer]")
{
    LineFramer f;
    const std::string chunk(64 * 1024, 'Z');
    auto r = f.parse(":");
    CHECK(r.status == LineFramer::Status::NeedMore);
    for (int i = 0; i < 160; ++i) {   // 10 MiB
        r = f.parse(chunk);
        CHECK(r.status == LineFramer::Status::NeedMore);
        CHECK(r.consumed == chunk.size());
    }
    CHECK(f.in_command());
    CHECK(frame(f, "\n:GNC\n", 100) == std::vector<std::string>{"O", "C:GNC"});
}

} // namespace test_line_framer
