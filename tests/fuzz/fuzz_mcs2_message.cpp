// Fuzz target: the MCS2 ASCII message framer and grammar (emulator/mcs2/line_framer.*, message.*).
// Input: one byte choosing how the rest is cut into reads, then the bytes of a TCP stream.
// Checked beyond the sanitizers: the framer finds the same lines and overruns however the bytes are
// cut (whole, byte by byte, in the chosen pieces), no line is longer than its limit or holds a line
// feed; every command of a line is a piece of it, its error lies within it, and its keywords,
// parameters and count keep the grammar's bounds; each well-formed command resolves in a command
// tree of the guide's paths (or not) with as many indices as its path has.
#include "emulator/mcs2/command_tree.hpp"
#include "emulator/mcs2/line_framer.hpp"
#include "emulator/mcs2/message.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace {

using namespace rigsim::mcs2;

void check(bool ok)
{
    if (!ok)
        __builtin_trap();
}

constexpr std::size_t kMaxLine = 512;   // small, so that overruns are reached

const CommandTree& tree()
{
    static const CommandTree t({"[:PROPerty]:DEVice:SNUMber", "[:PROPerty]:MODule#:PSUPply[:ENABled]",
                                "[:PROPerty]:CHANnel#:MMODe", "[:PROPerty]:CHANnel#:VELocity",
                                "[:PROPerty]:CHANnel#:POSition[:CURRent]", "[:PROPerty]:CHANnel#:POSition:TARGet",
                                "[:PROPerty]:CHANnel#:PTYPe[:CODE]", ":MOVE#", ":STOP#", ":SYSTem:ERRor[:NEXT]",
                                ":STReam:FRAMe", "*IDN"});
    return t;
}

void check_message(std::string_view line)
{
    const auto commands = parse_message(line);
    CommandTree::Level level;
    for (const auto& c : commands) {
        const auto found = tree().resolve(c, level);
        if (found) {
            check(c.error == ScpiError::None && found->node >= 0);
            std::size_t indexed = 0;
            for (const auto& k : c.path)
                indexed += k.index ? 1 : 0;
            check(found->indices.size() >= indexed && found->indices.size() <= indexed + level.indices.size() + kMaxKeywords);
        }
        check(level.node >= 0 && static_cast<std::size_t>(level.node) < tree().size());
    }
    check(commands.size() <= kMaxCommandsPerMessage + 1);
    for (const auto& c : commands) {
        check(!c.text.empty() && c.text.data() >= line.data() && c.text.data() + c.text.size() <= line.data() + line.size());
        check(c.path.size() <= kMaxKeywords && c.params.size() <= kMaxParams);
        if (c.error != ScpiError::None)
            check(c.error_at <= line.size());
        else
            check(!c.path.empty() && (!c.common || c.path.size() == 1));
        check(!scpi_error_text(c.error).empty());
    }
}

std::vector<std::string> frame_all(std::string_view bytes, std::uint8_t cut)
{
    LineFramer framer(kMaxLine);
    std::vector<std::string> out;
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
            check(r.consumed > 0 && r.consumed <= read.size());
            read.remove_prefix(r.consumed);
            if (r.status == LineFramer::Status::Line) {
                check(r.line.size() <= kMaxLine && r.line.find('\n') == std::string_view::npos);
                if (cut == 0)
                    check_message(r.line);
                out.emplace_back(r.line);
            } else if (r.status == LineFramer::Status::Overrun) {
                out.emplace_back("\n");   // no line holds a line feed: the overrun's mark
            } else {
                check(read.empty());
            }
        }
    }
    check(framer.buffered() <= kMaxLine);
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
    // The bytes as one message, however long (the grammar's own bounds, not the framer's).
    check_message(bytes.substr(0, bytes.find('\n')));
    return 0;
}
