// parse_json_text: the one JSON reader of rig files, stage files, state files and control-API
// bodies. Values as nlohmann's own parser builds them; the depth and key checks with the
// pointer of the value at fault; errors as nlohmann reports them.
#include "emulator/core/json_text.hpp"

#include <catch2/catch.hpp>

#include <string>

namespace test_json_text {

using rigsim::JsonTextError;
using rigsim::JsonTextLimits;
using rigsim::parse_json_text;
using Kind = JsonTextError::Kind;
using nlohmann::json;

namespace {

JsonTextError error_of(const std::string& text, JsonTextLimits limits = {})
{
    try {
        parse_json_text(text, limits);
    } catch (const JsonTextError& e) {
        return e;
    }
    FAIL("no error for " << text);
    return JsonTextError(Kind::Syntax, "", 0, "");
}

} // namespace

TEST_CASE("json text: values come out as nlohmann's parser makes them", "[unit][json]")
{
    const std::string text = R"({"a":[1,-2,3.5,true,null,"s",{"b":[]},[[{}]]],"c":{"d":{"e":18446744073709551615}},"f":""})";
    CHECK(parse_json_text(text) == json::parse(text));
    CHECK(parse_json_text(" 7 ") == json(7));
    CHECK(parse_json_text("\"x\"") == json("x"));
    CHECK(parse_json_text("[]") == json::array());
    CHECK(parse_json_text("{}") == json::object());
}

TEST_CASE("json text: a key twice is refused at the object holding it, or kept last when allowed", "[unit][json]")
{
    const auto e = error_of(R"({"a":[{"x":1},{"y":{"k":1,"k":2}}]})");
    CHECK(e.kind == Kind::DuplicateKey);
    CHECK(e.pointer == "/a/1/y");
    CHECK(std::string(e.what()) == "duplicate key \"k\"");
    CHECK(error_of(R"({"k":1,"k":2})").pointer.empty());
    CHECK(error_of(R"({"a~/b":{"x":[],"x":{}}})").pointer == "/a~0~1b");
    // the same key in two objects is no duplicate
    CHECK(parse_json_text(R"([{"k":1},{"k":2}])").size() == 2);
    CHECK(parse_json_text(R"({"k":1,"k":2})", JsonTextLimits{100, false}) == json{{"k", 2}});
}

TEST_CASE("json text: max_depth containers nest, one more is refused where it opens", "[unit][json]")
{
    const JsonTextLimits four{4, true};
    CHECK(parse_json_text("[[[[1]]]]", four).dump() == "[[[[1]]]]");
    auto e = error_of("[[[[[1]]]]]", four);
    CHECK(e.kind == Kind::TooDeep);
    CHECK(std::string(e.what()) == "nested deeper than 4 levels");
    CHECK(e.pointer == "/0/0/0/0");
    e = error_of(R"({"a":[0,{"b":{"c":[]}}]})", four);
    CHECK(e.kind == Kind::TooDeep);
    CHECK(e.pointer == "/a/1/b/c");
    // 64 KiB of '[' stops at the limit, before anything recurses
    CHECK(error_of(std::string(64 * 1024, '[')).kind == Kind::TooDeep);
}

TEST_CASE("json text: a number no double holds is named by its pointer", "[unit][json]")
{
    auto e = error_of(R"({"a":[1,2,1e400]})");
    CHECK(e.kind == Kind::NumberOverflow);
    CHECK(e.pointer == "/a/2");
    CHECK(std::string(e.what()).find("number overflow parsing '1e400'") != std::string::npos);
    e = error_of(R"({"x":{"y":-1e999}})");
    CHECK(e.pointer == "/x/y");
    CHECK(error_of("1e400").pointer.empty());
}

TEST_CASE("json text: syntax errors carry nlohmann's 1-based byte and message", "[unit][json]")
{
    for (const std::string bad : {"", "{", "[1,]", "{\"a\" 1}", "[1] x", "\"\x01\"", "{\"a\":tru}"}) {
        CAPTURE(bad);
        const auto e = error_of(bad);
        CHECK(e.kind == Kind::Syntax);
        std::size_t expected = 0;
        try {
            const auto parsed = json::parse(bad);
            CHECK(parsed.is_discarded());
        } catch (const json::parse_error& p) {
            expected = p.byte;
            CHECK(std::string(e.what()) == p.what());
        }
        CHECK(e.byte == expected);
        CHECK(e.pointer.empty());
    }
}

TEST_CASE("json text: 400,000 objects in one array parse, one value each", "[unit][json]")
{
    // The callback parser this replaces took 43 s on this (quadratic); the time is measured in
    // bench/, this checks the result.
    std::string text = "[";
    for (int i = 0; i < 400'000; ++i)
        text += i == 0 ? "{}" : ",{}";
    text += "]";
    const auto v = parse_json_text(text);
    CHECK(v.size() == 400'000);
    CHECK(v.back() == json::object());
}

} // namespace test_json_text
