#include "emulator/transport/pty_endpoint.hpp"
#include "emulator/core/log_format.hpp"

#include "emulator/transport/link_lock.hpp"

#include <boost/asio/post.hpp>
#include <boost/asio/write.hpp>

#include <algorithm>

#include <cerrno>
#include <climits>
#include <cstring>
#include <fcntl.h>
#include <pty.h>
#include <sys/inotify.h>
#include <sys/ioctl.h>
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

/// The rate of a termios speed constant; 0 for B0 and unknown ones.
std::uint32_t baud_of(speed_t speed)
{
    static constexpr std::pair<speed_t, std::uint32_t> kRates[] = {
        {B50, 50},         {B75, 75},           {B110, 110},         {B134, 134},         {B150, 150},
        {B200, 200},       {B300, 300},         {B600, 600},         {B1200, 1200},       {B1800, 1800},
        {B2400, 2400},     {B4800, 4800},       {B9600, 9600},       {B19200, 19200},     {B38400, 38400},
        {B57600, 57600},   {B115200, 115200},   {B230400, 230400},   {B460800, 460800},   {B500000, 500000},
        {B576000, 576000}, {B921600, 921600},   {B1000000, 1000000}, {B1152000, 1152000}, {B1500000, 1500000},
        {B2000000, 2000000}, {B2500000, 2500000}, {B3000000, 3000000}, {B3500000, 3500000}, {B4000000, 4000000},
    };
    for (const auto& [s, rate] : kRates)
        if (s == speed)
            return rate;
    return 0;
}

} // namespace

PtyEndpoint::PtyEndpoint(asio::io_context& io, Device& device, std::string symlink_path,
                         std::shared_ptr<spdlog::logger> log, InotifyWatcher& watcher, long group)
    : device_(device), master_(io), watcher_(watcher), pacing_timer_(io), hangup_timer_(io),
      symlink_path_(std::move(symlink_path)), group_(group), log_(std::move(log))
{
    make_pty();
    open_session();
}

void PtyEndpoint::make_pty()
{
    int master = -1;
    char name[PATH_MAX] = {};
    if (::openpty(&master, &slave_fd_, name, nullptr, nullptr) != 0)
        throw_errno("openpty failed");
    slave_name_ = name;
    // --pty-group: the group's members open it as they open a serial port (root:dialout 0660).
    if (group_ >= 0
        && (::fchown(slave_fd_, static_cast<uid_t>(-1), static_cast<gid_t>(group_)) != 0 || ::fchmod(slave_fd_, 0660) != 0)) {
        const int e = errno;
        ::close(master);
        ::close(slave_fd_);
        slave_fd_ = -1;
        errno = e;
        throw_errno("cannot give " + slave_name_ + " to group " + std::to_string(group_));
    }
    // Raw: no echo, no line editing, no CR/LF mapping. A client's own termios settings
    // (it opens the slave) replace these; the daemon resets only ECHO behind its back.
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
    std::weak_ptr<bool> alive = alive_;
    try {
        watch_ = watcher_.add(slave_name_, IN_OPEN | IN_CLOSE,
                              [this, alive](const std::vector<std::uint32_t>& masks) {
                                  if (alive.lock())
                                      on_open_events(masks);
                              });
        make_parent_dirs(symlink_path_);
        replace_symlink(slave_name_, symlink_path_);
    } catch (...) {
        watcher_.remove(watch_);
        watch_ = -1;
        boost::system::error_code ec;
        master_.close(ec);
        ::close(slave_fd_);
        slave_fd_ = -1;
        throw;
    }
}

PtyEndpoint::~PtyEndpoint()
{
    stop();
    alive_.reset();
    if (slave_fd_ >= 0)
        ::close(slave_fd_);
}

void PtyEndpoint::open_session()
{
    session_.reset();   // detach the old one from the device first
    std::weak_ptr<bool> alive = alive_;
    Connection conn;
    // A session of an earlier pty (before a hang-up) asks nothing of this one.
    conn.hangup = [this, alive, generation = generation_](Hangup how) {
        if (!alive.lock())
            return;
        asio::post(master_.get_executor(), [this, alive, generation, how] {
            if (alive.lock() && !stopped_ && generation == generation_)
                hang_up(how);
        });
    };
    conn.queued_bytes = [this, alive] { return alive.lock() ? queued_bytes_ : 0; };
    conn.max_queued_bytes = kMaxQueuedBytes;
    conn.frame_overhead = kQueuedFrameOverhead;
    conn.client_baud = [this, alive] { return alive.lock() ? client_baud() : 0; };
    session_ = device_.open_connection(
        [this, alive](std::string_view bytes) {
            if (alive.lock())
                send(bytes);
        },
        std::move(conn), "pty " + symlink_path_);
}

