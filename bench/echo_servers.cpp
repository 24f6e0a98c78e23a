#include "echo_servers.hpp"

#include "cpu_placement.hpp"
#include "roundtrip.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <pty.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <functional>
#include <future>
#include <stdexcept>

namespace rigsim::bench {

namespace {

/// Writes all of `data`; false if the peer went away.
bool write_all(int fd, const char* data, std::size_t size)
{
    while (size > 0) {
        const ssize_t n = ::write(fd, data, size);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            return false;
        }
        data += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

/// Fills `reply` with `request` repeated (a non-empty request).
void fill_echo(const std::string& request, std::string& reply)
{
    for (std::size_t i = 0; i < reply.size(); ++i)
        reply[i] = request[i % request.size()];
}

/// Reads requests of shape.request_bytes and answers each with shape.reply_bytes
/// until end of file or an error; `stopping` is checked after each read so that the
/// owner can wake the loop and end it.
void echo_loop(int fd, EchoShape shape, const std::atomic<bool>* stopping)
{
    std::string request(shape.request_bytes, '\0');
    std::string reply(shape.reply_bytes, '\0');
    for (;;) {
        std::size_t used = 0;
        while (used < request.size()) {
            const ssize_t n = ::read(fd, request.data() + used, request.size() - used);
            if (n < 0 && errno == EINTR)
                continue;
            if (n <= 0)
                return;
            if (stopping && stopping->load())
                return;
            used += static_cast<std::size_t>(n);
        }
        fill_echo(request, reply);
        if (!write_all(fd, reply.data(), reply.size()))
            return;
    }
}

/// Starts `body` on a new thread pinned to `cpu` if given; returns once the
/// thread runs and its id is known.
std::thread start_thread(std::optional<int> cpu, pid_t& thread_id, std::function<void()> body)
{
    std::promise<pid_t> started;
    auto id = started.get_future();
    std::thread thread{[cpu, started = std::move(started), body = std::move(body)]() mutable {
        try {
            if (cpu)
                pin_this_thread(*cpu);
        } catch (...) {
            started.set_exception(std::current_exception());
            return;
        }
        started.set_value(::gettid());
        body();
    }};
    try {
        thread_id = id.get();
    } catch (...) {
        thread.join();
        throw;
    }
    return thread;
}

/// A shape the echo loop can serve: a request of at least one byte.
EchoShape checked(EchoShape shape)
{
    if (shape.request_bytes == 0)
        throw std::invalid_argument("echo server: requests of 0 bytes");
    return shape;
}

}  // namespace

std::string echo_reply(const std::string& request, std::size_t reply_bytes)
{
    std::string reply(request.empty() ? 0 : reply_bytes, '\0');
    fill_echo(request, reply);
    return reply;
}

TcpEchoServer::TcpEchoServer(EchoShape shape, std::optional<int> cpu) : shape_(checked(shape))
{
    listener_ = UniqueFd{::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0)};
    if (listener_.get() < 0)
        throw std::runtime_error(errno_message("socket"));
    const int one = 1;
    ::setsockopt(listener_.get(), SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);

    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = 0;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::bind(listener_.get(), reinterpret_cast<const sockaddr*>(&addr), sizeof addr) < 0)
        throw std::runtime_error(errno_message("bind 127.0.0.1:0"));
    if (::listen(listener_.get(), 1) < 0)
        throw std::runtime_error(errno_message("listen"));
    socklen_t len = sizeof addr;
    if (::getsockname(listener_.get(), reinterpret_cast<sockaddr*>(&addr), &len) < 0)
        throw std::runtime_error(errno_message("getsockname"));
    port_ = ntohs(addr.sin_port);

    thread_ = start_thread(cpu, thread_id_, [this] { run(); });
}

TcpEchoServer::~TcpEchoServer()
{
    /*
     * Normally the client has closed and the thread has returned already.
     * Otherwise shutdown() wakes a blocked accept() or read(); stopping_ and
     * connection_fd_ are a Dekker pair, so one side always sees the other.
     * The connection is closed only after the join, so its number is not reused
     * while the thread might still use it.
     */
    stopping_.store(true);
    ::shutdown(listener_.get(), SHUT_RDWR);
    const int fd = connection_fd_.load();
    if (fd >= 0)
        ::shutdown(fd, SHUT_RDWR);
    thread_.join();
    if (const int accepted = connection_fd_.load(); accepted >= 0)
        ::close(accepted);
}

void TcpEchoServer::run()
{
    int fd;
    do
        fd = ::accept4(listener_.get(), nullptr, nullptr, SOCK_CLOEXEC);
    while (fd < 0 && errno == EINTR);
    if (fd < 0)
        return;
    connection_fd_.store(fd);
    if (stopping_.load())
        return;
    const int one = 1;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    echo_loop(fd, shape_, nullptr);
}

PtyEchoServer::PtyEchoServer(EchoShape shape, std::optional<int> cpu) : shape_(checked(shape))
{
    int master = -1;
    int slave = -1;
    char name[PATH_MAX] = {};
    if (::openpty(&master, &slave, name, nullptr, nullptr) < 0)
        throw std::runtime_error(errno_message("openpty"));
    master_ = UniqueFd{master};
    slave_ = UniqueFd{slave};
    slave_path_ = name;
    // Line discipline settings live on the slave side; clients set raw as well.
    make_raw(slave_.get());

    thread_ = start_thread(cpu, thread_id_, [this] { run(); });
}

PtyEchoServer::~PtyEchoServer()
{
    // A byte written to the slave wakes the blocked read on the master.
    stopping_.store(true);
    const char wake = '\n';
    write_all(slave_.get(), &wake, 1);
    thread_.join();
}

void PtyEchoServer::run()
{
    echo_loop(master_.get(), shape_, &stopping_);
}

}  // namespace rigsim::bench
