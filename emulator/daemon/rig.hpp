#pragma once
// A running rig: its clock, its devices and their endpoints, on one io_context.

#include "emulator/core/atomic_file.hpp"
#include "models/clock.hpp"
#include "emulator/core/control_surface.hpp"
#include "emulator/core/device.hpp"
#include "emulator/core/event_bus.hpp"
#include "emulator/daemon/link.hpp"
#include "emulator/daemon/memory_trim.hpp"
#include "emulator/daemon/rig_kinematics.hpp"
#include "emulator/core/logging.hpp"
#include "emulator/core/rig_config.hpp"
#include "emulator/core/state_store.hpp"
#include "emulator/daemon/ticker.hpp"
#include "emulator/transport/inotify_watcher.hpp"
#include "emulator/transport/pty_endpoint.hpp"
#include "emulator/transport/tcp_endpoint.hpp"
#include "models/collision_watch.hpp"
#include "models/kinematics.hpp"
#include "models/world.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/address.hpp>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace rigsim {

struct RigOptions {
    std::string pty_dir = "/tmp/rigsim";   ///< where pty symlinks go unless the config names one
    long pty_group = -1;                    ///< --pty-group: the ptys' group (mode 0660), or -1
    bool ephemeral_ports = false;           ///< every TCP endpoint on port 0
    bool rfc2217 = false;                   ///< --rfc2217: every device gets an RFC 2217 endpoint
    boost::asio::ip::address bind = boost::asio::ip::make_address("127.0.0.1");
    double time_scale = 1.0;
    bool paused = false;                    ///< the clock starts paused (--paused, "clock": {"paused"})
    LogLevels log_levels;
    std::string state_file;                 ///< --state-file; empty: non-volatile saves last the run
    bool state_sync = false;                ///< --state-sync: a save returns once written
    std::size_t max_connections = 256;      ///< TCP connections open at once, all devices together
    std::size_t max_connections_per_device = 32;   ///< TCP connections open at once on one device
};

/// Where a client reaches one device.
struct DeviceEndpoints {
    std::string name;
    std::string protocol;   ///< the family: "mcs", "apt"
    std::string model;
    std::string tcp;   ///< "127.0.0.1:40100", "[::1]:40100" (where a local client connects)
    std::string pty;   ///< symlink path
    std::string firmware;   ///< the firmware generation the device follows (DeviceConfig::firmware)
    std::string rfc2217;    ///< its RFC 2217 endpoint, as `tcp`; empty: none
};

/// A device as the control API steers it.
struct ControlledDevice {
    DeviceEndpoints endpoints;
    ControlSurface* surface = nullptr;   ///< state, set-up, device faults, power cycle, wire log
    Link* link = nullptr;                ///< faults on the wire
};

class Rig {
public:
    /// Builds every device and opens every endpoint (throws on failure to bind or open).
    Rig(boost::asio::io_context& io, const RigConfig& config, const RigOptions& options);
    ~Rig();
    Rig(const Rig&) = delete;
    Rig& operator=(const Rig&) = delete;

    void start();
    /// Stop I/O, remove pty symlinks.
    void stop();

    const std::vector<DeviceEndpoints>& endpoints() const { return endpoints_; }
    Clock& clock() { return clock_; }
    models::World& world() { return world_; }
    /// The timer pacing the clock: pause, resume, step, scale (the control API).
    Ticker& ticker() { return ticker_; }
    /// The control API's event stream (GET /api/events).
    EventBus& events() { return events_; }
    /// Gives freed memory back to the system after clients go (device and control connections).
    MemoryTrim& memory_trim() { return memory_trim_; }
    /// Every device, in config order, as the control API steers it.
    std::vector<ControlledDevice> controlled();
    /// Something moves: the world changes by itself at some later tick, or a device is busy
    /// (ControlSurface::busy(): a calibration, a move delay, a LUT running).
    bool busy() const;
    /// The rig's frames (rig JSON "kinematics", docs/config.md), or nullptr when it has none.
    models::Kinematics* kinematics() { return kinematics_.get(); }
    /// What drives each frame's joint, indexed like the frames of kinematics() (an empty
    /// binding for a fixed frame or a tool); empty when the rig has no frames.
    const std::vector<JointBinding>& joint_bindings() const { return joint_bindings_; }
    /// The pairs of frames (indices of kinematics()) whose boxes are checked for contact
    /// ("collisions" of the rig JSON, "auto" resolved); empty when the rig has no frames.
    const std::vector<std::pair<std::size_t, std::size_t>>& collision_pairs() const { return collision_pairs_; }
    /// The pairs of collision_pairs() whose boxes touch now (as of the collision watch's last
    /// check: it checks on every tick while a joint between them moves), in that order.
    std::vector<std::pair<std::size_t, std::size_t>> contacts() const;

private:
    struct Entry;

    Clock clock_;
    /// Before the devices: every device's bodies live here, and the world ticks first.
    models::World world_;
    Ticker ticker_;
    /// Before the devices, which publish to it.
    EventBus events_;
    /// Before the endpoints, whose sessions ask it to trim when they end.
    MemoryTrim memory_trim_;
    std::unique_ptr<StateStore> store_;
    /// Shared by every endpoint, so declared before (destroyed after) the entries.
    InotifyWatcher watcher_;
    TcpConnectionBudget tcp_budget_;
    std::vector<std::unique_ptr<Entry>> entries_;
    std::vector<DeviceEndpoints> endpoints_;
    /// After the devices: the joints read their channels.
    std::unique_ptr<models::Kinematics> kinematics_;
    std::vector<JointBinding> joint_bindings_;
    std::vector<std::pair<std::size_t, std::size_t>> collision_pairs_;
    /// A body of world_ (nullptr: no pair to watch).
    models::CollisionWatch* collisions_ = nullptr;
};

/// What --check-config checks beyond the loader: every device built in a world of its own (no
/// endpoints, no state file, nothing served) and powered up (an APT unit's rig "eeprom" replayed),
/// and when the rig has frames, every joint bound to its channel
/// (emulator/daemon/rig_kinematics.hpp). Throws ConfigError.
void check_rig_devices(const RigConfig& config);

/// The address a client on this machine connects to for a socket bound to `bound`: loopback
/// for a wildcard address (0.0.0.0, ::), `bound` otherwise.
boost::asio::ip::address client_address(const boost::asio::ip::address& bound);
/// "127.0.0.1:40100", "[::1]:40100".
std::string tcp_address_text(const boost::asio::ip::address& address, std::uint16_t port);

/// The endpoints document: {"devices":[{"name","protocol","model","tcp","pty"}]}, and
/// "control": `control_url` when the control API is on (`control_url` not empty).
std::string endpoints_json(const std::vector<DeviceEndpoints>& endpoints, const std::string& control_url = {});

} // namespace rigsim