std::uint32_t PtyEndpoint::client_baud() const
{
    struct termios tio {};
    if (slave_fd_ < 0 || ::tcgetattr(slave_fd_, &tio) != 0)
        return 0;
    return baud_of(::cfgetospeed(&tio));
}

void PtyEndpoint::hang_up(Hangup how)
{
    if (stopped_ || hanging_up_)
        return;
    // The session goes now: the device hears nothing more of this line.
    session_.reset();
    hanging_up_ = true;
    if (how == Hangup::Close && openers_ > 0) {
        hangup_deadline_ = std::chrono::steady_clock::now() + kHangupDrain;
        empty_looks_ = 0;
        wait_until_read();
        return;
    }
    replace_pty();
}

void PtyEndpoint::wait_until_read()
{
    // A pty tells nobody when its reader has caught up: look every few milliseconds until
    // the queue is written and the slave's input is empty, or the client has closed the port.
    // Bytes written to the master reach the slave's input a moment later (the kernel's flip
    // buffer is pushed by a worker), so empty counts only when two looks in a row find it so.
    int unread = 0;
    if (queue_.empty() && ::ioctl(slave_fd_, FIONREAD, &unread) == 0 && unread == 0) {
        if (++empty_looks_ >= 2) {
            replace_pty();
            return;
        }
    } else {
        empty_looks_ = 0;
    }
    if (openers_ == 0 || std::chrono::steady_clock::now() >= hangup_deadline_) {
        replace_pty();
        return;
    }
    hangup_timer_.expires_after(std::chrono::milliseconds(2));
    std::weak_ptr<bool> alive = alive_;
    hangup_timer_.async_wait([this, alive](const boost::system::error_code& ec) {
        if (!alive.lock() || stopped_ || ec)
            return;
        watcher_.drain();   // a close of the port ends the wait
        wait_until_read();
    });
}

void PtyEndpoint::replace_pty()
{
    // Closing the master hangs the slave up for every process that has it open (reads give
    // end of file, writes EIO, poll POLLHUP); the symlink then points at a fresh pty, as a USB
    // serial adapter that is unplugged and plugged in again comes back under its name.
    log_->info("pty {}: hung up by a wire fault ({} replaced)", symlink_path_, slave_name_);
    ++generation_;
    watcher_.remove(watch_);
    watch_ = -1;
    boost::system::error_code ec;
    master_.cancel(ec);
    master_.close(ec);
    pacing_timer_.cancel();
    ::close(slave_fd_);
    slave_fd_ = -1;
    openers_ = 0;
    leftovers_.clear();
    queue_.clear();
    front_written_ = 0;
    queued_bytes_ = 0;
    dropping_ = false;
    abandon_front_ = false;
    hanging_up_ = false;
    try {
        make_pty();
    } catch (const std::system_error& e) {
        // Out of ptys or descriptors: the port stays gone; other devices are untouched.
        log_->error("pty {}: cannot open a new pty after the hang-up: {}", symlink_path_, e.what());
        stopped_ = true;
        ::unlink(symlink_path_.c_str());   // it names the pty that is gone
        return;
    }
    open_session();
    read();
}

void PtyEndpoint::start()
{
    read();
}

void PtyEndpoint::on_open_events(const std::vector<std::uint32_t>& masks)
{
    if (stopped_)
        return;
    for (auto it = masks.begin(); it != masks.end(); ++it) {
        if (*it & IN_OPEN) {
            if (openers_++ == 0)
                log_->info("pty {}: opened", symlink_path_);
            continue;
        }
        if (!(*it & IN_CLOSE))
            continue;
        openers_ = std::max(0, openers_ - 1);
        if (openers_ > 0)
            continue;
        const bool reopened = std::any_of(it + 1, masks.end(), [](std::uint32_t m) { return (m & IN_OPEN) != 0; });
        if (!reopened) {
            close_port();
            continue;
        }
        // The next process has opened the port already, and its bytes may have been read
        // and answered before this close was: nothing is flushed, the line carries on.
        log_->info("pty {}: closed", symlink_path_);
    }
}

