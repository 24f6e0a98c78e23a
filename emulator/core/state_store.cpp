#include "emulator/core/state_store.hpp"
#include "emulator/core/log_format.hpp"

#include "emulator/core/atomic_file.hpp"
#include "emulator/core/device.hpp"
#include "emulator/core/json_text.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace rigsim {

namespace {

/// A state file holds a few hundred bytes per device; anything this large is not one.
constexpr std::size_t kMaxStateFileBytes = 16 * 1024 * 1024;
/// Containers nested deeper than this are refused: rigsim writes three levels.
constexpr std::size_t kMaxStateDepth = 64;

std::runtime_error state_file_error(const std::string& path, const std::string& what)
{
    return std::runtime_error("state file " + path + ": " + what);
}

/// The content of `file`, or nullopt if there is no such file; throws naming `path` and the
/// reason for anything else (a directory, a device, EACCES, EIO, ...).
std::optional<std::string> read_state_file(const std::string& path, const std::string& file)
{
    struct stat st {};
    if (::stat(file.c_str(), &st) != 0) {
        if (errno == ENOENT)
            return std::nullopt;
        throw state_file_error(path, std::string("cannot read it: ") + std::strerror(errno));
    }
    if (S_ISDIR(st.st_mode))
        throw state_file_error(path, "is a directory, not a file");
    if (!S_ISREG(st.st_mode))
        throw state_file_error(path, "is not a regular file");
    // O_NONBLOCK: a pipe put there since the check would otherwise wait for a writer for ever.
    const int fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        throw state_file_error(path, std::string("cannot read it: ") + std::strerror(errno));
    std::string text;
    char buffer[65536];
    for (;;) {
        const auto n = ::read(fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0) {
            const int e = errno;
            ::close(fd);
            throw state_file_error(path, std::string("cannot read it: ") + std::strerror(e));
        }
        if (n == 0)
            break;
        text.append(buffer, static_cast<std::size_t>(n));
        if (text.size() > kMaxStateFileBytes) {
            ::close(fd);
            throw state_file_error(path, "larger than 16 MiB: not a rigsim state file");
        }
    }
    ::close(fd);
    return text;
}

std::string parent_of(const std::string& file)
{
    const auto slash = file.rfind('/');
    if (slash == std::string::npos)
        return ".";
    return slash == 0 ? "/" : file.substr(0, slash);
}

} // namespace

StateStore::StateStore(std::shared_ptr<spdlog::logger> log)
    : log_(log ? std::move(log) : spdlog::default_logger())
{
}

StateStore::StateStore(std::string path, std::shared_ptr<spdlog::logger> log, WriteFn write)
    : log_(log ? std::move(log) : spdlog::default_logger()), path_(std::move(path)),
      write_(write ? std::move(write) : WriteFn(write_file_atomically))
{
    try {
        file_ = resolve_symlinks(path_);
    } catch (const std::system_error& e) {
        throw state_file_error(path_, e.what());
    }
    const auto text = read_state_file(path_, file_);
    // Saves replace the file by a rename in its directory: find out now, not at the first save.
    const auto dir = parent_of(file_);
    if (::access(dir.c_str(), W_OK | X_OK) != 0)
        throw state_file_error(path_, "cannot write in " + dir + ": " + std::strerror(errno));
    if (text) {
        try {
            // Linear time and bounded depth; a key twice keeps the last, as the writer never
            // writes one twice.
            state_ = parse_json_text(*text, JsonTextLimits{kMaxStateDepth, false});
        } catch (const JsonTextError& e) {
            throw state_file_error(path_, std::string("not a rigsim state file: ") + e.what());
        }
        if (!state_.is_object())
            throw state_file_error(path_, "not a rigsim state file: expected an object");
        original_ = *text;
        for (auto it = state_.begin(); it != state_.end();) {
            if (it->is_object()) {
                ++it;
                continue;
            }
            log_->warn("state file {}: device \"{}\": skipped: expected an object of saved entries, got {}", path_,
                       printable(it.key(), 64), it->type_name());
            damaged_ = true;
            it = state_.erase(it);
        }
    }
    for (const auto& removed : remove_stale_temporaries(file_))
        log_->info("state file {}: removed {}, left by a rigsimd that was killed while saving", path_, removed);
    writer_ = std::thread([this] { writer_loop(); });
}

StateStore::~StateStore()
{
    if (!writer_.joinable())
        return;
    flush();
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    changed_.notify_all();
    writer_.join();
}

const nlohmann::json* StateStore::get(const std::string& device, const std::string& key) const
{
    const auto d = state_.find(device);
    if (d == state_.end() || !d->is_object())
        return nullptr;
    const auto k = d->find(key);
    return k == d->end() ? nullptr : &*k;
}

const nlohmann::json& StateStore::device_state(const std::string& device) const
{
    static const nlohmann::json kEmpty = nlohmann::json::object();
    const auto d = state_.find(device);
    return d == state_.end() || !d->is_object() ? kEmpty : *d;
}

void StateStore::set(const std::string& device, const std::string& key, nlohmann::json value)
{
    state_[device][key] = std::move(value);
    if (file_.empty())
        return;
    auto text = state_.dump(2) + "\n";
    {
        std::lock_guard<std::mutex> lock(mutex_);
        pending_ = std::move(text);
        ++saves_;
    }
    changed_.notify_all();
    if (sync_)
        flush();
}

void StateStore::erase(const std::string& device)
{
    if (state_.erase(device) == 0 || file_.empty())
        return;
    auto text = state_.dump(2) + "\n";
    {
        std::lock_guard<std::mutex> lock(mutex_);
        pending_ = std::move(text);
        ++saves_;
    }
    changed_.notify_all();
    if (sync_)
        flush();
}

void StateStore::reject(const std::string& device, const std::string& key, const std::string& why)
{
    log_->warn("state file {}: device \"{}\", key \"{}\": skipped: {}", file_.empty() ? "(in memory)" : path_,
               printable(device, 64), printable(key, 64), why);
    const auto d = state_.find(device);
    if (d != state_.end() && d->is_object())
        d->erase(key);
    std::lock_guard<std::mutex> lock(mutex_);
    damaged_ = damaged_ || original_.has_value();
}

void StateStore::flush()
{
    if (!writer_.joinable())
        return;
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return written_ >= saves_; });
}

void StateStore::writer_loop()
{
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
        changed_.wait(lock, [this] { return pending_ || stopping_; });
        if (!pending_)
            return;
        const auto text = std::move(*pending_);
        pending_.reset();
        const auto taken = saves_;
        const bool keep_first = damaged_ && original_;
        lock.unlock();

        // A file with damaged entries is evidence: keep it before the first rewrite, and
        // never overwrite it if that fails.
        const bool may_write = !keep_first || keep_damaged_original();
        if (may_write) {
            try {
                write_(file_, text);
            } catch (const std::exception& e) {
                log_->error("state file {}: cannot save: {}", path_, e.what());
            }
        }

        lock.lock();
        written_ = taken;
        changed_.notify_all();
    }
}

bool StateStore::keep_damaged_original()
{
    std::string original;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        original = *original_;
    }
    try {
        const auto kept = write_new_file(file_ + ".damaged", original);
        log_->warn("state file {}: had damaged entries (logged at start-up): kept the file as loaded as {} before saving",
                   path_, kept);
    } catch (const std::exception& e) {
        log_->error("state file {}: had damaged entries and cannot be kept ({}): not overwritten; the next save "
                    "tries again",
                    path_, e.what());
        return false;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    original_.reset();
    damaged_ = false;
    return true;
}

} // namespace rigsim
