#include "emulator/core/rate_limited_sink.hpp"

#include <spdlog/details/log_msg.h>

#include <algorithm>
#include <cstdio>

namespace rigsim {

std::string_view log_peer(std::string_view payload)
{
    const auto colon = payload.find(": ");
    // Peers are short ("tcp 127.0.0.1:53122", "pty /tmp/rigsim/mcs0"); a long prefix is prose.
    if (colon == std::string_view::npos || colon > 200)
        return {};
    return payload.substr(0, colon);
}

RateLimitedSink::RateLimitedSink(std::shared_ptr<spdlog::sinks::sink> inner, std::uint32_t burst,
                                 std::chrono::milliseconds window, NowFn now)
    : inner_(std::move(inner)), burst_(std::max<std::uint32_t>(burst, 1)), window_(window),
      now_(now ? std::move(now) : NowFn([] { return std::chrono::steady_clock::now(); }))
{
}

RateLimitedSink::~RateLimitedSink()
{
    flush_summaries();
}

std::uint64_t RateLimitedSink::suppressed_total() const
{
    const std::lock_guard lock(mutex_);
    return suppressed_total_;
}

void RateLimitedSink::log(const spdlog::details::log_msg& msg)
{
    const std::lock_guard lock(mutex_);
    const auto now = now_();
    if (now >= next_roll_)
        roll_windows(now);
    const bool info = msg.level == spdlog::level::info;
    if (msg.level != spdlog::level::warn && !info) {
        inner_->log(msg);
        return;
    }
    const std::string_view logger(msg.logger_name.data(), msg.logger_name.size());
    const auto peer = log_peer(std::string_view(msg.payload.data(), msg.payload.size()));
    if (info && peer.empty()) {   // the daemon's own news, not a client's doing
        inner_->log(msg);
        return;
    }
    std::string key;
    key.reserve(logger.size() + 1 + peer.size());
    key.append(logger).push_back('\0');
    key.append(peer);
    auto [it, fresh] = sources_.try_emplace(std::move(key));
    auto& s = it->second;
    if (fresh) {
        s.logger.assign(logger);
        s.peer.assign(peer);
        s.window_start = now;
    }
    if (s.logged < burst_) {
        ++s.logged;
        inner_->log(msg);
        return;
    }
    ++(info ? s.suppressed_info : s.suppressed);
    ++suppressed_total_;
}

void RateLimitedSink::roll_windows(TimePoint now)
{
    for (auto it = sources_.begin(); it != sources_.end();) {
        auto& s = it->second;
        if (now - s.window_start < window_) {
            ++it;
            continue;
        }
        if (s.suppressed + s.suppressed_info > 0)
            write_summary(s, now);
        if (s.logged == 0) {   // a whole window without a warning: forget the source
            it = sources_.erase(it);
            continue;
        }
        s.window_start = now;
        s.logged = 0;
        ++it;
    }
    next_roll_ = now + window_ / 4;
}

void RateLimitedSink::write_summary(Source& s, TimePoint now)
{
    const auto seconds = std::chrono::duration<double>(now - s.window_start).count();
    char span[32];
    std::snprintf(span, sizeof span, "%.1f", seconds);
    std::string text = s.peer.empty() ? std::string() : s.peer + ": ";
    if (s.suppressed > 0)
        text += std::to_string(s.suppressed) + " more warning(s)";
    if (s.suppressed > 0 && s.suppressed_info > 0)
        text += " and ";
    if (s.suppressed_info > 0)
        text += std::to_string(s.suppressed_info) + " more info line(s)";
    text += std::string(" suppressed in the last ") + span
            + " s (at most " + std::to_string(burst_) + " per " + std::to_string(window_.count())
            + " ms are logged)";
    const spdlog::details::log_msg summary(spdlog::string_view_t(s.logger.data(), s.logger.size()),
                                           spdlog::level::warn,
                                           spdlog::string_view_t(text.data(), text.size()));
    inner_->log(summary);
    s.suppressed = 0;
    s.suppressed_info = 0;
}

void RateLimitedSink::flush()
{
    const std::lock_guard lock(mutex_);
    const auto now = now_();
    if (now >= next_roll_)
        roll_windows(now);
    inner_->flush();
}

void RateLimitedSink::flush_summaries()
{
    const std::lock_guard lock(mutex_);
    const auto now = now_();
    for (auto& [key, s] : sources_)
        if (s.suppressed + s.suppressed_info > 0)
            write_summary(s, now);
    inner_->flush();
}

void RateLimitedSink::set_pattern(const std::string& pattern)
{
    const std::lock_guard lock(mutex_);
    inner_->set_pattern(pattern);
}

void RateLimitedSink::set_formatter(std::unique_ptr<spdlog::formatter> formatter)
{
    const std::lock_guard lock(mutex_);
    inner_->set_formatter(std::move(formatter));
}

} // namespace rigsim
