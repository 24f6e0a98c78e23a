// The RFC 2217 access server's codec (emulator/transport/rfc2217.hpp): Telnet negotiation as
// pyserial's rfc2217:// client opens a port, each COM-PORT-OPTION command acknowledged with the
// port's value, data with 0xFF doubled, and what a client may get wrong.
#include "emulator/transport/rfc2217.hpp"

#include <catch2/catch.hpp>

#include <initializer_list>
#include <string>

namespace test_rfc2217 {

using rigsim::Rfc2217Codec;

namespace {

std::string bytes(std::initializer_list<int> b)
{
    std::string out;
    for (const int c : b)
        out.push_back(static_cast<char>(c));
    return out;
}

/// IAC SB COM-PORT-OPTION command value IAC SE.
std::string sb(int command, const std::string& value)
{
    return bytes({255, 250, 44, command}) + value + bytes({255, 240});
}

} // namespace

TEST_CASE("rfc2217: pyserial's opening gets each option it asks for, once, and the modem state", "[unit][rfc2217]")
{
    Rfc2217Codec codec(115200);
    Rfc2217Codec::Out out;
    // DO ECHO, WILL SGA, DO SGA, DO COM-PORT, WILL COM-PORT (pyserial's Serial.open).
    codec.receive(bytes({255, 253, 1, 255, 251, 3, 255, 253, 3, 255, 253, 44, 255, 251, 44}), out);
    CHECK(out.reply == bytes({255, 252, 1,              // WONT ECHO: the unit does not echo
                              255, 253, 3,              // DO SGA
                              255, 251, 3,              // WILL SGA
                              255, 251, 44})            // WILL COM-PORT-OPTION
                           + sb(107, bytes({0xB0}))     // NOTIFY-MODEMSTATE: CTS, DSR, CD
                           + bytes({255, 253, 44}));    // DO COM-PORT-OPTION
    CHECK(out.data.empty());
    CHECK(out.notes.empty());
    // Asked again: no answer (RFC 854: a request that changes nothing is not acknowledged).
    Rfc2217Codec::Out again;
    codec.receive(bytes({255, 251, 44, 255, 253, 44, 255, 253, 3}), again);
    CHECK(again.reply.empty());
    // An option it does not do: refused, and a WONT/DONT of one it never had: nothing.
    Rfc2217Codec::Out other;
    codec.receive(bytes({255, 251, 24, 255, 253, 31, 255, 252, 24, 255, 254, 31}), other);
    CHECK(other.reply == bytes({255, 254, 24, 255, 252, 31}));
    // Switched off: acknowledged once.
    Rfc2217Codec::Out off;
    codec.receive(bytes({255, 254, 3, 255, 254, 3}), off);
    CHECK(off.reply == bytes({255, 252, 3}));
}

TEST_CASE("rfc2217: the port's settings are set, asked for, and each acknowledged with its value", "[unit][rfc2217]")
{
    Rfc2217Codec codec(115200);
    CHECK(codec.settings().baud == 115200);
    Rfc2217Codec::Out out;
    codec.receive(sb(1, bytes({0, 0, 0x25, 0x80})), out);   // SET-BAUDRATE 9600
    CHECK(out.reply == sb(101, bytes({0, 0, 0x25, 0x80})));
    CHECK(out.line_changed);
    CHECK(codec.settings().baud == 9600);
    Rfc2217Codec::Out ask;
    codec.receive(sb(1, bytes({0, 0, 0, 0})) + sb(2, bytes({0})) + sb(3, bytes({0})) + sb(4, bytes({0})), ask);
    CHECK(ask.reply == sb(101, bytes({0, 0, 0x25, 0x80})) + sb(102, bytes({8})) + sb(103, bytes({1})) + sb(104, bytes({1})));
    CHECK_FALSE(ask.line_changed);
    Rfc2217Codec::Out line;
    codec.receive(sb(2, bytes({7})) + sb(3, bytes({3})) + sb(4, bytes({2})), line);
    CHECK(line.line_changed);
    CHECK(codec.settings().data_bits == 7);
    CHECK(codec.settings().parity == 3);
    CHECK(codec.settings().stop_bits == 2);
    // A baud rate whose bytes hold 0xFF: doubled in both directions.
    Rfc2217Codec::Out ff;
    codec.receive(sb(1, bytes({0, 0, 255, 255, 255, 255})), ff);   // 65535
    CHECK(codec.settings().baud == 65535);
    CHECK(ff.reply == sb(101, bytes({0, 0, 255, 255, 255, 255})));
}

TEST_CASE("rfc2217: SET-CONTROL's flow control, BREAK, DTR and RTS, and their requests", "[unit][rfc2217]")
{
    Rfc2217Codec codec(9600);
    Rfc2217Codec::Out out;
    codec.receive(sb(5, bytes({7})) + sb(5, bytes({10})) + sb(5, bytes({0})) + sb(5, bytes({4})), out);
    CHECK(out.reply == sb(105, bytes({8})) + sb(105, bytes({11})) + sb(105, bytes({1})) + sb(105, bytes({6})));
    Rfc2217Codec::Out set;
    codec.receive(sb(5, bytes({9})) + sb(5, bytes({12})) + sb(5, bytes({3})) + sb(5, bytes({5})), set);
    CHECK(set.reply == sb(105, bytes({9})) + sb(105, bytes({12})) + sb(105, bytes({3})) + sb(105, bytes({5})));
    CHECK_FALSE(codec.settings().dtr);
    CHECK_FALSE(codec.settings().rts);
    CHECK(codec.settings().flow == 3);
    CHECK(codec.settings().brk);
    Rfc2217Codec::Out bad;
    codec.receive(sb(5, bytes({20})), bad);
    CHECK(bad.reply.empty());
    CHECK(bad.notes == std::vector<std::string>{"SET-CONTROL 20 (0..19): ignored"});
}

TEST_CASE("rfc2217: states, masks, purge, suspend and the signature", "[unit][rfc2217]")
{
    Rfc2217Codec codec(9600);
    Rfc2217Codec::Out out;
    codec.receive(sb(7, "") + sb(6, "") + sb(10, bytes({0x60})) + sb(6, "") + sb(11, bytes({0x10})) + sb(7, ""), out);
    CHECK(out.reply == sb(107, bytes({0xB0})) + sb(106, bytes({0})) + sb(110, bytes({0x60})) + sb(106, bytes({0x60}))
                           + sb(111, bytes({0x10})) + sb(107, bytes({0x10})));
    Rfc2217Codec::Out purge;
    codec.receive(sb(12, bytes({2})), purge);
    CHECK_FALSE(codec.take_purge_request());                   // the unit's side: nothing held
    codec.receive(sb(12, bytes({1})) + sb(8, ""), purge);
    CHECK(codec.take_purge_request());
    CHECK_FALSE(codec.take_purge_request());
    CHECK(codec.suspended());
    codec.receive(sb(9, ""), purge);
    CHECK_FALSE(codec.suspended());
    CHECK(purge.reply == sb(112, bytes({2})) + sb(112, bytes({1})));
    Rfc2217Codec::Out signature;
    codec.receive(sb(0, "") + sb(0, "pyserial"), signature);
    CHECK(signature.reply == sb(100, "rigsim"));
}

TEST_CASE("rfc2217: data passes with 0xFF doubled, however the bytes are cut", "[unit][rfc2217]")
{
    const std::string wire = bytes({0x05, 0, 0, 0, 0x50, 0x01, 255, 255, 0x41}) + sb(1, bytes({0, 1, 0xC2, 0})) + bytes({0x42});
    Rfc2217Codec whole(9600);
    Rfc2217Codec::Out a;
    whole.receive(wire, a);
    Rfc2217Codec cut(9600);
    Rfc2217Codec::Out b;
    for (const char c : wire)
        cut.receive(std::string(1, c), b);
    CHECK(a.data == bytes({0x05, 0, 0, 0, 0x50, 0x01, 255, 0x41, 0x42}));
    CHECK(b.data == a.data);
    CHECK(b.reply == a.reply);
    CHECK(cut.settings().baud == 115200);
    CHECK(Rfc2217Codec::escape(bytes({1, 255, 2, 255})) == bytes({1, 255, 255, 2, 255, 255}));
}

TEST_CASE("rfc2217: what it cannot read is ignored with a note, never answered", "[unit][rfc2217]")
{
    Rfc2217Codec codec(9600);
    Rfc2217Codec::Out out;
    codec.receive(sb(1, bytes({0, 0, 0x25})) + sb(99, "") + sb(2, bytes({9})) + sb(12, bytes({4}))
                      + bytes({255, 250, 24, 1, 255, 240})        // another option's subnegotiation
                      + bytes({255, 250, 255, 240})               // an empty one
                      + bytes({255, 250, 44, 1, 255, 1, 2})       // IAC 0x01 inside: dropped, data follows
                      + bytes({255, 250, 44, 1}) + std::string(100, 'x') + bytes({255, 240}),   // too long
                  out);
    CHECK(out.notes == std::vector<std::string>{
                           "SET-BAUDRATE with 3 value bytes, not 4: ignored",
                           "COM-PORT-OPTION command 99 (0..12): ignored",
                           "SET-DATASIZE 9 (5..8): the size stays",
                           "PURGE-DATA 4 (1..3): ignored",
                           "a subnegotiation of option 24, not COM-PORT-OPTION (44): ignored",
                           "an empty subnegotiation: ignored",
                           "IAC 0x01 inside a subnegotiation: the subnegotiation is dropped",
                           "a subnegotiation longer than 64 bytes: dropped",
                       });
    CHECK(out.reply == sb(102, bytes({8})));   // SET-DATASIZE 9 still gets the size it has
    CHECK(out.data == bytes({2}));
    CHECK(codec.settings().baud == 9600);
}

} // namespace test_rfc2217
