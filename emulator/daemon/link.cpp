#include "emulator/daemon/link.hpp"

#include <algorithm>
#include <cmath>

namespace rigsim {

/// One connection through the link: client bytes to the device's session, the device's bytes
/// to the client, each through the link's faults.
class Link::LinkSession : public Session {
public:
    LinkSession(Link& link, SendFn send, std::string peer)
        : link_(link), send_(std::move(send)), serial_(peer.rfind("pty ", 0) == 0)
    {
        link_.sessions_.push_back(this);
        inner_ = link_.inner_.open_session([this](std::string_view bytes) { out(bytes); }, std::move(peer));
    }
    ~LinkSession() override
    {
        inner_.reset();   // before the link forgets us: it may still send while closing
        link_.held_frames_ -= held_.size();
        auto& s = link_.sessions_;
        s.erase(std::remove(s.begin(), s.end(), this), s.end());
        link_.clock_.changed(link_);
    }

    void receive(std::string_view bytes) override
    {
        if (link_.unplugged())
            return;
        if (link_.byte_faults_.empty()) {
            inner_->receive(bytes);
            return;
        }
        const auto kept = link_.filter(bytes, true);
        if (!kept.empty())
            inner_->receive(kept);
    }

    /// Held bytes whose time has come go out.
    void release(Ticks now)
    {
        while (!held_.empty() && held_.front().first <= now) {
            held_bytes_ -= held_.front().second.size();
            --link_.held_frames_;
            const auto bytes = std::move(held_.front().second);
            held_.pop_front();
            send_(bytes);
        }
    }
    Ticks next_due() const { return held_.empty() ? kNever : held_.front().first; }
    void drop_held()
    {
        link_.held_frames_ -= held_.size();
        held_.clear();
        held_bytes_ = 0;
        line_free_ = 0;
        link_.clock_.changed(link_);
    }
    std::size_t held() const { return held_.size(); }

private:
    void out(std::string_view bytes)
    {
        if (link_.unplugged())
            return;
        std::string filtered;
        if (!link_.byte_faults_.empty()) {
            filtered = link_.filter(bytes, false);
            if (filtered.empty())
                return;
            bytes = filtered;
        }
        const Ticks now = link_.clock_.now();
        Ticks at = link_.due(now);
        // Faithful timing (a PtyEndpoint names its session "pty <path>"): the bytes arrive when
        // the line has carried them, 10 bits per byte at the device's baud rate, after
        // whatever it still carries.
        if (const auto baud = serial_ ? link_.inner_.serial_baud() : 0; baud > 0) {
            const double ticks = static_cast<double>(bytes.size()) * 10.0 * link_.clock_.tick_hz() / baud;
            line_free_ = std::max(line_free_, static_cast<double>(at)) + ticks;
            at = static_cast<Ticks>(std::ceil(line_free_));
        }
        if (at <= now && held_.empty()) {
            send_(bytes);
            return;
        }
        if (held_bytes_ + bytes.size() > kMaxHeldBytes)
            return;   // nobody reads the port: as the pty would, drop rather than grow
        held_bytes_ += bytes.size();
        ++link_.held_frames_;
        // A serial line keeps its order: a later answer never overtakes an earlier one.
        held_.emplace_back(std::max(at, held_.empty() ? at : held_.back().first), std::string(bytes));
        link_.clock_.changed(link_);   // held: the link is due when they are
    }

    Link& link_;
    SendFn send_;
    std::unique_ptr<Session> inner_;
    bool serial_;
    double line_free_ = 0;   ///< tick (fractional) at which the serial line has sent all it was given
    std::deque<std::pair<Ticks, std::string>> held_;
    std::size_t held_bytes_ = 0;
};

Link::Link(Device& inner, Clock& clock) : inner_(inner), clock_(clock)
{
    // Its next change moves only when it holds an answer (announced there), when held answers
    // go (a tick, a session closed, a reset) or when the clock ticks.
    clock_.add(this, Clock::Schedule::Announced);
}

Link::~Link()
{
    clock_.remove(this);
}

std::unique_ptr<Session> Link::open_session(SendFn send, std::string peer)
{
    return std::make_unique<LinkSession>(*this, std::move(send), std::move(peer));
}

void Link::set_unplugged(std::uint64_t id, bool unplugged)
{
    unplugged_ = unplugged ? id : 0;
}

void Link::add(const ByteFault& f)
{
    byte_faults_.push_back(ActiveByteFault{f, std::mt19937(f.seed)});
}

void Link::add(const LatencyFault& f)
{
    latency_ = f;
    latency_rng_.seed(f.seed);
}

bool Link::remove(std::uint64_t id)
{
    if (id == 0)
        return false;
    if (unplugged_ == id) {
        unplugged_ = 0;
        return true;
    }
    if (latency_.id == id) {
        latency_ = LatencyFault{};
        return true;
    }
    const auto it = std::find_if(byte_faults_.begin(), byte_faults_.end(),
                                 [&](const ActiveByteFault& a) { return a.f.id == id; });
    if (it == byte_faults_.end())
        return false;
    byte_faults_.erase(it);
    return true;
}

void Link::reset()
{
    unplugged_ = 0;
    byte_faults_.clear();
    latency_ = LatencyFault{};
    for (auto* s : sessions_)
        s->drop_held();
    dropped_ = 0;
    corrupted_ = 0;
}

std::size_t Link::held() const
{
    std::size_t n = 0;
    for (const auto* s : sessions_)
        n += s->held();
    return n;
}

std::string Link::filter(std::string_view bytes, bool inbound)
{
    std::string out(bytes);
    for (auto& a : byte_faults_) {
        if (inbound ? !a.f.inbound : !a.f.outbound)
            continue;
        std::uniform_real_distribution<double> chance(0.0, 1.0);
        std::string kept;
        kept.reserve(out.size());
        for (const char c : out) {
            if (chance(a.rng) >= a.f.probability) {
                kept.push_back(c);
            } else if (a.f.corrupt) {
                kept.push_back(static_cast<char>(static_cast<unsigned char>(c) ^ (1u << (a.rng() % 8))));
                ++corrupted_;
            } else {
                ++dropped_;
            }
        }
        out.swap(kept);
    }
    return out;
}

Ticks Link::due(Ticks now)
{
    if (latency_.id == 0)
        return now;
    Ticks jitter = 0;
    if (latency_.jitter > 0)
        jitter = std::uniform_int_distribution<Ticks>(0, latency_.jitter)(latency_rng_);
    return now + latency_.latency + jitter;
}

Ticks Link::next_change(Ticks now) const
{
    // Asked at every wake-up of the clock, for every device: nothing held is the usual answer.
    if (held_frames_ == 0)
        return kNever;
    Ticks next = kNever;
    for (const auto* s : sessions_)
        next = std::min(next, s->next_due());
    return next <= now ? now + 1 : next;
}

void Link::tick(Ticks now)
{
    // A session may close while it sends (a write error): walk a copy.
    const auto sessions = sessions_;
    for (auto* s : sessions)
        if (std::find(sessions_.begin(), sessions_.end(), s) != sessions_.end())
            s->release(now);
}

} // namespace rigsim
