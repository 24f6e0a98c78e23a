#pragma once
// The rig: every device and its endpoints, as read from JSON. Core knows the generic device
// fields only; each protocol family (emulator/mcs/config, emulator/apt/config) reads its own
// section of a device, found through the family registry (emulator/core/family_registry.hpp).
// The loader rejects unknown keys, wrong types, out-of-range values and collisions, naming
// the JSON pointer (docs/config.md).

#include "emulator/core/kinematics_config.hpp"

#include <any>
#include <optional>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace rigsim {

class FamilyRegistry;

/// The timing of the link between a unit and its host ("link" in the rig JSON; docs/config.md
/// "The link model"): a USB-serial chip's latency timer, packet and frame, and the unit's
/// processing time per answer.
struct LinkModel {
    std::uint32_t latency_timer_ms = 16;   ///< 1..255 (FTDI; Linux's default since 4.10)
    std::uint32_t packet_bytes = 62;       ///< data bytes of a full USB packet (64 less 2 status bytes)
    std::uint32_t usb_frame_us = 1000;     ///< a USB frame (full speed: 1 ms)
    std::uint32_t processing_us = 0;       ///< the unit's time from a message to its answer
    bool tcp = false;                      ///< on TCP connections too (always on the pty)
};

struct DeviceConfig {
    std::string name;                 ///< unique; names the pty symlink and the logger
    std::string protocol;             ///< the family's name: "mcs", "apt"
    std::string model;                ///< controller model (the family's default when not given)
    /// The firmware generation whose behaviour the device follows ("firmware"): empty in the
    /// rig text means the family's default (the manual's version); the family's loader checks
    /// the name and sets the default, so after loading it always names a generation.
    std::string firmware;
    std::uint16_t tcp_port = 0;       ///< 0 = ephemeral
    /// An RFC 2217 endpoint's port ("rfc2217_port"): 0 = ephemeral; absent = none (unless
    /// --rfc2217 gives every device one).
    std::optional<std::uint16_t> rfc2217_port;
    std::string pty;                  ///< symlink path; empty = <pty dir>/<name>
    /// Pace the pty's output at the controller's baud rate (MCS: CB, effective after R).
    bool faithful_timing = false;
    /// The link model; absent: answers leave as soon as the line (if paced) has carried them.
    std::optional<LinkModel> link;
    /// The family's own section (mcs::McsConfig, apt::AptConfig); read it with section_of.
    std::any section;
    /// Where the rig text describes the device ("rig.json", "/devices/2"): errors found after
    /// loading name it as the loader's do.
    std::string source;
    std::string pointer;
};

/// The family section of `device` as `Section`; an empty section becomes a default one.
/// Throws std::bad_any_cast when the device holds another family's section.
template <class Section>
Section& section_of(DeviceConfig& device)
{
    if (!device.section.has_value())
        device.section = Section{};
    return std::any_cast<Section&>(device.section);
}

/// The family section of `device` as `Section`; throws std::bad_any_cast for another type.
template <class Section>
const Section& section_of(const DeviceConfig& device)
{
    return std::any_cast<const Section&>(device.section);
}

/// The control API's listener ("control" in the rig JSON; docs/control-api.md).
struct ControlConfig {
    std::uint16_t port = 0;           ///< 0 = ephemeral
};

/// How the clock starts ("clock" in the rig JSON; --time-scale and --paused win).
struct ClockStart {
    double time_scale = 1.0;          ///< 0.001..1000
    bool paused = false;
};

struct RigConfig {
    std::uint32_t tick_hz = 1000;     ///< physics tick (1..100000 Hz)
    ClockStart clock;
    std::vector<DeviceConfig> devices;
    std::optional<ControlConfig> control;   ///< the control API; absent = off unless --control
    std::optional<KinematicsConfig> kinematics;   ///< the frames; absent = none
};

/// A config error: `what()` is the whole message, naming the JSON pointer.
class ConfigError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Parse and validate a rig from JSON text, each device's section by its family in
/// `families`. `source` names the text in messages (a file name); throws ConfigError.
RigConfig parse_rig_config(std::string_view json_text, std::string_view source, const FamilyRegistry& families);
/// Read and parse a rig file; throws ConfigError (also for unreadable files).
RigConfig load_rig_config(const std::string& path, const FamilyRegistry& families);

/// Give every device without a configured pty path the path `<pty_dir>/<name>`, and
/// reject two devices whose resolved paths collide (ConfigError naming /devices/N/pty).
void resolve_pty_paths(RigConfig& config, const std::string& pty_dir, std::string_view source);

} // namespace rigsim
