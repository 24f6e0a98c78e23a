#include "soak_api.hpp"

#include <nlohmann/json.hpp>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

namespace rigsim::bench {

namespace {

using SteadyClock = std::chrono::steady_clock;

double seconds_since(SteadyClock::time_point t)
{
    return std::chrono::duration<double>(SteadyClock::now() - t).count();
}

/// A non-blocking TCP connection to host:port, or an invalid fd when it is refused or takes
/// longer than `timeout_ms` (a full listen backlog).
UniqueFd connect_nonblocking(const std::string& host, std::uint16_t port, int timeout_ms)
{
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(port);
    if (::inet_pton(AF_INET, host.c_str(), &addr.sin_addr) != 1)
        throw std::runtime_error("not an IPv4 address: " + host);
    UniqueFd fd{::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0)};
    if (fd.get() < 0)
        throw std::runtime_error(errno_message("socket"));
    const int one = 1;
    ::setsockopt(fd.get(), IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    if (::connect(fd.get(), reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0)
        return fd;
    if (errno != EINPROGRESS)
        return UniqueFd{};
    pollfd p{fd.get(), POLLOUT, 0};
    if (::poll(&p, 1, timeout_ms) != 1)
        return UniqueFd{};
    int err = 0;
    socklen_t len = sizeof err;
    ::getsockopt(fd.get(), SOL_SOCKET, SO_ERROR, &err, &len);
    return err == 0 ? std::move(fd) : UniqueFd{};
}

/// Writes all of `data` to a non-blocking socket within `timeout_ms`; false if it cannot.
bool send_all(int fd, const std::string& data, int timeout_ms)
{
    const auto deadline = SteadyClock::now() + std::chrono::milliseconds(timeout_ms);
    std::size_t sent = 0;
    while (sent < data.size()) {
        const auto n = ::send(fd, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
        if (n > 0) {
            sent += static_cast<std::size_t>(n);
            continue;
        }
        if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)
            return false;
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - SteadyClock::now());
        pollfd p{fd, POLLOUT, 0};
        if (left.count() <= 0 || ::poll(&p, 1, static_cast<int>(left.count())) != 1)
            return false;
    }
    return true;
}

/// The status of the answer that starts what arrives on `fd` within `timeout_ms`, -1 if none.
int read_status(int fd, int timeout_ms)
{
    const auto deadline = SteadyClock::now() + std::chrono::milliseconds(timeout_ms);
    std::string got;
    char buf[4096];
    while (got.find("\r\n") == std::string::npos) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - SteadyClock::now());
        pollfd p{fd, POLLIN, 0};
        if (left.count() <= 0 || ::poll(&p, 1, static_cast<int>(left.count())) != 1)
            return -1;
        const auto n = ::recv(fd, buf, sizeof buf, 0);
        if (n <= 0)
            return -1;
        got.append(buf, static_cast<std::size_t>(n));
    }
    if (got.rfind("HTTP/1.1 ", 0) != 0 || got.size() < 12)
        return -1;
    return std::atoi(got.c_str() + 9);
}

std::string request_text(const ApiAddress& api, const std::string& method, const std::string& path,
                         const std::string& body)
{
    std::string text = method + " " + path + " HTTP/1.1\r\nHost: " + api.host + ":" + std::to_string(api.port) +
                       "\r\nConnection: close\r\n";
    if (!body.empty())
        text += "Content-Type: application/json\r\nContent-Length: " + std::to_string(body.size()) + "\r\n";
    return text + "\r\n" + body;
}

/// Closed by the peer (end of stream or reset), seen without reading what is queued.
bool peer_closed(int fd)
{
    pollfd p{fd, POLLRDHUP, 0};
    return ::poll(&p, 1, 0) == 1 && (p.revents & (POLLRDHUP | POLLHUP | POLLERR)) != 0;
}

} // namespace

ApiAddress parse_control(const std::string& endpoints_json)
{
    const auto doc = nlohmann::json::parse(endpoints_json);
    if (!doc.contains("control"))
        throw std::runtime_error("the endpoints file has no \"control\" URL (is the control API on?)");
    const auto url = doc["control"].get<std::string>();
    const std::string scheme = "http://";
    const auto colon = url.rfind(':');
    if (url.rfind(scheme, 0) != 0 || colon == std::string::npos || colon < scheme.size())
        throw std::runtime_error("control URL not http://HOST:PORT: " + url);
    ApiAddress api;
    api.host = url.substr(scheme.size(), colon - scheme.size());
    api.port = static_cast<std::uint16_t>(std::stoi(url.substr(colon + 1)));
    return api;
}

