#pragma once
// Log amplification guard: a client that sends megabytes of bad input must not make the daemon
// write a log many times that size. Warnings are counted per source, a source being the
// logger and the connection the message names (device loggers start every per-connection
// line with the peer: "tcp 127.0.0.1:53122: ..."). Each source may log `burst` warnings per
// window; the rest of the window's warnings are counted and replaced by one summary line
// when the window ends. Info lines that name a connection (a client's MOD_IDENTIFY, a reset, a
// save) share that budget: a client repeating one must not write 47 MB of log for 3 MB of
// input. Other lines pass untouched: an info line naming no connection is not a client's
// doing, errors are rare and must all be seen, and debug/trace were asked for. Thread-safe: a
// periodic flush (spdlog::flush_every) writes the summaries of ended windows.

#include <spdlog/sinks/sink.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace rigsim {

class RateLimitedSink : public spdlog::sinks::sink {
public:
    using TimePoint = std::chrono::steady_clock::time_point;
    using NowFn = std::function<TimePoint()>;

    static constexpr std::uint32_t kDefaultBurst = 10;
    static constexpr std::chrono::milliseconds kDefaultWindow{1000};

    /// Forwards to `inner`; `now` is the steady clock unless a test supplies its own.
    explicit RateLimitedSink(std::shared_ptr<spdlog::sinks::sink> inner,
                             std::uint32_t burst = kDefaultBurst,
                             std::chrono::milliseconds window = kDefaultWindow, NowFn now = {});
    ~RateLimitedSink() override;

    void log(const spdlog::details::log_msg& msg) override;
    /// Writes the summaries of windows that have ended, then flushes `inner`.
    void flush() override;
    void set_pattern(const std::string& pattern) override;
    void set_formatter(std::unique_ptr<spdlog::formatter> formatter) override;

    /// Writes every pending summary now, whether its window has ended or not (at exit).
    void flush_summaries();

    /// Warnings and info lines suppressed since construction (for tests and the closing log line).
    std::uint64_t suppressed_total() const;

private:
    struct Source {
        std::string logger;
        std::string peer;
        TimePoint window_start;
        std::uint32_t logged = 0;       ///< warnings passed in this window
        std::uint64_t suppressed = 0;        ///< warnings held back in this window
        std::uint64_t suppressed_info = 0;   ///< info lines held back in this window
    };

    /// Summaries of ended windows; sources idle for a whole window are forgotten.
    void roll_windows(TimePoint now);
    void write_summary(Source& s, TimePoint now);

    mutable std::mutex mutex_;
    std::shared_ptr<spdlog::sinks::sink> inner_;
    std::uint32_t burst_;
    std::chrono::milliseconds window_;
    NowFn now_;
    std::map<std::string, Source> sources_;   ///< key: logger '\0' peer
    TimePoint next_roll_{};
    std::uint64_t suppressed_total_ = 0;
};

/// The peer a device log line names: its text up to the first ": ", or empty.
std::string_view log_peer(std::string_view payload);

} // namespace rigsim
