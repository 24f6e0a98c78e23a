// The APT wire log as a client's author reads it (docs/control-api/apt.md "Wire log"): the bytes
// the unit drops, in wire order, and each unit's frames decoded with their own field and status
// bit names (a stepper's end-of-move status, a piezo's, a solenoid's).
#include "apt_harness.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace test_apt_wire_log {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;

namespace {

/// The decoded form of the newest entry named `name`, or null.
nlohmann::json last_named(AptDevice& d, const std::string& name)
{
    const auto log = d.wire_log().to_json(d.wire_log().size());
    for (auto it = log.rbegin(); it != log.rend(); ++it)
        if ((*it)["decoded"].value("name", "") == name)
            return (*it)["decoded"];
    return nullptr;
}

/// A single unit `model` without a stage (piezo, solenoid).
DeviceConfig unit(const std::string& model)
{
    DeviceConfig c;
    c.name = "unit";
    c.protocol = "apt";
    c.model = model;
    config_of(c).solenoid.interlock_fitted = true;
    return c;
}

} // namespace

TEST_CASE("the wire log keeps the bytes it drops: garbage before a frame, in order, and an unfinished message",
          "[device][apt][framing][wire]")
{
    AptHarness h;
    CHECK(h.send("48 65 6C 6C 6F 11 04 01 00 50 01") == "12 04 06 00 81 50 01 00 00 00 00 00");   // "Hello", REQ
    auto log = h.device().wire_log().to_json(3);
    CHECK(log[0]["hex"] == "48 65 6c 6c 6f");
    CHECK(log[0]["decoded"]["name"] == "not a frame");
    CHECK(log[0]["notes"][0] == "ignored by the unit: 5 byte(s) that start no valid message (an unknown message ID, "
                                "address or data length)");
    CHECK(log[1]["decoded"]["name"] == "MGMSG_MOT_REQ_POSCOUNTER");
    CHECK(log[2]["direction"] == "out");
    // Half a SET_VELPARAMS, then silence beyond the inter-byte timeout: its 12 bytes in one entry.
    CHECK(h.send("13 04 0E 00 D0 01 01 00 C0 C6 2D 00") == "");
    h.advance_ms(AptDevice::kInterByteTimeout_ms + 1);
    CHECK(h.send("11 04 01 00 50 01") == "12 04 06 00 81 50 01 00 00 00 00 00");
    log = h.device().wire_log().to_json(3);
    CHECK(log[0]["hex"] == "13 04 0e 00 d0 01 01 00 c0 c6 2d 00");
    CHECK(log[0]["notes"][0] == "12 byte(s) of an unfinished message dropped: the rest did not come within 50 ms");
    CHECK(log[1]["decoded"]["name"] == "MGMSG_MOT_REQ_POSCOUNTER");
    // 300 bytes of noise: one entry, its first 256 bytes shown.
    std::string noise;
    for (int i = 0; i < 300; ++i)
        noise += i == 0 ? "FF" : " FF";
    CHECK(h.send(noise + " 11 04 01 00 50 01").size() > 0);
    log = h.device().wire_log().to_json(3);
    CHECK(log[0]["hex"].get<std::string>().size() == 256 * 3 - 1);
    CHECK(log[0]["notes"][0].get<std::string>().find("300 byte(s) that start no valid message") != std::string::npos);
    CHECK(log[0]["notes"][0].get<std::string>().find("(the first 256 shown)") != std::string::npos);
}

TEST_CASE("the wire log decodes a stepper's MOVE_COMPLETED with its encoder count, a DC servo's with its velocity",
          "[device][apt][wire]")
{
    AptHarness st(apt_cube("TST001", "DRV001"));
    CHECK(st.send("48 04 06 00 D0 01 01 00 00 64 00 00") == "");   // MOVE_RELATIVE 25,600 microsteps
    st.advance_ms(10000);
    REQUIRE(frames(st.take()).size() == 1);
    const auto stepper = last_named(st.device(), "MGMSG_MOT_MOVE_COMPLETED");
    REQUIRE(stepper.is_object());
    CHECK(stepper["fields"]["position"] == 25600);
    CHECK(stepper["fields"]["enc_count"] == 25600);   // MOT_GET_STATUSUPDATE's long, not a velocity word
    CHECK_FALSE(stepper["fields"].contains("velocity"));

    AptHarness dc;   // TDC001
    CHECK(dc.send("48 04 06 00 D0 01 01 00 00 86 00 00") == "");
    dc.advance_ms(5000);
    REQUIRE(frames(dc.take()).size() == 1);
    const auto servo = last_named(dc.device(), "MGMSG_MOT_MOVE_COMPLETED");
    REQUIRE(servo.is_object());
    CHECK(servo["fields"]["position"] == 34304);
    CHECK(servo["fields"].contains("velocity"));
    CHECK_FALSE(servo["fields"].contains("enc_count"));
}

TEST_CASE("the wire log names a piezo's and a solenoid's status bits as their manual sections do",
          "[device][apt][wire]")
{
    AptHarness pz(unit("TPZ001"));
    CHECK(pz.send("11 00 00 00 50 01") == "");   // HW_START_UPDATEMSGS
    pz.advance_ms(100);
    REQUIRE(!pz.take().empty());
    const auto update = last_named(pz.device(), "MGMSG_PZ_GET_PZSTATUSUPDATE");
    REQUIRE(update.is_object());
    CHECK(update["fields"]["status_set"] == nlohmann::json{"actuator_connected"});   // p. 103, not a motor's limit

    AptHarness sc(unit("TSC001"));
    CHECK(sc.send("CB 04 01 01 50 01") == "");   // SET_SOL_STATE ON (manual mode)
    CHECK(sc.send("11 00 00 00 50 01") == "");
    sc.advance_ms(100);
    REQUIRE(!sc.take().empty());
    const auto status = last_named(sc.device(), "MGMSG_MOT_GET_STATUSUPDATE");
    REQUIRE(status.is_object());
    CHECK(status["fields"]["status_set"] == nlohmann::json{"output_on", "interlock"});   // D-4, p. 77
}

} // namespace test_apt_wire_log
