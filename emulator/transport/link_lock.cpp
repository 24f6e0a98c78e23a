#include "emulator/transport/link_lock.hpp"

#include <cerrno>
#include <cstdlib>
#include <fcntl.h>
#include <sys/stat.h>
#include <system_error>
#include <unistd.h>

namespace rigsim {

namespace {

[[noreturn]] void throw_errno(int e, const std::string& what)
{
    throw std::system_error(e, std::generic_category(), what);
}

/// The message of LinkInUse.
std::string in_use_text(const std::string& link, pid_t pid)
{
    const std::string who = pid > 0 ? "a running rigsimd (pid " + std::to_string(pid) + ")"
                                    : "a running rigsimd (pid unknown: another pid namespace)";
    return "pty link " + link + " is in use by " + who + "; stop that daemon, give this one another --pty-dir"
           " (or other pty paths), or pass --replace-links to take its links over";
}

/// True if `fd` is still the file at `path` (not unlinked or replaced since it was opened).
bool is_file_at(int fd, const std::string& path)
{
    struct stat by_fd {};
    struct stat by_path {};
    return ::fstat(fd, &by_fd) == 0 && ::lstat(path.c_str(), &by_path) == 0 && by_fd.st_dev == by_path.st_dev
           && by_fd.st_ino == by_path.st_ino;
}

/// The pid of the process whose lock conflicts with ours on `fd`: the kernel's answer, else
/// the pid the holder wrote in the file, else 0.
pid_t holder_of(int fd)
{
    struct flock fl {};
    fl.l_type = F_WRLCK;
    fl.l_whence = SEEK_SET;
    if (::fcntl(fd, F_GETLK, &fl) == 0 && fl.l_type != F_UNLCK && fl.l_pid > 0)
        return fl.l_pid;
    char text[32] = {};
    if (::pread(fd, text, sizeof text - 1, 0) <= 0)
        return 0;
    const long pid = std::strtol(text, nullptr, 10);
    return pid > 0 ? static_cast<pid_t>(pid) : 0;
}

/// Our pid as the file's content, for people who look; false if it could not be written
/// (the lock, not the text, is what counts).
bool write_pid(int fd)
{
    const auto text = std::to_string(::getpid()) + "\n";
    return ::ftruncate(fd, 0) == 0
           && ::pwrite(fd, text.data(), text.size(), 0) == static_cast<ssize_t>(text.size());
}

} // namespace

std::optional<std::string> unsafe_link_dir(const std::string& dir, uid_t owner)
{
    struct stat st {};
    if (::stat(dir.c_str(), &st) != 0)
        return std::nullopt;   // creating or using it fails with its own message
    if (!S_ISDIR(st.st_mode))
        return std::nullopt;
    const auto who = "the pty directory " + dir;
    const auto advice = "another user could replace its links with their own: give --pty-dir a directory of your "
                        "own (or pty paths in one)";
    if (st.st_uid != owner && st.st_uid != 0)
        return who + " belongs to uid " + std::to_string(st.st_uid) + ", not to this user (uid "
               + std::to_string(owner) + ") or root: " + advice;
    // A sticky directory (/tmp) lets no one else remove or rename what this user puts there.
    if ((st.st_mode & (S_IWGRP | S_IWOTH)) != 0 && (st.st_mode & S_ISVTX) == 0)
        return who + " is writable by " + ((st.st_mode & S_IWOTH) != 0 ? "everyone" : "its group")
               + " and not sticky: " + advice;
    return std::nullopt;
}

UnsafeLinkDir::UnsafeLinkDir(const std::string& why) : std::runtime_error(why) {}

LinkInUse::LinkInUse(const std::string& link, pid_t pid)
    : std::runtime_error(in_use_text(link, pid)), link_(link), pid_(pid)
{
}

std::string link_lock_path(const std::string& link_path)
{
    const auto slash = link_path.rfind('/');
    const auto dir = slash == std::string::npos ? std::string() : link_path.substr(0, slash + 1);
    const auto name = slash == std::string::npos ? link_path : link_path.substr(slash + 1);
    return dir + "." + name + ".lock";
}

void make_parent_dirs(const std::string& path)
{
    for (auto pos = path.find('/', 1); pos != std::string::npos; pos = path.find('/', pos + 1)) {
        const auto dir = path.substr(0, pos);
        if (::mkdir(dir.c_str(), 0755) != 0 && errno != EEXIST)
            throw_errno(errno, "cannot create directory " + dir);
    }
}

LinkLock::LinkLock(const std::string& link_path, bool replace) : path_(link_lock_path(link_path))
{
    make_parent_dirs(link_path);
    const auto slash = link_path.rfind('/');
    if (const auto why = unsafe_link_dir(slash == 0 ? "/" : link_path.substr(0, slash), ::geteuid()))
        throw UnsafeLinkDir(*why);
    // A file unlinked or replaced between our open and our lock is not the lock any more:
    // try the one at the path now. Bounded, so that a file someone keeps replacing cannot
    // hold start-up forever.
    for (int attempt = 0; attempt < 16; ++attempt) {
        const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
        if (fd < 0)
            throw_errno(errno, "cannot open the lock file " + path_ + " of pty link " + link_path);
        struct flock fl {};
        fl.l_type = F_WRLCK;
        fl.l_whence = SEEK_SET;
        if (::fcntl(fd, F_SETLK, &fl) == 0) {
            if (is_file_at(fd, path_)) {
                write_pid(fd);
                fd_ = fd;
                return;
            }
            ::close(fd);
            continue;
        }
        const int e = errno;
        if (e != EACCES && e != EAGAIN) {
            ::close(fd);
            throw_errno(e, "cannot lock " + path_ + " of pty link " + link_path);
        }
        const pid_t holder = holder_of(fd);
        if (!replace) {
            ::close(fd);
            throw LinkInUse(link_path, holder);
        }
        // Told to replace: the live daemon keeps its lock on a file that is no longer there.
        if (is_file_at(fd, path_))
            ::unlink(path_.c_str());
        ::close(fd);
        replaced_pid_ = holder;
    }
    throw_errno(EBUSY, "cannot lock " + path_ + " of pty link " + link_path + ": it keeps being replaced");
}

LinkLock::LinkLock(LinkLock&& other) noexcept
    : path_(std::move(other.path_)), fd_(other.fd_), replaced_pid_(other.replaced_pid_)
{
    other.fd_ = -1;
}

LinkLock::~LinkLock()
{
    if (fd_ < 0)
        return;
    // Unlink first: a daemon that opens the file meanwhile gets the lock on a file no longer
    // at the path, sees so and makes a new one.
    if (is_file_at(fd_, path_))
        ::unlink(path_.c_str());
    ::close(fd_);
}

} // namespace rigsim
