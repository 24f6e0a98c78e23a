#include "emulator/core/rig.hpp"

#include "emulator/apt/apt_device.hpp"
#include "emulator/mcs/mcs_device.hpp"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cstdio>
#include <fcntl.h>
#include <system_error>
#include <unistd.h>

namespace rigsim {

namespace {

/// The device as its transports see it: every batch of input first brings the clock to
/// the current wall time, and may start motion that the ticker must then pace.
class PacedDevice : public Device {
public:
    PacedDevice(Device& inner, Ticker& ticker) : inner_(inner), ticker_(ticker) {}

    const DeviceConfig& config() const override { return inner_.config(); }
    std::uint32_t serial_baud() const override { return inner_.serial_baud(); }

    std::unique_ptr<Session> open_session(SendFn send, std::string peer) override
    {
        return std::make_unique<PacedSession>(inner_.open_session(std::move(send), std::move(peer)), ticker_);
    }

private:
    class PacedSession : public Session {
    public:
        PacedSession(std::unique_ptr<Session> inner, Ticker& ticker)
            : inner_(std::move(inner)), ticker_(ticker) {}
        void receive(std::string_view bytes) override
        {
            ticker_.sync();
            inner_->receive(bytes);
            ticker_.reschedule();
        }

    private:
        std::unique_ptr<Session> inner_;
        Ticker& ticker_;
    };

    Device& inner_;
    Ticker& ticker_;
};

std::unique_ptr<Device> make_device(const DeviceConfig& config, Clock& clock,
                                    std::shared_ptr<spdlog::logger> log, StateStore& store)
{
    switch (config.protocol) {
    case Protocol::Mcs:
        return std::make_unique<mcs::McsDevice>(config, clock, std::move(log));
    case Protocol::Apt:
        return std::make_unique<apt::AptDevice>(config, clock, std::move(log), &store);
    }
    throw ConfigError("device \"" + config.name + "\": unknown protocol");
}

} // namespace

struct Rig::Entry {
    std::unique_ptr<Device> device;
    std::unique_ptr<PacedDevice> paced;
    std::unique_ptr<TcpEndpoint> tcp;
    std::unique_ptr<PtyEndpoint> pty;
};

Rig::Rig(boost::asio::io_context& io, const RigConfig& config, const RigOptions& options)
    : clock_(config.tick_hz), ticker_(io, clock_, options.time_scale),
      store_(options.state_file.empty() ? std::make_unique<StateStore>() : std::make_unique<StateStore>(options.state_file)),
      watcher_(io)
{
    tcp_budget_.max_total = options.max_connections;
    tcp_budget_.max_per_device = options.max_connections_per_device;
    for (const auto& dc : config.devices) {
        auto log = make_logger(dc.name, options.log_levels);
        auto e = std::make_unique<Entry>();
        e->device = make_device(dc, clock_, log, *store_);
        e->paced = std::make_unique<PacedDevice>(*e->device, ticker_);
        const std::uint16_t port = options.ephemeral_ports ? 0 : dc.tcp_port;
        e->tcp = std::make_unique<TcpEndpoint>(io, *e->paced, options.bind, port, log, tcp_budget_);
        const auto pty_path = dc.pty.empty() ? options.pty_dir + "/" + dc.name : dc.pty;
        e->pty = std::make_unique<PtyEndpoint>(io, *e->paced, pty_path, log, watcher_);

        const auto ep = e->tcp->local_endpoint();
        endpoints_.push_back(DeviceEndpoints{dc.name, dc.protocol, dc.model,
                                             ep.address().to_string() + ":" + std::to_string(ep.port()),
                                             e->pty->symlink_path()});
        log->info("listening on tcp {} and pty {} -> {}", endpoints_.back().tcp, pty_path,
                  e->pty->device_path());
        entries_.push_back(std::move(e));
    }
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
    }
}

void Rig::stop()
{
    ticker_.stop();
    for (auto& e : entries_) {
        e->tcp->stop();
        e->pty->stop();
    }
    watcher_.stop();
}

std::string endpoints_json(const std::vector<DeviceEndpoints>& endpoints)
{
    auto devices = nlohmann::json::array();
    for (const auto& e : endpoints)
        devices.push_back({{"name", e.name}, {"protocol", std::string(to_string(e.protocol))},
                           {"model", e.model}, {"tcp", e.tcp}, {"pty", e.pty}});
    return nlohmann::json{{"devices", devices}}.dump(2) + "\n";
}

void write_file_atomically(const std::string& path, const std::string& text)
{
    const auto tmp = path + ".tmp" + std::to_string(::getpid());
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0)
        throw std::system_error(errno, std::generic_category(), "cannot write " + tmp);
    std::size_t done = 0;
    while (done < text.size()) {
        const auto n = ::write(fd, text.data() + done, text.size() - done);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            const int e = errno;
            ::close(fd);
            ::unlink(tmp.c_str());
            throw std::system_error(e, std::generic_category(), "cannot write " + tmp);
        }
        done += static_cast<std::size_t>(n);
    }
    ::fsync(fd);
    ::close(fd);
    if (::rename(tmp.c_str(), path.c_str()) != 0) {
        const int e = errno;
        ::unlink(tmp.c_str());
        throw std::system_error(e, std::generic_category(), "cannot rename " + tmp + " to " + path);
    }
}

} // namespace rigsim