int http_status(const ApiAddress& api, const std::string& method, const std::string& path, const std::string& body,
                int timeout_ms)
{
    auto fd = connect_nonblocking(api.host, api.port, timeout_ms);
    if (fd.get() < 0 || !send_all(fd.get(), request_text(api, method, path, body), timeout_ms))
        return -1;
    return read_status(fd.get(), timeout_ms);
}

// ---- Event streams

namespace {

/// Opens the event stream `path` and waits for its opening comment (the subscription is live);
/// an invalid fd if the daemon refused it (503 while streams closed just before still count).
UniqueFd open_stream(const ApiAddress& api, const std::string& path)
{
    auto fd = connect_nonblocking(api.host, api.port, 5000);
    if (fd.get() < 0 || !send_all(fd.get(), request_text(api, "GET", path, ""), 5000))
        return UniqueFd{};
    std::string got;
    const auto deadline = SteadyClock::now() + std::chrono::seconds(10);
    char buf[4096];
    while (got.find(": rigsim event stream\n\n") == std::string::npos) {
        pollfd p{fd.get(), POLLIN, 0};
        if (SteadyClock::now() > deadline || ::poll(&p, 1, 100) < 0)
            throw std::runtime_error("event stream " + path + " did not start: " + got.substr(0, 200));
        if (p.revents == 0)
            continue;
        const auto n = ::recv(fd.get(), buf, sizeof buf, 0);
        if (n <= 0)
            return UniqueFd{};
        got.append(buf, static_cast<std::size_t>(n));
    }
    return fd;
}

} // namespace

