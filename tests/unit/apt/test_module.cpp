// APT Module (emulator/apt/module.hpp), what every module kind shares: the model's MessageSet
// check in dispatch, and the stored form of the SETs an EEPROMPARAMS message saves.
#include "emulator/apt/motor_module.hpp"
#include "emulator/apt/shipped_stages.hpp"
#include "models/world.hpp"
#include "tests/support/hex.hpp"

#include <catch2/catch.hpp>
#include <spdlog/logger.h>
#include <spdlog/sinks/ostream_sink.h>

#include <memory>
#include <sstream>
#include <string>

namespace test_module {

using namespace rigsim;
using namespace rigsim::apt;
using rigsim::test::bytes;
using rigsim::test::hex;

namespace {

/// A TDC001 whose model takes only MOT_REQ_VELPARAMS and PZ_SET_TPZ_DISPSETTINGS (a MessageSet built here: the catalogue's
/// motor models have none), as a DC servo module on a stepped clock with its log captured.
class RestrictedCube {
public:
    RestrictedCube()
        : model_(restricted(*find_controller("TDC001"))), unit_{"TDC001", model_, 83000001, 1},
          channel_(model_, *find_stage("MTS50-Z8"), world_, "cube/1"),
          log_("apt", std::make_shared<spdlog::sinks::ostream_sink_st>(log_text_)),
          module_(unit_, 0, kGenericUsb, channel_, log_, [](std::uint16_t, std::string_view) {})
    {
    }
    /// One whole frame (hex) in; the module's answer (hex) out; `request` as the module left it.
    std::string send(const std::string& frame_hex)
    {
        FrameFramer framer;
        const auto frame_bytes = bytes(frame_hex);
        const auto parsed = framer.parse(frame_bytes);
        REQUIRE(parsed.status == FrameFramer::Status::Frame);
        std::string reply;
        Request r{parsed.frame, "test", reply, kHost};
        module_.handle(msg::decode(parsed.frame), r);
        ignored = r.ignored;
        why = r.why;
        return hex(reply);
    }
    /// The log written since the last call.
    std::string take_log()
    {
        auto text = log_text_.str();
        log_text_.str("");
        return text;
    }

    bool ignored = false;
    std::string why;

private:
    static ControllerModel restricted(ControllerModel m)
    {
        static constexpr std::uint16_t kTakes[] = {MGMSG_MOT_REQ_VELPARAMS, MGMSG_PZ_SET_TPZ_DISPSETTINGS};
        m.takes = {kTakes, 2};
        return m;
    }

    ControllerModel model_;
    UnitIdentity unit_;
    Clock clock_;
    models::World world_{clock_};
    MotorChannel channel_;
    std::ostringstream log_text_;
    spdlog::logger log_;
    DcServoModule module_;
};

} // namespace

TEST_CASE("apt module: a message outside the model's MessageSet is ignored and logged, one in it answered",
          "[unit][apt][module]")
{
    RestrictedCube cube;
    // MOT_REQ_POSCOUNTER (p. 28): a DC servo module has its handler, the model does not take it.
    CHECK(cube.send("11 04 01 00 50 01").empty());
    CHECK(cube.ignored);
    CHECK(cube.why == "MGMSG_MOT_REQ_POSCOUNTER is not a message a TDC001 acts on: ignored");
    CHECK(cube.take_log().find("test: MGMSG_MOT_REQ_POSCOUNTER is not a message a TDC001 acts on: ignored")
          != std::string::npos);
    // MOT_SET_VELPARAMS is outside the set too: ignored before its fields are looked at.
    CHECK(cube.send("13 04 0E 00 D0 01 01 00 00 00 00 00 01 00 00 00 02 00 00 00").empty());
    CHECK(cube.ignored);
    CHECK(cube.take_log().find("MGMSG_MOT_SET_VELPARAMS is not a message a TDC001 acts on: ignored") != std::string::npos);
    // MOT_REQ_VELPARAMS (p. 30) is in the set: answered.
    CHECK(cube.send("14 04 01 00 50 01").substr(0, 17) == "15 04 0E 00 81 50");
    CHECK_FALSE(cube.ignored);
    CHECK(cube.take_log().empty());
    // Generic messages are never checked against the set: HW_REQ_INFO (p. 21), MOD_REQ_CHANENABLESTATE (p. 17).
    CHECK(cube.send("05 00 00 00 50 01").substr(0, 17) == "06 00 54 00 81 50");
    CHECK(cube.send("11 02 01 00 50 01") == "12 02 01 01 01 50");
    CHECK_FALSE(cube.ignored);
}

TEST_CASE("apt module: a data packet without a channel word is not read as a channel", "[unit][apt][module]")
{
    // PZ_SET_TPZ_DISPSETTINGS (p. 114): its first word is the intensity (100), not a channel.
    // Taken by the model, it reaches the module's handlers: a DC servo module has none for
    // the piezo family, so it is "not a message a TDC001 acts on" -- never "for channel 100".
    RestrictedCube cube;
    CHECK(cube.send("D1 07 02 00 D0 01 64 00").empty());
    CHECK(cube.ignored);
    CHECK(cube.why == "MGMSG_PZ_SET_TPZ_DISPSETTINGS is not a message a TDC001 acts on: ignored");
}

TEST_CASE("apt module: SavedSets stores a SET for channel 1: its data packet, or a header-only SET's params",
          "[unit][apt][module][eeprom]")
{
    using Saved = SavedSets<msg::SetVelParams, msg::SetTpzDispSettings, msg::PzSetPosControlMode>;
    CHECK(Saved::saves(MGMSG_MOT_SET_VELPARAMS));
    CHECK(Saved::saves(MGMSG_PZ_SET_POSCONTROLMODE));
    CHECK_FALSE(Saved::saves(MGMSG_MOT_SET_POSCOUNTER));
    // A data packet's channel word becomes 1, whatever the SET carried.
    msg::SetVelParams vel{{2, 10, 20, 30}};
    CHECK(hex(*Saved::data(vel)) == "01 00 0A 00 00 00 14 00 00 00 1E 00 00 00");
    // TPZ_DISPSETTINGS has no channel word (p. 114): stored as sent.
    msg::SetTpzDispSettings display{};
    display.params.disp_intensity = 100;
    CHECK(hex(*Saved::data(display)) == "64 00");
    // A header-only SET: param1 (the channel, as 1) and param2.
    msg::PzSetPosControlMode mode{};
    mode.chan_ident = 0;
    mode.mode = 2;
    CHECK(hex(*Saved::data(mode)) == "01 02");
    // Not one of the set: nothing stored.
    CHECK_FALSE(Saved::data(msg::SetPosCounter{{1, 5}}).has_value());
}

} // namespace test_module
