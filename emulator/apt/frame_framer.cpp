#include "emulator/apt/frame_framer.hpp"

#include <algorithm>
#include <cstring>

namespace rigsim::apt {

namespace {

enum class Verdict {
    Implausible,   ///< not the start of a frame: drop one byte
    Undecided,     ///< plausible so far, more header bytes needed
    Plausible,     ///< a whole plausible header
};

struct HeaderCheck {
    Verdict verdict = Verdict::Implausible;
    std::size_t data_length = 0;   ///< for Plausible: bytes of data after the header
};

/// The resync rule of frame_framer.hpp applied to the first `n` (<= 6) bytes of a candidate
/// header: each byte is judged as soon as it is there, so garbage is dropped early.
HeaderCheck check_header(const unsigned char* h, std::size_t n)
{
    HeaderCheck c;
    if (n < 2) {
        c.verdict = Verdict::Undecided;
        return c;
    }
    const MessageInfo* info = find_message(static_cast<std::uint16_t>(h[0] | (h[1] << 8)));
    if (!info)
        return c;
    if (n < 5) {
        c.verdict = Verdict::Undecided;
        return c;
    }
    if (!is_valid_address(static_cast<std::uint8_t>(h[4] & ~kDataFlag)))
        return c;
    if (h[4] & kDataFlag) {
        // Any length up to 255 is framed (frame_framer.hpp): the unit decides what it makes of
        // a packet shorter or longer than the table's layout. A longer one than 255 is not
        // believed: no packet exceeds it (section 4).
        const std::size_t length = static_cast<std::size_t>(h[2] | (h[3] << 8));
        if (info->header_only() || length > kMaxDataLength)
            return c;
        c.data_length = length;
    } else if (!info->header_only() && !info->header_only_allowed) {
        return c;   // this message always carries a data packet
    }
    if (n < kHeaderSize) {
        c.verdict = Verdict::Undecided;
        return c;
    }
    if (!is_valid_address(h[5]))   // a source never carries the data flag
        return c;
    c.verdict = Verdict::Plausible;
    return c;
}

const unsigned char* bytes_of(std::string_view s)
{
    return reinterpret_cast<const unsigned char*>(s.data());
}

} // namespace

void FrameFramer::drop(Result& r, char byte)
{
    ++r.dropped;
    ++dropped_bytes_;
    keep_dropped(std::string_view(&byte, 1));
    if (!dropping_) {
        dropping_ = true;
        ++garbage_runs_;
    }
}

void FrameFramer::keep_dropped(std::string_view bytes)
{
    dropped_.count += bytes.size();
    const std::size_t room = kKeptDropped - std::min(kKeptDropped, dropped_.bytes.size());
    dropped_.bytes.append(bytes.substr(0, room));
}

FrameFramer::Dropped FrameFramer::take_dropped()
{
    Dropped out = std::move(dropped_);
    dropped_ = {};
    return out;
}

void FrameFramer::emit(Result& r, std::string_view bytes)
{
    const auto* h = bytes_of(bytes);
    Frame& f = r.frame;
    f.id = static_cast<std::uint16_t>(h[0] | (h[1] << 8));
    f.dest = static_cast<std::uint8_t>(h[4] & ~kDataFlag);
    f.source = h[5];
    f.has_data = (h[4] & kDataFlag) != 0;
    if (f.has_data) {
        f.data = bytes.substr(kHeaderSize);
    } else {
        f.param1 = h[2];
        f.param2 = h[3];
    }
    f.info = find_message(f.id);
    f.bytes = bytes;
    r.status = Status::Frame;
    ++frames_;
    dropping_ = false;
}

std::size_t FrameFramer::discard_partial()
{
    const std::size_t n = buffered();
    if (n == 0)
        return 0;
    keep_dropped(pending_);
    pending_.clear();
    expected_ = 0;
    dropped_bytes_ += n;
    ++garbage_runs_;
    dropping_ = false;
    return n;
}

FrameFramer::Result FrameFramer::parse(std::string_view in)
{
    if (frame_in_pending_) {   // the last result's frame lived in pending_: it is used now
        pending_.clear();
        frame_in_pending_ = false;
    }
    Result r;
    std::size_t i = 0;

    // Bytes held from earlier input first: a plausible header prefix, or a whole plausible
    // header waiting for its data.
    while (!pending_.empty()) {
        if (pending_.size() >= kHeaderSize) {
            const std::size_t take = std::min(expected_ - pending_.size(), in.size() - i);
            pending_.append(in.substr(i, take));
            i += take;
            r.consumed = i;
            if (pending_.size() == expected_) {
                emit(r, pending_);
                frame_in_pending_ = true;
            }
            return r;
        }
        // A header prefix: judge it together with the next input bytes, consuming them only
        // when the header stands, since after a rejection they are candidates themselves.
        unsigned char window[kHeaderSize];
        const std::size_t held = pending_.size();
        const std::size_t extra = std::min(kHeaderSize - held, in.size() - i);
        std::memcpy(window, pending_.data(), held);
        std::memcpy(window + held, in.data() + i, extra);
        const HeaderCheck c = check_header(window, held + extra);
        switch (c.verdict) {
        case Verdict::Implausible:
            drop(r, pending_[0]);
            pending_.erase(0, 1);
            break;
        case Verdict::Undecided:   // the input ran out before the header did
            pending_.append(in.substr(i, extra));
            r.consumed = in.size();
            return r;
        case Verdict::Plausible:
            pending_.append(in.substr(i, extra));
            i += extra;
            expected_ = kHeaderSize + c.data_length;
            break;
        }
    }

    // The rest of the input, zero-copy while whole frames are in it.
    while (i < in.size()) {
        const std::size_t avail = in.size() - i;
        const HeaderCheck c = check_header(bytes_of(in) + i, std::min(avail, kHeaderSize));
        if (c.verdict == Verdict::Implausible) {
            drop(r, in[i]);
            ++i;
            continue;
        }
        if (c.verdict == Verdict::Plausible) {
            const std::size_t total = kHeaderSize + c.data_length;
            if (avail >= total) {
                emit(r, in.substr(i, total));
                r.consumed = i + total;
                return r;
            }
            expected_ = total;
        }
        pending_.assign(in.substr(i));   // a header prefix, or a frame short of data
        break;
    }
    r.consumed = in.size();
    return r;
}

} // namespace rigsim::apt
