#pragma once
// Non-volatile memory of the rig's devices (APT MOT_SET_EEPROMPARAMS, ...), kept in a JSON
// state file so that what a device saved survives a daemon restart (--state-file). Without a
// file, saves last until the daemon exits.
//
// The loop thread reads and changes the state; a writer thread of the store writes it, so a
// save costs the loop a JSON dump, not an fsync. Saves in a burst coalesce: the writer
// writes the latest state. flush() and the destructor wait until it is on disk.

#include <nlohmann/json.hpp>
#include <spdlog/logger.h>

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace rigsim {

class StateStore {
public:
    /// Writes `text` to the file at `path` (throws on failure); write_file_atomically by default.
    using WriteFn = std::function<void(const std::string& path, const std::string& text)>;

    /// In memory only.
    explicit StateStore(std::shared_ptr<spdlog::logger> log = nullptr);
    /// Backed by `path` (a symlink is followed: its target is written): loaded now if it
    /// exists, stale temporaries beside it removed. A file that exists but cannot be read, is
    /// not a regular file or is not a rigsim state file is an error: throws std::runtime_error
    /// naming it and the reason. `log` (null: spdlog's default logger) must have thread-safe
    /// sinks: the writer thread logs its errors there.
    explicit StateStore(std::string path, std::shared_ptr<spdlog::logger> log = nullptr, WriteFn write = {});
    /// Waits until the latest save is written (flush()), then stops the writer.
    ~StateStore();
    StateStore(const StateStore&) = delete;
    StateStore& operator=(const StateStore&) = delete;

    /// What device `device` saved under `key`, or null.
    const nlohmann::json* get(const std::string& device, const std::string& key) const;
    /// Save; with a file, hand the new state to the writer and return (no I/O here).
    void set(const std::string& device, const std::string& key, nlohmann::json value);
    /// Forget everything device `device` saved (its non-volatile memory erased).
    void erase(const std::string& device);
    /// Everything device `device` saved (an empty object if nothing).
    const nlohmann::json& device_state(const std::string& device) const;

    /// An entry that `device` cannot restore: one warn line naming the file, the device, the
    /// key and `why`; the entry is dropped, and before the file is next written, the file as
    /// loaded is kept as `<file>.damaged` (or `.damaged.1`, ...).
    void reject(const std::string& device, const std::string& key, const std::string& why);
    /// Wait until every save made so far has been written (or its write failed and was logged).
    void flush();
    /// Durable saves (--state-sync): set() and erase() return only once the file is written
    /// (fsync'd), so a save a client has made survives even kill -9 or a power loss, at the cost
    /// of the loop waiting for the disk at each save. Off: saves are written behind.
    void set_sync(bool sync) { sync_ = sync; }

    /// The file written (symlinks resolved); empty in memory.
    const std::string& file() const { return file_; }

private:
    void writer_loop();
    /// Writer thread: keep the damaged file as loaded; false (logged) if that failed.
    bool keep_damaged_original();

    std::shared_ptr<spdlog::logger> log_;
    std::string path_;              ///< as given, for messages
    std::string file_;              ///< resolved target; empty: in memory
    WriteFn write_;
    nlohmann::json state_ = nlohmann::json::object();
    bool sync_ = false;

    std::mutex mutex_;              // guards everything below
    std::condition_variable changed_;
    std::optional<std::string> pending_;   ///< the latest snapshot not yet taken by the writer
    std::uint64_t saves_ = 0;              ///< snapshots handed over
    std::uint64_t written_ = 0;            ///< snapshots the writer has finished with
    bool stopping_ = false;
    bool damaged_ = false;                 ///< reject() was called for an entry of the loaded file
    std::optional<std::string> original_;  ///< the file as loaded, until kept as .damaged
    std::thread writer_;
};

} // namespace rigsim
