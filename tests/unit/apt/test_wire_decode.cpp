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
        std::string data(info.header_only() ? 0 : static_cast<std::size_t>(info.data_length), '\0');
        if (info.id == MGMSG_PZMOT_SET_PARAMS || info.id == MGMSG_PZMOT_GET_PARAMS)
            data[0] = 0x07;   // a sub-message the codec knows (DriveOPParams): sub-message 0 has no block
        const std::string frame = info.header_only() ? encode_header_only(info.id, 1, 0, 0x50, 0x01)
                                                     : encode_with_data(info.id, 0x50, 0x01, data);
        nlohmann::json out = nlohmann::json::object();
        decode_for_log(frame, out);
        INFO(info.name);
        CHECK(out["name"] == std::string(info.name));
        if (const auto* names = field_names(info.id))
            for (const auto name : *names)
                CHECK(out["fields"].contains(std::string(name)));
    }
}

TEST_CASE("every message of the table has the field names of its codec struct", "[unit][apt][wire]")
{
    for (const auto& info : all_messages()) {
        INFO(info.name);
        const auto* names = field_names(info.id);
        // The end-of-move messages' status structure is named by its kind (put_status).
        const bool end_of_move = info.id == MGMSG_MOT_MOVE_COMPLETED || info.id == MGMSG_MOT_MOVE_STOPPED;
        if (!info.header_only() && !end_of_move)
            REQUIRE(names != nullptr);
        if (names)
            for (const auto name : *names)
                CHECK((!name.empty() && name.find_first_of(" .,") == std::string_view::npos));
    }
    // The names of a nested block are its members' own (codec_kcube.hpp: s.params.actuator_ident).
    CHECK(*field_names(MGMSG_MOT_SET_TSTACTUATORTYPE) == std::vector<std::string_view>{"actuator_ident", "unused"});
    CHECK(*field_names(MGMSG_MOT_GET_VELPARAMS)
          == std::vector<std::string_view>{"chan_ident", "min_velocity", "acceleration", "max_velocity"});
    CHECK(*field_names(MGMSG_MOT_REQ_VELPARAMS) == std::vector<std::string_view>{"chan_ident"});
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
    // The same bits mean other things on other units.
    CHECK(status_bit_names(0x00003001, StatusTable::Solenoid)
          == std::vector<std::string_view>{"output_on", "interlock", "key_unlocked"});
    CHECK(status_bit_names(0xA0201511, StatusTable::Piezo)
          == std::vector<std::string_view>{"actuator_connected", "zeroed", "gauge_connected", "closed_loop",
                                           "hw_max_75v", "digital_input_2", "active", "enabled"});
    CHECK(status_bit_names(0x00000031, StatusTable::StrainGauge)
          == std::vector<std::string_view>{"gauge_connected", "zeroed", "zeroing"});
    CHECK(status_bit_names(0x00000005, StatusTable::Rack) == std::vector<std::string_view>{"user_io_1", "user_io_3"});
}

TEST_CASE("decode_for_log: a stepper's MOVE_COMPLETED has an encoder count, piezo and solenoid status bits their own names",
          "[unit][apt][wire]")
{
    // MOVE_COMPLETED from a KST101: position 409,600, encoder count 409,601 (MOT_GET_STATUSUPDATE's
    // layout, p. 44 and p. 77), status homed | enabled.
    std::string status;
    put_u16(status, 1);
    put_i32(status, 409600);
    put_i32(status, 409601);
    put_u32(status, 0x80000400);
    const std::string completed = encode_with_data(MGMSG_MOT_MOVE_COMPLETED, 0x01, 0x50, status);
    LogContext stepper;
    stepper.stepper_status = true;
    nlohmann::json out = nlohmann::json::object();
    decode_for_log(completed, out, stepper);
    CHECK(out["fields"] == nlohmann::json{{"chan_ident", 1}, {"position", 409600}, {"enc_count", 409601},
                                          {"status_bits", 0x80000400u}, {"status_set", {"homed", "enabled"}}});
    // The same bytes from a DC servo: velocity and the reserved word (the DC structure, p. 79).
    out = nlohmann::json::object();
    decode_for_log(completed, out);
    CHECK(out["fields"].contains("velocity"));
    CHECK_FALSE(out["fields"].contains("enc_count"));
    // PZ_GET_PZSTATUSUPDATE (p. 103): the piezo chapter's bits, whatever the unit; a reader's bit 0.
    std::string pz;
    put_u16(pz, 1);
    put_i16(pz, 0x3FFF);
    put_i16(pz, 0x1000);
    put_u32(pz, 0x00000411);
    const std::string update = encode_with_data(MGMSG_PZ_GET_PZSTATUSUPDATE, 0x01, 0x50, pz);
    out = nlohmann::json::object();
    decode_for_log(update, out);
    CHECK(out["fields"]["status_set"] == nlohmann::json{"actuator_connected", "zeroed", "closed_loop"});
    LogContext gauge;
    gauge.unit = StatusTable::StrainGauge;
    out = nlohmann::json::object();
    decode_for_log(update, out, gauge);
    CHECK(out["fields"]["status_set"][0] == "gauge_connected");
    // MOT_GET_STATUSBITS from a KSC101: the output, the interlock and the key (D-4).
    std::string bits;
    put_u16(bits, 1);
    put_u32(bits, 0x00003001);
    LogContext solenoid;
    solenoid.unit = StatusTable::Solenoid;
    out = nlohmann::json::object();
    decode_for_log(encode_with_data(MGMSG_MOT_GET_STATUSBITS, 0x01, 0x50, bits), out, solenoid);
    CHECK(out["fields"]["status_set"] == nlohmann::json{"output_on", "interlock", "key_unlocked"});
}

} // namespace test_wire_decode
