#include "emulator/core/rig_config.hpp"

#include "emulator/apt/catalogue.hpp"
#include "emulator/mcs/sensor_types.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <sys/stat.h>

namespace rigsim {
namespace {

using nlohmann::json;

constexpr std::size_t kMaxNameLength = 64;
/// A rig file larger than this is refused (the largest example is a few kB).
constexpr std::size_t kMaxConfigBytes = 4 << 20;
constexpr std::size_t kMaxChannels = 255;
constexpr std::int64_t kTravelLimitNm = 2'000'000'000;
constexpr std::int64_t kMaxSystemId = std::numeric_limits<std::uint32_t>::max();

// The keys each object may hold; anything else is an error.
constexpr std::array<std::string_view, 2> kRigKeys{"tick_hz", "devices"};
constexpr std::array<std::string_view, 8> kDeviceKeys{
    "name", "protocol", "model", "tcp_port", "pty", "faithful_timing", "mcs", "apt"};
constexpr std::array<std::string_view, 3> kAptKeys{"stage", "bays", "serial_number"};
constexpr std::array<std::string_view, 3> kMcsKeys{"system_id", "interface_version", "channels"};
constexpr std::array<std::string_view, 16> kChannelKeys{
    "kind", "gripper_contact_cv", "gripper_stiffness_dun_per_cv", "sensor_type", "travel_nm", "start_position_nm", "max_speed_nm_per_s",
    "closed_loop_speed_nm_per_s", "closed_loop_acceleration_um_per_s2", "travel_udeg",
    "reference_position", "coded_mark_spacing", "calibration_ms", "step_width_nm",
    "step_jitter_percent", "scan_range_nm"};

/// A channel integer whose range does not depend on other keys.
struct ChannelIntKey {
    std::string_view key;
    std::int64_t min;
    std::int64_t max;
    std::int64_t McsChannelConfig::*member;
};

constexpr std::array<ChannelIntKey, 11> kChannelIntKeys{{
    {"gripper_contact_cv", 0, 22'500, &McsChannelConfig::gripper_contact_cv},
    {"gripper_stiffness_dun_per_cv", 1, 100'000, &McsChannelConfig::gripper_stiffness_dun_per_cv},
    {"step_width_nm", 1, 100'000, &McsChannelConfig::step_width_nm},
    {"step_jitter_percent", 0, 50, &McsChannelConfig::step_jitter_percent},
    {"scan_range_nm", 1, 1'000'000, &McsChannelConfig::scan_range_nm},
    {"reference_position", -2'000'000'000, 2'000'000'000, &McsChannelConfig::reference_position},
    {"coded_mark_spacing", 1'000, 100'000'000, &McsChannelConfig::coded_mark_spacing},
    {"calibration_ms", 0, 60'000, &McsChannelConfig::calibration_ms},
    {"max_speed_nm_per_s", 1, 100'000'000, &McsChannelConfig::max_speed_nm_per_s},
    {"closed_loop_speed_nm_per_s", 0, 100'000'000, &McsChannelConfig::closed_loop_speed_nm_per_s},
    {"closed_loop_acceleration_um_per_s2", 0, 10'000'000,
     &McsChannelConfig::closed_loop_acceleration_um_per_s2},
}};

/// [A-Za-z0-9_.-]: safe in a file name and a logger name.
bool is_name_char(char c)
{
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '.' || c == '-';
}

/// Echoed values and keys longer than this are cut in messages.
constexpr std::size_t kMaxEcho = 80;

/// `text` cut to kMaxEcho bytes (on a UTF-8 character boundary), marked as cut.
std::string cut(std::string text)
{
    if (text.size() <= kMaxEcho)
        return text;
    const auto total = text.size();
    std::size_t end = kMaxEcho;
    while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80)
        --end;
    text.resize(end);
    return text + "... (" + std::to_string(total) + " characters)";
}

/// What kind of file a non-regular st_mode is, for messages.
std::string file_kind(mode_t mode)
{
    if (S_ISDIR(mode))
        return "a directory";
    if (S_ISCHR(mode))
        return "a character device";
    if (S_ISBLK(mode))
        return "a block device";
    if (S_ISFIFO(mode))
        return "a pipe";
    if (S_ISSOCK(mode))
        return "a socket";
    return "not a regular file";
}

/// `value` as compact JSON, cut to a sane length; never throws on odd UTF-8.
std::string dump(const json& value)
{
    return cut(value.dump(-1, ' ', false, json::error_handler_t::replace));
}

/// `s` as a JSON string literal (quoted, escaped).
std::string quote(std::string_view s)
{
    return dump(json(std::string(s)));
}

/// A value for "got ..." in a message: scalars as JSON, containers by kind and size.
std::string describe(const json& value)
{
    if (value.is_array()) {
        if (value.empty())
            return "[]";
        return "an array of " + std::to_string(value.size()) +
               (value.size() == 1 ? " element" : " elements");
    }
    if (value.is_object())
        return value.empty() ? "{}" : "an object";
    return dump(value);
}

/// `parent` extended by an object key, escaped as RFC 6901 says (`~` -> `~0`, `/` -> `~1`).
std::string pointer_to(const std::string& parent, std::string_view key)
{
    std::string p = parent + '/';
    for (char c : key) {
        if (c == '~')
            p += "~0";
        else if (c == '/')
            p += "~1";
        else
            p += c;
    }
    return p;
}

/// `parent` extended by an array index.
std::string pointer_to(const std::string& parent, std::size_t index)
{
    return parent + '/' + std::to_string(index);
}

/// Throw the one error format: `<source>: <pointer>: <what>`; the root shows as "/".
[[noreturn]] void fail(std::string_view source, const std::string& pointer, const std::string& what)
{
    constexpr std::size_t kMaxPointer = 160;
    const auto shown = pointer.size() <= kMaxPointer ? pointer : pointer.substr(0, kMaxPointer) + "...";
    throw ConfigError(std::string(source) + ": " + (pointer.empty() ? "/" : shown) + ": " + what);
}

/// 1-based line and column of nlohmann's 1-based byte position in `text`.
std::pair<std::size_t, std::size_t> line_column(std::string_view text, std::size_t byte)
{
    const std::size_t offset = byte == 0 ? 0 : std::min(byte - 1, text.size());
    std::size_t line = 1;
    std::size_t column = 1;
    for (std::size_t i = 0; i < offset; ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    return {line, column};
}

/// nlohmann's explanation without its "[json.exception...] parse error at ...: " prefix.
std::string explanation(const json::parse_error& e)
{
    const std::string_view what = e.what();
    const auto colon = what.find(": ");
    return std::string(colon == std::string_view::npos ? what : what.substr(colon + 2));
}

/// Follows the parser through the document to reject duplicate keys (nlohmann would keep
/// the last value silently), naming the object that holds the duplicate.
class DuplicateKeyCheck {
public:
    explicit DuplicateKeyCheck(std::string_view source) : source_(source) {}

    /// A nlohmann parser callback event; always keeps the value.
    bool on_event(json::parse_event_t event, const json& parsed)
    {
        switch (event) {
        case json::parse_event_t::object_start:
            stack_.push_back(Frame{true, {}, {}, 0});
            break;
        case json::parse_event_t::array_start:
            stack_.push_back(Frame{false, {}, {}, 0});
            break;
        case json::parse_event_t::key: {
            auto& top = stack_.back();
            top.key = parsed.get<std::string>();
            if (!top.keys.insert(top.key).second)
                fail(source_, pointer(), "duplicate key " + quote(top.key));
            break;
        }
        case json::parse_event_t::object_end:
        case json::parse_event_t::array_end:
            stack_.pop_back();
            next_element();
            break;
        case json::parse_event_t::value:
            next_element();
            break;
        }
        return true;
    }

    struct Frame {
        bool is_object;
        std::set<std::string> keys;
        std::string key;          ///< current key (objects)
        std::size_t index;        ///< current index (arrays)
    };

    /// A value ended: inside an array, the next one has the next index.
    void next_element()
    {
        if (!stack_.empty() && !stack_.back().is_object)
            ++stack_.back().index;
    }

    /// The pointer of the value being parsed: inside the innermost open container, the
    /// value of its current key or index (for errors the parser raises on a value).
    std::string value_pointer() const
    {
        if (stack_.empty())
            return {};
        const auto& top = stack_.back();
        return top.is_object ? pointer_to(pointer(), top.key) : pointer_to(pointer(), top.index);
    }

private:
    /// The pointer of the innermost open container.
    std::string pointer() const
    {
        std::string p;
        for (std::size_t i = 0; i + 1 < stack_.size(); ++i)
            p = stack_[i].is_object ? pointer_to(p, stack_[i].key) : pointer_to(p, stack_[i].index);
        return p;
    }

    std::string_view source_;
    std::vector<Frame> stack_;
};

/// Validates a parsed document into a RigConfig, one object kind per function.
class RigLoader {
public:
    explicit RigLoader(std::string_view source) : source_(source) {}

    RigConfig load(const json& root)
    {
        RigConfig rig;
        check_keys(root, "", kRigKeys);
        if (const auto* v = find(root, "tick_hz"))
            rig.tick_hz = static_cast<std::uint32_t>(get_int(*v, "/tick_hz", 1, 100'000));
        const auto& devices = require(root, "", "devices");
        if (!devices.is_array())
            fail("/devices", "expected a non-empty array, got " + describe(devices));
        if (devices.empty())
            fail("/devices", "expected a non-empty array");
        for (std::size_t i = 0; i < devices.size(); ++i)
            rig.devices.push_back(load_device(devices[i], pointer_to("/devices", i)));
        return rig;
    }

private:
    [[noreturn]] void fail(const std::string& pointer, const std::string& what) const
    {
        rigsim::fail(source_, pointer, what);
    }

    /// `value` must be an object holding no key outside `allowed`.
    template <std::size_t N>
    void check_keys(const json& value, const std::string& pointer,
                    const std::array<std::string_view, N>& allowed) const
    {
        if (!value.is_object())
            fail(pointer, "expected an object, got " + describe(value));
        for (const auto& item : value.items()) {
            bool known = false;
            for (auto key : allowed)
                known = known || item.key() == key;
            if (known)
                continue;
            std::string list;
            for (auto key : allowed)
                list += (list.empty() ? "" : ", ") + std::string(key);
            fail(pointer, "unknown key " + quote(item.key()) + " (allowed: " + list + ")");
        }
    }

    /// The value of an optional key, or nullptr.
    static const json* find(const json& object, std::string_view key)
    {
        const auto it = object.find(std::string(key));
        return it == object.end() ? nullptr : &*it;
    }

    /// The value of a required key; the error names the missing key's pointer.
    const json& require(const json& object, const std::string& pointer, std::string_view key) const
    {
        const auto* v = find(object, key);
        if (!v)
            fail(pointer_to(pointer, key), "required key missing");
        return *v;
    }

    /// An integer in min..max; floats and booleans are type errors.
    std::int64_t get_int(const json& v, const std::string& pointer, std::int64_t min,
                         std::int64_t max, std::string_view note = {}) const
    {
        bool ok = false;
        std::int64_t n = 0;
        if (v.is_number_unsigned()) {
            // nlohmann reads every non-negative integer as unsigned.
            const auto u = v.get<std::uint64_t>();
            n = static_cast<std::int64_t>(u);
            ok = max >= 0 && u <= static_cast<std::uint64_t>(max) && n >= min;
        } else if (v.is_number_integer()) {
            n = v.get<std::int64_t>();
            ok = n >= min && n <= max;
        }
        if (!ok)
            fail(pointer, "expected an integer " + std::to_string(min) + ".." +
                              std::to_string(max) + std::string(note) + ", got " + describe(v));
        return n;
    }

    /// A non-empty string; `expected` completes "expected ..." in the error.
    const std::string& get_string(const json& v, const std::string& pointer,
                                  std::string_view expected = "a non-empty string") const
    {
        if (!v.is_string() || v.get_ref<const std::string&>().empty())
            fail(pointer, "expected " + std::string(expected) + ", got " + describe(v));
        return v.get_ref<const std::string&>();
    }

    DeviceConfig load_device(const json& v, const std::string& pointer)
    {
        DeviceConfig d;
        check_keys(v, pointer, kDeviceKeys);

        const auto name_pointer = pointer_to(pointer, "name");
        d.name = load_name(require(v, pointer, "name"), name_pointer);
        claim(names_, d.name, name_pointer, pointer, "name " + quote(d.name));

        d.protocol =
            load_protocol(require(v, pointer, "protocol"), pointer_to(pointer, "protocol"));
        d.model = DeviceConfig{}.model;
        if (const auto* m = find(v, "model"))
            d.model = get_string(*m, pointer_to(pointer, "model"));
        if (const auto* p = find(v, "tcp_port")) {
            const auto port_pointer = pointer_to(pointer, "tcp_port");
            d.tcp_port = static_cast<std::uint16_t>(get_int(*p, port_pointer, 0, 65535));
            if (d.tcp_port != 0)
                claim(ports_, std::to_string(d.tcp_port), port_pointer, pointer,
                      "port " + std::to_string(d.tcp_port));
        }
        if (const auto* p = find(v, "pty")) {
            const auto pty_pointer = pointer_to(pointer, "pty");
            const std::string_view expected = "an absolute path (starting with '/')";
            d.pty = get_string(*p, pty_pointer, expected);
            if (d.pty.front() != '/')
                fail(pty_pointer, "expected " + std::string(expected) + ", got " + quote(d.pty));
            claim(ptys_, d.pty, pty_pointer, pointer, "path " + quote(d.pty));
        }
        if (const auto* t = find(v, "faithful_timing")) {
            if (!t->is_boolean())
                fail(pointer_to(pointer, "faithful_timing"), "expected true or false, got " + describe(*t));
            d.faithful_timing = t->get<bool>();
        }
        if (d.protocol == Protocol::Mcs) {
            if (find(v, "apt"))
                fail(pointer_to(pointer, "apt"), "an \"apt\" object belongs to an APT device, not to protocol \"mcs\"");
            d.mcs = load_mcs(require(v, pointer, "mcs"), pointer_to(pointer, "mcs"));
            return d;
        }
        if (find(v, "mcs"))
            fail(pointer_to(pointer, "mcs"), "an \"mcs\" object belongs to an MCS device, not to protocol \"apt\"");
        d.apt = load_apt(v, pointer, d.model);
        return d;
    }

    /// The "apt" object of an APT device whose model is `model`.
    AptConfig load_apt(const json& device, const std::string& pointer, const std::string& model) const
    {
        AptConfig apt;
        const auto* controller = apt::find_controller(model);
        if (!find(device, "model") || !controller)
            fail(pointer_to(pointer, "model"), "expected an APT controller model (" + std::string(apt::controller_names())
                                                  + "), got " + (find(device, "model") ? quote(model) : std::string("nothing")));
        const auto apt_pointer = pointer_to(pointer, "apt");
        const auto& a = require(device, pointer, "apt");
        if (!a.is_object())
            fail(apt_pointer, "expected an object, got " + describe(a));
        check_keys(a, apt_pointer, kAptKeys);
        if (const auto* st = find(a, "stage"))
            apt.stage = load_apt_stage(*st, pointer_to(apt_pointer, "stage"), *controller, model);
        if (controller->rack) {
            if (find(a, "stage"))
                fail(pointer_to(apt_pointer, "stage"), "a rack controller names a stage per bay in \"bays\"");
            const auto bays_pointer = pointer_to(apt_pointer, "bays");
            const auto& bays = require(a, apt_pointer, "bays");
            const auto max = static_cast<std::size_t>(controller->max_bays);
            if (!bays.is_array() || bays.empty() || bays.size() > max)
                fail(bays_pointer, "expected an array of 1.." + std::to_string(max) + " stages, got " + describe(bays));
            for (std::size_t i = 0; i < bays.size(); ++i)
                apt.bays.push_back(load_apt_stage(bays[i], pointer_to(bays_pointer, i), *controller, model));
        } else if (find(a, "bays")) {
            fail(pointer_to(apt_pointer, "bays"), "only rack controllers have bays; " + model + " names one \"stage\"");
        } else if (!find(a, "stage") && apt::find_stage(apt.stage)->motor != controller->motor) {
            fail(pointer_to(apt_pointer, "stage"), "required key missing (the default " + apt.stage
                                                       + " is not a stage for a " + model + ")");
        }
        if (const auto* sn = find(a, "serial_number")) {
            const std::int64_t lo = controller->serial_prefix * 1'000'000LL;
            apt.serial_number = static_cast<std::uint32_t>(get_int(*sn, pointer_to(apt_pointer, "serial_number"), lo,
                                                                   lo + 999'999, " (the model's serial prefix)"));
        }
        return apt;
    }

    /// A stage of the catalogue whose motor suits `controller` (a single unit's "stage", or one of a rack's "bays").
    std::string load_apt_stage(const json& v, const std::string& pointer, const apt::ControllerModel& controller,
                               const std::string& model) const
    {
        auto stage = get_string(v, pointer);
        const auto* found = apt::find_stage(stage);
        if (!found)
            fail(pointer, "unknown stage " + quote(stage) + " (expected one of " + std::string(apt::stage_names()) + ")");
        if (found->motor != controller.motor)
            fail(pointer, "stage " + quote(stage) + " has another kind of motor than a " + model);
        return stage;
    }

    /// Record that device `owner` uses `value`; a second user is an error at `pointer`.
    void claim(std::map<std::string, std::string>& used, const std::string& value,
               const std::string& pointer, const std::string& owner, const std::string& what) const
    {
        const auto [it, inserted] = used.emplace(value, owner);
        if (!inserted)
            fail(pointer, what + " is already used by " + it->second);
    }

    std::string load_name(const json& v, const std::string& pointer) const
    {
        bool ok = v.is_string();
        if (ok) {
            const auto& s = v.get_ref<const std::string&>();
            ok = !s.empty() && s.size() <= kMaxNameLength;
            for (char c : s)
                ok = ok && is_name_char(c);
            // The name is a file name in the pty directory: "." and ".." are that directory
            // and its parent.
            if (s == "." || s == "..")
                fail(pointer, "expected a device name, got " + quote(s) + " (\".\" and \"..\" name directories)");
        }
        if (!ok)
            fail(pointer, "expected a name of 1.." + std::to_string(kMaxNameLength) +
                              " characters [A-Za-z0-9_.-], got " + describe(v));
        return v.get<std::string>();
    }

    Protocol load_protocol(const json& v, const std::string& pointer) const
    {
        if (!v.is_string())
            fail(pointer, "expected a string, got " + describe(v));
        const auto& s = v.get_ref<const std::string&>();
        if (s == "mcs")
            return Protocol::Mcs;
        if (s == "apt")
            return Protocol::Apt;
        fail(pointer, "unknown protocol " + quote(s) + " (expected \"mcs\" or \"apt\")");
    }

    McsConfig load_mcs(const json& v, const std::string& pointer) const
    {
        McsConfig mcs;
        check_keys(v, pointer, kMcsKeys);
        if (const auto* id = find(v, "system_id"))
            mcs.system_id = static_cast<std::uint32_t>(
                get_int(*id, pointer_to(pointer, "system_id"), 0, kMaxSystemId));
        if (const auto* iv = find(v, "interface_version"))
            mcs.interface_version = load_interface_version(*iv, pointer_to(pointer, "interface_version"));
        const auto channels_pointer = pointer_to(pointer, "channels");
        const auto& channels = require(v, pointer, "channels");
        const std::string expected =
            "expected an array of 1.." + std::to_string(kMaxChannels) + " channels, got ";
        if (!channels.is_array())
            fail(channels_pointer, expected + describe(channels));
        if (channels.empty() || channels.size() > kMaxChannels)
            fail(channels_pointer, expected + std::to_string(channels.size()) + " channels");
        for (std::size_t i = 0; i < channels.size(); ++i)
            mcs.channels.push_back(load_channel(channels[i], pointer_to(channels_pointer, i)));
        return mcs;
    }

    /// "<high>.<low>.<update>", each 0..65535: the GIV answer (MCS manual 3.1).
    McsInterfaceVersion load_interface_version(const json& v, const std::string& pointer) const
    {
        const std::string expected = "expected a version \"<high>.<low>.<update>\" of three numbers 0..65535, got ";
        if (!v.is_string())
            fail(pointer, expected + describe(v));
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
                fail(pointer, expected + describe(v));
            }
        }
        if (part != 2 || digits == 0 || parts[0] > 65535 || parts[1] > 65535 || parts[2] > 65535)
            fail(pointer, expected + describe(v));
        return {parts[0], parts[1], parts[2]};
    }

    McsChannelConfig load_channel(const json& v, const std::string& pointer) const
    {
        McsChannelConfig c;
        check_keys(v, pointer, kChannelKeys);
        if (const auto* k = find(v, "kind")) {
            const auto kind_pointer = pointer_to(pointer, "kind");
            if (!k->is_string() || (k->get<std::string>() != "positioner" && k->get<std::string>() != "end_effector"))
                fail(kind_pointer, "expected \"positioner\" or \"end_effector\", got " + describe(*k));
            c.kind = k->get<std::string>();
        }
        if (const auto* t = find(v, "sensor_type")) {
            const auto type_pointer = pointer_to(pointer, "sensor_type");
            const std::string symbols(mcs::sensor_type_symbols());
            if (!t->is_string())
                fail(type_pointer, "expected a string, got " + describe(*t));
            c.sensor_type = t->get<std::string>();
            if (c.sensor_type != "none" && !mcs::sensor_type_by_symbol(c.sensor_type))
                fail(type_pointer, "unknown sensor type " + quote(c.sensor_type) +
                                       " (expected one of " + symbols + ", or \"none\")");
        }
        if (const auto* t = find(v, "travel_nm")) {
            const auto travel_pointer = pointer_to(pointer, "travel_nm");
            if (!t->is_array() || t->size() != 2)
                fail(travel_pointer, "expected [min, max], two integers, got " + describe(*t));
            c.travel_min_nm =
                get_int((*t)[0], pointer_to(travel_pointer, 0), -kTravelLimitNm, kTravelLimitNm);
            c.travel_max_nm =
                get_int((*t)[1], pointer_to(travel_pointer, 1), -kTravelLimitNm, kTravelLimitNm);
            if (c.travel_min_nm >= c.travel_max_nm)
                fail(travel_pointer, "expected min < max, got " + dump(*t));
        }
        if (const auto* t = find(v, "travel_udeg")) {
            const auto travel_pointer = pointer_to(pointer, "travel_udeg");
            if (!t->is_array() || t->size() != 2)
                fail(travel_pointer, "expected [min, max], two integers, got " + describe(*t));
            c.travel_min_udeg =
                get_int((*t)[0], pointer_to(travel_pointer, 0), -kTravelLimitNm, kTravelLimitNm);
            c.travel_max_udeg =
                get_int((*t)[1], pointer_to(travel_pointer, 1), -kTravelLimitNm, kTravelLimitNm);
            if (c.travel_min_udeg >= c.travel_max_udeg)
                fail(travel_pointer, "expected min < max, got " + dump(*t));
        }
        if (const auto* p = find(v, "start_position_nm"))
            c.start_position_nm = get_int(*p, pointer_to(pointer, "start_position_nm"),
                                          c.travel_min_nm, c.travel_max_nm, " (within travel_nm)");
        for (const auto& k : kChannelIntKeys)
            if (const auto* n = find(v, k.key))
                c.*k.member = get_int(*n, pointer_to(pointer, k.key), k.min, k.max);
        return c;
    }

    std::string_view source_;
    std::map<std::string, std::string> names_;  ///< name -> pointer of the device using it
    std::map<std::string, std::string> ports_;  ///< non-zero tcp_port -> device pointer
    std::map<std::string, std::string> ptys_;   ///< explicit pty path -> device pointer
};

} // namespace

RigConfig parse_rig_config(std::string_view json_text, std::string_view source)
{
    DuplicateKeyCheck duplicates{source};
    try {
        const auto root = json::parse(
            json_text.begin(), json_text.end(),
            [&duplicates](int, json::parse_event_t event, json& parsed) {
                return duplicates.on_event(event, parsed);
            });
        return RigLoader{source}.load(root);
    } catch (const json::parse_error& e) {
        const auto [line, column] = line_column(json_text, e.byte);
        throw ConfigError(std::string(source) + ": line " + std::to_string(line) + ", column " +
                          std::to_string(column) + ": " + explanation(e));
    } catch (const json::out_of_range& e) {
        // A number the parser cannot hold (1e400): name where it is.
        const std::string_view what = e.what();
        const auto at = what.find("number overflow");
        fail(source, duplicates.value_pointer(),
             at == std::string_view::npos ? std::string(what) : cut(std::string(what.substr(at)))
                 + " (not a finite number)");
    } catch (const json::exception& e) {
        throw ConfigError(std::string(source) + ": " + e.what());
    }
}

RigConfig load_rig_config(const std::string& path)
{
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file{std::fopen(path.c_str(), "rb"),
                                                               &std::fclose};
    if (!file)
        throw ConfigError(path + ": cannot read: " + std::strerror(errno));
    struct stat st {};
    if (::fstat(::fileno(file.get()), &st) != 0)
        throw ConfigError(path + ": cannot read: " + std::strerror(errno));
    if (!S_ISREG(st.st_mode))
        throw ConfigError(path + ": not a regular file (" + file_kind(st.st_mode) + "): a rig is read from a JSON file");
    if (static_cast<std::uint64_t>(st.st_size) > kMaxConfigBytes)
        throw ConfigError(path + ": " + std::to_string(st.st_size) + " bytes: a rig file may hold at most "
                          + std::to_string(kMaxConfigBytes) + " bytes");
    std::string text;
    std::array<char, 4096> buffer;
    std::size_t n = 0;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), file.get())) > 0) {
        text.append(buffer.data(), n);
        if (text.size() > kMaxConfigBytes)   // it grew while being read
            throw ConfigError(path + ": more than " + std::to_string(kMaxConfigBytes)
                              + " bytes: a rig file may hold at most that");
    }
    if (std::ferror(file.get()))
        throw ConfigError(path + ": cannot read: " + std::strerror(errno));
    return parse_rig_config(text, path);
}

RigConfig default_rig_config()
{
    return parse_rig_config(default_rig_json(), "built-in default rig");
}

std::string_view to_string(Protocol p)
{
    switch (p) {
    case Protocol::Mcs:
        return "mcs";
    case Protocol::Apt:
        return "apt";
    }
    return "unknown";
}

} // namespace rigsim

namespace rigsim {

void resolve_pty_paths(RigConfig& config, const std::string& pty_dir, std::string_view source)
{
    std::map<std::string, std::size_t> used;   // resolved path -> device index
    for (std::size_t i = 0; i < config.devices.size(); ++i) {
        auto& d = config.devices[i];
        const bool defaulted = d.pty.empty();
        if (defaulted)
            d.pty = pty_dir + "/" + d.name;
        const auto [it, fresh] = used.emplace(d.pty, i);
        if (!fresh)
            throw ConfigError(std::string(source) + ": /devices/" + std::to_string(i) + "/"
                              + (defaulted ? "name" : "pty") + ": pty path \"" + d.pty
                              + "\" is already used by /devices/" + std::to_string(it->second)
                              + (defaulted ? " (this device's default is <pty-dir>/<name>)" : ""));
    }
}

} // namespace rigsim