void PtyEndpoint::close_port()
{
    // Nobody listens any more: answers not read by now are lost, as on a serial line whose
    // host port is closed: flushed from the pty, dropped from the queue. None of them is a
    // later opener's: its IN_OPEN would have been queued before its first byte, so it would
    // be in the batch that ends here.
    ::tcflush(slave_fd_, TCIFLUSH);
    queue_.keep_front_only();
    queued_bytes_ = queue_.empty() ? 0 : queue_.front().size() + kQueuedFrameOverhead;
    if (!queue_.empty()) {
        // The front frame is waiting for the line or for room in the pty: cancel that
        // wait rather than let it reach the next opener (the read is cancelled with it and
        // started again by its handler).
        abandon_front_ = true;
        pacing_timer_.cancel();
        boost::system::error_code ec;
        master_.cancel(ec);
    }
    dropping_ = false;
    // What the process wrote before it closed the port is all in the master now (a read
    // of a pty waits for the line discipline's pending input): take it here, before a next
    // opener's bytes can follow it (logging the close first would let a client that waits
    // for the log line slip in), and hand it to the process's session from the loop (this
    // may run inside a call into the device). If somebody has opened the port since the
    // batch was read, the bytes may end with that opener's: they keep the session.
    Leftover left;
    char buf[4096];
    while (left.bytes.size() < kMaxQueuedBytes) {
        const auto n = ::read(master_.native_handle(), buf, sizeof buf);
        if (n <= 0)
            break;
        left.bytes.append(buf, static_cast<std::size_t>(n));
    }
    left.replace_session = left.bytes.empty() || !watcher_.has_pending(watch_);
    leftovers_.push_back(std::move(left));
    log_->info("pty {}: closed", symlink_path_);
    std::weak_ptr<bool> alive = alive_;
    asio::post(master_.get_executor(), [this, alive] {
        if (alive.lock() && !stopped_)
            finish_process();
    });
}

void PtyEndpoint::stop()
{
    if (stopped_)
        return;
    stopped_ = true;
    boost::system::error_code ec;
    master_.cancel(ec);
    master_.close(ec);
    watcher_.remove(watch_);
    pacing_timer_.cancel();
    hangup_timer_.cancel();
    // The io_context may outlive the device: nothing may reach it after this.
    session_.reset();
    leftovers_.clear();
    queue_.clear();
    front_written_ = 0;
    queued_bytes_ = 0;
    // Remove the symlink only if it is still ours.
    char target[PATH_MAX] = {};
    const auto n = ::readlink(symlink_path_.c_str(), target, sizeof target - 1);
    if (n > 0 && std::string(target, static_cast<std::size_t>(n)) == slave_name_)
        ::unlink(symlink_path_.c_str());
}

void PtyEndpoint::finish_process()
{
    while (!leftovers_.empty()) {
        const auto left = std::move(leftovers_.front());
        leftovers_.pop_front();
        if (!left.bytes.empty() && session_)
            session_->receive(left.bytes);
        // Whatever the process left unfinished in the framer is not the start of the next
        // opener's frame: the next one starts from an empty framer.
        if (left.replace_session && !hanging_up_)
            open_session();
    }
}

void PtyEndpoint::read()
{
    // Wait, then read here rather than let Asio read: the bytes must be taken after the
    // pending opens and closes are applied, so that a closing process's bytes and a next
    // opener's never meet in one read.
    std::weak_ptr<bool> alive = alive_;
    master_.async_wait(asio::posix::stream_descriptor::wait_read,
        [this, alive, generation = generation_](const boost::system::error_code& ec) {
            if (!alive.lock() || stopped_ || generation != generation_)
                return;
            if (ec == asio::error::operation_aborted) {
                read();   // cancelled with an abandoned write (close_port)
                return;
            }
            if (ec) {
                log_->error("pty {}: wait for input failed: {}", symlink_path_, ec.message());
                return;
            }
            if (take_input())
                read();
        });
}

bool PtyEndpoint::take_input()
{
    watcher_.drain();    // an open always precedes the opener's first bytes
    finish_process();    // a close seen now: the closing process's bytes go to its session
    const auto n = ::read(master_.native_handle(), buffer_.data(), buffer_.size());
    if (n < 0 && errno != EAGAIN && errno != EINTR) {
        // EIO cannot happen while slave_fd_ is open; anything else ends the pty.
        log_->error("pty {}: read failed: {}", symlink_path_, std::strerror(errno));
        return false;
    }
    if (n > 0 && session_)   // no session while a hang-up waits for the client to read
        session_->receive(std::string_view(buffer_.data(), static_cast<std::size_t>(n)));
    finish_process();    // a close seen while the device answered
    return true;
}

