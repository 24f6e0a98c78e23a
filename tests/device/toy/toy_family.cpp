#include "toy_family.hpp"

#include "emulator/core/config_reader.hpp"
#include "models/world.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>

namespace rigsim::toy {

namespace {

constexpr double kCountsPerMm = 1000;   // the stage counts µm
constexpr double kSpeed = 10 * kCountsPerMm;          // 10 mm/s
constexpr double kAcceleration = 100 * kCountsPerMm;  // 100 mm/s²
constexpr std::size_t kMaxLine = 64;

models::AxisConfig axis_config(const ToyConfig& c)
{
    models::AxisConfig a;
    a.travel_max_counts = c.travel_mm * kCountsPerMm;
    a.start_position_counts = a.travel_max_counts / 2;
    a.si_per_count = 1e-3 / kCountsPerMm;
    return a;
}

/// Splits the bytes at '\n' (a line over kMaxLine is dropped) and answers each line.
class ToySession : public Session {
public:
    ToySession(ToyDevice& device, SendFn send, std::string peer)
        : device_(device), send_(std::move(send)), peer_(std::move(peer))
    {
    }
    void receive(std::string_view bytes) override
    {
        for (const char c : bytes) {
            if (c != '\n') {
                if (line_.size() < kMaxLine)
                    line_ += c;
                continue;
            }
            device_.record(true, peer_, line_ + "\n");
            const std::string answer = device_.handle(line_) + "\n";
            device_.record(false, peer_, answer);
            send_(answer);
            line_.clear();
        }
    }

private:
    ToyDevice& device_;
    SendFn send_;
    std::string peer_;
    std::string line_;
};

void load(const ConfigReader& reader, const nlohmann::json& device, const std::string& pointer, DeviceConfig& config)
{
    const auto toy_pointer = pointer_to(pointer, "toy");
    const auto& section = reader.require(device, pointer, "toy");
    reader.check_keys(section, toy_pointer, std::array<std::string_view, 1>{"travel_mm"});
    ToyConfig toy;
    if (const auto* travel = ConfigReader::find(section, "travel_mm"))
        toy.travel_mm = static_cast<double>(reader.get_int(*travel, pointer_to(toy_pointer, "travel_mm"), 1, 1000));
    if (config.model.empty())
        config.model = "TOY-1";
    config.firmware = "1";
    config.section = toy;
}

} // namespace

ToyDevice::ToyDevice(const DeviceConfig& config, const DeviceContext& context)
    : clock_(context.world.clock()),
      axis_(context.world.emplace<models::Axis>(config.name + "/0", context.world.clock(),
                                                axis_config(section_of<ToyConfig>(config)))),
      log_(config.name, context.world.clock().tick_hz(), context.events, context.log)
{
    axis_.set_listener([this](models::AxisEvent e) { stalled_ = e == models::AxisEvent::Stalled; });
}

ToyDevice::~ToyDevice()
{
    axis_.set_listener({});   // the world outlives its devices
}

std::unique_ptr<Session> ToyDevice::open_session(SendFn send, std::string peer)
{
    return std::make_unique<ToySession>(*this, std::move(send), std::move(peer));
}

void ToyDevice::record(bool inbound, std::string_view peer, std::string_view bytes)
{
    log_.add(clock_.now(), inbound, peer, bytes);
}

std::string ToyDevice::handle(const std::string& line)
{
    char text[32];
    if (line == "POS?") {
        std::snprintf(text, sizeof text, "POS %.3f", axis_.position_counts() / kCountsPerMm);
        return text;
    }
    if (line == "STA?")
        return axis_.moving() ? "STA 1" : stalled_ ? "STA 2" : "STA 0";
    if (line == "STP") {
        axis_.stop_immediately();
        return "OK";
    }
    double mm = 0;
    char end = 0;
    if (std::sscanf(line.c_str(), "MOV %lf%c", &mm, &end) != 1 || !std::isfinite(mm))
        return "ERR 0";   // not a command
    if (mm < 0 || mm * kCountsPerMm > axis_.travel_max_counts())
        return "ERR 1";   // outside the travel
    stalled_ = false;
    axis_.move_to(mm * kCountsPerMm, kSpeed, kAcceleration);
    return "OK";
}

void ToyDevice::describe(nlohmann::json& out) const
{
    out["channels"] = nlohmann::json::array(
        {{{"index", 0}, {"kind", "linear"}, {"moving", axis_.moving()}, {"status", stalled_ ? 2 : axis_.moving() ? 1 : 0}}});
}

Refused ToyDevice::patch_channel(std::size_t index, const nlohmann::json& body)
{
    if (index != 0)
        return Refusal{404, "no channel " + std::to_string(index)};
    if (!body.empty())
        return Refusal{400, "the toy takes no set-up"};
    return std::nullopt;
}

Refused ToyDevice::axis_body_key(std::size_t index, std::string& out) const
{
    if (index != 0)
        return Refusal{404, "no channel " + std::to_string(index)};
    out = axis_.key();
    return std::nullopt;
}

Refused ToyDevice::add_fault(const DeviceFault&, bool*)
{
    return Refusal{400, "\"kind\": the toy has no reference to lose"};
}

void ToyDevice::power_cycle(const PowerCycle&)
{
    axis_.stop_immediately();
    stalled_ = false;
}

Family toy_family()
{
    return Family{"toy", "a toy device", &load, [](const DeviceConfig& config, const DeviceContext& context) {
                      return std::unique_ptr<Device>(std::make_unique<ToyDevice>(config, context));
                  }};
}

} // namespace rigsim::toy
