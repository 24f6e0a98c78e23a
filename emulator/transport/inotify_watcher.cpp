#include "emulator/transport/inotify_watcher.hpp"

#include <algorithm>
#include <cerrno>
#include <fstream>
#include <sys/inotify.h>
#include <system_error>
#include <unistd.h>
#include <vector>

namespace rigsim {

namespace asio = boost::asio;

namespace {

/// The value of a /proc/sys setting, or "?" if it cannot be read.
std::string proc_value(const std::string& path)
{
    std::ifstream f(path);
    std::string v;
    if (!(f >> v))
        return "?";
    return v;
}

/// errno as an exception whose message names the limit the kernel hit: EMFILE from
/// inotify_init1 blames "Too many open files" for the per-user instance limit too.
[[noreturn]] void throw_inotify_error(int e, const std::string& what)
{
    std::string hint;
    if (e == EMFILE && what.rfind("inotify_init1", 0) == 0)
        hint = " (the per-user inotify instance limit /proc/sys/fs/inotify/max_user_instances is "
               + proc_value("/proc/sys/fs/inotify/max_user_instances")
               + ", shared by all of this user's processes; or the open-file limit, ulimit -n)";
    else if (e == ENOSPC)
        hint = " (the per-user inotify watch limit /proc/sys/fs/inotify/max_user_watches is "
               + proc_value("/proc/sys/fs/inotify/max_user_watches") + ")";
    throw std::system_error(e, std::generic_category(), what + hint);
}

} // namespace

InotifyWatcher::InotifyWatcher(asio::io_context& io) : fd_(io)
{
    const int fd = ::inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    if (fd < 0)
        throw_inotify_error(errno, "inotify_init1: cannot watch the ptys' openers");
    fd_.assign(fd);
}

InotifyWatcher::~InotifyWatcher()
{
    stop();
    alive_.reset();
}

int InotifyWatcher::add(const std::string& path, std::uint32_t mask, Handler handler)
{
    const int wd = ::inotify_add_watch(fd_.native_handle(), path.c_str(), mask);
    if (wd < 0)
        throw_inotify_error(errno, "inotify_add_watch: cannot watch " + path);
    handlers_[wd] = std::move(handler);
    return wd;
}

void InotifyWatcher::remove(int wd)
{
    if (handlers_.erase(wd) > 0 && fd_.is_open())
        ::inotify_rm_watch(fd_.native_handle(), wd);
}

void InotifyWatcher::start()
{
    wait();
}

void InotifyWatcher::stop()
{
    if (stopped_)
        return;
    stopped_ = true;
    handlers_.clear();
    pending_.clear();
    boost::system::error_code ec;
    fd_.close(ec);
}

void InotifyWatcher::wait()
{
    std::weak_ptr<bool> alive = alive_;
    fd_.async_wait(asio::posix::stream_descriptor::wait_read,
        [this, alive](const boost::system::error_code& ec) {
            if (!alive.lock() || stopped_ || ec)
                return;
            drain();
            wait();
        });
}

void InotifyWatcher::read_pending()
{
    if (stopped_)
        return;
    alignas(inotify_event) char buf[4096];
    while (true) {
        const auto n = ::read(fd_.native_handle(), buf, sizeof buf);
        if (n <= 0)
            return;   // EAGAIN: nothing pending
        for (std::size_t off = 0; off + sizeof(inotify_event) <= static_cast<std::size_t>(n);) {
            const auto* e = reinterpret_cast<const inotify_event*>(buf + off);
            off += sizeof(inotify_event) + e->len;
            pending_.push_back(Event{e->wd, e->mask});
        }
    }
}

bool InotifyWatcher::has_pending(int wd)
{
    read_pending();
    return std::any_of(pending_.begin(), pending_.end(), [wd](const Event& e) { return e.wd == wd; });
}

void InotifyWatcher::dispatch(const std::vector<Event>& batch)
{
    std::map<int, std::vector<std::uint32_t>> by_watch;
    for (const auto& e : batch)
        by_watch[e.wd].push_back(e.mask);
    for (const auto& [wd, masks] : by_watch) {
        // Unknown descriptors: IN_IGNORED after remove(), or events queued before it.
        const auto it = handlers_.find(wd);
        if (it == handlers_.end())
            continue;
        const auto handler = it->second;   // a copy: the handler may remove its watch
        handler(masks);
    }
}

void InotifyWatcher::drain()
{
    read_pending();
    if (dispatching_)
        return;
    struct Dispatching {
        bool& flag;
        explicit Dispatching(bool& f) : flag(f) { flag = true; }
        ~Dispatching() { flag = false; }
    } guard(dispatching_);
    // Events a handler read (has_pending) follow as the next batch.
    while (!pending_.empty() && !stopped_) {
        std::vector<Event> batch;
        batch.swap(pending_);
        dispatch(batch);
    }
    pending_.clear();
}

} // namespace rigsim
