#pragma once
// One inotify instance for the whole daemon, shared by every pty endpoint.
//
// Linux limits inotify instances per user (/proc/sys/fs/inotify/max_user_instances, 128 by
// default) far more tightly than watches (max_user_watches): one instance per pty capped a
// user at about a hundred devices across all daemons. Here each pty costs one watch on the
// one descriptor, and events go to the endpoint whose watch descriptor they carry.
//
// The kernel queues a process's IN_OPEN before its open() returns and its IN_CLOSE before
// its close() returns, so the events of one watch come in the order the opens and closes
// happened; but they reach the daemon on another descriptor than the bytes, so a drain may
// find a close whose successor has already opened the port (and written to it). A drain
// therefore reads every event queued before it dispatches any, and hands each watch its
// events together: an endpoint sees "closed, opened again" as one batch, never the close
// alone.

#include <boost/asio/io_context.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace rigsim {

class InotifyWatcher {
public:
    /// Receives the masks of the watched path's events that one drain read, in their order.
    using Handler = std::function<void(const std::vector<std::uint32_t>& masks)>;

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
    /// handles input, so that an open always precedes the opener's first bytes). Called
    /// while events are being dispatched, it only reads them: the running drain hands them
    /// out after the current batch.
    void drain();
    /// Reads the events queued now without dispatching them; true if one of them is for
    /// watch `wd` (a handler asks whether its path has been opened since its batch).
    bool has_pending(int wd);

private:
    struct Event {
        int wd;
        std::uint32_t mask;
    };
    void wait();
    /// Appends every event the kernel holds to pending_.
    void read_pending();
    /// Hands each watch its events of `batch`, in order.
    void dispatch(const std::vector<Event>& batch);

    boost::asio::posix::stream_descriptor fd_;
    std::map<int, Handler> handlers_;
    std::vector<Event> pending_;   ///< read, not dispatched yet
    bool dispatching_ = false;
    bool stopped_ = false;
    std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

} // namespace rigsim
