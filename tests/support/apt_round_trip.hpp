#pragma once
// The APT codec tests' round trip: a typed message encodes to the bytes a test writes out by
// hand (or quotes from a public source), and those bytes, through the framer, decode back to
// the same struct, with the same ID, and encode again to the same bytes.
#include "emulator/apt/codec.hpp"
#include "tests/support/hex.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <string>

namespace rigsim::test {

/// Decode `bytes` (one whole frame) through the framer.
inline apt::msg::Message decode_frame(const std::string& bytes)
{
    apt::FrameFramer framer;
    const auto r = framer.parse(bytes);
    REQUIRE(r.status == apt::FrameFramer::Status::Frame);
    REQUIRE(r.consumed == bytes.size());
    return apt::msg::decode(r.frame);
}

/// encode(m) from `source` (the host, 0x01) to `dest` (a single unit, 0x50) is `frame_hex`,
/// which decodes to m and encodes back to `frame_hex`.
template <class T>
void round_trip(const T& m, const std::string& frame_hex, std::uint8_t dest = 0x50, std::uint8_t source = 0x01)
{
    CHECK(hex(apt::msg::encode(m, dest, source)) == frame_hex);
    const std::string frame = bytes(frame_hex);   // outlives the decoded message
    const auto decoded = decode_frame(frame);
    REQUIRE(apt::msg::holds<T>(decoded));
    CHECK((*apt::msg::get_if<T>(decoded) == m));
    CHECK(apt::msg::message_id(decoded) == (static_cast<unsigned char>(frame[0]) | static_cast<unsigned char>(frame[1]) << 8));
    CHECK(hex(apt::msg::encode(decoded, dest, source)) == frame_hex);
}

} // namespace rigsim::test
