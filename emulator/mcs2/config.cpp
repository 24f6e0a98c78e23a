#include "emulator/mcs2/config_loader.hpp"

#include "emulator/core/config_reader.hpp"
#include "emulator/mcs2/device.hpp"
#include "emulator/mcs2/positioner_types.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <string_view>

namespace rigsim::mcs2 {
namespace {

using nlohmann::json;

/// Three channels a driver module; rigsim takes up to eight modules.
constexpr std::size_t kMaxChannels = 24;
constexpr std::int64_t kTravel = 1'000'000'000'000'000;   // 1 m (pm) or 1000° (n°): far past any stage

constexpr std::array<std::string_view, 3> kKeys{"serial_number", "io_module", "channels"};
constexpr std::array<std::string_view, 13> kChannelKeys{
    "positioner_type", "travel", "start_position", "reference_position", "coded_mark_spacing", "max_speed",
    "step_width", "step_jitter_percent", "scan_range", "calibration_ms", "drift", "temperature_c", "sensor"};

struct IntKey {
    std::string_view key;
    std::int64_t min;
    std::int64_t max;
    std::int64_t ChannelConfig::*member;
};

constexpr std::array<IntKey, 10> kIntKeys{{
    {"reference_position", -kTravel, kTravel, &ChannelConfig::reference_position},
    {"coded_mark_spacing", 1'000'000, 100'000'000'000, &ChannelConfig::coded_mark_spacing},
    {"max_speed", 1, 100'000'000'000, &ChannelConfig::max_speed},
    {"step_width", 1, 100'000'000, &ChannelConfig::step_width},
    {"step_jitter_percent", 0, 50, &ChannelConfig::step_jitter_percent},
    {"scan_range", 1, 1'000'000'000, &ChannelConfig::scan_range},
    {"calibration_ms", 0, 60'000, &ChannelConfig::calibration_ms},
    {"drift", -1'000'000'000, 1'000'000'000, &ChannelConfig::drift},
    {"temperature_c", -40, 125, &ChannelConfig::temperature_c},
    {"start_position", -kTravel, kTravel, &ChannelConfig::start_position},
}};

ChannelConfig load_channel(const ConfigReader& r, const json& v, const std::string& pointer)
{
    ChannelConfig c;
    r.check_keys(v, pointer, kChannelKeys);
    if (const auto* t = r.find(v, "positioner_type")) {
        const auto p = pointer_to(pointer, "positioner_type");
        c.positioner_type = static_cast<std::int32_t>(r.get_int(*t, p, 0, 1000));
        if (!positioner_type(c.positioner_type))
            r.fail(p, "unknown positioner type " + std::to_string(c.positioner_type) + " (expected one of " +
                          std::string(positioner_type_codes()) + ")");
    }
    if (const auto* t = r.find(v, "travel")) {
        const auto p = pointer_to(pointer, "travel");
        if (!t->is_array() || t->size() != 2)
            r.fail(p, "expected [min, max], two integers (pm, or n° on a rotary stage), got " + describe(*t));
        const auto lo = r.get_int((*t)[0], pointer_to(p, 0), -kTravel, kTravel);
        const auto hi = r.get_int((*t)[1], pointer_to(p, 1), -kTravel, kTravel);
        if (lo >= hi)
            r.fail(p, "expected min < max, got " + t->dump());
        c.travel_min = lo;
        c.travel_max = hi;
    }
    for (const auto& k : kIntKeys)
        if (const auto* n = r.find(v, k.key))
            c.*k.member = r.get_int(*n, pointer_to(pointer, k.key), k.min, k.max);
    if (c.travel_min && (c.start_position < *c.travel_min || c.start_position > *c.travel_max))
        r.fail(pointer_to(pointer, "start_position"), "expected a position within \"travel\", got " +
                                                          std::to_string(c.start_position));
    if (const auto* s = r.find(v, "sensor")) {
        if (!s->is_boolean())
            r.fail(pointer_to(pointer, "sensor"), "expected true or false, got " + describe(*s));
        c.sensor = s->get<bool>();
    }
    return c;
}

} // namespace

void load_device_section(const ConfigReader& reader, const json& device, const std::string& pointer,
                         DeviceConfig& config)
{
    if (config.model.empty())
        config.model = kDefaultModel;
    Config out;
    if (config.firmware.empty() || config.firmware == "current") {
        out.firmware = Firmware::Current;
        config.firmware = "current";
    } else if (config.firmware == "1.0.6") {
        out.firmware = Firmware::Guide106;
    } else {
        reader.fail(pointer_to(pointer, "firmware"), "unknown MCS2 firmware generation " + quote(config.firmware) +
                                                         " (expected \"1.0.6\" or \"current\")");
    }
    const auto section_pointer = pointer_to(pointer, "mcs2");
    const auto& v = reader.require(device, pointer, "mcs2");
    reader.check_keys(v, section_pointer, kKeys);
    if (const auto* s = reader.find(v, "serial_number")) {
        const auto p = pointer_to(section_pointer, "serial_number");
        if (!s->is_string() || s->get<std::string>().empty() || s->get<std::string>().size() > 32)
            reader.fail(p, "expected a string of 1..32 characters (\"MCS2-00001234\"), got " + describe(*s));
        for (const char ch : s->get<std::string>())
            if (ch < 0x20 || ch > 0x7e || ch == '"')
                reader.fail(p, "expected printable ASCII without quotes, got " + s->dump());
        out.serial_number = s->get<std::string>();
    }
    if (const auto* io = reader.find(v, "io_module")) {
        if (!io->is_boolean())
            reader.fail(pointer_to(section_pointer, "io_module"), "expected true or false, got " + describe(*io));
        out.io_module = io->get<bool>();
    }
    const auto channels_pointer = pointer_to(section_pointer, "channels");
    const auto& channels = reader.require(v, section_pointer, "channels");
    const std::string expected = "expected an array of 1.." + std::to_string(kMaxChannels) + " channels, got ";
    if (!channels.is_array())
        reader.fail(channels_pointer, expected + describe(channels));
    if (channels.empty() || channels.size() > kMaxChannels)
        reader.fail(channels_pointer, expected + std::to_string(channels.size()) + " channels");
    for (std::size_t i = 0; i < channels.size(); ++i)
        out.channels.push_back(load_channel(reader, channels[i], pointer_to(channels_pointer, i)));
    config.section = std::move(out);
}

} // namespace rigsim::mcs2
