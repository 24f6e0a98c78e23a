#include "emulator/transport/rfc2217_device.hpp"

#include "emulator/transport/rfc2217.hpp"

#include <spdlog/logger.h>

#include <utility>

namespace rigsim {
namespace {

/// RFC 2217's parity codes, for the log.
const char* parity_name(std::uint8_t p)
{
    switch (p) {
    case 1:
        return "none";
    case 2:
        return "odd";
    case 3:
        return "even";
    case 4:
        return "mark";
    case 5:
        return "space";
    default:
        return "?";
    }
}

class Rfc2217Session : public Session {
public:
    Rfc2217Session(Device& inner, SendFn send, Connection conn, std::string peer, spdlog::logger* log)
        : send_(std::move(send)), codec_(inner.line_baud()), log_(log)
    {
        // "tcp 127.0.0.1:53122" -> "rfc2217 127.0.0.1:53122": a serial line to the device.
        peer_ = "rfc2217 " + (peer.rfind("tcp ", 0) == 0 ? peer.substr(4) : peer);
        conn.client_baud = [this] { return codec_.settings().baud; };
        inner_ = inner.open_connection([this](std::string_view bytes) { out(bytes); }, std::move(conn), peer_);
    }

    void receive(std::string_view bytes) override
    {
        Rfc2217Codec::Out o;
        codec_.receive(bytes, o);
        if (!o.reply.empty())
            send_(o.reply);
        if (log_) {
            for (const auto& note : o.notes)
                log_->warn("{}: RFC 2217: {}", peer_, note);
            if (o.line_changed) {
                const auto& s = codec_.settings();
                log_->info("{}: RFC 2217: the client set {} baud, {} data bits, parity {}, {} stop bits", peer_, s.baud,
                           s.data_bits, parity_name(s.parity), s.stop_bits == 3 ? "1.5" : s.stop_bits == 2 ? "2" : "1");
            }
        }
        if (codec_.take_purge_request())
            held_.clear();
        if (!codec_.suspended() && !held_.empty()) {
            std::string held;
            held.swap(held_);
            send_(held);
        }
        if (!o.data.empty())
            inner_->receive(o.data);
    }

private:
    void out(std::string_view bytes)
    {
        auto escaped = Rfc2217Codec::escape(bytes);
        if (!codec_.suspended()) {
            send_(escaped);
            return;
        }
        if (held_.size() + escaped.size() > Rfc2217Device::kMaxSuspendedBytes) {
            if (log_)
                log_->warn("{}: RFC 2217: the client suspended the flow and {} bytes are held: {} more dropped", peer_,
                           held_.size(), escaped.size());
            return;
        }
        held_ += escaped;
    }

    SendFn send_;
    Rfc2217Codec codec_;
    spdlog::logger* log_;
    std::string peer_;
    std::string held_;   ///< for the client while it has suspended the flow
    std::unique_ptr<Session> inner_;
};

} // namespace

Rfc2217Device::Rfc2217Device(Device& inner, std::shared_ptr<spdlog::logger> log) : inner_(inner), log_(std::move(log)) {}

std::unique_ptr<Session> Rfc2217Device::open_session(SendFn send, std::string peer)
{
    return open_connection(std::move(send), Connection{}, std::move(peer));
}

std::unique_ptr<Session> Rfc2217Device::open_connection(SendFn send, Connection conn, std::string peer)
{
    return std::make_unique<Rfc2217Session>(inner_, std::move(send), std::move(conn), std::move(peer), log_.get());
}

} // namespace rigsim
