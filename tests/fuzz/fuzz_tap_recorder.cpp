// Fuzz target: the conformance tap's recorder (emulator/tap/recording.*): bytes of both directions
// of two connections, cut into frames by the family's framer and written as JSON lines.
// Input: a first byte choosing the protocol (its value modulo 3: apt, mcs, mcs2), then chunks, each
// a byte (bit 0: the direction; bit 1: a new connection first; bits 2-7: the length, 0..63) and
// that many bytes. The recording goes to one file of this process under $TMPDIR (removed at exit).
// Checked beyond the sanitizers: every line is a JSON object with consecutive `seq`, and the bytes
// of each direction's lines, concatenated, are exactly the bytes fed in that direction: the tap
// loses, repeats and reorders no byte, whatever the framers make of them.
#include "emulator/tap/recording.hpp"

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>

namespace {

const std::string& recording_path()
{
    static const std::string path = [] {
        const char* dir = std::getenv("TMPDIR");
        const std::string p = std::string(dir && *dir ? dir : "/tmp") + "/rigsim-fuzz-tap-" + std::to_string(::getpid());
        std::atexit([] { std::remove(recording_path().c_str()); });
        return p;
    }();
    return path;
}

std::string unhex(const std::string& h)
{
    std::string out;
    for (std::size_t i = 0; i + 1 < h.size(); i += 2)
        out += static_cast<char>(std::stoi(h.substr(i, 2), nullptr, 16));
    return out;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size == 0)
        return 0;
    const rigsim::tap::Protocol protocols[] = {rigsim::tap::Protocol::Apt, rigsim::tap::Protocol::Mcs,
                                               rigsim::tap::Protocol::Mcs2};
    const auto protocol = protocols[data[0] % 3];
    std::string fed[2];
    {
        rigsim::tap::Recorder rec(recording_path(), protocol, nlohmann::json::object());
        std::uint64_t conn = 1;
        std::int64_t t = 0;
        std::size_t i = 1;
        while (i < size) {
            const std::uint8_t head = data[i++];
            const auto dir = (head & 1) ? rigsim::tap::Direction::Out : rigsim::tap::Direction::In;
            if (head & 2) {
                rec.event("disconnect", conn, t, nlohmann::json::object());
                ++conn;
                rec.event("connect", conn, t, nlohmann::json::object());
            }
            const std::size_t n = std::min<std::size_t>(head >> 2, size - i);
            const std::string_view chunk(reinterpret_cast<const char*>(data + i), n);
            i += n;
            fed[head & 1].append(chunk);
            rec.bytes(conn, dir, chunk, ++t);
        }
        rec.event("stop", conn, ++t, nlohmann::json::object());
    }
    std::ifstream in(recording_path());
    std::string line;
    std::string recorded[2];
    std::int64_t seq = -1;
    bool header = true;
    while (std::getline(in, line)) {
        const auto j = nlohmann::json::parse(line);   // throws (and the fuzzer reports it) if not JSON
        if (!j.is_object())
            std::abort();
        if (header) {
            header = false;
            continue;
        }
        if (j.at("seq").get<std::int64_t>() != seq + 1)
            std::abort();
        seq = j.at("seq").get<std::int64_t>();
        if (j.contains("bytes"))
            recorded[j.at("dir") == "out" ? 1 : 0] += unhex(j.at("bytes").get<std::string>());
    }
    if (recorded[0] != fed[0] || recorded[1] != fed[1])
        std::abort();
    return 0;
}
