// APT input a real unit drops: frames cut short (the inter-byte timeout) and SETs with
// values outside the manual's ranges.
#include "apt_harness.hpp"

#include <cstdint>
#include <vector>

namespace test_apt_frames_ranges {

using namespace rigsim;
using namespace rigsim::apt;
using namespace rigsim::test;

namespace {

constexpr std::uint8_t kCube = 0x50;
constexpr std::uint8_t kBay0Address = 0x21;

/// REQ of the trio whose SET is `set_id`, to channel 1 of module `dest`.
std::string req_hex(std::uint16_t set_id, std::uint8_t dest)
{
    return hex(encode_header_only(static_cast<std::uint16_t>(set_id + 1), 1, 0, dest, kHost));
}

/// The data packet of a GET answer (hex) as bytes.
std::string data_of(const std::string& get_hex)
{
    const auto b = bytes(get_hex);
    REQUIRE(b.size() > kHeaderSize);
    return b.substr(kHeaderSize);
}

enum class Width { W16, W32 };

void put_at(std::string& data, std::size_t offset, Width w, std::int64_t v)
{
    std::string field;
    if (w == Width::W16)
        put_u16(field, static_cast<std::uint16_t>(v));
    else
        put_u32(field, static_cast<std::uint32_t>(v));
    data.replace(offset, field.size(), field);
}

struct RangeCase {
    const char* what;
    std::uint16_t set_id;
    bool rack;                    ///< BBD203 bay 0, else a TDC001
    std::size_t offset;
    Width width;
    std::int64_t good;            ///< accepted: REQ reads it back
    std::vector<std::int64_t> bad;   ///< each ignored: REQ reads back the good value
    std::size_t fix_offset = 0;   ///< another field the SET needs valid (0: none)
    std::int64_t fix_value = 0;
};

} // namespace

TEST_CASE("a frame cut short is dropped after the 50 ms inter-byte timeout, the next request is answered", "[device][apt][framing]")
{
    AptHarness h;
    const auto vel = h.send("14 04 01 00 50 01");
    // Half a SET_VELPARAMS with minimum 3,000,000 above maximum 1,841,682 ...
    CHECK(h.send("13 04 0E 00 D0 01 01 00 C0 C6 2D 00") == "");
    h.advance_ms(AptDevice::kInterByteTimeout_ms + 1);
    // ... then silence; the next request is a request, not the rest of the SET.
    CHECK(h.send("11 04 01 00 50 01") == "12 04 06 00 81 50 01 00 00 00 00 00");
    CHECK(h.send("14 04 01 00 50 01") == vel);
    // A partial header too.
    CHECK(h.send("11 04 01") == "");
    h.advance_ms(1000);
    CHECK(h.send("11 04 01 00 50 01") == "12 04 06 00 81 50 01 00 00 00 00 00");
}

TEST_CASE("a SET split across two receives within the inter-byte timeout is one frame", "[device][apt][framing]")
{
    AptHarness h;
    // SET_VELPARAMS 0, 500, 1,000,000 in two pieces, exactly the timeout apart.
    CHECK(h.send("13 04 0E 00 D0 01 01 00 00 00 00 00") == "");
    h.advance_ms(AptDevice::kInterByteTimeout_ms);
    CHECK(h.send("F4 01 00 00 40 42 0F 00") == "");
    CHECK(h.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 01 00 00 00 00 00 F4 01 00 00 40 42 0F 00");
    // Three pieces, each within the timeout of the one before: 150 ms in all.
    CHECK(h.send("13 04 0E") == "");
    h.advance_ms(50);
    CHECK(h.send("00 D0 01 01 00 00 00 00 00") == "");
    h.advance_ms(50);
    CHECK(h.send("E8 03 00 00") == "");
    h.advance_ms(50);
    CHECK(h.send("40 42 0F 00") == "");
    CHECK(h.send("14 04 01 00 50 01") == "15 04 0E 00 81 50 01 00 00 00 00 00 E8 03 00 00 40 42 0F 00");
}

TEST_CASE("SETs outside the manual's ranges are ignored: REQ reads back the old value", "[device][apt][ranges]")
{
    constexpr std::int64_t kMinus1 = 0xFFFFFFFF;
    const std::vector<RangeCase> cases = {
        // p. 30 VELPARAMS (channel word, min, acceleration, max; power-up 0, 393, 1,841,682)
        {"VELPARAMS minimum above maximum", MGMSG_MOT_SET_VELPARAMS, false, 2, Width::W32, 1'841'682, {1'841'683, 3'000'000}},
        {"VELPARAMS negative minimum", MGMSG_MOT_SET_VELPARAMS, false, 2, Width::W32, 0, {kMinus1}},
        {"VELPARAMS acceleration 0", MGMSG_MOT_SET_VELPARAMS, false, 6, Width::W32, 1, {0, kMinus1}},
        {"VELPARAMS maximum 0", MGMSG_MOT_SET_VELPARAMS, false, 10, Width::W32, 1'000'000, {0, kMinus1}},
        // p. 32 JOGPARAMS (mode, step, min, acceleration, max, stop mode)
        {"JOGPARAMS mode", MGMSG_MOT_SET_JOGPARAMS, false, 2, Width::W16, 1, {0, 3}},
        {"JOGPARAMS negative step", MGMSG_MOT_SET_JOGPARAMS, false, 4, Width::W32, 0, {kMinus1}},
        {"JOGPARAMS minimum above maximum", MGMSG_MOT_SET_JOGPARAMS, false, 8, Width::W32, 1'841'682, {1'841'683, kMinus1}},
        {"JOGPARAMS acceleration", MGMSG_MOT_SET_JOGPARAMS, false, 12, Width::W32, 1, {0, kMinus1}},
        {"JOGPARAMS maximum", MGMSG_MOT_SET_JOGPARAMS, false, 16, Width::W32, 1'000'000, {0, kMinus1}},
        {"JOGPARAMS stop mode", MGMSG_MOT_SET_JOGPARAMS, false, 20, Width::W16, 1, {0, 3}},
        // p. 51 DCPIDPARAMS terms 0..32767
        {"DCPIDPARAMS integral", MGMSG_MOT_SET_DCPIDPARAMS, false, 6, Width::W32, 32767, {32768, kMinus1}},
        // p. 52 AVMODES: bits 1, 2, 8
        {"AVMODES bits", MGMSG_MOT_SET_AVMODES, false, 2, Width::W16, 0x09, {0x04, 0x10, 0xFFFF}},
        // p. 58 BUTTONPARAMS mode 1 jog, 2 go to position
        {"BUTTONPARAMS mode", MGMSG_MOT_SET_BUTTONPARAMS, false, 2, Width::W16, 2, {0, 3}},
        // p. 61 PMDPOSITIONLOOPPARAMS (KdTimePos at 12 must be 1..32767 for any SET)
        {"PMDPOSITIONLOOPPARAMS Kp", MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, true, 2, Width::W16, 32767, {32768}, 12, 1},
        {"PMDPOSITIONLOOPPARAMS integral limit", MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, true, 6, Width::W32, 0x7FFFFFFF, {0x80000000}, 12, 1},
        {"PMDPOSITIONLOOPPARAMS KdTimePos", MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, true, 12, Width::W16, 32767, {0, 32768}},
        {"PMDPOSITIONLOOPPARAMS KaffPos", MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, true, 18, Width::W16, 1000, {32768}, 12, 1},
        {"PMDPOSITIONLOOPPARAMS PosErrLim", MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, true, 20, Width::W32, 20'000, {0x80000000}, 12, 1},
        // p. 63 PMDMOTOROUTPUTPARAMS
        {"PMDMOTOROUTPUTPARAMS ContCurrentLim", MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS, true, 2, Width::W16, 6554, {32768}},
        {"PMDMOTOROUTPUTPARAMS MotorLim", MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS, true, 6, Width::W16, 32767, {0xFFFF}},
        {"PMDMOTOROUTPUTPARAMS MotorBias", MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS, true, 8, Width::W16, 0x8001, {0x8000}},
        // p. 66 PMDTRACKSETTLEPARAMS settle time
        {"PMDTRACKSETTLEPARAMS time", MGMSG_MOT_SET_PMDTRACKSETTLEPARAMS, true, 2, Width::W16, 32767, {32768}},
        // p. 69 PMDPROFILEMODEPARAMS mode 0 or 2
        {"PMDPROFILEMODEPARAMS mode", MGMSG_MOT_SET_PMDPROFILEMODEPARAMS, true, 2, Width::W16, 2, {1, 3}},
        // p. 71, 73 current loops: phase 0..2, terms 0..32767
        {"PMDCURRENTLOOPPARAMS phase", MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS, true, 2, Width::W16, 2, {3}},
        {"PMDCURRENTLOOPPARAMS Kff", MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS, true, 12, Width::W16, 100, {32768}},
        {"PMDSETTLEDCURRENTLOOPPARAMS phase", MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS, true, 2, Width::W16, 1, {3}},
        {"PMDSETTLEDCURRENTLOOPPARAMS KiSettled", MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS, true, 6, Width::W16, 40, {32768}},
    };
    for (const auto& c : cases) {
        INFO(c.what);
        AptHarness h(c.rack ? apt_rack("BBD203", {"MLS203-X", "MLS203-Y", "MLS203-X"}) : tdc001());
        const std::uint8_t dest = c.rack ? kBay0Address : kCube;
        auto data = data_of(h.send(req_hex(c.set_id, dest)));
        if (c.fix_offset != 0)
            put_at(data, c.fix_offset, Width::W16, c.fix_value);
        put_at(data, c.offset, c.width, c.good);
        CHECK(h.send(hex(encode_with_data(c.set_id, dest, kHost, data))) == "");
        const auto accepted = h.send(req_hex(c.set_id, dest));
        CHECK(data_of(accepted) == data);
        for (const auto bad : c.bad) {
            INFO("value " << bad);
            auto wrong = data;
            put_at(wrong, c.offset, c.width, bad);
            CHECK(h.send(hex(encode_with_data(c.set_id, dest, kHost, wrong))) == "");
            CHECK(h.send(req_hex(c.set_id, dest)) == accepted);
        }
    }
}

TEST_CASE("PMDSTAGEAXISPARAMS only narrows the travel: a wider or inverted one is ignored", "[device][apt][ranges][rack]")
{
    AptHarness h(apt_rack("BBD203", {"MLS203-X", "MLS203-Y", "MLS203-X"}));
    const auto before = h.send(req_hex(MGMSG_MOT_SET_PMDSTAGEAXISPARAMS, kBay0Address));
    const auto block = data_of(before);
    const auto min_position = get_i32(block, 30), max_position = get_i32(block, 34);
    auto set = [&](std::int32_t lo, std::int32_t hi) {
        auto d = block;
        std::string v;
        put_i32(v, lo);
        put_i32(v, hi);
        d.replace(30, 8, v);
        return h.send(hex(encode_with_data(MGMSG_MOT_SET_PMDSTAGEAXISPARAMS, kBay0Address, kHost, d)));
    };
    CHECK(set(min_position - 1, max_position - 1000) == "");            // wider at one end: not half applied
    CHECK(set(min_position - 1, max_position) == "");                   // wider at the low end
    CHECK(set(min_position, max_position + 1) == "");                   // wider at the high end
    CHECK(set(min_position + 1000, min_position + 1000) == "");         // empty
    CHECK(set(min_position + 2000, min_position + 1000) == "");         // inverted
    CHECK(h.send(req_hex(MGMSG_MOT_SET_PMDSTAGEAXISPARAMS, kBay0Address)) == before);
    CHECK(set(min_position + 1000, max_position - 1000) == "");
    const auto narrowed = data_of(h.send(req_hex(MGMSG_MOT_SET_PMDSTAGEAXISPARAMS, kBay0Address)));
    CHECK(get_i32(narrowed, 30) == min_position + 1000);
    CHECK(get_i32(narrowed, 34) == max_position - 1000);
}

} // namespace test_apt_frames_ranges
