#include "emulator/core/wire_log.hpp"
#include "emulator/core/log_format.hpp"

#include "emulator/core/event_bus.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>

namespace rigsim {

namespace {

/// `to` = `from`. An entry is mostly overwritten by a frame that fits the string it holds
/// (the same command again): then one copy, without assign()'s general path.
void overwrite(std::string& to, std::string_view from)
{
    if (from.size() > to.capacity()) {
        to.assign(from);
        return;
    }
    if (from.size() != to.size())   // resize() is a call even when the size stays
        to.resize(from.size());
    if (!from.empty())
        std::memcpy(to.data(), from.data(), from.size());
}

} // namespace

WireLog::WireLog(std::string device, std::uint32_t tick_hz, EventBus* bus, std::shared_ptr<spdlog::logger> log,
                 std::size_t capacity)
    : device_(std::move(device)), tick_hz_(tick_hz == 0 ? 1 : tick_hz), bus_(bus), log_(std::move(log)),
      ring_(std::max<std::size_t>(capacity, 1))
{
}

WireLog::~WireLog() = default;

void WireLog::add(std::int64_t tick, bool inbound, std::string_view peer, std::string_view bytes,
                  std::vector<std::string> notes, bool unprompted)
{
    auto& e = ring_[next_];
    e.seq = ++seq_;
    e.tick = tick;
    e.inbound = inbound;
    e.unprompted = unprompted;
    if (e.peer != peer)   // mostly the same connection as the entry it overwrites: no copy
        e.peer.assign(peer);
    overwrite(e.bytes, bytes);
    if (!notes.empty() || !e.notes.empty())   // mostly none, and none overwritten
        e.notes = std::move(notes);
    if (++next_ == ring_.size())
        next_ = 0;
    if (count_ < ring_.size())
        ++count_;
    if (!e.notes.empty())
        ++noted_;
    // Debug level only: a client's mistakes are already warned about where the protocol's
    // log does (rate-limited); a flood of bad commands must not flood the log twice.
    if ((bus_ && bus_->wants(device_, "wire")) || (log_ && log_->should_log(spdlog::level::debug)))
        show(e);
}

void WireLog::show(const WireEntry& e) const
{
    const auto j = entry_json(e);
    if (log_ && log_->should_log(spdlog::level::debug))
        log_->debug("wire: {}", j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    if (bus_ && bus_->wants(device_, "wire"))
        bus_->publish(device_, "wire", static_cast<double>(e.tick) * 1000.0 / tick_hz_, j);
}

void WireLog::annotate_last(std::string note)
{
    if (count_ == 0)
        return;
    auto& e = ring_[(next_ + ring_.size() - 1) % ring_.size()];
    if (e.notes.empty())
        ++noted_;
    if (log_)
        log_->debug("wire: seq {}: {}", e.seq, note);
    e.notes.push_back(std::move(note));
}

const WireEntry* WireLog::last() const
{
    return count_ == 0 ? nullptr : &ring_[(next_ + ring_.size() - 1) % ring_.size()];
}

nlohmann::json WireLog::entry_json(const WireEntry& e) const
{
    nlohmann::json j{{"seq", e.seq},
                     {"time_ms", static_cast<double>(e.tick) * 1000.0 / tick_hz_},
                     {"direction", e.inbound ? "in" : "out"},
                     {"peer", e.peer},
                     {"hex", hex_bytes(e.bytes)}};
    if (!e.inbound)
        j["unprompted"] = e.unprompted;
    if (decoder_) {
        nlohmann::json d = nlohmann::json::object();
        decoder_(e, d);
        j["decoded"] = std::move(d);
    }
    j["notes"] = e.notes;
    return j;
}

nlohmann::json WireLog::to_json(std::size_t n) const
{
    auto out = nlohmann::json::array();
    const auto k = std::min(n, count_);
    for (std::size_t i = 0; i < k; ++i)
        out.push_back(entry_json(ring_[(next_ + ring_.size() - k + i) % ring_.size()]));
    return out;
}

void WireLog::clear()
{
    for (auto& e : ring_) {
        e.peer.clear();
        e.bytes.clear();
        e.notes.clear();
    }
    next_ = 0;
    count_ = 0;
    seq_ = 0;
    noted_ = 0;
}

std::string hex_bytes(std::string_view bytes)
{
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string out;
    out.reserve(bytes.size() * 3);
    for (const auto c : bytes) {
        if (!out.empty())
            out.push_back(' ');
        const auto b = static_cast<unsigned char>(c);
        out.push_back(kDigits[b >> 4]);
        out.push_back(kDigits[b & 15]);
    }
    return out;
}

} // namespace rigsim
