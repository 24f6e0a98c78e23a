#pragma once
// APT framing (manual sections 3 and 4): a 6-byte header, and after it a data packet when
// the destination byte carries the 0x80 flag. APT has no start byte and no checksum, so
// the framer resyncs the way MAVLink's does, by checking each header against the message
// table: a header is plausible when
//   - its ID is in the table (messages.hpp),
//   - its destination (without the flag) and its source are addresses of section 4
//     (0x01, 0x11, 0x21..0x2A, 0x50),
//   - a header-only message carries no data flag, unless the table lists a long form too
//     (MOVE_RELATIVE, MOVE_ABSOLUTE), and a message with a data packet carries the flag and a
//     length of at most 255 (section 4: "currently no datapacket exceeds 255 bytes").
// Otherwise the framer drops ONE byte and looks again at the next, so a frame that follows
// garbage is found whatever the garbage; a header is rejected as soon as its first bytes
// rule it out, so partial headers of garbage are not kept.
//
// Within that bound the length is the header's (section 3: it lets "the receiving process ...
// keep track of the beginning and the end of messages"), whatever the table's layout: public
// clients send the later K-Cube blocks without all of their reserved tail, or with more bytes
// than the layout, and a unit reads what it needs of them (messages.hpp fields_length; a packet
// short of that is ignored and logged, the tail of a longer one ignored). The price is the real
// unit's too: a header made of noise (a known ID, a destination of section 4 with bit 7 set, a
// valid source) holds the next bytes, up to 255 of them, as its data, requests included; a
// length that lies beyond what follows is cut off by the session's inter-byte timeout.
//
// Pure and resumable, with the calling convention of mcs::LineFramer: parse() consumes
// input up to the end of one frame and says what it found; the caller loops until the input
// is used up. At most one frame (6 + 255 bytes) is held between calls, so a 10 MB blob of
// garbage costs no memory.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "emulator/apt/messages.hpp"
#include "emulator/apt/wire.hpp"

namespace rigsim::apt {

/// One message as it came off the wire.
struct Frame {
    std::uint16_t id = 0;
    std::uint8_t param1 = 0;          ///< header-only messages; 0 when a data packet follows
    std::uint8_t param2 = 0;          ///< header-only messages; 0 when a data packet follows
    std::uint8_t dest = 0;            ///< without the 0x80 data flag
    std::uint8_t source = 0;
    bool has_data = false;
    std::string_view data;            ///< the data packet; valid until the next parse() call
    const MessageInfo* info = nullptr;   ///< the table entry of `id`
    std::string_view bytes;           ///< the whole frame as it came; valid until the next parse() call
};

class FrameFramer {
public:
    enum class Status {
        NeedMore,   ///< all input consumed, no complete frame yet
        Frame,      ///< `frame` holds one message
    };

    struct Result {
        Status status = Status::NeedMore;
        std::size_t consumed = 0;   ///< bytes of the input used by this call
        Frame frame;                ///< valid until the next parse() call (while the input lives)
        std::size_t dropped = 0;    ///< garbage bytes skipped by this call (some may be from earlier input)
    };

    Result parse(std::string_view in);

    /// Bytes held between calls: a partial header or a frame waiting for its data.
    std::size_t buffered() const { return frame_in_pending_ ? 0 : pending_.size(); }
    /// True while a plausible header has arrived but its data packet has not.
    bool in_frame() const { return pending_.size() >= kHeaderSize && !frame_in_pending_; }

    /// Drop a partial header or a frame short of its data (the inter-byte timeout ran out);
    /// returns the bytes dropped, which count as garbage.
    std::size_t discard_partial();

    /// The bytes dropped since the last take_dropped() (skipped as garbage or discarded): how
    /// many, and the first kKeptDropped of them, for the wire log.
    struct Dropped {
        std::size_t count = 0;
        std::string bytes;
    };
    static constexpr std::size_t kKeptDropped = 256;
    Dropped take_dropped();
    /// Bytes dropped since the last take_dropped() (take_dropped() would return some).
    bool has_dropped() const { return dropped_.count != 0; }

    // Counters for logs, since construction.
    std::uint64_t frames() const { return frames_; }                 ///< frames returned
    std::uint64_t dropped_bytes() const { return dropped_bytes_; }   ///< garbage bytes skipped
    std::uint64_t garbage_runs() const { return garbage_runs_; }     ///< resyncs: runs of dropped bytes

private:
    void drop(Result& r, char byte);
    /// Keep `bytes` (dropped) for take_dropped(), up to kKeptDropped of them.
    void keep_dropped(std::string_view bytes);
    void emit(Result& r, std::string_view bytes);

    std::string pending_;             ///< a plausible header prefix, or header + partial data
    std::size_t expected_ = 0;        ///< whole frame size once pending_ holds a plausible header
    bool frame_in_pending_ = false;   ///< the last result's frame lives in pending_
    bool dropping_ = false;           ///< the last byte looked at was dropped
    Dropped dropped_;                 ///< since the last take_dropped()
    std::uint64_t frames_ = 0;
    std::uint64_t dropped_bytes_ = 0;
    std::uint64_t garbage_runs_ = 0;
};

} // namespace rigsim::apt
