#include "emulator/core/rig_config.hpp"

#include "emulator/core/config_reader.hpp"
#include "emulator/core/family_registry.hpp"
#include "emulator/core/json_text.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace rigsim {
namespace {

using nlohmann::json;

/// A rig file larger than this is refused (the largest example is a few kB).
constexpr std::size_t kMaxConfigBytes = 4 << 20;
/// Longest model or firmware name (the longest the families know is 12 characters).
constexpr std::size_t kMaxLabelLength = 64;
/// Containers nested deeper than this are refused (a rig nests six deep; copying and printing a
/// value recurse).
constexpr std::size_t kMaxConfigDepth = 64;

// The keys each object may hold; anything else is an error. A device also holds the section
// of each family, under the family's name.
constexpr std::array<std::string_view, 5> kRigKeys{"tick_hz", "devices", "control", "clock", "kinematics"};
constexpr std::array<std::string_view, 1> kControlKeys{"port"};
constexpr std::array<std::string_view, 2> kClockKeys{"time_scale", "paused"};
constexpr std::array<std::string_view, 9> kDeviceKeys{"name",     "protocol", "model",           "firmware",
                                                      "tcp_port", "pty",      "faithful_timing", "link",
                                                      "rfc2217_port"};
constexpr std::array<std::string_view, 5> kLinkKeys{"latency_timer_ms", "packet_bytes", "usb_frame_us",
                                                    "processing_us", "tcp"};


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

/// Validates a parsed document into a RigConfig: the generic device fields here, each
/// device's section by its family.
class RigLoader : private ConfigReader {
public:
    RigLoader(std::string_view source, const FamilyRegistry& families)
        : ConfigReader(source), source_name_(source), families_(families),
          device_keys_(kDeviceKeys.begin(), kDeviceKeys.end())
    {
        for (const auto& f : families.all())
            device_keys_.push_back(f.name);
    }

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
        for (const auto& f : families_.all())
            if (f.validate_rig)
                f.validate_rig(*this, rig);
        if (const auto* c = find(root, "control")) {
            check_keys(*c, "/control", kControlKeys);
            ControlConfig control;
            control.port = static_cast<std::uint16_t>(get_int(require(*c, "/control", "port"), "/control/port", 0, 65535));
            if (control.port != 0)   // a device listening there would make the run fail to bind
                claim(ports_, std::to_string(control.port), "/control/port", "/control",
                      "port " + std::to_string(control.port));
            rig.control = control;
        }
        if (const auto* c = find(root, "clock"))
            rig.clock = load_clock(*c);
        if (const auto* k = find(root, "kinematics"))
            rig.kinematics = load_kinematics_config(*this, source_name_, *k, rig.devices);
        return rig;
    }

private:
    ClockStart load_clock(const json& c) const
    {
        check_keys(c, "/clock", kClockKeys);
        ClockStart clock;
        if (const auto* v = find(c, "time_scale")) {
            if (!v->is_number() || v->get<double>() < 0.001 || v->get<double>() > 1000)
                fail("/clock/time_scale", "expected a number 0.001..1000, got " + describe(*v));
            clock.time_scale = v->get<double>();
        }
        if (const auto* v = find(c, "paused")) {
            if (!v->is_boolean())
                fail("/clock/paused", "expected true or false, got " + describe(*v));
            clock.paused = v->get<bool>();
        }
        return clock;
    }

