// Fuzz target: the APT frame framer, codec and the wire log's decoder alone (emulator/apt/
// frame_framer.*, codec.*, wire_decode.*), fast.
// Input: one byte choosing how the rest is cut into reads, then the bytes of a serial line.
// Checked beyond the sanitizers: the framer finds the same frames and drops the same number of
// bytes however the bytes are cut (whole, byte by byte, in the chosen pieces); every frame is a
// plausible header of the message table with the data its header announces; decoding a frame and
// encoding the message is stable (encode(decode(encode(decode(f)))) == encode(decode(f))); the
// wire log reads every frame, and any bytes, as one kind of unit or another would.
#include "emulator/apt/codec.hpp"
#include "emulator/apt/frame_framer.hpp"
#include "emulator/apt/wire_decode.hpp"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

namespace {

using namespace rigsim::apt;
using rigsim::apt::msg::Message;
using rigsim::apt::msg::decode;
using rigsim::apt::msg::encode;
using rigsim::apt::msg::message_id;

void check(bool ok)
{
    if (!ok)
        __builtin_trap();
}

const LogContext kContexts[] = {
    {false, StatusTable::Motor},  {true, StatusTable::Motor},        {false, StatusTable::Solenoid},
    {false, StatusTable::Piezo},  {false, StatusTable::StrainGauge}, {false, StatusTable::Rack},
};

/// The one frame of `bytes`, which must be exactly one frame.
Message decode_alone(const std::string& bytes)
{
    FrameFramer framer;
    const auto r = framer.parse(bytes);
    check(r.status == FrameFramer::Status::Frame && r.consumed == bytes.size() && r.dropped == 0);
    return decode(r.frame);
}

/// Everything checked of one frame the framer returned.
void check_frame(const Frame& f, bool deep)
{
    check(f.info != nullptr && f.info->id == f.id && f.bytes.size() == kHeaderSize + f.data.size());
    check(f.has_data == (f.data.size() > 0 || (f.bytes.size() > 4 && (static_cast<unsigned char>(f.bytes[4]) & 0x80))));
    if (!deep)
        return;
    const auto message = decode(f);
    check(message_id(message) == f.id);
    const auto once = encode(message, f.dest, f.source);
    const auto again = decode_alone(once);
    check(message_id(again) == f.id);
    check(encode(again, f.dest, f.source) == once);
    nlohmann::json out;   // as one kind of unit would log it (all six would cost six times as much)
    decode_for_log(f.bytes, out, kContexts[f.bytes.size() % std::size(kContexts)]);
    check(out.contains("name"));
    (void)field_names(f.id);
}

struct Outcome {
    std::vector<std::string> frames;
    std::uint64_t dropped = 0;
    std::size_t buffered = 0;
    bool operator==(const Outcome& o) const
    {
        return frames == o.frames && dropped == o.dropped && buffered == o.buffered;
    }
};

Outcome frame_all(std::string_view bytes, std::uint8_t cut)
{
    FrameFramer framer;
    Outcome out;
    std::uint32_t state = 0x9E3779B9u ^ cut;
    std::size_t at = 0;
    while (at < bytes.size()) {
        std::size_t n = bytes.size() - at;
        if (cut == 1) {
            n = 1;
        } else if (cut > 1) {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            n = std::min<std::size_t>(n, 1 + state % (2u * cut));
        }
        std::string_view read = bytes.substr(at, n);
        at += n;
        while (!read.empty()) {
            const auto r = framer.parse(read);
            check(r.consumed <= read.size());
            out.dropped += r.dropped;
            if (r.status == FrameFramer::Status::NeedMore) {
                check(r.consumed == read.size());
                break;
            }
            check(r.consumed > 0);
            check_frame(r.frame, cut == 0);
            out.frames.emplace_back(r.frame.bytes);
            read.remove_prefix(r.consumed);
        }
    }
    check(framer.frames() == out.frames.size());
    const auto kept = framer.take_dropped();
    check(kept.count == framer.dropped_bytes() && kept.bytes.size() <= FrameFramer::kKeptDropped);
    out.buffered = framer.buffered();
    return out;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size == 0)
        return 0;
    const std::string_view bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
    const auto whole = frame_all(bytes, 0);
    check(frame_all(bytes, 1) == whole);
    check(frame_all(bytes, data[0] < 2 ? 2 : data[0]) == whole);
    nlohmann::json out;   // bytes that may be no frame at all
    decode_for_log(bytes, out, kContexts[data[0] % std::size(kContexts)]);
    return 0;
}
