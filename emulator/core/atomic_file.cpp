#include "emulator/core/atomic_file.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <random>
#include <system_error>

namespace rigsim {

namespace {

[[noreturn]] void fail_with(int error, const std::string& what)
{
    throw std::system_error(error, std::generic_category(), what);
}

std::string directory_of(const std::string& path)
{
    const auto slash = path.rfind('/');
    if (slash == std::string::npos)
        return ".";
    return slash == 0 ? "/" : path.substr(0, slash);
}

std::string name_of(const std::string& path)
{
    const auto slash = path.rfind('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string random_suffix()
{
    static constexpr char kChars[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
    thread_local std::mt19937_64 generator{std::random_device{}()};
    std::uniform_int_distribution<std::size_t> pick(0, sizeof(kChars) - 2);
    std::string s;
    for (int i = 0; i < 8; ++i)
        s += kChars[pick(generator)];
    return s;
}

/// Writes all of `text` to `fd`, then fsync; returns 0 or the errno.
int write_and_sync(int fd, const std::string& text)
{
    std::size_t done = 0;
    while (done < text.size()) {
        const auto n = ::write(fd, text.data() + done, text.size() - done);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            return errno;
        }
        done += static_cast<std::size_t>(n);
    }
    return ::fsync(fd) == 0 ? 0 : errno;
}

/// After a rename or create in `dir`: the new directory entry itself must reach the disk.
void sync_directory(const std::string& dir)
{
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        fail_with(errno, "cannot open directory " + dir + " to sync it");
    // EINVAL: a file system that cannot sync directories (nothing more to do there).
    const int rc = ::fsync(fd) == 0 || errno == EINVAL ? 0 : errno;
    ::close(fd);
    if (rc != 0)
        fail_with(rc, "cannot sync directory " + dir);
}

/// Opens `path` for a new file (O_EXCL|O_NOFOLLOW: an existing file or link is not touched);
/// returns the fd, or -1 with errno.
int create_new(const std::string& path)
{
    return ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
}

/// True for "<name>.tmp<digits>" and "<name>.tmp<digits>.<alnum>"; `pid` gets the digits.
bool is_temporary_of(const std::string& entry, const std::string& name, long& pid)
{
    const std::string prefix = name + ".tmp";
    if (entry.size() <= prefix.size() || entry.compare(0, prefix.size(), prefix) != 0)
        return false;
    std::size_t i = prefix.size();
    const std::size_t digits_from = i;
    while (i < entry.size() && entry[i] >= '0' && entry[i] <= '9')
        ++i;
    if (i == digits_from || i - digits_from > 10)
        return false;
    pid = std::strtol(entry.c_str() + digits_from, nullptr, 10);
    if (i == entry.size())
        return true;
    if (entry[i] != '.' || i + 1 == entry.size())
        return false;
    for (++i; i < entry.size(); ++i) {
        const char c = entry[i];
        if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z')))
            return false;
    }
    return true;
}

} // namespace

std::string resolve_symlinks(const std::string& path)
{
    std::string p = path;
    for (int hops = 0; hops < 40; ++hops) {
        struct stat st {};
        if (::lstat(p.c_str(), &st) != 0) {
            if (errno == ENOENT)
                return p;   // the file a write creates
            fail_with(errno, "cannot examine " + p);
        }
        if (!S_ISLNK(st.st_mode))
            return p;
        std::string target(static_cast<std::size_t>(st.st_size > 0 ? st.st_size : 255) + 1, '\0');
        const auto n = ::readlink(p.c_str(), target.data(), target.size());
        if (n < 0)
            fail_with(errno, "cannot read the symlink " + p);
        target.resize(static_cast<std::size_t>(n));
        p = !target.empty() && target[0] == '/' ? target : directory_of(p) + "/" + target;
    }
    fail_with(ELOOP, "cannot follow the symlink " + path);
}

void write_file_atomically(const std::string& path, const std::string& text)
{
    const auto dest = resolve_symlinks(path);
    std::string tmp;
    int fd = -1;
    for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
        tmp = dest + ".tmp" + std::to_string(::getpid()) + "." + random_suffix();
        fd = create_new(tmp);
        if (fd < 0 && errno != EEXIST)
            fail_with(errno, "cannot create " + tmp);
    }
    if (fd < 0)
        fail_with(EEXIST, "cannot create a temporary file beside " + dest);

    // A replaced file keeps its permissions (a lab may have made it group-writable).
    struct stat existing {};
    int rc = 0;
    if (::stat(dest.c_str(), &existing) == 0 && S_ISREG(existing.st_mode))
        rc = ::fchmod(fd, existing.st_mode & 07777) == 0 ? 0 : errno;
    if (rc == 0)
        rc = write_and_sync(fd, text);
    if (::close(fd) != 0 && rc == 0)
        rc = errno;
    if (rc == 0 && ::rename(tmp.c_str(), dest.c_str()) != 0)
        rc = errno;
    if (rc != 0) {
        ::unlink(tmp.c_str());
        fail_with(rc, "cannot write " + dest + " (through " + tmp + ")");
    }
    sync_directory(directory_of(dest));
}

std::vector<std::string> remove_stale_temporaries(const std::string& path)
{
    const auto dest = resolve_symlinks(path);
    const auto dir = directory_of(dest);
    const auto name = name_of(dest);
    std::vector<std::string> removed;
    DIR* d = ::opendir(dir.c_str());
    if (!d)
        return removed;
    while (const dirent* e = ::readdir(d)) {
        const std::string entry = e->d_name;
        long pid = 0;
        if (!is_temporary_of(entry, name, pid))
            continue;
        // kill(pid, 0): ESRCH means no such process; EPERM is someone else's live process.
        const bool running = pid > 0 && pid <= 0x7fffffff
                             && (pid == ::getpid() || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH);
        if (running)
            continue;
        const auto full = dir + "/" + entry;
        if (::unlink(full.c_str()) == 0)
            removed.push_back(full);
    }
    ::closedir(d);
    return removed;
}

std::string write_new_file(const std::string& base, const std::string& text)
{
    for (int n = 0; n < 1000; ++n) {
        const auto path = n == 0 ? base : base + "." + std::to_string(n);
        const int fd = create_new(path);
        if (fd < 0) {
            if (errno == EEXIST)
                continue;
            fail_with(errno, "cannot create " + path);
        }
        int rc = write_and_sync(fd, text);
        if (::close(fd) != 0 && rc == 0)
            rc = errno;
        if (rc != 0) {
            ::unlink(path.c_str());
            fail_with(rc, "cannot write " + path);
        }
        sync_directory(directory_of(path));
        return path;
    }
    fail_with(EEXIST, "cannot create " + base + " or " + base + ".1 to .999");
}

} // namespace rigsim
