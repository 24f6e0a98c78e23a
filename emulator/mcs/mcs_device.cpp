#include "emulator/mcs/mcs_device.hpp"

#include "emulator/mcs/line_framer.hpp"

#include <spdlog/logger.h>
#include <spdlog/spdlog.h>

#include <algorithm>

namespace rigsim::mcs {

class McsSession : public Session {
public:
    McsSession(McsDevice& device, SendFn send, std::string peer, spdlog::logger& log)
        : device_(device), send_(std::move(send)), peer_(std::move(peer)), log_(log)
    {
        device_.attach(this);
    }
    ~McsSession() override { device_.detach(this); }

    /// Unprompted output (asynchronous mode).
    void send(std::string_view bytes) { send_(bytes); }

    void receive(std::string_view bytes) override
    {
        out_.clear();
        std::size_t ignored = 0;
        while (!bytes.empty()) {
            const auto r = framer_.parse(bytes);
            bytes.remove_prefix(r.consumed);
            ignored += r.ignored;
            switch (r.status) {
            case LineFramer::Status::NeedMore:
                break;
            case LineFramer::Status::Command:
                device_.execute(r.line, peer_, out_);
                break;
            case LineFramer::Status::Oversize:
                // Not in the manual: a line too long for the controller's buffer is a
                // syntax error, answered when its '\n' arrives (docs/protocol/mcs.md).
                log_.warn("{}: command longer than {} bytes discarded: error 1", peer_,
                          LineFramer::kDefaultMaxLine);
                encode(Error{kSystem, ErrorCode::Syntax}, out_);
                break;
            case LineFramer::Status::Interrupted:
                log_.warn("{}: ':' inside a command, dropped \"{}\"", peer_, printable(r.line));
                break;
            }
        }
        if (ignored > 0)
            log_.warn("{}: ignored {} byte(s) outside ':'...'\\n'", peer_, ignored);
        if (!out_.empty())
            send_(out_);
        device_.flush_outbox();
    }

private:
    McsDevice& device_;
    SendFn send_;
    std::string peer_;
    spdlog::logger& log_;
    LineFramer framer_;
    std::string out_;
};

McsDevice::McsDevice(const DeviceConfig& config, models::World& world, std::shared_ptr<spdlog::logger> log,
                     EventBus* events)
    : config_(config), clock_(world.clock()), log_(std::move(log)), controller_(config_of(config), world, config.name),
      handler_(controller_), events_(events)
{
    clock_.add(this);
}

McsDevice::~McsDevice()
{
    clock_.remove(this);
}

void McsDevice::detach(McsSession* s)
{
    sessions_.erase(std::remove(sessions_.begin(), sessions_.end(), s), sessions_.end());
}

void McsDevice::tick(Ticks now)
{
    controller_.tick(now);
    flush_outbox();
}

void McsDevice::flush_outbox()
{
    // Queued commands whose trigger arrived run now; their errors go out unprompted.
    for (std::size_t i = 0; i < controller_.channel_count(); ++i)
        if (auto* ch = controller_.channel(static_cast<std::int32_t>(i)))
            for (const auto& command : ch->take_triggered())
                if (auto r = handler_.execute(command); std::holds_alternative<Error>(r))
                    controller_.outbox().push_back(r);
    controller_.collect_events();
    auto& outbox = controller_.outbox();
    if (outbox.empty())
        return;
    std::string text;
    for (const auto& r : outbox)
        encode(r, text);
    outbox.clear();
    if (log_->should_log(spdlog::level::debug))
        log_->debug("unprompted: \"{}\"", printable(text));
    for (auto* s : sessions_)
        s->send(text);
}

std::unique_ptr<Session> McsDevice::open_session(SendFn send, std::string peer)
{
    return std::make_unique<McsSession>(*this, std::move(send), std::move(peer), *log_);
}

void McsDevice::execute(std::string_view line, std::string_view peer, std::string& out)
{
    const auto decoded = decode(line);
    if (!decoded.command) {
        log_->warn("{}: \"{}\": error {}", peer, printable(line), static_cast<int>(decoded.error.code));
        encode(decoded.error, out);
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
    if (handler_.take_reset_request()) {
        log_->info("{}: reset", peer);
        controller_.reset();
    }
}

} // namespace rigsim::mcs
