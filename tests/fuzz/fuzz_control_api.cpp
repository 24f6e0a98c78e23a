// Fuzz target: the control API's requests (emulator/control/: http_access, control_api and what
// its routes reach: fault_book, frame_book, body_state, json_reply, the devices' control
// surfaces, the links, the ticker's clock jobs, the event stream).
// Input: raw HTTP/1.1 requests, one after the other as on a keep-alive connection. Each is read by
// Boost.Beast's request parser with the control server's limits (emulator/control/http_server.cpp:
// 64 KiB body, 8 KiB headers), its head checked by the access rules as the server checks it, and
// an allowed request answered by ControlApi over a small rig: an MCS with three channels under a
// kinematic stack, a KDC101 turning the stack, a TPZ001 and its TSG001 strain gauge reader. The
// first request the parser refuses ends the input, as the server closes that connection.
// Deterministic: the ticker starts paused and is paused again after each request (a "resume" is
// answered, but no wall time ever reaches the clock); a clock job (step_ms, run_until_idle) runs
// its slices on the io_context until it answers.
#include "tests/fuzz/fuzz_rig.hpp"

#include "emulator/control/control_api.hpp"
#include "emulator/control/frame_book.hpp"
#include "emulator/control/http_access.hpp"
#include "emulator/control/http_server.hpp"
#include "emulator/daemon/rig.hpp"
#include "emulator/daemon/ticker.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/beast/http.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace {

namespace http = boost::beast::http;
using namespace rigsim;

constexpr std::string_view kRig = R"({"tick_hz":1000,"devices":[)"
    R"({"name":"xyz","protocol":"mcs","model":"MCS-3D","mcs":{"channels":[)"
    R"({"sensor_type":"S","travel_nm":[-10500000,10500000]},{"sensor_type":"S","travel_nm":[-10500000,10500000]},)"
    R"({"sensor_type":"SC","travel_nm":[-13000000,13000000],"coded_mark_spacing":2000000}]}},)"
    R"({"name":"rot","protocol":"apt","model":"KDC101","apt":{"stage":"PRM1-Z8"}},)"
    R"({"name":"tpz","protocol":"apt","model":"TPZ001","apt":{"actuator":{"travel_um":20,"max_voltage_v":75}}},)"
    R"({"name":"tsg","protocol":"apt","model":"TSG001","apt":{"gauge":{"mounted_on":"tpz","route":"hub_a","seed":1}}}],)"
    R"("kinematics":{"frames":[{"name":"table"},)"
    R"({"name":"rotation","parent":"table","offset":{"translation_mm":[0,0,30]},"axis":{"device":"rot","channel":0},)"
    R"("joint":{"type":"revolute","axis":[0,0,1],"point_mm":[0,0,0]},"box_mm":{"min":[-25,-25,-30],"max":[25,25,0]}},)"
    R"({"name":"x","parent":"rotation","offset":{"translation_mm":[0,0,10]},"axis":{"device":"xyz","channel":0},)"
    R"("joint":{"type":"prismatic","axis":[1,0,0]}},)"
    R"({"name":"y","parent":"x","offset":{"translation_mm":[0,0,10]},"axis":{"device":"xyz","channel":1},)"
    R"("joint":{"type":"prismatic","axis":[0,1,0]}},)"
    R"({"name":"z","parent":"y","offset":{"translation_mm":[0,0,10]},"axis":{"device":"xyz","channel":2},)"
    R"("joint":{"type":"prismatic","axis":[0,0,1]},"box_mm":{"min":[-11,-11,0],"max":[11,11,8]}}],)"
    R"("tools":[{"name":"sample","parent":"z","offset":{"translation_mm":[0,0,12]}}],"collisions":[["rotation","z"]]}})";

void check(bool ok)
{
    if (!ok)
        __builtin_trap();
}

/// A header's value, if the request has it (as http_server.cpp reads it).
std::optional<std::string_view> field(const http::request<http::string_body>& req, boost::beast::string_view name)
{
    const auto it = req.find(name);
    if (it == req.end())
        return std::nullopt;
    return std::string_view(it->value().data(), it->value().size());
}

/// What the access rules read of a parsed request (http_server.cpp's head_of).
control::RequestHead head_of(const http::request_parser<http::string_body>& parser)
{
    const auto& req = parser.get();
    control::RequestHead head;
    head.method = std::string_view(req.method_string().data(), req.method_string().size());
    head.version = req.version();
    head.host = field(req, "Host");
    head.origin = field(req, "Origin");
    head.sec_fetch_site = field(req, "Sec-Fetch-Site");
    head.content_type = field(req, "Content-Type");
    head.authorization = field(req, "Authorization");
    head.chunked = parser.chunked();
    head.has_body = parser.content_length().value_or(0) > 0;
    return head;
}

