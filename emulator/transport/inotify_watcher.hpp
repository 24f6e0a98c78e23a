#pragma once
// One inotify instance for the whole daemon, shared by every pty endpoint.
//
// Linux limits inotify instances per user (/proc/sys/fs/inotify/max_user_instances, 128 by
// default) far more tightly than watches (max_user_watches): one instance per pty capped a
// user at about a hundred devices across all daemons. Here each pty costs one watch on the
// one descriptor, and events go to the endpoint whose watch descriptor they carry.

#include <boost/asio/io_context.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>

namespace rigsim {

class InotifyWatcher {
public:
    /// Receives the event mask of one event on the watched path.
    using Handler = std::function<void(std::uint32_t mask)>;

    /// Creates the inotify instance (throws std::system_error naming the kernel limit).
    explicit InotifyWatcher(boost::asio::io_context& io);
    ~InotifyWatcher();
    InotifyWatcher(const InotifyWatcher&) = delete;
    InotifyWatcher& operator=(const InotifyWatcher&) = delete;

    /// Watches `path` for `mask`; returns the watch descriptor (throws std::system_error).
    int add(const std::string& path, std::uint32_t mask, Handler handler);
    /// Stops delivering events of watch `wd` (idempotent).
    void remove(int wd);
    /// Starts dispatching events as they arrive.
    void start();
    /// Stops dispatching and closes the descriptor.
    void stop();
    /// Reads and dispatches every pending event now (an endpoint calls this before it
    /// handles input, so that an open always precedes the opener's first bytes).
    void drain();

private:
    void wait();

    boost::asio::posix::stream_descriptor fd_;
    std::map<int, Handler> handlers_;
    bool stopped_ = false;
    std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

} // namespace rigsim
