// GET /api/frames, GET /api/frames/{name} and the "frames" event over a stand-in device whose
// channel drives a prismatic joint: what the routes answer, when an event comes (a motion's
// end, a PATCH, a reset; not while moving, not when nothing moved) and what it carries.
#include "emulator/control/control_api.hpp"
#include "emulator/core/control_surface.hpp"
#include "emulator/core/wire_log.hpp"
#include "models/kinematics.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <boost/asio/io_context.hpp>

#include <string>
#include <vector>

namespace test_control_frames {

using namespace rigsim;
using rigsim::control::ControlApi;
using nlohmann::json;

namespace {

/// One linear channel whose physical position (m) PATCH sets.
class Stage : public ControlSurface {
public:
    explicit Stage(Clock& clock) : log_("dev", clock.tick_hz(), nullptr) {}

    void describe(json& out) const override
    {
        out["channels"] = json::array({json{{"index", 0}, {"kind", "linear"}, {"position_si", position_m}}});
    }
    Refused patch_channel(std::size_t, const json& body) override
    {
        position_m = body.at("position_si").get<double>();
        return std::nullopt;
    }
    Refused add_fault(const DeviceFault&, bool*) override { return Refusal{400, "none"}; }
    void remove_fault(std::uint64_t) override {}
    void power_cycle(const PowerCycle&) override { position_m = 0; }   // back to the start position
    WireLog& wire_log() override { return log_; }

    double position_m = 0;

private:
    WireLog log_;
};

/// Channels 0..n-1 whose joints drive the world bodies `keys` (an empty key: moves nothing).
class Mounts : public ControlSurface {
public:
    Mounts(Clock& clock, std::vector<std::string> keys) : keys_(std::move(keys)), log_("m", clock.tick_hz(), nullptr) {}

    void describe(json& out) const override
    {
        out["channels"] = json::array();
        for (std::size_t i = 0; i < keys_.size(); ++i)
            out["channels"].push_back(json{{"index", i}});
    }
    Refused axis_body_key(std::size_t index, std::string& out) const override
    {
        if (index >= keys_.size())
            return Refusal{404, "no channel"};
        if (keys_[index].empty())
            return Refusal{400, "moves nothing"};
        out = keys_[index];
        return std::nullopt;
    }
    Refused patch_channel(std::size_t, const json&) override { return std::nullopt; }
    Refused add_fault(const DeviceFault&, bool*) override { return Refusal{400, "none"}; }
    void remove_fault(std::uint64_t) override {}
    void power_cycle(const PowerCycle&) override {}
    WireLog& wire_log() override { return log_; }

private:
    std::vector<std::string> keys_;
    WireLog log_;
};

class NullDevice : public Device {
public:
    std::unique_ptr<Session> open_session(SendFn, std::string) override { return nullptr; }
};

/// table; "x" on the channel, 10 mm up; a tool "tip" 5 mm above x.
struct Fixture {
    Fixture()
    {
        Eigen::Isometry3d up = Eigen::Isometry3d::Identity();
        up.translation() = Eigen::Vector3d(0, 0, 10);
        kinematics.add_frame("x", 0, up,
                             models::Joint{models::JointType::Prismatic, Eigen::Vector3d::UnitX(), Eigen::Vector3d::Zero()},
                             [this] { return stage.position_m * 1000; });
        Eigen::Isometry3d above = Eigen::Isometry3d::Identity();
        above.translation() = Eigen::Vector3d(0, 0, 5);
        kinematics.add_tool("tip", 1, above);
    }

    std::pair<unsigned, json> call(const std::string& method, const std::string& target, const std::string& body = {})
    {
        const auto reply = api->handle(method, target, body);
        INFO(method << " " << target << " -> " << reply.status << " " << reply.body);
        const auto parsed = json::parse(reply.body, nullptr, false);
        REQUIRE_FALSE(parsed.is_discarded());
        return {reply.status, parsed};
    }
    void make_api(bool with_frames)
    {
        control::FrameSource source;
        if (with_frames)
            source = control::FrameSource{&kinematics, {std::nullopt, control::JointAxis{"dev", 0}, std::nullopt}, {}};
        api = std::make_unique<ControlApi>(
            clock, ticker, [] { return false; },
            std::vector<ControlledDevice>{ControlledDevice{
                DeviceEndpoints{"dev", "mcs", "MCS-3D", "127.0.0.1:1", "/tmp/x/dev", "1.2.44", ""}, &stage, &link}},
            &bus, std::move(source));
    }
    /// The "frames" events written to `text` so far, as their data.
    static std::vector<json> frames_events(const std::string& text)
    {
        std::vector<json> out;
        std::size_t at = 0;
        while ((at = text.find("event: frames\n", at)) != std::string::npos) {
            const auto data = text.find("data: ", at) + 6;
            out.push_back(json::parse(text.substr(data, text.find('\n', data) - data)));
            at = data;
        }
        return out;
    }