/// Feed `input` to `parser` until its head (`head_only`) or its whole request is parsed,
/// consuming what it used; false when the parser refuses the bytes or they end too soon.
bool put(http::request_parser<http::string_body>& parser, std::string_view& input, bool head_only)
{
    while (head_only ? !parser.is_header_done() : !parser.is_done()) {
        boost::beast::error_code ec;
        const auto used = parser.put(boost::asio::buffer(input.data(), input.size()), ec);
        check(used <= input.size());
        input.remove_prefix(used);
        if (ec == http::error::need_more && used > 0)
            continue;
        if (ec)
            return false;
        if (used == 0)
            return false;
    }
    return true;
}

/// The small rig, its ticker and its control API, built afresh for each input.
struct Harness {
    explicit Harness(const RigConfig& config) : rig(config)
    {
        std::vector<ControlledDevice> devices;
        for (std::size_t i = 0; i < config.devices.size(); ++i) {
            const auto& dc = config.devices[i];
            devices.push_back(ControlledDevice{DeviceEndpoints{dc.name, dc.protocol, dc.model, "127.0.0.1:1",
                                                               "/nonexistent/rigsim-fuzz/" + dc.name, dc.firmware, ""},
                                               rig.device(i).control(), &rig.link(i)});
        }
        control::FrameSource frames{rig.kinematics(), control::joint_axes(rig.bindings(), devices), {}};
        if (config.kinematics)
            frames.collision_pairs = config.kinematics->collisions;
        api.emplace(rig.clock(), ticker, [this] { return busy(); }, std::move(devices), &rig.events(), std::move(frames),
                    &rig.world());
    }
    ~Harness()
    {
        for (auto& stop : streams)   // the clients of the event streams go away
            stop();
        api.reset();
    }

    bool busy()
    {
        if (rig.world().next_change(rig.clock().now()) != kNever || rig.world().settling())
            return true;
        for (std::size_t i = 0; i < rig.size(); ++i)
            if (const auto* surface = rig.device(i).control(); surface && surface->busy())
                return true;
        return false;
    }

    /// One request, as the server hands it to the router; a later answer waited for.
    void answer(std::string_view method, std::string_view target, std::string_view body)
    {
        auto reply = api->handle(method, target, body);
        if (reply.later) {
            std::optional<control::HttpReply> answered;
            reply.later([&answered](control::HttpReply r) { answered = std::move(r); });
            io.restart();
            while (!answered && io.run_one() > 0) {
            }
            check(answered.has_value());
            reply = std::move(*answered);
        }
        if (reply.stream)
            streams.push_back(
                reply.stream([this](std::shared_ptr<const std::string> chunk) { streamed += chunk ? chunk->size() : 0; }));
        else
            check(reply.status >= 200 && reply.status < 600 && !reply.body.empty());
        if (!ticker.paused())
            ticker.pause();
    }

    boost::asio::io_context io;
    fuzz::FuzzRig rig;
    Ticker ticker{io, rig.clock(), 1.0, Ticker::Start::Paused};
    std::optional<control::ControlApi> api;
    std::vector<std::function<void()>> streams;
    std::size_t streamed = 0;
};

const RigConfig& rig_config()
{
    static const RigConfig config = parse_rig_config(kRig, "fuzz-control-rig.json");
    return config;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    fuzz::quiet_logging();
    std::string_view input(reinterpret_cast<const char*>(data), size);
    const control::HttpAccess open_access{{"rig.example"}, ""};
    const control::HttpAccess token_access{{}, "fuzz-token"};
    std::optional<Harness> harness;
    while (!input.empty()) {
        http::request_parser<http::string_body> parser;
        parser.body_limit(64 * 1024);
        parser.header_limit(8 * 1024);
        // The head first, then the access rules, then the body (the server's order).
        if (!put(parser, input, true))
            break;   // refused by the parser (400, 431) or unfinished: the server closes
        const auto head = head_of(parser);
        (void)control::check_access(token_access, head);
        if (head.host)
            (void)control::host_name_of(*head.host);
        if (control::check_access(open_access, head))
            break;   // refused (401, 403, 411, 415): the body is not read, the connection closes
        parser.eager(true);
        if (!put(parser, input, false))
            break;   // a body over the limit (413), malformed or unfinished
        if (!harness)
            harness.emplace(rig_config());
        const auto& req = parser.get();
        harness->answer(std::string_view(req.method_string().data(), req.method_string().size()),
                        std::string_view(req.target().data(), req.target().size()), req.body());
        if (!req.keep_alive())
            break;
    }
    return 0;
}
