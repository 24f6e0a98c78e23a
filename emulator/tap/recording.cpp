#include "emulator/tap/recording.hpp"

#include "emulator/apt/frame_framer.hpp"
#include "emulator/apt/wire_decode.hpp"
#include "emulator/mcs/line_framer.hpp"
#include "emulator/mcs/wire_names.hpp"
#include "emulator/mcs2/line_framer.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace rigsim::tap {

namespace {

std::string hex(std::string_view bytes)
{
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string out;
    out.reserve(bytes.size() * 2);
    for (const char c : bytes) {
        const auto b = static_cast<unsigned char>(c);
        out += kDigits[b >> 4];
        out += kDigits[b & 15];
    }
    return out;
}

/// Bytes kept waiting for the end of a frame before they are written as a line of their own
/// (garbage with no frame in it: a unit at the wrong baud rate).
constexpr std::size_t kMaxPending = 4096;

} // namespace

bool parse_protocol(std::string_view name, Protocol& out)
{
    if (name == "apt")
        out = Protocol::Apt;
    else if (name == "mcs")
        out = Protocol::Mcs;
    else if (name == "mcs2")
        out = Protocol::Mcs2;
    else
        return false;
    return true;
}

std::string_view protocol_name(Protocol p)
{
    switch (p) {
    case Protocol::Apt:
        return "apt";
    case Protocol::Mcs:
        return "mcs";
    case Protocol::Mcs2:
        return "mcs2";
    }
    return "apt";
}

class Stream {
public:
    Stream(Recorder& r, Protocol p, Direction d) : r_(r), protocol_(p), dir_(d) {}

    void feed(std::uint64_t conn, std::string_view data, std::int64_t t_us)
    {
        while (!data.empty()) {
            std::size_t used = 0;
            bool frame = false;
            nlohmann::json decoded;
            switch (protocol_) {
            case Protocol::Apt: {
                const auto res = apt_.parse(data);
                used = res.consumed;
                if (res.status == apt::FrameFramer::Status::Frame) {
                    frame = true;
                    apt::decode_for_log(res.frame.bytes, decoded);
                }
                break;
            }
            case Protocol::Mcs: {
                const auto res = mcs_.parse(data);
                used = res.consumed;
                if (res.status == mcs::LineFramer::Status::Command) {
                    frame = true;
                    mcs::decode_line(res.line, dir_ == Direction::In, decoded);
                }
                break;
            }
            case Protocol::Mcs2: {
                const auto res = mcs2_.parse(data);
                used = res.consumed;
                if (res.status == mcs2::LineFramer::Status::Line) {
                    frame = true;
                    decoded["text"] = std::string(res.line);
                }
                break;
            }
            }
            if (used == 0)
                used = data.size();   // a framer that took nothing: keep the bytes, never loop
            pending_.append(data.substr(0, used));
            data.remove_prefix(used);
            if (frame)
                emit(conn, t_us, &decoded);
            else if (pending_.size() >= kMaxPending)
                emit(conn, t_us, nullptr);
        }
    }

    /// What is waiting for the end of its frame, as a line of its own.
    void flush(std::uint64_t conn, std::int64_t t_us)
    {
        if (!pending_.empty())
            emit(conn, t_us, nullptr);
    }

private:
    void emit(std::uint64_t conn, std::int64_t t_us, const nlohmann::json* decoded)
    {
        nlohmann::json line;
        line["seq"] = r_.seq_++;
        line["t_us"] = t_us;
        line["conn"] = conn;
        line["dir"] = dir_ == Direction::In ? "in" : "out";
        line["bytes"] = hex(pending_);
        if (decoded) {
            line["decoded"] = *decoded;
            r_.latency(line, dir_, *decoded);
        } else
            line["partial"] = true;   // no whole frame: garbage, or cut off
        pending_.clear();
        r_.write(line);
    }

    Recorder& r_;
    Protocol protocol_;
    Direction dir_;
    std::string pending_;
    apt::FrameFramer apt_;
    mcs::LineFramer mcs_;
    mcs2::LineFramer mcs2_;
};

Recorder::Recorder(const std::string& path, Protocol protocol, const nlohmann::json& header)
    : protocol_(protocol), path_(path)
{
    file_ = std::fopen(path.c_str(), "w");
    if (!file_)
        throw std::runtime_error(path + ": cannot write the recording: " + std::strerror(errno));
    nlohmann::json head = header;
    head["rigsim_recording"] = kRecordingVersion;
    head["protocol"] = protocol_name(protocol);
    write(head);
    lines_ = 0;
}

