#pragma once
// Which daemon a pty symlink belongs to, so that a second daemon on the same links does not
// silently take them over (and delete them when it exits, leaving the first without them).
//
// Beside each link `<dir>/<name>` the daemon that made it holds `<dir>/.<name>.lock` for its
// whole life: a POSIX record lock (fcntl F_SETLK), which the kernel releases when the process
// ends, however it ends. A held lock therefore means a live daemon, and F_GETLK names its
// pid; the file also holds that pid as text, for people. A link whose lock file is unlocked
// or missing was left by a daemon that died (kill -9) and is taken over without a word.
//
// Replacing a live daemon's links (--replace-links) unlinks its lock file and locks a fresh
// one in its place: a third daemon then names the second; the first, at exit, removes neither
// that file nor the links that no longer point at its ptys.
//
// Record locks belong to the process and go with any close of the file by it: the daemon
// opens each lock file once, here, and never elsewhere.

#include <sys/types.h>

#include <optional>
#include <stdexcept>
#include <string>

namespace rigsim {

/// Why the directory `dir` holding pty links is unsafe for a daemon of uid `owner`, or nullopt:
/// it must belong to `owner` or root and be writable by no one else unless sticky (as /tmp is),
/// as OpenSSH's StrictModes and tmux ask of their directories. A directory that does not exist
/// is not judged here.
std::optional<std::string> unsafe_link_dir(const std::string& dir, uid_t owner);

/// The directory of a link is unsafe (unsafe_link_dir()).
class UnsafeLinkDir : public std::runtime_error {
public:
    explicit UnsafeLinkDir(const std::string& why);
};

/// A live process holds the link: its path and the holder's pid (0 if not known).
class LinkInUse : public std::runtime_error {
public:
    LinkInUse(const std::string& link, pid_t pid);
    const std::string& link() const { return link_; }
    pid_t pid() const { return pid_; }

private:
    std::string link_;
    pid_t pid_;
};

class LinkLock {
public:
    /// Locks the link at `link_path` for this process, creating the link's directory if
    /// missing. Throws UnsafeLinkDir if that directory is another user's or writable by others,
    /// LinkInUse if a live process holds it and `replace` is false, and
    /// std::system_error if the lock file cannot be made.
    LinkLock(const std::string& link_path, bool replace);
    /// Removes the lock file if it is still the one this lock made, then releases it.
    ~LinkLock();
    LinkLock(LinkLock&& other) noexcept;
    LinkLock& operator=(LinkLock&&) = delete;
    LinkLock(const LinkLock&) = delete;
    LinkLock& operator=(const LinkLock&) = delete;

    /// The lock file: `<dir>/.<name>.lock` for the link `<dir>/<name>`.
    const std::string& path() const { return path_; }
    /// The pid of the live process whose lock this one replaced (`replace`; 0 if not
    /// known), or nullopt if the link was nobody's.
    std::optional<pid_t> replaced_pid() const { return replaced_pid_; }

private:
    std::string path_;
    int fd_ = -1;
    std::optional<pid_t> replaced_pid_;
};

/// The lock file of the link at `link_path`.
std::string link_lock_path(const std::string& link_path);

/// mkdir -p for the directory that holds `path` (throws std::system_error).
void make_parent_dirs(const std::string& path);

} // namespace rigsim
