#include "emulator/transport/pty_endpoint.hpp"

#include <boost/asio/write.hpp>

#include <algorithm>

#include <cerrno>
#include <climits>
#include <fcntl.h>
#include <pty.h>
#include <sys/inotify.h>
#include <sys/stat.h>
#include <system_error>
#include <termios.h>
#include <unistd.h>

namespace rigsim {

namespace asio = boost::asio;

namespace {

[[noreturn]] void throw_errno(const std::string& what)
{
    throw std::system_error(errno, std::generic_category(), what);
}

/// mkdir -p for the symlink's directory.
void make_parent_dirs(const std::string& path)
{
    for (auto pos = path.find('/', 1); pos != std::string::npos; pos = path.find('/', pos + 1)) {
        const auto dir = path.substr(0, pos);
        if (::mkdir(dir.c_str(), 0755) != 0 && errno != EEXIST)
            throw_errno("cannot create directory " + dir);
    }
}

/// Point `link` at `target` atomically, replacing a stale symlink but never a real file.
void replace_symlink(const std::string& target, const std::string& link)
{
    struct stat st {};
    if (::lstat(link.c_str(), &st) == 0 && !S_ISLNK(st.st_mode)) {
        errno = EEXIST;
        throw_errno("pty path " + link + " exists and is not a symlink");
    }
    const auto tmp = link + ".tmp" + std::to_string(::getpid());
    ::unlink(tmp.c_str());
    if (::symlink(target.c_str(), tmp.c_str()) != 0)
        throw_errno("cannot create symlink " + tmp);
    if (::rename(tmp.c_str(), link.c_str()) != 0) {
        const int e = errno;
        ::unlink(tmp.c_str());
        errno = e;
        throw_errno("cannot create symlink " + link);
    }
}

} // namespace

PtyEndpoint::PtyEndpoint(asio::io_context& io, Device& device, std::string symlink_path,
                         std::shared_ptr<spdlog::logger> log)
    : device_(device), master_(io), inotify_(io), pacing_timer_(io), symlink_path_(std::move(symlink_path)), log_(std::move(log))
{
    int master = -1;
    char name[PATH_MAX] = {};
    if (::openpty(&master, &slave_fd_, name, nullptr, nullptr) != 0)
        throw_errno("openpty failed");
    slave_name_ = name;
    // Raw: no echo, no line editing, no CR/LF mapping. A client's own termios settings
    // (it opens the slave) replace these; the daemon never resets them behind its back.
    struct termios tio {};
    ::tcgetattr(slave_fd_, &tio);
    ::cfmakeraw(&tio);
    ::cfsetispeed(&tio, B115200);
    ::cfsetospeed(&tio, B115200);
    ::tcsetattr(slave_fd_, TCSANOW, &tio);
    ::fcntl(master, F_SETFD, FD_CLOEXEC);
    ::fcntl(slave_fd_, F_SETFD, FD_CLOEXEC);
    master_.assign(master);
    master_.non_blocking(true);
    const int in = ::inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    if (in < 0 || ::inotify_add_watch(in, slave_name_.c_str(), IN_OPEN | IN_CLOSE) < 0) {
        const int e = errno;
        if (in >= 0)
            ::close(in);
        ::close(slave_fd_);
        errno = e;
        throw_errno("cannot watch " + slave_name_);
    }
    inotify_.assign(in);
    try {
        make_parent_dirs(symlink_path_);
        replace_symlink(slave_name_, symlink_path_);
    } catch (...) {
        ::close(slave_fd_);
        throw;
    }
    std::weak_ptr<bool> alive = alive_;
    session_ = device.open_session(
        [this, alive](std::string_view bytes) {
            if (alive.lock())
                send(bytes);
        },
        "pty " + symlink_path_);
}

PtyEndpoint::~PtyEndpoint()
{
    stop();
    alive_.reset();
    if (slave_fd_ >= 0)
        ::close(slave_fd_);
}

void PtyEndpoint::start()
{
    read();
    watch_openers();
}

void PtyEndpoint::watch_openers()
{
    std::weak_ptr<bool> alive = alive_;
    inotify_.async_wait(asio::posix::stream_descriptor::wait_read,
        [this, alive](const boost::system::error_code& ec) {
            if (!alive.lock() || stopped_ || ec)
                return;
            drain_open_events();
            watch_openers();
        });
}

void PtyEndpoint::drain_open_events()
{
    alignas(inotify_event) char buf[4096];
    while (true) {
        const auto n = ::read(inotify_.native_handle(), buf, sizeof buf);
        if (n <= 0)
            return;   // EAGAIN: nothing pending
        for (std::size_t off = 0; off + sizeof(inotify_event) <= static_cast<std::size_t>(n);) {
            const auto* e = reinterpret_cast<const inotify_event*>(buf + off);
            off += sizeof(inotify_event) + e->len;
            if (e->mask & IN_OPEN) {
                if (openers_++ == 0)
                    log_->info("pty {}: opened", symlink_path_);
            } else if (e->mask & IN_CLOSE) {
                openers_ = std::max(0, openers_ - 1);
                if (openers_ > 0)
                    continue;
                // Nobody listens any more: answers not read by now are lost, as on a
                // serial line whose host port is closed.
                ::tcflush(slave_fd_, TCIFLUSH);
                if (queue_.size() > 1)
                    queue_.erase(queue_.begin() + 1, queue_.end());
                log_->info("pty {}: closed", symlink_path_);
            }
        }
    }
}

void PtyEndpoint::stop()
{
    if (stopped_)
        return;
    stopped_ = true;
    boost::system::error_code ec;
    master_.cancel(ec);
    master_.close(ec);
    inotify_.close(ec);
    pacing_timer_.cancel();
    // Remove the symlink only if it is still ours.
    char target[PATH_MAX] = {};
    const auto n = ::readlink(symlink_path_.c_str(), target, sizeof target - 1);
    if (n > 0 && std::string(target, static_cast<std::size_t>(n)) == slave_name_)
        ::unlink(symlink_path_.c_str());
}

void PtyEndpoint::read()
{
    std::weak_ptr<bool> alive = alive_;
    master_.async_read_some(asio::buffer(buffer_),
        [this, alive](const boost::system::error_code& ec, std::size_t n) {
            if (!alive.lock() || stopped_)
                return;
            if (ec) {
                if (ec == asio::error::operation_aborted)
                    return;
                // EIO cannot happen while slave_fd_ is open; anything else ends the pty.
                log_->error("pty {}: read failed: {}", symlink_path_, ec.message());
                return;
            }
            drain_open_events();   // an open always precedes the opener's first bytes
            session_->receive(std::string_view(buffer_.data(), n));
            read();
        });
}

void PtyEndpoint::send(std::string_view bytes)
{
    if (stopped_)
        return;
    if (openers_ == 0)
        drain_open_events();
    // Nobody has the port open: lost, as on a real serial line. (Bytes sent just before a
    // close that is not yet seen stay in the pty until the close is seen and flushes them.)
    if (openers_ == 0)
        return;
    if (queued_bytes_ + bytes.size() > kMaxQueuedBytes) {
        if (!dropping_)
            log_->warn("pty {}: nobody reads the port, dropping output", symlink_path_);
        dropping_ = true;
        return;
    }
    dropping_ = false;
    queued_bytes_ += bytes.size();
    queue_.emplace_back(bytes);
    if (queue_.size() == 1)
        write();
}

void PtyEndpoint::write()
{
    const auto baud = device_.serial_baud();
    if (baud == 0) {
        paced_write();
        return;
    }
    const auto now = std::chrono::steady_clock::now();
    const auto transmit = std::chrono::nanoseconds(
        static_cast<std::int64_t>(queue_.front().size() * 10 * 1'000'000'000ULL / baud));
    line_free_ = std::max(line_free_, now) + transmit;
    pacing_timer_.expires_at(line_free_);
    std::weak_ptr<bool> alive = alive_;
    pacing_timer_.async_wait([this, alive](const boost::system::error_code& ec) {
        if (!alive.lock() || stopped_ || ec)
            return;
        paced_write();
    });
}

void PtyEndpoint::paced_write()
{
    std::weak_ptr<bool> alive = alive_;
    asio::async_write(master_, asio::buffer(queue_.front()),
        [this, alive](const boost::system::error_code& ec, std::size_t) {
            if (!alive.lock() || stopped_)
                return;
            if (ec) {
                if (ec != asio::error::operation_aborted)
                    log_->error("pty {}: write failed: {}", symlink_path_, ec.message());
                return;
            }
            queued_bytes_ -= queue_.front().size();
            queue_.pop_front();
            if (!queue_.empty())
                write();
        });
}

} // namespace rigsim