EventStreams::EventStreams(const ApiAddress& api, const std::vector<std::string>& paths, bool reading)
{
    for (const auto& path : paths) {
        UniqueFd fd;
        const auto deadline = SteadyClock::now() + std::chrono::seconds(10);
        while ((fd = open_stream(api, path)).get() < 0) {
            if (SteadyClock::now() > deadline)
                throw std::runtime_error("the daemon refuses the event stream " + path);
            ::usleep(20000);
        }
        if (!reading) {
            // A client that reads nothing: a small receive buffer, so that the daemon's side fills.
            const int small = 4096;
            ::setsockopt(fd.get(), SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
        }
        fds_.push_back(std::move(fd));
    }
    if (reading)
        reader_ = std::thread([this] { read_loop(); });
}

EventStreams::~EventStreams()
{
    stop_ = true;
    if (reader_.joinable())
        reader_.join();
}

void EventStreams::read_loop()
{
    std::vector<pollfd> polls;
    for (const auto& fd : fds_)
        polls.push_back(pollfd{fd.get(), POLLIN, 0});
    char buf[65536];
    while (!stop_) {
        if (::poll(polls.data(), polls.size(), 50) <= 0)
            continue;
        for (auto& p : polls) {
            if (p.fd < 0 || p.revents == 0)
                continue;
            const auto n = ::recv(p.fd, buf, sizeof buf, 0);
            if (n > 0)
                bytes_ += static_cast<std::uint64_t>(n);
            else if (n == 0 || (errno != EAGAIN && errno != EINTR))
                p.fd = -1;   // closed by the daemon: counted by closed_by_daemon()
        }
    }
}

std::size_t EventStreams::closed_by_daemon() const
{
    std::size_t n = 0;
    for (const auto& fd : fds_)
        n += peer_closed(fd.get()) ? 1 : 0;
    return n;
}

// ---- The hostile client and the honest one

struct HostileApiClient::Slow {
    UniqueFd fd;
    SteadyClock::time_point opened;
    SteadyClock::time_point next_byte;
    std::string text;   ///< what it sends, a byte at a time
    std::size_t sent = 0;
};

HostileApiClient::HostileApiClient(const ApiAddress& api, Settings settings) : api_(api), settings_(settings)
{
    thread_ = std::thread([this] { run(); });
}

HostileApiClient::~HostileApiClient()
{
    stop();
}

HostileReport HostileApiClient::stop()
{
    stop_ = true;
    if (thread_.joinable())
        thread_.join();
    return report_;
}

void HostileApiClient::tend_slow(std::vector<Slow>& slow, bool body)
{
    const auto now = SteadyClock::now();
    for (auto& s : slow) {
        if (s.fd.get() >= 0 && peer_closed(s.fd.get())) {
            if (body)
                ++report_.slow_bodies_closed;
            else
                report_.slow_closed_after_s.push_back(seconds_since(s.opened));
            s.fd.reset();
        }
        if (s.fd.get() < 0) {
            s.fd = connect_nonblocking(api_.host, api_.port, 1000);
            s.opened = SteadyClock::now();
            s.next_byte = s.opened;
            s.sent = 0;
            const std::string host = "Host: " + api_.host + ":" + std::to_string(api_.port) + "\r\n";
            // A header that never ends, or a body that never comes whole.
            s.text = body ? "POST /api/faults HTTP/1.1\r\n" + host +
                                "Content-Type: application/json\r\nContent-Length: 60000\r\n\r\n" +
                                std::string(60000, ' ')
                          : "GET /api/clock HTTP/1.1\r\n" + host + "X-Slow: " + std::string(100000, 'a');
            if (s.fd.get() >= 0 && !body)
                ++report_.slow_opened;
            if (body && s.fd.get() >= 0) {
                // The header at once; then the body a byte at a time.
                const auto header_end = s.text.find("\r\n\r\n") + 4;
                send_all(s.fd.get(), s.text.substr(0, header_end), 1000);
                s.sent = header_end;
            }
            continue;
        }
        if (now >= s.next_byte && s.sent < s.text.size()) {
            if (::send(s.fd.get(), s.text.data() + s.sent, 1, MSG_NOSIGNAL) == 1)
                ++s.sent;
            s.next_byte = now + std::chrono::milliseconds(settings_.slow_interval_ms);
        }
    }
}

void HostileApiClient::run()
{
    std::vector<Slow> slow(static_cast<std::size_t>(settings_.slow));
    std::vector<Slow> slow_bodies(settings_.bodies ? 2 : 0);
    auto next_honest = SteadyClock::now();
    auto next_body = SteadyClock::now();
    while (!stop_) {
        tend_slow(slow, false);
        tend_slow(slow_bodies, true);
        const auto now = SteadyClock::now();
        if (now >= next_honest) {
            next_honest = now + std::chrono::milliseconds(settings_.honest_interval_ms);
            const auto t0 = SteadyClock::now();
            const int status = http_status(api_, "GET", "/api/clock", "", settings_.honest_timeout_ms);
            if (status == 200) {
                ++report_.honest_ok;
                report_.honest_ms.push_back(seconds_since(t0) * 1000.0);
            } else {
                ++report_.honest_failed;
            }
        }
        if (settings_.bodies && now >= next_body) {
            // Headers that announce 1 MiB: refused with 413 before the body is read.
            next_body = now + std::chrono::milliseconds(200);
            auto fd = connect_nonblocking(api_.host, api_.port, 1000);
            ++report_.big_bodies;
            if (fd.get() >= 0) {
                const std::string head = "POST /api/faults HTTP/1.1\r\nHost: " + api_.host + ":" +
                                         std::to_string(api_.port) +
                                         "\r\nContent-Type: application/json\r\nContent-Length: 1048576\r\n\r\n";
                send_all(fd.get(), head + std::string(16384, '{'), 1000);
                if (read_status(fd.get(), 2000) == 413)
                    ++report_.big_refused;
            }
        }
        ::usleep(10000);
    }
}

// ---- Clients that never read

NonReadingClients::NonReadingClients(std::vector<Target> targets) : count_(targets.size())
{
    std::vector<UniqueFd> fds;
    std::vector<std::string> requests;
    for (const auto& t : targets) {
        auto fd = connect_nonblocking(t.host, t.port, 5000);
        if (fd.get() < 0)
            throw std::runtime_error("cannot connect a non-reading client to port " + std::to_string(t.port));
        const int small = 4096;
        ::setsockopt(fd.get(), SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
        fds.push_back(std::move(fd));
        std::string burst;
        while (burst.size() < 16384)
            burst += t.request;
        requests.push_back(std::move(burst));
    }
    thread_ = std::thread([this, f = std::move(fds), r = std::move(requests)]() mutable {
        run(std::move(f), std::move(r));
    });
}

NonReadingClients::~NonReadingClients()
{
    stop_ = true;
    if (thread_.joinable())
        thread_.join();
}

void NonReadingClients::run(std::vector<UniqueFd> fds, std::vector<std::string> requests)
{
    std::vector<bool> gone(fds.size(), false);
    while (!stop_) {
        std::vector<pollfd> polls;
        std::vector<std::size_t> index;
        for (std::size_t i = 0; i < fds.size(); ++i)
            if (!gone[i]) {
                polls.push_back(pollfd{fds[i].get(), POLLOUT | POLLRDHUP, 0});
                index.push_back(i);
            }
        if (polls.empty() || ::poll(polls.data(), polls.size(), 50) <= 0)
            continue;
        for (std::size_t k = 0; k < polls.size(); ++k) {
            const auto i = index[k];
            bool closed = (polls[k].revents & (POLLRDHUP | POLLHUP | POLLERR)) != 0;
            if (!closed && (polls[k].revents & POLLOUT) != 0) {
                const auto n = ::send(fds[i].get(), requests[i].data(), requests[i].size(), MSG_NOSIGNAL);
                closed = n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR;
            }
            if (closed) {
                gone[i] = true;
                ++dropped_;
            }
        }
    }
}

} // namespace rigsim::bench
