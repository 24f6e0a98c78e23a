// Piezo, strain gauge and solenoid messages to a motor controller, and motor moves to a
// solenoid controller: the framer knows them (they are in the message table), the unit has no
// such module, so it ignores each one and logs it, and answers the next request as if nothing
// had come before.
#include "apt_harness.hpp"

#include <spdlog/sinks/ostream_sink.h>

#include <sstream>

namespace test_apt_unknown_modules {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;

namespace {

/// A device whose log is captured.
class LoggedDevice {
public:
    explicit LoggedDevice(const DeviceConfig& config)
        : log_(std::make_shared<spdlog::logger>("apt", std::make_shared<spdlog::sinks::ostream_sink_st>(log_text_))),
          device_(config, world_, log_, nullptr),
          session_(device_.open_session([this](std::string_view b) { out_.append(b); }, "test"))
    {
    }
    /// Bytes in; everything sent since the last call out.
    std::string send(const std::string& in)
    {
        session_->receive(in);
        std::string r;
        r.swap(out_);
        return r;
    }
    /// The log written since the last call.
    std::string take_log()
    {
        std::string r = log_text_.str();
        log_text_.str("");
        return r;
    }

private:
    std::ostringstream log_text_;
    std::shared_ptr<spdlog::logger> log_;
    Clock clock_;
    models::World world_{clock_};
    AptDevice device_;
    std::string out_;
    std::unique_ptr<Session> session_;
};

/// The message `m` as a client sends it to `dest`: channel 1, data bytes 1, 2, 3, ...
std::string client_frame(const MessageInfo& m, std::uint8_t dest)
{
    if (m.header_only())
        return encode_header_only(m.id, 0x01, 0x00, dest, kHost);
    std::string data;
    put_u16(data, 1);
    for (int k = 2; k < m.data_length; ++k)
        data.push_back(static_cast<char>(k));
    return encode_with_data(m.id, dest, kHost, data);
}

std::vector<const MessageInfo*> piezo_and_strain_gauge_messages()
{
    std::vector<const MessageInfo*> out;
    for (const auto& m : all_messages())
        if (m.group == Group::Piezo || m.group == Group::StrainGauge)
            out.push_back(&m);
    return out;
}

/// A controller of `model` with the default "apt" section; a BPC303 with one default bay.
DeviceConfig motorless_unit(const std::string& model)
{
    DeviceConfig c;
    c.name = "unit";
    c.protocol = "apt";
    c.model = model;
    auto& apt = config_of(c);
    if (model == "BPC303")
        apt.piezo_bays = {PiezoBayConfig{}};
    return c;
}

/// Motor messages a client might send any APT unit (p.27-83): no piezo, strain gauge or
/// solenoid unit moves a motor (their tables p.132-134, p.138; D-4).
const std::vector<std::uint16_t> kMotorMoves{
    MGMSG_MOT_MOVE_HOME,       MGMSG_MOT_MOVE_ABSOLUTE, MGMSG_MOT_MOVE_RELATIVE,   MGMSG_MOT_MOVE_JOG,
    MGMSG_MOT_MOVE_STOP,       MGMSG_MOT_SET_VELPARAMS, MGMSG_MOT_REQ_VELPARAMS,   MGMSG_MOT_SET_HOMEPARAMS,
    MGMSG_MOT_REQ_POSCOUNTER,  MGMSG_MOT_SET_EEPROMPARAMS,
};

} // namespace

TEST_CASE("apt TDC001 ignores and logs a piezo request, then answers the next one", "[device][apt][unknown-modules]")
{
    LoggedDevice d(tdc001());
    // MGMSG_PZ_REQ_OUTPUTVOLTS (p.96) to the cube: no answer.
    CHECK(d.send(bytes("44 06 01 00 50 01")).empty());
    const auto log = d.take_log();
    CHECK(log.find("MGMSG_PZ_REQ_OUTPUTVOLTS is not a message a TDC001 acts on: ignored") != std::string::npos);
    CHECK(log.find("[warning]") != std::string::npos);
    CHECK(log.find("skipped") == std::string::npos);   // a frame, not garbage
    // MGMSG_MOT_REQ_STATUSBITS right after: answered.
    const auto reply = d.send(bytes("29 04 01 00 50 01"));
    REQUIRE(reply.size() == 12);
    CHECK(hex(reply.substr(0, 8)) == "2A 04 06 00 81 50 01 00");
    CHECK(d.take_log().empty());
}

TEST_CASE("apt TDC001 ignores and logs every piezo and strain gauge message", "[device][apt][unknown-modules]")
{
    const auto messages = piezo_and_strain_gauge_messages();
    REQUIRE(messages.size() == 52 + 13);   // the manual's, and the K-Cube units' of later issues
    LoggedDevice d(tdc001());
    const std::string req_info = encode_header_only(MGMSG_HW_REQ_INFO, 0, 0, kGenericUsb, kHost);
    for (const auto* m : messages) {
        INFO(m->name);
        // The message and a request in one read, as a client's burst arrives.
        const auto reply = d.send(client_frame(*m, kGenericUsb) + req_info);
        REQUIRE(reply.size() == 6 + 84);
        CHECK(hex(reply.substr(0, 6)) == "06 00 54 00 81 50");   // HW_GET_INFO, and nothing else
        const auto log = d.take_log();
        CHECK(log.find(std::string(m->name) + " is not a message a TDC001 acts on: ignored") != std::string::npos);
        CHECK(log.find("skipped") == std::string::npos);
    }
}

TEST_CASE("apt TDC001 does not save an ignored piezo SET to its EEPROM", "[device][apt][unknown-modules]")
{
    LoggedDevice d(tdc001());
    // MGMSG_PZ_SET_OUTPUTVOLTS (p.96 example), then MOT_SET_EEPROMPARAMS naming it.
    CHECK(d.send(bytes("43 06 04 00 D0 01 01 00 77 77")).empty());
    d.take_log();
    CHECK(d.send(bytes("B9 04 04 00 D0 01 01 00 43 06")).empty());
    CHECK(d.take_log().find("MOT_SET_EEPROMPARAMS for 0x0643 (MGMSG_PZ_SET_OUTPUTVOLTS): not a parameter SET it "
                            "saves, nothing saved")
          != std::string::npos);
}

TEST_CASE("apt BBD203 ignores and logs piezo messages to a bay and to the motherboard", "[device][apt][unknown-modules]")
{
    LoggedDevice d(apt_rack("BBD203", {"MLS203-X"}));
    const auto* set_zero = find_message(MGMSG_PZ_SET_ZERO);
    const auto* tsg = find_message(MGMSG_PZ_REQ_TSG_READING);
    REQUIRE(set_zero != nullptr);
    REQUIRE(tsg != nullptr);
    const std::string req_bay = encode_header_only(MGMSG_RACK_REQ_BAYUSED, 0, 0, kRack, kHost);

    auto reply = d.send(client_frame(*set_zero, kBay0) + req_bay);
    CHECK(hex(reply) == "61 00 00 01 01 11");   // RACK_GET_BAYUSED only
    auto log = d.take_log();
    CHECK(log.find("MGMSG_PZ_SET_ZERO is not a message a BBD203 acts on: ignored") != std::string::npos);

    reply = d.send(client_frame(*tsg, kRack) + req_bay);
    CHECK(hex(reply) == "61 00 00 01 01 11");
    log = d.take_log();
    CHECK(log.find("MGMSG_PZ_REQ_TSG_READING to the motherboard: it acts on no such message, ignored")
          != std::string::npos);
    CHECK(log.find("skipped") == std::string::npos);
}

TEST_CASE("apt TDC001 ignores and logs every solenoid SET and REQ", "[device][apt][unknown-modules][solenoid]")
{
    LoggedDevice d(tdc001());
    const std::string req_info = encode_header_only(MGMSG_HW_REQ_INFO, 0, 0, kGenericUsb, kHost);
    int seen = 0;
    for (const auto& m : all_messages()) {
        const std::string_view name = m.name;
        if (m.id < MGMSG_MOT_SET_SOL_OPERATINGMODE || m.id > MGMSG_MOT_GET_SOL_STATE || name.find("_GET_") != name.npos)
            continue;
        INFO(m.name);
        ++seen;
        const auto reply = d.send(client_frame(m, kGenericUsb) + req_info);
        REQUIRE(reply.size() == 6 + 84);
        CHECK(hex(reply.substr(0, 6)) == "06 00 54 00 81 50");   // HW_GET_INFO, and nothing else
        // SET_SOL_CYCLEPARAMS with these bytes is also out of range (OnTime 0x05040302): the range
        // check logs it first, as for any SET whose fields the manual bounds.
        const auto log = d.take_log();
        CHECK(log.find(std::string(m.name)) != std::string::npos);
        CHECK(log.find(": ignored") != std::string::npos);
    }
    CHECK(seen == 8);
}

TEST_CASE("apt TSC001 ignores and logs a motor move (D-4), then answers the next request",
          "[device][apt][unknown-modules][solenoid]")
{
    DeviceConfig c;
    c.name = "sol";
    c.protocol = "apt";
    c.model = "TSC001";
    config_of(c);   // the default "apt" section
    LoggedDevice d(c);
    // MGMSG_MOT_MOVE_ABSOLUTE (p.45, in the TSC001 table p.138 but without a solenoid meaning).
    CHECK(d.send(bytes("53 04 01 00 50 01")).empty());
    CHECK(d.take_log().find("MGMSG_MOT_MOVE_ABSOLUTE is not a message a TSC001 acts on: ignored") != std::string::npos);
    CHECK(d.send(bytes("43 04 01 00 50 01")).empty());   // MGMSG_MOT_MOVE_HOME: not in its table either
    CHECK(d.take_log().find("MGMSG_MOT_MOVE_HOME is not a message a TSC001 acts on: ignored") != std::string::npos);
    CHECK(hex(d.send(bytes("CC 04 01 00 50 01"))) == "CD 04 01 02 01 50");
    CHECK(d.take_log().empty());
}

TEST_CASE("apt piezo, strain gauge and solenoid units ignore and log motor messages, no bytes out",
          "[device][apt][unknown-modules][piezo]")
{
    for (const std::string model : {"TPZ001", "KPZ101", "BPC303", "TSG001", "KSG101", "TSC001", "KSC101"}) {
        LoggedDevice d(motorless_unit(model));
        // A BPC303's channels are its bays (0x21...): the motor message goes to bay 0.
        const std::uint8_t dest = model == "BPC303" ? kBay0 : kGenericUsb;
        const std::string req_info = encode_header_only(MGMSG_HW_REQ_INFO, 0, 0, dest, kHost);
        for (const auto id : kMotorMoves) {
            if (id == MGMSG_MOT_SET_EEPROMPARAMS && (model == "TSC001" || model == "KSC101"))
                continue;   // the solenoid units save with it (TSC001 table, p.138)
            const auto* m = find_message(id);
            REQUIRE(m != nullptr);
            INFO(model << ": " << m->name);
            // The message and a request in one read, as a client's burst arrives.
            const auto reply = d.send(client_frame(*m, dest) + req_info);
            REQUIRE(reply.size() == 6 + 84);
            CHECK(hex(reply.substr(0, 4)) == "06 00 54 00");   // HW_GET_INFO, and nothing else
            const auto log = d.take_log();
            CHECK(log.find(std::string(m->name) + " is not a message a " + model + " acts on: ignored")
                  != std::string::npos);
            CHECK(log.find("[warning]") != std::string::npos);
        }
    }
}

TEST_CASE("apt stepper and DC servo units ignore and log every piezo and strain gauge message",
          "[device][apt][unknown-modules][piezo]")
{
    const auto messages = piezo_and_strain_gauge_messages();
    for (const auto& config : {apt_cube("KDC101", "Z825B"), apt_cube("TST001", "DRV001"), apt_cube("KST101", "ZST225B"),
                               apt_rack("BSC203", {"DRV001"})}) {
        LoggedDevice d(config);
        const std::uint8_t dest = config.model == "BSC203" ? kBay0 : kGenericUsb;
        const std::string req_info = encode_header_only(MGMSG_HW_REQ_INFO, 0, 0, dest, kHost);
        for (const auto* m : messages) {
            INFO(config.model << ": " << m->name);
            const auto reply = d.send(client_frame(*m, dest) + req_info);
            REQUIRE(reply.size() == 6 + 84);
            CHECK(hex(reply.substr(0, 4)) == "06 00 54 00");
            CHECK(d.take_log().find(std::string(m->name) + " is not a message a " + config.model + " acts on: ignored")
                  != std::string::npos);
        }
    }
}

TEST_CASE("apt BPC303 bay ignores and logs PZ_SET_EEPROMPARAMS (not in the BPC30x table, p.132)",
          "[device][apt][unknown-modules][piezo]")
{
    LoggedDevice d(motorless_unit("BPC303"));
    CHECK(d.send(bytes("80 06 06 00 A1 01 01 00 E8 03 00 00")).size() == 12 + 10);   // GET_OUTPUTMAXVOLTS + GET_MAXTRAVEL
    d.take_log();
    CHECK(d.send(bytes("D0 07 04 00 A1 01 01 00 80 06")).empty());
    CHECK(d.take_log().find("MGMSG_PZ_SET_EEPROMPARAMS is not a message a BPC303 acts on: ignored") != std::string::npos);
}

} // namespace test_apt_unknown_modules
