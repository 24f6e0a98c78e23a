#pragma once
// Pseudo-terminal endpoint of one device: what a legacy application opens as its serial port.
//
// openpty + cfmakeraw + a stable symlink (simavr's uart_pty). The daemon keeps its own
// descriptor of the slave side open for its whole life, so the master never sees a hang-up:
// a client may open, close and reopen the port and change its termios settings (baud rate,
// flow control) while the device keeps its state, as a controller on a real serial line
// would. The serial line is one connection: one Session for all processes that have it open
// at the same time.
//
// Like a real serial port, what the device sends while no application has the port open
// is lost: inotify reports opens and closes of the slave device (one inotify instance per
// daemon, InotifyWatcher), and when the last client closes it, the answers it never read are
// flushed, so the next opener never reads stale answers. Open events are drained before any
// input is handled, so a client that opens the port and writes at once always gets its answer.
// When the last client closes the port, the bytes it wrote are still handed to its Session
// (read from the master at once, before a next opener can add its own), then the Session is
// replaced: the next opener starts from an empty framer, its first bytes never glued to a
// frame or line that the previous process left unfinished.
//
// On a real serial port one process's close never takes bytes from the next, and here
// neither: the events and the bytes come on two descriptors, so a process may open the
// port, write and even be answered before the daemon has read the previous process's close.
// The port counts as closed only when the events queued so far leave nobody with it open
// (InotifyWatcher hands "closed, opened again" over as one batch): then no byte read from the
// master, and no answer in the pty or the queue, can be the next opener's, since an opener's
// IN_OPEN is queued before its first byte. A close the next opener has already followed
// flushes nothing and keeps the Session: the line simply carries on, as a real one does, and
// the new process may read what the old one left unread. Likewise the bytes read at the last
// close feed the old Session, which is replaced only if nobody had opened the port again by
// the time they were read (or they were none): otherwise they may end with the next opener's
// first request.
//
// A real serial line never echoes. A pty slave with ECHO set (a naive client that skips
// cfmakeraw, `cat`) would send every answer back to the device as input, and the device
// would answer its own answers: before each write the daemon clears ECHO and ECHONL on the
// slave (it owns the line, as a UART does), leaving every other setting to the client.
//
// A wire fault may end the line (Connection::hangup): a serial line has no end of stream, but a
// USB serial adapter that goes away does, and so does the pty: the master is closed, so every
// process that has the slave open sees a hang-up (read gives end of file, write EIO, poll
// POLLHUP), and a new pty with a new session takes the symlink, as the adapter comes back
// under its name. Hangup::Close waits (at most kHangupDrain) until the client has read what was
// written; Hangup::Reset does not.

#include "emulator/core/device.hpp"
#include "emulator/core/frame_queue.hpp"
#include "emulator/transport/inotify_watcher.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>
#include <boost/asio/steady_timer.hpp>
#include <spdlog/logger.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

namespace rigsim {

class PtyEndpoint {
public:
    /// Output that no client reads is dropped beyond this, as on an unread serial line.
    static constexpr std::size_t kMaxQueuedBytes = 1 << 20;
    /// What a queued frame is counted beyond its bytes against kMaxQueuedBytes, so that the
    /// bound is one of memory rather than payload (as TcpEndpoint::kQueuedFrameOverhead).
    static constexpr std::size_t kQueuedFrameOverhead = 64;
    /// A hang-up the wire asks for after what was sent (Hangup::Close) waits at most this long
    /// for the client to read it.
    static constexpr std::chrono::seconds kHangupDrain{2};

    /// Creates the pty, its watch on `watcher` and the symlink at once (throws
    /// std::system_error if it cannot). `watcher` must outlive the endpoint. With `group` >= 0
    /// (--pty-group), the pty device belongs to that group with mode 0660, as a serial port does
    /// (every pty the endpoint makes: a hang-up's replacement too); -1 leaves it as openpty made
    /// it (the daemon's user's, mode 0620).
    PtyEndpoint(boost::asio::io_context& io, Device& device, std::string symlink_path,
                std::shared_ptr<spdlog::logger> log, InotifyWatcher& watcher, long group = -1);
    ~PtyEndpoint();
    PtyEndpoint(const PtyEndpoint&) = delete;
    PtyEndpoint& operator=(const PtyEndpoint&) = delete;

    const std::string& symlink_path() const { return symlink_path_; }
    const std::string& device_path() const { return slave_name_; }
    void start();
    /// Stop I/O, release the session and remove the symlink.
    void stop();

private:
    void read();
    /// Reads input into the session, in order with the opens and closes of the port;
    /// false if the pty failed.
    bool take_input();
    /// Feeds the leftovers to the session, replacing it after each where that is due.
    void finish_process();
    void send(std::string_view bytes);
    void write();
    /// The opens and closes of the slave device that one drain of the watcher read, in order.
    void on_open_events(const std::vector<std::uint32_t>& masks);
    /// The last client closed the port and nobody has opened it since: flush what it did not
    /// read and take what it wrote.
    void close_port();
    void open_session();
    /// A UART does not echo: clears ECHO and ECHONL if the client set them.
    void keep_echo_off();
    /// openpty, raw mode, the watch and the symlink (throws std::system_error).
    void make_pty();
    /// The rate the client set on the line (termios), 0 when not a standard one.
    std::uint32_t client_baud() const;
    /// The wire asked for a hang-up (Connection::hangup): at once, or once the client has read
    /// what was written (Hangup::Close).
    void hang_up(Hangup how);
    void wait_until_read();
    /// Closes the pty (every process that has the slave open sees a hang-up) and puts a new one,
    /// with a new session, behind the symlink.
    void replace_pty();

    /// Faithful timing: a frame leaves once the line has had time to transmit it at the
    /// device's baud rate (10 bits per byte: 8N1).
    void paced_write();
    /// Drops the front frame, whose write the last client's close cancelled, and goes on.
    void drop_abandoned_front();

    Device& device_;
    boost::asio::posix::stream_descriptor master_;
    InotifyWatcher& watcher_;
    int watch_ = -1;
    boost::asio::steady_timer pacing_timer_;
    boost::asio::steady_timer hangup_timer_;
    std::chrono::steady_clock::time_point hangup_deadline_{};
    bool hanging_up_ = false;        ///< a hang-up waits for the client to read
    int empty_looks_ = 0;            ///< looks in a row that found the client had read everything
    std::uint64_t generation_ = 0;   ///< pty replaced by hang-ups so far: older handlers stand down
    std::chrono::steady_clock::time_point line_free_{};
    /// What the last client wrote, read when it closed the port.
    struct Leftover {
        std::string bytes;
        bool replace_session = false;   ///< then a fresh session for the next opener
    };
    int openers_ = 0;   ///< client descriptors open on the slave (ours not counted)
    std::deque<Leftover> leftovers_;
    int slave_fd_ = -1;
    std::string slave_name_;
    std::string symlink_path_;
    long group_ = -1;   ///< --pty-group: the pty device's group, or -1
    std::shared_ptr<spdlog::logger> log_;
    std::unique_ptr<Session> session_;
    std::array<char, 4096> buffer_{};
    FrameQueue queue_;   ///< what the pty did not take yet, in pages of its own
    std::size_t front_written_ = 0;   ///< bytes of the front frame send() wrote before queuing it
    std::size_t queued_bytes_ = 0;
    bool dropping_ = false;
    bool abandon_front_ = false;   ///< the front frame was queued for a client now gone
    bool stopped_ = false;
    std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

} // namespace rigsim
