#include "emulator/mcs/mcs_device.hpp"
#include "emulator/core/log_format.hpp"

#include "emulator/core/event_bus.hpp"
#include "emulator/mcs/line_framer.hpp"
#include "emulator/mcs/wire_names.hpp"

#include <nlohmann/json.hpp>

#include <spdlog/spdlog.h>

#include <algorithm>

namespace rigsim::mcs {

class McsSession : public Session {
public:
    McsSession(McsDevice& device, SendFn send, std::string peer, spdlog::logger& log, Clock& clock)
        : device_(device), send_(std::move(send)), peer_(std::move(peer)), log_(log), clock_(clock),
          paced_(is_serial_peer(peer_))
    {
        device_.attach(this);
        clock_.changed(device_);
    }
    ~McsSession() override
    {
        device_.detach(this);
        clock_.changed(device_);
    }

    /// Unprompted output (asynchronous mode).
    void send(std::string_view bytes) { send_(bytes); }

    void receive(std::string_view bytes) override
    {
        out_.clear();
        std::size_t ignored = 0;
        // A client that waits for each answer (sync mode, 2.1) never has a command ready
        // while the last answer is still on the serial line, nor two in one read.
        auto early = paced_ && clock_.now() < line_free_ ? McsDevice::Early::Paced : McsDevice::Early::No;
        while (!bytes.empty()) {
            const auto r = framer_.parse(bytes);
            bytes.remove_prefix(r.consumed);
            ignored += r.ignored;
            switch (r.status) {
            case LineFramer::Status::NeedMore:
                break;
            case LineFramer::Status::Command:
                device_.execute(r.line, peer_, out_, early, r.frame);
                early = device_.controller().communication_mode() == CommunicationMode::Sync
                            ? McsDevice::Early::SameRead
                            : McsDevice::Early::No;
                break;
            case LineFramer::Status::Oversize:
                // Not in the manual: a line too long for the controller's buffer is a
                // syntax error, answered when its '\n' arrives (docs/protocol/mcs.md).
                log_.warn("{}: command longer than {} bytes discarded: error 1", peer_,
                          LineFramer::kDefaultMaxLine);
                {
                    const auto at = out_.size();
                    encode(Error{kSystem, ErrorCode::Syntax}, out_);
                    device_.log_answer(peer_, std::string_view(out_).substr(at),
                                       "command longer than the controller's buffer: E-1,1 Syntax Error (appendix 4.2)");
                }
                break;
            case LineFramer::Status::Interrupted:
                log_.warn("{}: ':' inside a command, dropped \"{}\"", peer_, printable(r.line));
                device_.log_dropped(peer_, r.line);
                break;
            }
        }
        if (ignored > 0)
            log_.warn("{}: ignored {} byte(s) outside ':'...'\\n'", peer_, ignored);
        if (!out_.empty()) {
            send_(out_);
            if (const auto baud = paced_ ? device_.serial_baud() : 0; baud > 0) {   // 8N1: 10 bits a byte
                const auto bits = static_cast<Ticks>(out_.size() * 10) * clock_.tick_hz();
                line_free_ = std::max(line_free_, clock_.now()) + (bits + baud - 1) / baud;
            }
        }
        device_.flush_outbox();
        device_.publish_changes();
        clock_.changed(device_);   // a command may have started a timer (models/clock.hpp, "The schedule")
    }

private:
    McsDevice& device_;
    SendFn send_;
    std::string peer_;
    spdlog::logger& log_;
    Clock& clock_;
    bool paced_;            ///< a serial line: answers take time to go out (faithful_timing)
    Ticks line_free_ = 0;   ///< when the last answer has left the serial line
    LineFramer framer_;
    std::string out_;
};

McsDevice::McsDevice(const DeviceConfig& config, models::World& world, std::shared_ptr<spdlog::logger> log,
                     EventBus* events)
    : config_(config), clock_(world.clock()), log_(std::move(log)),
      controller_(config_of(config), world, config.name),
      handler_(controller_), events_(events), wire_log_(config.name, clock_.tick_hz(), events, log_)
{
    wire_log_.set_decoder([](const WireEntry& e, nlohmann::json& out) { decode_line(e.bytes, e.inbound, out); });
    // Its timers move in its tick(), in a session (announced there), through a body's event (a
    // tick of the clock) or a control request (Ticker::reschedule()).
    clock_.add(this, Clock::Schedule::Announced);
}

McsDevice::~McsDevice()
{
    clock_.remove(this);
}

void McsDevice::log_dropped(std::string_view peer, std::string_view partial)
{
    line_text_.assign(1, ':');
    line_text_.append(partial);
    std::vector<std::string> notes;
    notes.emplace_back("':' inside a command: the unfinished command was dropped unanswered (1.1)");
    wire_log_.add(clock_.now(), true, peer, line_text_, std::move(notes));
}

void McsDevice::detach(McsSession* s)
{
    sessions_.erase(std::remove(sessions_.begin(), sessions_.end(), s), sessions_.end());
}

void McsDevice::tick(Ticks now)
{
    controller_.tick(now);
    if (controller_.take_keep_alive_expired())
        wire_log_.annotate_last("keep-alive expired: no command for " + std::to_string(controller_.keep_alive_ms())
                                + " ms, all positioners stopped (K)");
    flush_outbox();
    publish_changes();
}

void McsDevice::flush_outbox()
{
    // Queued commands whose trigger arrived run now; their errors go out unprompted.
    for (auto* ch : controller_.positioners())
        if (ch->has_triggered())
            for (const auto& command : ch->take_triggered())
                if (auto r = handler_.execute(command); std::holds_alternative<Error>(r))
                    controller_.outbox().push_back(r);
    controller_.collect_events();
    auto& outbox = controller_.outbox();
    if (outbox.empty())
        return;
    std::string text;
    for (const auto& r : outbox) {
        const auto at = text.size();
        encode(r, text);
        wire_log_.add(clock_.now(), false, "all", std::string_view(text).substr(at), {}, true);
    }
    outbox.clear();
    if (log_->should_log(spdlog::level::debug))
        log_->debug("unprompted: \"{}\"", printable(text));
    for (auto* s : sessions_)
        s->send(text);
}

std::unique_ptr<Session> McsDevice::open_session(SendFn send, std::string peer)
{
    return std::make_unique<McsSession>(*this, std::move(send), std::move(peer), *log_, clock_);
}

void McsDevice::execute(std::string_view line, std::string_view peer, std::string& out, Early early,
                        std::string_view frame)
{
    if (frame.empty()) {
        line_text_.assign(1, ':');
        line_text_.append(line);
        line_text_.push_back('\n');
        frame = line_text_;
    }
    line_ = frame;
    const auto at = out.size();
    std::vector<std::string> notes;   // empty, no allocation, unless the client slipped
    if (early == Early::SameRead)
        notes.emplace_back("sent before the answer to the previous command arrived (in one read with it; sync mode "
                           "answers every command, 2.1)");
    else if (early == Early::Paced)
        notes.emplace_back("sent while the previous answer was still going out on the serial line (1.2, CB)");
    const auto decoded = decode(line);
    if (!decoded.command) {
        log_->warn("{}: \"{}\": error {}", peer, printable(line), static_cast<int>(decoded.error.code));
        encode(decoded.error, out);
        note_command(nullptr, decoded.error, notes);
        wire_log_.add(clock_.now(), true, peer, line_, std::move(notes));
        wire_log_.add(clock_.now(), false, peer, std::string_view(out).substr(at));
        line_ = {};
        return;
    }
    controller_.note_command();   // K: any command that could be parsed
    auto reply = handler_.handle(*decoded.command);
    // 2.1: in asynchronous mode acknowledges are omitted (SCM answers in its new mode).
    if (std::holds_alternative<Ack>(reply) && controller_.communication_mode() == CommunicationMode::Async)
        reply = Silent{};
    if (const auto* err = std::get_if<Error>(&reply))
        log_->warn("{}: \"{}\": error {} (source channel {})", peer, printable(line),
                   static_cast<int>(err->code), err->channel);
    else if (log_->should_log(spdlog::level::debug))   // printable() is not free: only when logged
        log_->debug("{}: \"{}\"", peer, printable(line));
    encode(reply, out);
    note_command(&*decoded.command, reply, notes);
    wire_log_.add(clock_.now(), true, peer, line_, std::move(notes));
    line_ = {};
    if (out.size() > at)
        wire_log_.add(clock_.now(), false, peer, std::string_view(out).substr(at));
    if (handler_.take_reset_request()) {
        log_->info("{}: reset", peer);
        controller_.reset();
    }
}

} // namespace rigsim::mcs
