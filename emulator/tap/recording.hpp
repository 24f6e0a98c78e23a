#pragma once
// A conformance recording (docs/conformance.md, "The recording format"): what crossed a tap
// between a client and a unit, as versioned JSON lines. The first line says what was recorded;
// then one line per frame (an APT message, an MCS command or answer string, an MCS2 line) with
// its direction, its time, its raw bytes and what rigsim's codec reads in it, and one line per
// event (a client connecting or going, the unit lost or back). Every byte read is in exactly one
// line, in order: bytes that end no frame (garbage, a frame cut by a disconnect) are a line of
// their own. Each line is written and flushed as it is made, so an unplugged machine loses none.

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <cstdio>
#include <deque>
#include <memory>
#include <string>
#include <string_view>

namespace rigsim::tap {

/// The version of the format this program writes (the header's "rigsim_recording").
inline constexpr int kRecordingVersion = 1;

enum class Protocol { Apt, Mcs, Mcs2 };
/// "apt", "mcs", "mcs2" -> the protocol; false for another name.
bool parse_protocol(std::string_view name, Protocol& out);
std::string_view protocol_name(Protocol p);

/// Which way bytes went: "in" from the client to the unit, "out" from the unit to the client (the
/// wire log's words).
enum class Direction { In, Out };

/// Cuts one direction of one connection into frames and writes each as a line.
class Stream;

class Recorder {
public:
    /// Writes to `path` (created or truncated) the header line with `header`'s keys added.
    /// Throws std::runtime_error naming the file when it cannot be written.
    Recorder(const std::string& path, Protocol protocol, const nlohmann::json& header);
    ~Recorder();
    Recorder(const Recorder&) = delete;
    Recorder& operator=(const Recorder&) = delete;

    /// Bytes that crossed connection `conn` in `dir`, at `t_us` microseconds after the start.
    void bytes(std::uint64_t conn, Direction dir, std::string_view data, std::int64_t t_us);
    /// An event line: {"event": name, "conn": conn, ...extra}. A "disconnect", "stop" or
    /// "unit_lost" first writes the connection's bytes still waiting for the end of their frame
    /// (partial lines); other events ("connect", "unit", "baud") cut no frame.
    void event(std::string_view name, std::uint64_t conn, std::int64_t t_us, const nlohmann::json& extra);
    /// Frames and lines written so far (the header not counted).
    std::uint64_t lines() const { return lines_; }

private:
    friend class Stream;
    void write(const nlohmann::json& line);
    void flush_partial(std::uint64_t conn, std::int64_t t_us);
    Stream& stream(std::uint64_t conn, Direction dir);
    /// A frame line's reply timing: each client frame that asks for an answer waits, in order, for
    /// its reply (APT: the unit's next frame whose ID is the request's + 1, MGMSG_..._GET_ to
    /// _REQ_; MCS and MCS2: the unit's next frame), which gets "reply_to" (the request's seq) and
    /// "latency_us" (from the request's line to the reply's). At most kMaxAsked wait; the oldest
    /// goes first.
    void latency(nlohmann::json& line, Direction dir, const nlohmann::json& decoded);

    Protocol protocol_;
    std::FILE* file_ = nullptr;
    std::string path_;
    std::uint64_t lines_ = 0;
    std::uint64_t seq_ = 0;
    std::uint64_t conn_ = 0;                 ///< the connection the streams below belong to
    std::unique_ptr<Stream> in_;
    std::unique_ptr<Stream> out_;
    struct Asked {
        std::uint64_t seq = 0;
        std::int64_t t_us = 0;
        int reply_id = -1;   ///< APT: the reply's message ID; -1: the next frame
    };
    static constexpr std::size_t kMaxAsked = 64;
    std::deque<Asked> asked_;                ///< the connection's requests awaiting their replies
};

} // namespace rigsim::tap
