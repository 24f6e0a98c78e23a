// Fuzz target: the MCS line framer and codec alone (emulator/mcs/line_framer.*, codec.*), fast.
// Input: one byte choosing how the rest is cut into reads, then the bytes of a serial line.
// Checked beyond the sanitizers: the framer reports the same commands, interruptions and
// oversize lines however the bytes are cut (whole, byte by byte, in the chosen pieces), never
// consumes more than it was given, and consumes all of a read it says it needs more of; the
// codec decodes every command it reports (a command or the manual's error) and names it.
#include "emulator/mcs/codec.hpp"
#include "emulator/mcs/line_framer.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace {

using rigsim::mcs::LineFramer;

/// A finding: abort, so that libFuzzer keeps the input (a sanitizer would have, for its own).
void check(bool ok)
{
    if (!ok)
        __builtin_trap();
}

/// What the framer reported, in order: a status byte, then the line.
std::vector<std::string> frame_all(std::string_view bytes, std::uint8_t cut)
{
    LineFramer framer;
    std::vector<std::string> events;
    std::uint32_t state = 0x9E3779B9u ^ cut;
    std::size_t at = 0;
    while (at < bytes.size()) {
        std::size_t n = bytes.size() - at;   // cut 0: whole
        if (cut == 1) {
            n = 1;
        } else if (cut > 1) {   // pieces of 1..2*cut bytes, from a xorshift on the cut byte
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
            if (r.status == LineFramer::Status::NeedMore) {
                check(r.consumed == read.size());
                break;
            }
            check(r.consumed > 0);
            check(r.line.size() <= LineFramer::kDefaultMaxLine);
            if (!r.frame.empty())
                check(r.frame.size() == r.line.size() + 2 && r.frame.front() == ':' && r.frame.back() == '\n'
                      && r.frame.substr(1, r.line.size()) == r.line);
            events.push_back(std::string(1, static_cast<char>(r.status)) + std::string(r.line));
            if (r.status == LineFramer::Status::Command) {
                const auto decoded = rigsim::mcs::decode(r.line);
                check(decoded.command.has_value() == (decoded.error.code == rigsim::mcs::ErrorCode::None));
                if (decoded.command) {
                    (void)rigsim::mcs::channel_of(*decoded.command);
                    (void)rigsim::mcs::is_movement(*decoded.command);
                    check(rigsim::mcs::find_command(decoded.name) != nullptr);
                } else {
                    check(!rigsim::mcs::encode(decoded.error).empty());
                }
            }
            read.remove_prefix(r.consumed);
        }
    }
    return events;
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
    return 0;
}