    boost::asio::io_context io;
    Clock clock{1000};
    Ticker ticker{io, clock, 1.0, Ticker::Start::Paused};
    EventBus bus;
    Stage stage{clock};
    NullDevice null_device;
    Link link{null_device, clock};
    models::Kinematics kinematics{"table"};
    std::unique_ptr<ControlApi> api;
};

} // namespace

TEST_CASE("GET /api/frames: every frame and tool point, /api/frames/{name} one, 404 and 405", "[control]")
{
    Fixture f;
    f.make_api(true);
    f.stage.position_m = 0.002;
    const auto [status, all] = f.call("GET", "/api/frames");
    CHECK(status == 200);
    REQUIRE(all["frames"].size() == 2);
    CHECK(all["frames"][0]["name"] == "table");
    CHECK(all["frames"][1]["joint"] == json{{"type", "prismatic"}, {"device", "dev"}, {"channel", 0}, {"position", 2.0}});
    CHECK(all["frames"][1]["world"]["position_mm"] == json::array({2.0, 0.0, 10.0}));
    REQUIRE(all["tools"].size() == 1);
    CHECK(all["tools"][0]["world"]["position_mm"] == json::array({2.0, 0.0, 15.0}));
    CHECK(all["collisions"] == json::array());

    const auto [one_status, tip] = f.call("GET", "/api/frames/tip");
    CHECK(one_status == 200);
    CHECK(tip["name"] == "tip");
    CHECK(tip["tool"] == true);
    CHECK(tip["parent_relative"]["position_mm"] == json::array({0.0, 0.0, 5.0}));

    const auto [missing, error] = f.call("GET", "/api/frames/nope");
    CHECK(missing == 404);
    CHECK(error["error"] == "no frame named \"nope\"");
    CHECK(f.call("GET", "/api/frames/t%69p").second["name"] == "tip");   // percent-decoded
    CHECK(f.call("POST", "/api/frames").first == 405);
    CHECK(f.call("GET", "/api/frames/tip/x").first == 404);
}

TEST_CASE("GET /api/frames on a rig without kinematics: empty lists, any name is 404", "[control]")
{
    Fixture f;
    f.make_api(false);
    const auto [status, all] = f.call("GET", "/api/frames");
    CHECK(status == 200);
    CHECK(all == json{{"frames", json::array()}, {"tools", json::array()}, {"collisions", json::array()}});
    CHECK(f.call("GET", "/api/frames/table").first == 404);
}

TEST_CASE("The frames event: after a motion's end, a PATCH and a reset, with the frames that moved", "[control]")
{
    Fixture f;
    f.make_api(true);
    auto reply = f.api->handle("GET", "/api/events?type=frames", "");
    REQUIRE(reply.stream);
    std::string got;
    auto stop = reply.stream([&](control::StreamChunk b) { got.append(*b); });

    // A PATCH that places the stage: x and the tip moved, the table did not.
    f.call("PATCH", "/api/devices/dev/channels/0", R"({"position_si": 0.002})");
    auto events = Fixture::frames_events(got);
    REQUIRE(events.size() == 1);
    CHECK(events[0]["type"] == "frames");
    CHECK(events[0]["after"] == json{{"type", "channel_set"}, {"device", "dev"}});
    REQUIRE(events[0]["frames"].size() == 2);
    CHECK(events[0]["frames"][0]["name"] == "x");
    CHECK(events[0]["frames"][1]["world"]["position_mm"] == json::array({2.0, 0.0, 15.0}));

    // While the stage moves: status events bring no frames event; its move_ended does.
    f.stage.position_m = 0.003;
    f.bus.publish("dev", "move_started", 1, json{{"channel", 0}});
    f.bus.publish("dev", "status", 1, json{{"channel", 0}});
    CHECK(Fixture::frames_events(got).size() == 1);
    f.bus.publish("dev", "move_ended", 2, json{{"channel", 0}, {"outcome", "completed"}});
    events = Fixture::frames_events(got);
    REQUIRE(events.size() == 2);
    CHECK(events[1]["after"] == json{{"type", "move_ended"}, {"device", "dev"}});
    CHECK(events[1]["frames"][0]["joint"]["position"] == 3.0);

    // A move that ends where it started moved nothing: no event.
    f.bus.publish("dev", "move_ended", 3, json{{"channel", 0}, {"outcome", "stopped"}});
    CHECK(Fixture::frames_events(got).size() == 2);

    // A reset puts the stage back at its start: the event after the reset's.
    f.call("POST", "/api/reset");
    events = Fixture::frames_events(got);
    REQUIRE(events.size() == 3);
    CHECK(events[2]["after"] == json{{"type", "reset"}});
    CHECK(events[2]["frames"][0]["world"]["position_mm"] == json::array({0.0, 0.0, 10.0}));
    stop();
}

TEST_CASE("The frames event follows its cause on every stream, and none is built while no one listens", "[control]")
{
    Fixture f;
    f.make_api(true);
    f.stage.position_m = 0.001;
    f.bus.publish("dev", "move_ended", 1, json{{"channel", 0}});   // no stream: nothing at all
    auto first = f.api->handle("GET", "/api/events", "");
    auto second = f.api->handle("GET", "/api/events?device=dev", "");
    std::string a, b;
    auto stop_a = first.stream([&](control::StreamChunk s) { a.append(*s); });
    auto stop_b = second.stream([&](control::StreamChunk s) { b.append(*s); });
    f.stage.position_m = 0.004;
    f.bus.publish("dev", "move_ended", 2, json{{"channel", 0}});
    for (const auto* text : {&a, &b}) {
        const auto ended = text->find("event: move_ended\n");
        const auto frames = text->find("event: frames\n");
        REQUIRE(ended != std::string::npos);
        REQUIRE(frames != std::string::npos);
        CHECK(ended < frames);
        CHECK(Fixture::frames_events(*text)[0]["frames"][0]["joint"]["position"] == 4.0);
    }
    stop_a();
    stop_b();
}

TEST_CASE("The frames event: a new stream compares with the poses when it started, not a stale publication",
          "[control]")
{
    Fixture f;
    f.make_api(true);
    auto first = f.api->handle("GET", "/api/events?type=frames", "");
    std::string a;
    auto stop_a = first.stream([&](control::StreamChunk s) { a.append(*s); });
    f.stage.position_m = 0.002;
    f.bus.publish("dev", "move_ended", 1, json{{"channel", 0}});
    REQUIRE(Fixture::frames_events(a).size() == 1);   // published: x at 2 mm
    stop_a();

    // While no one listens the stage goes back to 0: nothing is published.
    f.stage.position_m = 0;
    f.bus.publish("dev", "move_ended", 2, json{{"channel", 0}});

    // A new stream; the stage moves to 2 mm again: a change from where it was when the stream began.
    auto second = f.api->handle("GET", "/api/events?type=frames", "");
    std::string b;
    auto stop_b = second.stream([&](control::StreamChunk s) { b.append(*s); });
    f.stage.position_m = 0.002;
    f.bus.publish("dev", "move_ended", 3, json{{"channel", 0}});
    const auto events = Fixture::frames_events(b);
    REQUIRE(events.size() == 1);
    CHECK(events[0]["frames"][0]["name"] == "x");
    CHECK(events[0]["frames"][0]["joint"]["position"] == 2.0);
    stop_b();
}

TEST_CASE("joint_axes: each binding's device and channel, found by the world body the channel drives", "[control]")
{
    Clock clock{1000};
    Mounts mcs(clock, {"mcs/0", "mcs/1"});
    Mounts apt(clock, {"apt/1", ""});   // an APT bay's body key counts from 1; bay 1 moves nothing
    const std::vector<ControlledDevice> devices{
        ControlledDevice{DeviceEndpoints{"mcs", "mcs", "MCS-2D", "", "", "1.2.44", ""}, &mcs, nullptr},
        ControlledDevice{DeviceEndpoints{"apt", "apt", "BBD202", "", "", "issue-3", ""}, &apt, nullptr},
        ControlledDevice{DeviceEndpoints{"bare", "mcs", "MCS-1D", "", "", "1.2.44", ""}, nullptr, nullptr}};
    std::vector<JointBinding> bindings(4);
    bindings[1].body_key = "apt/1";
    bindings[2].body_key = "mcs/1";
    bindings[3].body_key = "ghost/0";
    const auto axes = control::joint_axes(bindings, devices);
    REQUIRE(axes.size() == 4);
    CHECK_FALSE(axes[0]);
    REQUIRE(axes[1]);
    CHECK((axes[1]->device == "apt" && axes[1]->channel == 0));
    REQUIRE(axes[2]);
    CHECK((axes[2]->device == "mcs" && axes[2]->channel == 1));
    CHECK_FALSE(axes[3]);
}

} // namespace test_control_frames
