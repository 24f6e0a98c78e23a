// WireLog (emulator/core/wire_log.hpp): the ring keeps the last entries whole, each entry
// overwritten in place by a frame of any size.
#include "emulator/core/wire_log.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <string>

namespace test_wire_log {

using namespace rigsim;

TEST_CASE("wire log: an entry overwritten by a shorter, a longer and a much longer frame holds it whole",
          "[unit][wire_log]")
{
    WireLog log("dev", 1000, nullptr, nullptr, 2);
    const std::string sizes[] = {":GP0\n", ":P0,0\n", ":G\n", std::string(40, 'x'), "", ":GS0\n",
                                 std::string(1000, 'y'), ":E0,0\n"};
    std::uint64_t seq = 0;
    for (const auto& bytes : sizes) {
        log.add(static_cast<std::int64_t>(seq), seq % 2 == 0, seq % 3 == 0 ? "tcp 127.0.0.1:1" : "pty", bytes);
        ++seq;
        const auto* last = log.last();
        REQUIRE(last != nullptr);
        CHECK(last->bytes == bytes);
        CHECK(last->seq == seq);
        CHECK(last->peer == ((seq - 1) % 3 == 0 ? "tcp 127.0.0.1:1" : "pty"));
        CHECK(last->notes.empty());
    }
    CHECK(log.size() == 2);
    const auto entries = log.to_json(5);
    REQUIRE(entries.size() == 2);
    CHECK(entries[0]["hex"] == hex_bytes(std::string(1000, 'y')));
    CHECK(entries[1]["hex"] == hex_bytes(":E0,0\n"));
    log.add(9, true, "pty", ":GP0\n", {"a note"});
    log.add(10, true, "pty", ":GP1\n");   // no note: the one of the entry it overwrites goes
    CHECK(log.last()->notes.empty());
    CHECK(log.noted() == 1);
}

} // namespace test_wire_log
