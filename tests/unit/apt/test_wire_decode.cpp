// The wire log's decoding of APT frames: manual names, addresses and the codec's field names.

#include "emulator/apt/messages.hpp"
#include "emulator/apt/wire.hpp"
#include "emulator/apt/wire_decode.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

namespace test_wire_decode {

using namespace rigsim::apt;

TEST_CASE("decode_for_log names every field of the names table for every message", "[unit][apt][wire]")
{
    for (const auto& info : all_messages()) {
        const std::string frame = info.header_only()
                                      ? encode_header_only(info.id, 1, 0, 0x50, 0x01)
                                      : encode_with_data(info.id, 0x50, 0x01, std::string(info.data_length, '\0'));
        nlohmann::json out = nlohmann::json::object();
        decode_for_log(frame, out);
        INFO(info.name);
        CHECK(out["name"] == std::string(info.name));
        if (const auto* names = field_names(info.id))
            for (const auto name : *names)
                CHECK(out["fields"].contains(std::string(name)));
    }
}

TEST_CASE("decode_for_log: a MOVE_ABSOLUTE and a DC status update", "[unit][apt][wire]")
{
    nlohmann::json out = nlohmann::json::object();
    std::string data;
    put_u16(data, 1);
    put_i32(data, -1000);
    decode_for_log(encode_with_data(MGMSG_MOT_MOVE_ABSOLUTE, 0x50, 0x01, data), out);
    CHECK(out["id"] == "0x0453");
    CHECK(out["name"] == "MGMSG_MOT_MOVE_ABSOLUTE");
    CHECK(out["source"] == "0x01");
    CHECK(out["destination"] == "0x50");
    CHECK(out["fields"] == nlohmann::json{{"chan_ident", 1}, {"absolute_distance", -1000}});

    out = nlohmann::json::object();
    decode_for_log("\x01\x02", out);
    CHECK(out["name"] == "not a frame");
}

TEST_CASE("status_bit_names reads the manual's bits", "[unit][apt][wire]")
{
    CHECK(status_bit_names(0x80002500) == std::vector<std::string_view>{"motor_connected", "homed", "settled", "enabled"});
    CHECK(status_bit_names(0).empty());
}

} // namespace test_wire_decode