    DeviceConfig load_device(const json& v, const std::string& pointer)
    {
        DeviceConfig d;
        d.source = source_name_;
        d.pointer = pointer;
        check_keys(v, pointer, device_keys_.data(), device_keys_.size());

        const auto name_pointer = pointer_to(pointer, "name");
        d.name = load_name(require(v, pointer, "name"), name_pointer);
        claim(names_, d.name, name_pointer, pointer, "name " + quote(d.name));

        const auto& family = load_protocol(require(v, pointer, "protocol"), pointer_to(pointer, "protocol"));
        d.protocol = family.name;
        if (const auto* m = find(v, "model"))
            d.model = load_label(*m, pointer_to(pointer, "model"));
        if (const auto* f = find(v, "firmware"))
            d.firmware = load_label(*f, pointer_to(pointer, "firmware"));
        if (const auto* p = find(v, "tcp_port")) {
            const auto port_pointer = pointer_to(pointer, "tcp_port");
            d.tcp_port = static_cast<std::uint16_t>(get_int(*p, port_pointer, 0, 65535));
            if (d.tcp_port != 0)
                claim(ports_, std::to_string(d.tcp_port), port_pointer, pointer,
                      "port " + std::to_string(d.tcp_port));
        }
        if (const auto* p = find(v, "rfc2217_port")) {
            const auto port_pointer = pointer_to(pointer, "rfc2217_port");
            d.rfc2217_port = static_cast<std::uint16_t>(get_int(*p, port_pointer, 0, 65535));
            if (*d.rfc2217_port != 0)
                claim(ports_, std::to_string(*d.rfc2217_port), port_pointer, pointer,
                      "port " + std::to_string(*d.rfc2217_port));
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
        if (const auto* l = find(v, "link"))
            d.link = load_link(*l, pointer_to(pointer, "link"));
        for (const auto& other : families_.all())
            if (other.name != family.name && find(v, other.name))
                fail(pointer_to(pointer, other.name), "an " + quote(other.name) + " object belongs to " +
                                                          other.device_noun + ", not to protocol " + quote(family.name));
        family.load(*this, v, pointer, d);
        return d;
    }

    LinkModel load_link(const json& v, const std::string& pointer) const
    {
        if (!v.is_object())
            fail(pointer, "expected an object, got " + describe(v));
        check_keys(v, pointer, kLinkKeys);
        LinkModel link;
        const auto number = [&](const char* key, std::int64_t lo, std::int64_t hi, std::uint32_t& out) {
            if (const auto* n = find(v, key))
                out = static_cast<std::uint32_t>(get_int(*n, pointer_to(pointer, key), lo, hi));
        };
        number("latency_timer_ms", 1, 255, link.latency_timer_ms);
        number("packet_bytes", 1, 4096, link.packet_bytes);
        number("usb_frame_us", 125, 1000, link.usb_frame_us);
        number("processing_us", 0, 10'000'000, link.processing_us);
        if (const auto* t = find(v, "tcp")) {
            if (!t->is_boolean())
                fail(pointer_to(pointer, "tcp"), "expected true or false, got " + describe(*t));
            link.tcp = t->get<bool>();
        }
        return link;
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
        const bool ok = is_name(v);
        // The name is a file name in the pty directory: "." and ".." are that directory
        // and its parent.
        if (ok && (v == "." || v == ".."))
            fail(pointer, "expected a device name, got " + quote(v.get<std::string>()) +
                              " (\".\" and \"..\" name directories)");
        if (!ok)
            fail(pointer, "expected a name of 1.." + std::to_string(kMaxNameLength) +
                              " characters [A-Za-z0-9_.-], got " + describe(v));
        return v.get<std::string>();
    }

    /// A model or firmware name: printed in the endpoint list, the log and every answer of the
    /// control API, so short and printable.
    std::string load_label(const json& v, const std::string& pointer) const
    {
        const std::string_view expected = "a string of 1..64 printable ASCII characters";
        const auto& s = get_string(v, pointer, expected);
        const bool printable = std::all_of(s.begin(), s.end(), [](char c) { return c >= 0x20 && c < 0x7F; });
        if (s.size() > kMaxLabelLength || !printable)
            fail(pointer, "expected " + std::string(expected) + ", got " + describe(v));
        return s;
    }

    const Family& load_protocol(const json& v, const std::string& pointer) const
    {
        if (!v.is_string())
            fail(pointer, "expected a string, got " + describe(v));
        const auto& s = v.get_ref<const std::string&>();
        if (const auto* family = families_.find(s))
            return *family;
        fail(pointer, "unknown protocol " + quote(s) + " (expected " + families_.quoted_names() + ")");
    }

    std::string source_name_;   ///< for DeviceConfig::source
    const FamilyRegistry& families_;
    std::vector<std::string_view> device_keys_;  ///< generic keys, then one section per family
    std::map<std::string, std::string> names_;  ///< name -> pointer of the device using it
    std::map<std::string, std::string> ports_;  ///< non-zero tcp_port -> device pointer
    std::map<std::string, std::string> ptys_;   ///< explicit pty path -> device pointer
};

} // namespace

RigConfig parse_rig_config(std::string_view json_text, std::string_view source, const FamilyRegistry& families)
{
    json root;
    try {
        root = parse_json_text(json_text, JsonTextLimits{kMaxConfigDepth, true});
    } catch (const JsonTextError& e) {
        const std::string_view what = e.what();
        switch (e.kind) {
        case JsonTextError::Kind::Syntax: {
            const auto [line, column] = line_column(json_text, e.byte);
            const auto colon = what.find(": ");
            throw ConfigError(std::string(source) + ": line " + std::to_string(line) + ", column " +
                              std::to_string(column) + ": " +
                              std::string(colon == std::string_view::npos ? what : what.substr(colon + 2)));
        }
        case JsonTextError::Kind::NumberOverflow: {
            // A number the parser cannot hold (1e400): name where it is.
            const auto at = what.find("number overflow");
            fail(source, e.pointer,
                 at == std::string_view::npos ? std::string(what)
                                              : cut(std::string(what.substr(at))) + " (not a finite number)");
        }
        case JsonTextError::Kind::DuplicateKey:
        case JsonTextError::Kind::TooDeep:
            fail(source, e.pointer, std::string(what));
        }
        throw;
    }
    try {
        return RigLoader{source, families}.load(root);
    } catch (const json::exception& e) {
        throw ConfigError(std::string(source) + ": " + e.what());
    }
}

RigConfig load_rig_config(const std::string& path, const FamilyRegistry& families)
{
    // O_NONBLOCK: opening a pipe with no writer would wait for one for ever; the file kind is
    // checked before anything is read (reading a regular file ignores the flag).
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        throw ConfigError(path + ": cannot read: " + std::strerror(errno));
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file{::fdopen(fd, "rb"), &std::fclose};
    if (!file) {
        const int e = errno;
        ::close(fd);
        throw ConfigError(path + ": cannot read: " + std::strerror(e));
    }
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
    return parse_rig_config(text, path, families);
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
