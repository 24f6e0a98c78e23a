#include "emulator/daemon/rig.hpp"
#include "emulator/core/log_format.hpp"

#include "emulator/daemon/rig_families.hpp"
#include "emulator/daemon/rig_kinematics.hpp"
#include "emulator/transport/rfc2217_device.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <fcntl.h>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

namespace rigsim {

namespace {

/// The device as its transports see it: every batch of input first brings the clock to
/// the current wall time, and may start motion that the ticker must then pace.
class PacedDevice : public Device {
public:
    PacedDevice(Device& inner, Ticker& ticker, MemoryTrim& trim) : inner_(inner), ticker_(ticker), trim_(trim) {}

    std::uint32_t serial_baud() const override { return inner_.serial_baud(); }
    std::uint32_t line_baud() const override { return inner_.line_baud(); }

    std::unique_ptr<Session> open_session(SendFn send, std::string peer) override
    {
        return std::make_unique<PacedSession>(inner_.open_session(std::move(send), std::move(peer)), ticker_, trim_);
    }
    std::unique_ptr<Session> open_connection(SendFn send, Connection conn, std::string peer) override
    {
        return std::make_unique<PacedSession>(inner_.open_connection(std::move(send), std::move(conn), std::move(peer)),
                                              ticker_, trim_);
    }

private:
    class PacedSession : public Session {
    public:
        PacedSession(std::unique_ptr<Session> inner, Ticker& ticker, MemoryTrim& trim)
            : inner_(std::move(inner)), ticker_(ticker), trim_(trim) {}
        /// The client went: what its connection held (answers it did not read) is freed with
        /// the connection, and given back to the system soon after.
        ~PacedSession() override { trim_.request(); }
        void receive(std::string_view bytes) override
        {
            ticker_.sync();
            inner_->receive(bytes);
            ticker_.reschedule_announced();   // the device announced what its commands changed
        }

    private:
        std::unique_ptr<Session> inner_;
        Ticker& ticker_;
        MemoryTrim& trim_;
    };

