#include "soak_devices.hpp"

#include "roundtrip.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/epoll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

namespace rigsim::bench {

namespace {

using SteadyClock = std::chrono::steady_clock;

std::int64_t now_ns()
{
    return std::chrono::duration_cast<std::chrono::nanoseconds>(SteadyClock::now().time_since_epoch()).count();
}

/// A command's answer that never comes within this is lost.
constexpr std::int64_t kAnswerTimeoutNs = 10'000'000'000;

/// An APT request without data: id, two parameters, destination, source (the host, 0x01).
std::string apt_request(std::uint16_t id, std::uint8_t p1, std::uint8_t p2, std::uint8_t dest)
{
    return std::string{static_cast<char>(id & 0xff), static_cast<char>(id >> 8), static_cast<char>(p1),
                       static_cast<char>(p2),        static_cast<char>(dest),    '\x01'};
}

std::string apt_id(std::uint16_t id)
{
    return std::string{static_cast<char>(id & 0xff), static_cast<char>(id >> 8)};
}

/// The APT requests a soak client may send (each answered by another message id), for a device
/// whose channel 1 answers at `dest` and whose unit answers HW_REQ_INFO at `unit`.
std::vector<SoakCommand> apt_candidates(std::uint8_t dest, std::uint8_t unit)
{
    return {
        {apt_request(0x0005, 0, 0, unit), apt_id(0x0006)},   // HW_REQ_INFO -> HW_GET_INFO
        {apt_request(0x0411, 1, 0, dest), apt_id(0x0412)},   // MOT_REQ_POSCOUNTER
        {apt_request(0x0429, 1, 0, dest), apt_id(0x042A)},   // MOT_REQ_STATUSBITS
        {apt_request(0x0414, 1, 0, dest), apt_id(0x0415)},   // MOT_REQ_VELPARAMS
        {apt_request(0x0211, 1, 0, dest), apt_id(0x0212)},   // MOD_REQ_CHANENABLESTATE
        {apt_request(0x0644, 1, 0, dest), apt_id(0x0645)},   // PZ_REQ_OUTPUTVOLTS
        {apt_request(0x0490, 1, 0, dest), apt_id(0x0491)},   // MOT_REQ_DCSTATUSUPDATE
    };
}

/// The length of the APT frame at the front of `in` (0: not complete yet).
std::size_t apt_frame_size(const std::string& in)
{
    if (in.size() < 6)
        return 0;
    std::size_t size = 6;
    if ((static_cast<unsigned char>(in[4]) & 0x80) != 0)
        size += static_cast<unsigned char>(in[2]) | (static_cast<std::size_t>(static_cast<unsigned char>(in[3])) << 8);
    return in.size() >= size ? size : 0;
}

/// The size of the answer at the front of `in`, complete (0: not yet).
std::size_t answer_size(bool apt, const std::string& in)
{
    if (apt)
        return apt_frame_size(in);
    const auto nl = in.find('\n');
    return nl == std::string::npos ? 0 : nl + 1;
}

void set_nonblocking(int fd)
{
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
}

} // namespace

std::vector<SoakDevice> soak_devices(const std::vector<DeviceEndpoints>& endpoints)
{
    std::vector<SoakDevice> devices;
    std::vector<UniqueFd> probes;
    for (const auto& ep : endpoints) {
        SoakDevice d{ep, {}};
        if (ep.protocol == "mcs") {
            d.commands.push_back({":GNC\n", ":N"});
            d.commands.push_back({":GSI\n", ":ID"});
            for (int ch = 0; ch < 3; ++ch) {
                const auto c = std::to_string(ch);
                d.commands.push_back({":GP" + c + "\n", ":P" + c + ","});
                d.commands.push_back({":GS" + c + "\n", ":S" + c + ","});
                d.commands.push_back({":GCLS" + c + "\n", ":CLS" + c + ","});
                d.commands.push_back({":MPR" + c + "," + (ch % 2 ? "-" : "") + "1000,0\n", ":E" + c + ","});
            }
        }
        probes.push_back(ep.protocol == "apt" ? connect_tcp(ep.tcp_host, ep.tcp_port) : UniqueFd{});
        devices.push_back(std::move(d));
    }
    // APT: each request of the list to every device at once; a device keeps those it answers
    // with the expected message within 150 ms.
    const auto candidates = apt_candidates(0x50, 0x50);
    for (std::size_t k = 0; k < candidates.size(); ++k) {
        std::vector<std::string> got(devices.size());
        for (std::size_t i = 0; i < devices.size(); ++i) {
            if (probes[i].get() < 0)
                continue;
            // A benchtop rack (BSC, BBD, BPC) answers from its bays (0x21...) and its motherboard (0x11).
            const bool rack = devices[i].endpoints.model.rfind('B', 0) == 0;
            const auto c = apt_candidates(rack ? 0x21 : 0x50, rack ? 0x11 : 0x50)[k];
            if (::write(probes[i].get(), c.request.data(), c.request.size()) != 6)
                throw std::runtime_error(errno_message("write to " + devices[i].endpoints.name));
        }
        const auto deadline = SteadyClock::now() + std::chrono::milliseconds(150);
        while (SteadyClock::now() < deadline) {
            for (std::size_t i = 0; i < devices.size(); ++i) {
                pollfd p{probes[i].get(), POLLIN, 0};
                char buf[512];
                if (probes[i].get() >= 0 && ::poll(&p, 1, 0) == 1) {
                    const auto n = ::read(probes[i].get(), buf, sizeof buf);
                    if (n > 0)
                        got[i].append(buf, static_cast<std::size_t>(n));
                }
            }
            ::usleep(1000);
        }
        for (std::size_t i = 0; i < devices.size(); ++i) {
            if (probes[i].get() < 0)
                continue;
            const bool rack = devices[i].endpoints.model.rfind('B', 0) == 0;
            const auto c = apt_candidates(rack ? 0x21 : 0x50, rack ? 0x11 : 0x50)[k];
            if (got[i].size() == apt_frame_size(got[i]) && got[i].compare(0, 2, c.expect) == 0)
                devices[i].commands.push_back(c);
        }
    }
    for (const auto& d : devices)
        if (d.commands.size() < 2)
            throw std::runtime_error("device " + d.endpoints.name + " answers fewer than 2 of the soak's commands");
    return devices;
}

struct DeviceClients::Client {
    Spec spec;
    UniqueFd fd;
    std::string in;
    const SoakCommand* waiting = nullptr;   ///< the command whose answer is due
    std::int64_t sent_ns = 0;
    int done = 0;                           ///< commands of this block answered or abandoned
};

DeviceClients::DeviceClients(std::vector<Spec> specs, std::uint32_t seed, int disconnect_every)
    : epoll_(::epoll_create1(EPOLL_CLOEXEC)), rng_(seed), disconnect_every_(disconnect_every)
{
    if (epoll_.get() < 0)
        throw std::runtime_error(errno_message("epoll_create1"));
    for (const auto& s : specs) {
        clients_.push_back(std::make_unique<Client>());
        clients_.back()->spec = s;
        open(*clients_.back());
    }
}

DeviceClients::~DeviceClients() = default;

void DeviceClients::open(Client& c)
{
    const auto& ep = c.spec.device->endpoints;
    c.fd = c.spec.pty ? open_pty(ep.pty_path) : connect_tcp(ep.tcp_host, ep.tcp_port);
    set_nonblocking(c.fd.get());
    epoll_event ev{};
    ev.events = EPOLLIN | EPOLLRDHUP;
    ev.data.ptr = &c;
    if (::epoll_ctl(epoll_.get(), EPOLL_CTL_ADD, c.fd.get(), &ev) < 0)
        throw std::runtime_error(errno_message("epoll_ctl"));
    c.in.clear();
    c.waiting = nullptr;
}

void DeviceClients::reopen(Client& c)
{
    c.fd.reset();   // closing removes it from the epoll set
    ++totals_.reconnects;
    open(c);
}

void DeviceClients::close_all()
{
    for (auto& c : clients_) {
        c->fd.reset();
        c->waiting = nullptr;
    }
}

void DeviceClients::send_next(Client& c, int goal)
{
    while (c.done < goal && !c.waiting) {
        const auto& commands = c.spec.device->commands;
        const auto& cmd = commands[rng_() % commands.size()];
        const bool disconnect = disconnect_every_ > 0 && rng_() % static_cast<unsigned>(disconnect_every_) == 0;
        // A TCP client may go with its answer unread (the daemon then writes to a closed
        // socket); a pty client only between commands, since a port reopened at once may still
        // hold its last answer (docs/architecture.md "Connections").
        const bool with_answer_unread = disconnect && !c.spec.pty && rng_() % 2 == 0;
        if (disconnect && !with_answer_unread) {
            reopen(c);
            continue;
        }
        c.sent_ns = now_ns();
        const auto n = ::write(c.fd.get(), cmd.request.data(), cmd.request.size());
        if (n != static_cast<ssize_t>(cmd.request.size())) {
            // The daemon closed the connection (it does so for a client beyond its limits).
            ++totals_.refused;
            reopen(c);
            continue;
        }
        if (with_answer_unread) {
            ++totals_.abandoned;
            ++c.done;
            reopen(c);
            continue;
        }
        c.waiting = &cmd;
    }
}

bool DeviceClients::take_answers(Client& c, RoundTrips& into)
{
    const bool apt = c.spec.device->endpoints.protocol == "apt";
    for (;;) {
        const auto size = answer_size(apt, c.in);
        if (size == 0)
            return true;
        if (!c.waiting || c.in.compare(0, c.waiting->expect.size(), c.waiting->expect) != 0) {
            // Bytes nobody asked for, or the answer to another command: the stream of this
            // connection is no longer trusted.
            ++totals_.misrouted;
            if (c.waiting) {
                ++totals_.lost;
                ++c.done;
            }
            return false;
        }
        (c.spec.pty ? into.pty : into.tcp).push_back(now_ns() - c.sent_ns);
        ++totals_.answered;
        ++c.done;
        c.waiting = nullptr;
        c.in.erase(0, size);
    }
}

void DeviceClients::on_readable(Client& c, RoundTrips& into, int goal)
{
    char buf[8192];
    for (;;) {
        const auto n = ::read(c.fd.get(), buf, sizeof buf);
        if (n > 0) {
            c.in.append(buf, static_cast<std::size_t>(n));
            continue;
        }
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
            break;
        if (n < 0 && errno == EINTR)
            continue;
        // End of stream or an error: the daemon closed a client that did nothing wrong.
        if (c.waiting) {
            ++totals_.lost;
            ++c.done;
        }
        ++totals_.refused;
        reopen(c);
        send_next(c, goal);
        return;
    }
    if (!take_answers(c, into))
        reopen(c);
    send_next(c, goal);
}

void DeviceClients::run_block(int commands, RoundTrips& into, const std::function<void()>& every_100ms)
{
    for (auto& c : clients_) {
        c->done = 0;
        if (c->fd.get() < 0)   // closed by close_all()
            open(*c);
    }
    for (auto& c : clients_)
        send_next(*c, commands);
    auto next_tick = SteadyClock::now();
    std::vector<epoll_event> events(clients_.size());
    for (;;) {
        bool all_done = true;
        for (const auto& c : clients_)
            all_done = all_done && c->done >= commands && !c->waiting;
        if (all_done)
            return;
        const int n = ::epoll_wait(epoll_.get(), events.data(), static_cast<int>(events.size()), 20);
        if (n < 0 && errno != EINTR)
            throw std::runtime_error(errno_message("epoll_wait"));
        for (int i = 0; i < n; ++i)
            on_readable(*static_cast<Client*>(events[static_cast<std::size_t>(i)].data.ptr), into, commands);
        if (SteadyClock::now() >= next_tick) {
            next_tick = SteadyClock::now() + std::chrono::milliseconds(100);
            every_100ms();
            const auto now = now_ns();
            for (auto& c : clients_)
                if (c->waiting && now - c->sent_ns > kAnswerTimeoutNs) {
                    ++totals_.lost;
                    ++c->done;
                    reopen(*c);
                    send_next(*c, commands);
                }
        }
    }
}

} // namespace rigsim::bench
