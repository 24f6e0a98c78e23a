// Fuzz target: the RFC 2217 access server's codec (emulator/transport/rfc2217.*), the bytes a
// client sends to a device's RFC 2217 endpoint.
// Input: one byte choosing how the rest is cut into reads, then the client's bytes.
// Checked beyond the sanitizers: the codec reads the same (data, answers, settings) however the
// bytes are cut; its data is never longer than the input and its answers are bounded by it (a
// request yields one answer of at most 11 bytes, once); the settings stay within RFC 2217's
// codes; and any data escaped and read back is itself, with no answer.
#include "emulator/transport/rfc2217.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace {

using rigsim::Rfc2217Codec;

void check(bool ok)
{
    if (!ok)
        __builtin_trap();
}

struct Read {
    std::string data;
    std::string reply;
    std::size_t notes = 0;
    rigsim::SerialSettings settings;
};

Read run(std::string_view input, std::size_t piece)
{
    Rfc2217Codec codec(115200);
    Rfc2217Codec::Out out;
    for (std::size_t at = 0; at < input.size(); at += piece)
        codec.receive(input.substr(at, piece), out);
    return Read{out.data, out.reply, out.notes.size(), codec.settings()};
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size)
{
    if (size == 0)
        return 0;
    const std::size_t piece = 1 + bytes[0] % 17;
    const std::string_view input(reinterpret_cast<const char*>(bytes) + 1, size - 1);

    const auto whole = run(input, input.size() + 1);
    const auto cut = run(input, piece);
    check(whole.data == cut.data && whole.reply == cut.reply && whole.notes == cut.notes);
    check(whole.data.size() <= input.size());
    // Each answer (a 3-byte negotiation answer, or a subnegotiation of at most 7 + 2 x 4 bytes
    // plus the one modem state announcement) comes from at least 3 bytes of input.
    check(whole.reply.size() <= 11 * (input.size() / 3 + 1) + 16);
    const auto& s = whole.settings;
    check(s.baud > 0 && s.data_bits >= 5 && s.data_bits <= 8 && s.parity >= 1 && s.parity <= 5 && s.stop_bits >= 1
          && s.stop_bits <= 3);

    // The unit's bytes escaped and read back: the same bytes, nothing to answer.
    Rfc2217Codec echo(9600);
    Rfc2217Codec::Out back;
    echo.receive(Rfc2217Codec::escape(input), back);
    check(back.data == input && back.reply.empty() && back.notes.empty());
    return 0;
}