void PtyEndpoint::send(std::string_view bytes)
{
    if (stopped_ || hanging_up_)
        return;
    if (openers_ == 0)
        watcher_.drain();
    // Nobody has the port open: lost, as on a real serial line. (Bytes sent just before a
    // close that is not yet seen stay in the pty until the close is seen and flushes them.)
    if (openers_ == 0)
        return;
    const auto cost = bytes.size() + kQueuedFrameOverhead;
    if (queued_bytes_ + cost > kMaxQueuedBytes) {
        if (!dropping_)
            log_->warn("pty {}: nobody reads the port, dropping output", symlink_path_);
        dropping_ = true;
        return;
    }
    dropping_ = false;
    std::size_t written = 0;
    if (queue_.empty() && device_.serial_baud() == 0) {
        // Nothing ahead of it and no line to pace: written now, as far as the pty takes it (an
        // answer, whole); only what it leaves waits for the client to read.
        keep_echo_off();
        const auto n = ::write(master_.native_handle(), bytes.data(), bytes.size());
        if (n < 0 && errno != EAGAIN && errno != EINTR) {
            log_->error("pty {}: write failed: {}", symlink_path_, std::strerror(errno));
            return;
        }
        written = n > 0 ? static_cast<std::size_t>(n) : 0;
        if (written == bytes.size())
            return;
    }
    // Counted whole until written whole, its part already written included.
    queued_bytes_ += cost;
    queue_.push_back(bytes);
    if (queue_.size() == 1) {
        front_written_ = written;
        write();
    }
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
    pacing_timer_.async_wait([this, alive, generation = generation_](const boost::system::error_code& ec) {
        if (!alive.lock() || stopped_ || generation != generation_)
            return;
        if (abandon_front_) {
            drop_abandoned_front();
            return;
        }
        if (!ec)
            paced_write();
    });
}

void PtyEndpoint::drop_abandoned_front()
{
    abandon_front_ = false;
    queued_bytes_ -= queue_.front().size() + kQueuedFrameOverhead;
    queue_.pop_front();
    front_written_ = 0;
    if (!queue_.empty())
        write();
}

void PtyEndpoint::keep_echo_off()
{
    struct termios tio {};
    if (::tcgetattr(slave_fd_, &tio) != 0 || !(tio.c_lflag & (ECHO | ECHONL)))
        return;
    tio.c_lflag &= ~static_cast<tcflag_t>(ECHO | ECHONL);
    if (::tcsetattr(slave_fd_, TCSANOW, &tio) == 0)
        log_->info("pty {}: the client turned echo on; turned it off (a serial line does not echo)",
                   symlink_path_);
}

void PtyEndpoint::paced_write()
{
    // Checked before every write: a client may change its termios at any time, and the
    // echo of this write would come back as input.
    keep_echo_off();
    std::weak_ptr<bool> alive = alive_;
    const auto front = queue_.front();
    asio::async_write(master_, asio::buffer(front.data() + front_written_, front.size() - front_written_),
        [this, alive, generation = generation_](const boost::system::error_code& ec, std::size_t) {
            if (!alive.lock() || stopped_ || generation != generation_)
                return;
            if (ec) {
                if (ec == asio::error::operation_aborted) {
                    if (abandon_front_)
                        drop_abandoned_front();
                    return;
                }
                // The pending frames are lost; an empty queue lets the next answer try again.
                log_->error("pty {}: write failed: {}", symlink_path_, ec.message());
                queue_.clear();
                front_written_ = 0;
                queued_bytes_ = 0;
                abandon_front_ = false;
                return;
            }
            queued_bytes_ -= queue_.front().size() + kQueuedFrameOverhead;
            queue_.pop_front();
            front_written_ = 0;
            // Written in part before the close cancelled it, the rest after the close
            // flushed the pty: flush it too. A next opener may have the port already, but
            // its answers queue behind this frame: nothing of its own is in the pty yet.
            if (abandon_front_) {
                abandon_front_ = false;
                ::tcflush(slave_fd_, TCIFLUSH);
            }
            if (!queue_.empty())
                write();
        });
}

} // namespace rigsim