    Device& inner_;
    Ticker& ticker_;
    MemoryTrim& trim_;
};

std::unique_ptr<Device> make_device(const DeviceConfig& config, models::World& world,
                                    std::shared_ptr<spdlog::logger> log, StateStore& store, EventBus& events)
{
    const auto* family = rig_families().find(config.protocol);
    if (!family)
        throw ConfigError("device \"" + config.name + "\": unknown protocol \"" + config.protocol + "\"");
    return family->make(config, DeviceContext{world, std::move(log), store, &events});
}

/// The device of an entry (Rig::Entry) or the entry itself (a device).
Device& device_of(const std::unique_ptr<Device>& d)
{
    return *d;
}
template <class Entry>
Device& device_of(const std::unique_ptr<Entry>& e)
{
    return *e->device;
}

/// Finds the control surface of a device of `config` by name among `devices` (config order).
template <class Devices>
SurfaceOf surfaces_of(const RigConfig& config, const Devices& devices)
{
    return [&config, &devices](std::string_view name) -> ControlSurface* {
        for (std::size_t i = 0; i < config.devices.size(); ++i)
            if (config.devices[i].name == name)
                return device_of(devices[i]).control();
        return nullptr;
    };
}

} // namespace

boost::asio::ip::address client_address(const boost::asio::ip::address& bound)
{
    // A socket bound to the wildcard address is reached on loopback from this machine.
    if (bound.is_v6() && bound.is_unspecified())
        return boost::asio::ip::address_v6::loopback();
    if (bound.is_v4() && bound.is_unspecified())
        return boost::asio::ip::address_v4::loopback();
    return bound;
}

std::string tcp_address_text(const boost::asio::ip::address& address, std::uint16_t port)
{
    // RFC 3986 host syntax: an IPv6 address in brackets, so that the port stays separable.
    const auto host = address.is_v6() ? "[" + address.to_string() + "]" : address.to_string();
    return host + ":" + std::to_string(port);
}

struct Rig::Entry {
    std::unique_ptr<Device> device;
    std::unique_ptr<Link> link;
    std::unique_ptr<Device> paced;   ///< a PacedDevice around the link
    std::unique_ptr<TcpEndpoint> tcp;
    std::unique_ptr<PtyEndpoint> pty;
    std::unique_ptr<Rfc2217Device> rfc2217_device;   ///< the serial port over RFC 2217, if any
    std::unique_ptr<TcpEndpoint> rfc2217;
};

Rig::Rig(boost::asio::io_context& io, const RigConfig& config, const RigOptions& options)
    : clock_(config.tick_hz), world_(clock_), ticker_(io, clock_, options.time_scale, options.paused ? Ticker::Start::Paused : Ticker::Start::Running),
      memory_trim_(io),
      store_(options.state_file.empty()
                 ? std::make_unique<StateStore>()
                 : std::make_unique<StateStore>(options.state_file, make_logger("rigsimd", options.log_levels))),
      watcher_(io)
{
    store_->set_sync(options.state_sync);
    tcp_budget_.max_total = options.max_connections;
    tcp_budget_.max_per_device = options.max_connections_per_device;
    for (const auto& dc : config.devices) {
        auto e = std::make_unique<Entry>();
        e->device = make_device(dc, world_, make_logger(dc.name, options.log_levels), *store_, events_);
        e->link = std::make_unique<Link>(*e->device, clock_, make_logger(dc.name, options.log_levels));
        if (dc.link)
            e->link->set_model(*dc.link);
        e->paced = std::make_unique<PacedDevice>(*e->link, ticker_, memory_trim_);
        entries_.push_back(std::move(e));
    }
    // Bodies that read other bodies (a strain gauge on a piezo) find them once all exist, so
    // the JSON may list a gauge before its piezo.
    world_.link_all();
    // Then the devices power up (a piezo driver's saved closed loop needs its linked gauge),
    // the ones whose state others read first (a gauge reader's saved hub output).
    power_up_in_phases(entries_, [](auto& e) -> Device& { return *e->device; });
    // The frames' joints read the devices' channels; a channel that cannot drive its joint is
    // a config error, found before any endpoint opens.
    if (config.kinematics) {
        auto built = build_kinematics(*config.kinematics, surfaces_of(config, entries_), world_);
        collisions_ = watch_collisions(world_, built, *config.kinematics, events_);
        kinematics_ = std::move(built.kinematics);
        joint_bindings_ = std::move(built.bindings);
        collision_pairs_ = config.kinematics->collisions;
    }
    // From here every change outside a tick is announced: a device's by the device after each
    // batch of client bytes and each session opened or closed, a link's by the link, a control
    // request's by Ticker::reschedule() (models/clock.hpp, "The schedule").
    clock_.changed_all();
    clock_.keep_schedule();

    for (std::size_t i = 0; i < config.devices.size(); ++i) {
        const auto& dc = config.devices[i];
        auto& e = *entries_[i];
        auto log = make_logger(dc.name, options.log_levels);
        const std::uint16_t port = options.ephemeral_ports ? 0 : dc.tcp_port;
        try {
            e.tcp = std::make_unique<TcpEndpoint>(io, *e.paced, options.bind, port, log, tcp_budget_);
        } catch (const std::exception& ex) {
            throw std::runtime_error("device \"" + dc.name + "\": cannot listen on tcp "
                                     + tcp_address_text(options.bind, port) + ": " + ex.what());
        }
        const auto pty_path = dc.pty.empty() ? options.pty_dir + "/" + dc.name : dc.pty;
        try {
            e.pty = std::make_unique<PtyEndpoint>(io, *e.paced, pty_path, log, watcher_, options.pty_group);
        } catch (const std::exception& ex) {
            throw std::runtime_error("device \"" + dc.name + "\": cannot open its pty: " + ex.what());
        }

        std::string rfc2217;
        if (dc.rfc2217_port || options.rfc2217) {
            const std::uint16_t rport = options.ephemeral_ports ? 0 : dc.rfc2217_port.value_or(0);
            e.rfc2217_device = std::make_unique<Rfc2217Device>(*e.paced, log);
            try {
                e.rfc2217 = std::make_unique<TcpEndpoint>(io, *e.rfc2217_device, options.bind, rport, log, tcp_budget_);
            } catch (const std::exception& ex) {
                throw std::runtime_error("device \"" + dc.name + "\": cannot listen for RFC 2217 on tcp "
                                         + tcp_address_text(options.bind, rport) + ": " + ex.what());
            }
            const auto rep = e.rfc2217->local_endpoint();
            rfc2217 = tcp_address_text(client_address(rep.address()), rep.port());
        }

        const auto ep = e.tcp->local_endpoint();
        endpoints_.push_back(DeviceEndpoints{dc.name, dc.protocol, dc.model,
                                             tcp_address_text(client_address(ep.address()), ep.port()),
                                             e.pty->symlink_path(), dc.firmware, rfc2217});
        log->info("listening on tcp {} and pty {} -> {}{}", endpoints_.back().tcp, pty_path, e.pty->device_path(),
                  rfc2217.empty() ? "" : ", RFC 2217 on tcp " + rfc2217);
    }
}

std::vector<std::pair<std::size_t, std::size_t>> Rig::contacts() const
{
    std::vector<std::pair<std::size_t, std::size_t>> out;
    if (collisions_)
        for (const auto& c : collisions_->contacts())
            out.emplace_back(c.frame_a, c.frame_b);
    return out;
}

void check_rig_devices(const RigConfig& config)
{
    Clock clock(config.tick_hz);
    models::World world(clock);
    StateStore store;
    EventBus events;
    std::vector<std::unique_ptr<Device>> devices;
    for (const auto& dc : config.devices)   // loggers without sinks, not the daemon's
        devices.push_back(make_device(dc, world, std::make_shared<spdlog::logger>(dc.name), store, events));
    // As the rig does: an APT unit's power-up replays its rig "eeprom", whose entries the unit
    // may refuse.
    world.link_all();
    power_up_in_phases(devices, [](auto& d) -> Device& { return *d; });
    if (config.kinematics)
        build_kinematics(*config.kinematics, surfaces_of(config, devices), world);
}

Rig::~Rig()
{
    stop();
}

void Rig::start()
{
    watcher_.start();
    for (auto& e : entries_) {
        e->tcp->start();
        e->pty->start();
        if (e->rfc2217)
            e->rfc2217->start();
    }
}

void Rig::stop()
{
    ticker_.stop();
    for (auto& e : entries_) {
        e->tcp->stop();
        e->pty->stop();
        if (e->rfc2217)
            e->rfc2217->stop();
    }
    watcher_.stop();
}

bool Rig::busy() const
{
    if (world_.next_change(clock_.now()) != kNever || world_.settling())
        return true;
    return std::any_of(entries_.begin(), entries_.end(), [](const auto& e) {
        const auto* surface = e->device->control();
        return surface && surface->busy();
    });
}

std::vector<ControlledDevice> Rig::controlled()
{
    std::vector<ControlledDevice> out;
    for (std::size_t i = 0; i < entries_.size(); ++i)
        out.push_back(ControlledDevice{endpoints_[i], entries_[i]->device->control(), entries_[i]->link.get()});
    return out;
}

std::string endpoints_json(const std::vector<DeviceEndpoints>& endpoints, const std::string& control_url)
{
    auto devices = nlohmann::json::array();
    for (const auto& e : endpoints) {
        devices.push_back({{"name", e.name}, {"protocol", e.protocol},
                           {"model", e.model}, {"tcp", e.tcp}, {"pty", e.pty}});
        if (!e.rfc2217.empty())
            devices.back()["rfc2217"] = e.rfc2217;
    }
    nlohmann::json doc{{"devices", devices}};
    if (!control_url.empty())
        doc["control"] = control_url;
    return doc.dump(2) + "\n";
}

} // namespace rigsim