Recorder::~Recorder()
{
    if (file_)
        std::fclose(file_);
}

Stream& Recorder::stream(std::uint64_t conn, Direction dir)
{
    if (conn != conn_ || !in_) {
        asked_.clear();
        in_ = std::make_unique<Stream>(*this, protocol_, Direction::In);
        out_ = std::make_unique<Stream>(*this, protocol_, Direction::Out);
        conn_ = conn;
    }
    return dir == Direction::In ? *in_ : *out_;
}

void Recorder::bytes(std::uint64_t conn, Direction dir, std::string_view data, std::int64_t t_us)
{
    if (conn != conn_ && in_)
        flush_partial(conn_, t_us);
    stream(conn, dir).feed(conn, data, t_us);
}

namespace {

/// An APT frame's message ID, as the wire log's decoding gives it ("0x0411"), or -1.
int apt_id(const nlohmann::json& decoded)
{
    const auto id = decoded.find("id");
    if (id == decoded.end() || !id->is_string())
        return -1;
    const auto& text = id->get_ref<const std::string&>();
    char* end = nullptr;
    const auto value = std::strtol(text.c_str(), &end, 16);
    return end != text.c_str() && *end == '\0' && value >= 0 && value <= 0xFFFF ? static_cast<int>(value) : -1;
}

/// Whether the client's frame asks for an answer: an APT request (its name has _REQ_), every
/// MCS command (the unit acknowledges each in its default synchronous mode, manual 2.3), an
/// MCS2 line with a query.
bool asks(Protocol protocol, const nlohmann::json& decoded)
{
    switch (protocol) {
    case Protocol::Apt: {
        const auto name = decoded.find("name");
        return name != decoded.end() && name->is_string() && name->get<std::string>().find("_REQ_") != std::string::npos;
    }
    case Protocol::Mcs:
        return true;
    case Protocol::Mcs2: {
        const auto text = decoded.find("text");
        return text != decoded.end() && text->is_string() && text->get<std::string>().find('?') != std::string::npos;
    }
    }
    return false;
}

} // namespace

void Recorder::latency(nlohmann::json& line, Direction dir, const nlohmann::json& decoded)
{
    const auto seq = line["seq"].get<std::uint64_t>();
    const auto t_us = line["t_us"].get<std::int64_t>();
    const int id = protocol_ == Protocol::Apt ? apt_id(decoded) : -1;
    if (dir == Direction::In) {
        if (!asks(protocol_, decoded))
            return;
        if (asked_.size() == kMaxAsked)
            asked_.pop_front();
        asked_.push_back(Asked{seq, t_us, id < 0 ? -1 : id + 1});
        return;
    }
    const auto it = std::find_if(asked_.begin(), asked_.end(),
                                 [&](const Asked& a) { return a.reply_id < 0 || a.reply_id == id; });
    if (it == asked_.end())
        return;   // unprompted (a status update, a move's end)
    line["reply_to"] = it->seq;
    line["latency_us"] = t_us - it->t_us;
    asked_.erase(it);
}

void Recorder::flush_partial(std::uint64_t conn, std::int64_t t_us)
{
    if (!in_ || conn != conn_)
        return;
    in_->flush(conn, t_us);
    out_->flush(conn, t_us);
}

void Recorder::event(std::string_view name, std::uint64_t conn, std::int64_t t_us, const nlohmann::json& extra)
{
    // An end cuts the frames under way: their bytes go first, as partial lines.
    if (name == "disconnect" || name == "stop" || name == "unit_lost")
        flush_partial(conn, t_us);
    if (name == "disconnect") {   // the next connection's frames start afresh
        in_.reset();
        out_.reset();
        asked_.clear();
    }
    nlohmann::json line = extra.is_object() ? extra : nlohmann::json::object();
    line["seq"] = seq_++;
    line["t_us"] = t_us;
    line["conn"] = conn;
    line["event"] = std::string(name);
    write(line);
}

void Recorder::write(const nlohmann::json& line)
{
    // A unit's line need not be UTF-8: its decoded text gets U+FFFD where it is not (the raw bytes
    // are in hex, whole), as in the control API's wire log. (fuzz_tap_recorder's first finding.)
    const auto text = line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
    if (std::fwrite(text.data(), 1, text.size(), file_) != text.size() || std::fflush(file_) != 0)
        throw std::runtime_error(path_ + ": cannot write the recording: " + std::strerror(errno));
    ++lines_;
}

} // namespace rigsim::tap
