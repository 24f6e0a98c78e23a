#include "emulator/mcs/config.hpp"

#include "emulator/core/config_reader.hpp"
#include "emulator/mcs/sensor_types.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <limits>
#include <string>
#include <string_view>

namespace rigsim::mcs {
namespace {

using nlohmann::json;

constexpr std::size_t kMaxChannels = 255;
constexpr std::int64_t kTravelLimitNm = 2'000'000'000;
constexpr std::int64_t kMaxSystemId = std::numeric_limits<std::uint32_t>::max();

constexpr std::array<std::string_view, 3> kMcsKeys{"system_id", "interface_version", "channels"};
constexpr std::array<std::string_view, 17> kChannelKeys{
    "kind", "gripper_contact_cv", "gripper_stiffness_dun_per_cv", "sensor_type", "travel_nm", "start_position_nm", "max_speed_nm_per_s",
    "closed_loop_speed_nm_per_s", "closed_loop_acceleration_um_per_s2", "travel_udeg",
    "reference_position", "coded_mark_spacing", "calibration_ms", "step_width_nm",
    "step_jitter_percent", "scan_range_nm", "drift_nm_per_s"};

/// A channel integer whose range does not depend on other keys.
struct ChannelIntKey {
    std::string_view key;
    std::int64_t min;
    std::int64_t max;
    std::int64_t McsChannelConfig::*member;
};

constexpr std::array<ChannelIntKey, 12> kChannelIntKeys{{
    {"gripper_contact_cv", 0, 22'500, &McsChannelConfig::gripper_contact_cv},
    {"gripper_stiffness_dun_per_cv", 1, 100'000, &McsChannelConfig::gripper_stiffness_dun_per_cv},
    {"step_width_nm", 1, 100'000, &McsChannelConfig::step_width_nm},
    {"step_jitter_percent", 0, 50, &McsChannelConfig::step_jitter_percent},
    {"scan_range_nm", 1, 1'000'000, &McsChannelConfig::scan_range_nm},
    {"drift_nm_per_s", -1'000'000, 1'000'000, &McsChannelConfig::drift_nm_per_s},
    {"reference_position", -2'000'000'000, 2'000'000'000, &McsChannelConfig::reference_position},
    {"coded_mark_spacing", 1'000, 100'000'000, &McsChannelConfig::coded_mark_spacing},
    {"calibration_ms", 0, 60'000, &McsChannelConfig::calibration_ms},
    {"max_speed_nm_per_s", 1, 100'000'000, &McsChannelConfig::max_speed_nm_per_s},
    {"closed_loop_speed_nm_per_s", 0, 100'000'000, &McsChannelConfig::closed_loop_speed_nm_per_s},
    {"closed_loop_acceleration_um_per_s2", 0, 10'000'000,
     &McsChannelConfig::closed_loop_acceleration_um_per_s2},
}};

/// Validates one "mcs" object, one object kind per function.
class McsLoader {
public:
    explicit McsLoader(const ConfigReader& reader) : r_(reader) {}

    McsConfig load_mcs(const json& v, const std::string& pointer) const
    {
        McsConfig mcs;
        r_.check_keys(v, pointer, kMcsKeys);
        if (const auto* id = r_.find(v, "system_id"))
            mcs.system_id = static_cast<std::uint32_t>(
                r_.get_int(*id, pointer_to(pointer, "system_id"), 0, kMaxSystemId));
        if (const auto* iv = r_.find(v, "interface_version"))
            mcs.interface_version = load_interface_version(*iv, pointer_to(pointer, "interface_version"));
        const auto channels_pointer = pointer_to(pointer, "channels");
        const auto& channels = r_.require(v, pointer, "channels");
        const std::string expected =
            "expected an array of 1.." + std::to_string(kMaxChannels) + " channels, got ";
        if (!channels.is_array())
            r_.fail(channels_pointer, expected + describe(channels));
        if (channels.empty() || channels.size() > kMaxChannels)
            r_.fail(channels_pointer, expected + std::to_string(channels.size()) + " channels");
        for (std::size_t i = 0; i < channels.size(); ++i)
            mcs.channels.push_back(load_channel(channels[i], pointer_to(channels_pointer, i)));
        return mcs;
    }

private:
    /// "<high>.<low>.<update>", each 0..65535: the GIV answer (MCS manual 3.1).
    McsInterfaceVersion load_interface_version(const json& v, const std::string& pointer) const
    {
        const std::string expected = "expected a version \"<high>.<low>.<update>\" of three numbers 0..65535, got ";
        if (!v.is_string())
            r_.fail(pointer, expected + describe(v));
        const auto text = v.get<std::string>();
        std::int64_t parts[3] = {0, 0, 0};
        std::size_t part = 0, digits = 0;
        for (const char c : text) {
            if (c == '.' && digits > 0 && part < 2) {
                ++part;
                digits = 0;
            } else if (c >= '0' && c <= '9' && digits < 5) {
                parts[part] = parts[part] * 10 + (c - '0');
                ++digits;
            } else {
                r_.fail(pointer, expected + describe(v));
            }
        }
        if (part != 2 || digits == 0 || parts[0] > 65535 || parts[1] > 65535 || parts[2] > 65535)
            r_.fail(pointer, expected + describe(v));
        return {parts[0], parts[1], parts[2]};
    }

    /// "travel_nm" or "travel_udeg": [min, max] into `min`, `max`.
    void load_travel(const json& t, const std::string& travel_pointer, std::int64_t& min, std::int64_t& max) const
    {
        if (!t.is_array() || t.size() != 2)
            r_.fail(travel_pointer, "expected [min, max], two integers, got " + describe(t));
        min = r_.get_int(t[0], pointer_to(travel_pointer, 0), -kTravelLimitNm, kTravelLimitNm);
        max = r_.get_int(t[1], pointer_to(travel_pointer, 1), -kTravelLimitNm, kTravelLimitNm);
        if (min >= max)
            r_.fail(travel_pointer, "expected min < max, got " + dump(t));
    }

    McsChannelConfig load_channel(const json& v, const std::string& pointer) const
    {
        McsChannelConfig c;
        r_.check_keys(v, pointer, kChannelKeys);
        if (const auto* k = r_.find(v, "kind")) {
            const auto kind_pointer = pointer_to(pointer, "kind");
            if (!k->is_string() || (k->get<std::string>() != "positioner" && k->get<std::string>() != "end_effector"))
                r_.fail(kind_pointer, "expected \"positioner\" or \"end_effector\", got " + describe(*k));
            c.kind = k->get<std::string>();
        }
        if (const auto* t = r_.find(v, "sensor_type")) {
            const auto type_pointer = pointer_to(pointer, "sensor_type");
            const std::string symbols(sensor_type_symbols());
            if (!t->is_string())
                r_.fail(type_pointer, "expected a string, got " + describe(*t));
            c.sensor_type = t->get<std::string>();
            if (c.sensor_type != "none" && !sensor_type_by_symbol(c.sensor_type))
                r_.fail(type_pointer, "unknown sensor type " + quote(c.sensor_type) +
                                          " (expected one of " + symbols + ", or \"none\")");
        }
        if (const auto* t = r_.find(v, "travel_nm"))
            load_travel(*t, pointer_to(pointer, "travel_nm"), c.travel_min_nm, c.travel_max_nm);
        if (const auto* t = r_.find(v, "travel_udeg"))
            load_travel(*t, pointer_to(pointer, "travel_udeg"), c.travel_min_udeg, c.travel_max_udeg);
        if (const auto* p = r_.find(v, "start_position_nm"))
            c.start_position_nm = r_.get_int(*p, pointer_to(pointer, "start_position_nm"),
                                             c.travel_min_nm, c.travel_max_nm, " (within travel_nm)");
        for (const auto& k : kChannelIntKeys)
            if (const auto* n = r_.find(v, k.key))
                c.*k.member = r_.get_int(*n, pointer_to(pointer, k.key), k.min, k.max);
        return c;
    }

    const ConfigReader& r_;
};

} // namespace

void load_device_section(const ConfigReader& reader, const json& device, const std::string& pointer,
                         DeviceConfig& config)
{
    if (config.model.empty())
        config.model = kDefaultMcsModel;
    const auto mcs_pointer = pointer_to(pointer, "mcs");
    const auto& section = reader.require(device, pointer, "mcs");
    auto mcs = McsLoader{reader}.load_mcs(section, mcs_pointer);
    // Without "firmware" the device follows the manual, whatever GIV answers: the interface
    // version keeps the meaning it had before generations existed (the GIV answer only). With
    // "firmware", an interface version given beside it must belong to that generation
    // (docs/config.md, "firmware" and "interface_version").
    const bool version_given = reader.find(section, "interface_version") != nullptr;
    const auto& iv = mcs.interface_version;
    const Firmware of_version = firmware_of_version({iv.high, iv.low, iv.update});
    if (config.firmware.empty()) {
        mcs.firmware = Firmware::V1_2_44;
        config.firmware = firmware_name(mcs.firmware);
    } else {
        const auto firmware = find_firmware(config.firmware);
        if (!firmware)
            reader.fail(pointer_to(pointer, "firmware"), "unknown MCS firmware generation " + quote(config.firmware) +
                                                             " (expected " + std::string(firmware_names()) + ")");
        mcs.firmware = *firmware;
        if (version_given && of_version != mcs.firmware)
            reader.fail(pointer_to(mcs_pointer, "interface_version"),
                        "interface version " + quote(section["interface_version"].get<std::string>()) +
                            " belongs to firmware generation " + quote(std::string(firmware_name(of_version))) +
                            " (the newest whose version is not above it), but \"firmware\" is " +
                            quote(config.firmware));
    }
    if (!version_given) {
        const auto v = firmware_version(mcs.firmware);
        mcs.interface_version = {v[0], v[1], v[2]};
    }
    config.section = std::move(mcs);
}

} // namespace rigsim::mcs
