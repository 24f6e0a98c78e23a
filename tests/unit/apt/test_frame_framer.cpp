// APT frame framer (manual sections 3 and 4): arbitrary splits and coalescing, garbage,
// resync past implausible headers, bounded memory.
#include "emulator/apt/frame_framer.hpp"
#include "emulator/apt/messages.hpp"
#include "emulator/apt/wire.hpp"
#include "tests/support/hex.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace test_frame_framer {

using namespace rigsim::apt;
using rigsim::test::hex;

namespace {


/// "0453 d=50 s=01 p=01,00" for header-only frames, "0453 d=50 s=01 [01 00 ...]" with data.
std::string describe(const Frame& f)
{
    char head[32];
    std::snprintf(head, sizeof head, "%04X d=%02X s=%02X ", f.id, f.dest, f.source);
    std::string out = head;
    if (f.has_data) {
        out += "[" + hex(f.data) + "]";
    } else {
        char params[16];
        std::snprintf(params, sizeof params, "p=%02X,%02X", f.param1, f.param2);
        out += params;
    }
    return out;
}

/// Feed `input` in pieces of `chunk` bytes; describe every frame; add dropped bytes up.
std::vector<std::string> frame(FrameFramer& f, const std::string& input, std::size_t chunk,
                               std::size_t* dropped = nullptr)
{
    std::vector<std::string> frames;
    for (std::size_t pos = 0; pos < input.size(); pos += chunk) {
        std::string_view piece = std::string_view(input).substr(pos, chunk);
        while (!piece.empty()) {
            const auto r = f.parse(piece);
            REQUIRE(r.consumed > 0);
            REQUIRE(r.consumed <= piece.size());
            piece.remove_prefix(r.consumed);
            if (dropped)
                *dropped += r.dropped;
            switch (r.status) {
            case FrameFramer::Status::NeedMore:
                REQUIRE(piece.empty());
                break;
            case FrameFramer::Status::Frame: {
                REQUIRE(r.frame.info != nullptr);
                CHECK(r.frame.info->id == r.frame.id);
                // The frame's bytes as they came, whatever the split: what its fields encode.
                const auto& fr = r.frame;
                CHECK(hex(fr.bytes) == hex(fr.has_data ? encode_with_data(fr.id, fr.dest, fr.source, fr.data)
                                                       : encode_header_only(fr.id, fr.param1, fr.param2, fr.dest, fr.source)));
                frames.push_back(describe(r.frame));
                break;
            }
            }
        }
    }
    return frames;
}

std::vector<std::string> frame(const std::string& input, std::size_t chunk, std::size_t* dropped = nullptr)
{
    FrameFramer f;
    return frame(f, input, chunk, dropped);
}

std::string bytes(std::initializer_list<unsigned> list)
{
    std::string out;
    for (unsigned b : list)
        out.push_back(static_cast<char>(b));
    return out;
}

/// A MOVE_ABSOLUTE long form: chan 1, position.
std::string move_absolute(std::int32_t position, std::uint8_t dest = kGenericUsb)
{
    std::string data;
    put_u16(data, 1);
    put_i32(data, position);
    return encode_with_data(MGMSG_MOT_MOVE_ABSOLUTE, dest, kHost, data);
}

const std::string kReqInfo = bytes({0x05, 0x00, 0x00, 0x00, 0x50, 0x01});
const std::string kReqInfoSeen = "0005 d=50 s=01 p=00,00";

} // namespace

TEST_CASE("apt framer yields header-only and data frames", "[unit][apt][framer]")
{
    CHECK(frame(kReqInfo, 100) == std::vector<std::string>{kReqInfoSeen});
    CHECK(frame(move_absolute(200000), 100)
          == std::vector<std::string>{"0453 d=50 s=01 [01 00 40 0D 03 00]"});
    CHECK(frame(kReqInfo + move_absolute(-1, kBay0) + kReqInfo, 100)
          == std::vector<std::string>{kReqInfoSeen, "0453 d=21 s=01 [01 00 FF FF FF FF]", kReqInfoSeen});
}

TEST_CASE("apt framer reports the header fields", "[unit][apt][framer]")
{
    FrameFramer f;
    const std::string in = encode_header_only(MGMSG_MOT_MOVE_JOG, 0x01, 0x02, 0x22, kHost);
    const auto r = f.parse(in);
    REQUIRE(r.status == FrameFramer::Status::Frame);
    CHECK(r.consumed == 6);
    CHECK(r.dropped == 0);
    CHECK(r.frame.id == MGMSG_MOT_MOVE_JOG);
    CHECK(r.frame.param1 == 0x01);
    CHECK(r.frame.param2 == 0x02);
    CHECK(r.frame.dest == 0x22);
    CHECK(r.frame.source == kHost);
    CHECK_FALSE(r.frame.has_data);
    CHECK(r.frame.data.empty());
    CHECK(r.frame.info == find_message(MGMSG_MOT_MOVE_JOG));

    const std::string long_form = move_absolute(7, kBay9);
    const auto d = f.parse(long_form);
    REQUIRE(d.status == FrameFramer::Status::Frame);
    CHECK(d.frame.dest == kBay9);   // without the 0x80 flag
    CHECK(d.frame.has_data);
    CHECK(d.frame.param1 == 0);
    CHECK(d.frame.param2 == 0);
    CHECK(d.frame.data.size() == 6);
    CHECK(get_i32(d.frame.data, 2) == 7);
    CHECK(d.frame.data.data() == long_form.data() + 6);   // zero-copy when whole
    CHECK(f.frames() == 2);
}

TEST_CASE("apt framer gives the same frames for every split of the input", "[unit][apt][framer]")
{
    std::string info_data(84, '\0');
    info_data.replace(4, 6, "TDC001");
    const std::string input = bytes({0xFF, 0x00, 0x13})                  // garbage
        + kReqInfo
        + move_absolute(200000)
        + encode_header_only(MGMSG_MOT_MOVE_ABSOLUTE, 0x01, 0x00, 0x22, kHost)   // short form
        + bytes({0x04, 0x50, 0x01})                                        // garbage
        + encode_with_data(MGMSG_HW_GET_INFO, kHost, kGenericUsb, info_data)
        + encode_header_only(MGMSG_MOT_MOVE_STOP, 0x01, 0x02, kGenericUsb, kHost)
        + bytes({0x44});                                                   // garbage
    const auto expected = frame(input, input.size());
    REQUIRE(expected.size() == 5);
    CHECK(expected[0] == kReqInfoSeen);
    CHECK(expected[2] == "0453 d=22 s=01 p=01,00");
    CHECK(expected[4] == "0465 d=50 s=01 p=01,02");
    // The trailing 0x44 stays buffered (0x44 0x?? may still be MOVE_HOMED).
    const std::size_t garbage = 3 + 3;

    for (std::size_t chunk = 1; chunk <= input.size(); ++chunk) {
        INFO("chunk " << chunk);
        std::size_t dropped = 0;
        CHECK(frame(input, chunk, &dropped) == expected);
        CHECK(dropped == garbage);
    }
    // Every split into three pieces (Beast's parsegrind, and then some).
    for (std::size_t cut1 = 0; cut1 <= input.size(); ++cut1) {
        for (std::size_t cut2 = cut1; cut2 <= input.size(); ++cut2) {
            FrameFramer f;
            std::size_t dropped = 0;
            auto frames = frame(f, input.substr(0, cut1), input.size() + 1, &dropped);
            auto middle = frame(f, input.substr(cut1, cut2 - cut1), input.size() + 1, &dropped);
            auto rest = frame(f, input.substr(cut2), input.size() + 1, &dropped);
            frames.insert(frames.end(), middle.begin(), middle.end());
            frames.insert(frames.end(), rest.begin(), rest.end());
            if (frames != expected || dropped != garbage) {
                INFO("cuts " << cut1 << " " << cut2);
                CHECK(frames == expected);
                CHECK(dropped == garbage);
            }
            CHECK(f.buffered() == 1);
        }
    }
}

TEST_CASE("apt framer skips garbage before and between frames", "[unit][apt][framer]")
{
    const std::string prefix = "hello world\r\n";
    const std::string infix = bytes({0x00, 0x00, 0xFF, 0x80, 0x7F});
    const std::string input = prefix + kReqInfo + infix + move_absolute(5) + infix + kReqInfo;
    for (std::size_t chunk : {1u, 2u, 5u, 6u, 7u, 64u}) {
        INFO("chunk " << chunk);
        FrameFramer f;
        std::size_t dropped = 0;
        CHECK(frame(f, input, chunk, &dropped)
              == std::vector<std::string>{kReqInfoSeen, "0453 d=50 s=01 [01 00 05 00 00 00]", kReqInfoSeen});
        CHECK(dropped == prefix.size() + 2 * infix.size());
        CHECK(f.dropped_bytes() == dropped);
        CHECK(f.frames() == 3);
        CHECK(f.garbage_runs() == 3);
        CHECK(f.buffered() == 0);
    }
}

TEST_CASE("apt framer reports dropped bytes in the call that drops them", "[unit][apt][framer]")
{
    FrameFramer f;
    auto r = f.parse(bytes({0x05, 0x00, 0x00, 0x00}));   // plausible so far: held
    CHECK(r.status == FrameFramer::Status::NeedMore);
    CHECK(r.consumed == 4);
    CHECK(r.dropped == 0);
    CHECK(f.buffered() == 4);
    CHECK_FALSE(f.in_frame());
    r = f.parse(bytes({0x30}));   // 0x30 is no address: the held bytes are garbage after all
    CHECK(r.status == FrameFramer::Status::NeedMore);
    CHECK(r.dropped == 4);
    CHECK(f.buffered() == 1);     // 0x30 itself may still start a header
    r = f.parse(kReqInfo);        // 0x0530 is no message
    CHECK(r.status == FrameFramer::Status::Frame);
    CHECK(r.dropped == 1);
    CHECK(f.dropped_bytes() == 5);
    CHECK(f.garbage_runs() == 1);
}

TEST_CASE("apt framer resyncs past implausible headers", "[unit][apt][framer]")
{
    const std::string zeros14(14, '\0');
    struct Case {
        const char* what;
        std::string bad;
    };
    const std::vector<Case> cases{
        {"unknown ID", bytes({0xFF, 0xFF, 0x00, 0x00, 0x50, 0x01})},
        {"unknown ID 0x0000", bytes({0x00, 0x00, 0x00, 0x00, 0x50, 0x01})},
        {"wrong source", bytes({0x05, 0x00, 0x00, 0x00, 0x50, 0x02})},
        {"source with the data flag", bytes({0x05, 0x00, 0x00, 0x00, 0x50, 0x81})},
        {"source 0x00 (the HW_DISCONNECT example)", bytes({0x02, 0x00, 0x00, 0x00, 0x11, 0x00})},
        {"wrong destination", bytes({0x05, 0x00, 0x00, 0x00, 0x30, 0x01})},
        {"destination past the last bay", bytes({0x05, 0x00, 0x00, 0x00, 0x2B, 0x01})},
        {"header-only message with the data flag", bytes({0x05, 0x00, 0x00, 0x00, 0xD0, 0x01})},
        {"data message without the data flag", bytes({0x13, 0x04, 0x0E, 0x00, 0x50, 0x01}) + zeros14},
        {"absurd length", bytes({0x13, 0x04, 0xFF, 0xFF, 0xD0, 0x01}) + zeros14},
        {"length over 255", bytes({0x06, 0x00, 0x00, 0x01, 0x81, 0x50}) + zeros14},
        {"MOVE_COMPLETED without its status", bytes({0x64, 0x04, 0x01, 0x00, 0x01, 0x50})},
        {"MOVE_JOG with data", bytes({0x6A, 0x04, 0x06, 0x00, 0xD0, 0x01, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00})},
        // quantumion/thorlabs_cube's Message packs a REQ's channel word as a data packet.
        {"REQ_KCUBEMMIPARAMS with a data packet", bytes({0x21, 0x05, 0x02, 0x00, 0xD0, 0x01, 0x01, 0x00})},
    };
    for (const auto& c : cases) {
        INFO(c.what << ": " << hex(c.bad));
        const std::string input = c.bad + kReqInfo + c.bad + move_absolute(1);
        for (std::size_t chunk : {1u, 3u, 6u, 1000u}) {
            INFO("chunk " << chunk);
            std::size_t dropped = 0;
            CHECK(frame(input, chunk, &dropped)
                  == std::vector<std::string>{kReqInfoSeen, "0453 d=50 s=01 [01 00 01 00 00 00]"});
            CHECK(dropped == 2 * c.bad.size());
        }
    }
}

TEST_CASE("apt framer frames a data packet shorter than its table layout, at the header's length",
          "[unit][apt][framer]")
{
    // Section 3: the header says how long the packet is. pyLabLib sends MOT_SET_KCUBETRIGIOCONFIG
    // as 10 bytes (the table's layout, Thorlabs' example, has 22), yaq as 12, quantumion as 20;
    // VELPARAMS one byte short of its 14; an empty packet.
    const std::string trig10 = bytes({0x23, 0x05, 0x0A, 0x00, 0xD0, 0x01, 1, 0, 0x0A, 0, 1, 0, 0x0B, 0, 1, 0});
    const std::string trig12 = bytes({0x23, 0x05, 0x0C, 0x00, 0xD0, 0x01, 1, 0, 0x0A, 0, 1, 0, 0x0B, 0, 1, 0, 0, 0});
    const std::string vel13 = bytes({0x13, 0x04, 0x0D, 0x00, 0xD0, 0x01}) + std::string(13, '\x01');
    const std::string empty = bytes({0x13, 0x04, 0x00, 0x00, 0xD0, 0x01});
    const std::string input = trig10 + kReqInfo + trig12 + vel13 + empty + move_absolute(1);
    const std::vector<std::string> expected{
        "0523 d=50 s=01 [01 00 0A 00 01 00 0B 00 01 00]", kReqInfoSeen,
        "0523 d=50 s=01 [01 00 0A 00 01 00 0B 00 01 00 00 00]",
        "0413 d=50 s=01 [01 01 01 01 01 01 01 01 01 01 01 01 01]", "0413 d=50 s=01 []",
        "0453 d=50 s=01 [01 00 01 00 00 00]"};
    for (std::size_t chunk = 1; chunk <= input.size(); ++chunk) {
        INFO("chunk " << chunk);
        std::size_t dropped = 0;
        CHECK(frame(input, chunk, &dropped) == expected);
        CHECK(dropped == 0);
    }
}

TEST_CASE("apt framer frames a data packet longer than its table layout, at the header's length, up to 255",
          "[unit][apt][framer]")
{
    // Section 3: the header says how long the packet is, and the unit consumes that many bytes.
    // VELPARAMS two bytes past its 14; quantumion/thorlabs_cube kcube/ksc.py's KCUBEMMIPARAMS,
    // "<HHLLLHHLLLLH" (38 bytes, the table's layout 36); a long-form MOVE_ABSOLUTE two past its 6;
    // a MOVE_RELATIVE of 255 bytes.
    const std::string vel16 = bytes({0x13, 0x04, 0x10, 0x00, 0xD0, 0x01}) + std::string(16, '\x02');
    const std::string mmi38 = bytes({0x20, 0x05, 0x26, 0x00, 0xD0, 0x01}) + std::string(38, '\x03');
    const std::string abs8 = bytes({0x53, 0x04, 0x08, 0x00, 0xD0, 0x01, 1, 0, 0x10, 0, 0, 0, 0xEE, 0xEE});
    const std::string rel255 = encode_with_data(MGMSG_MOT_MOVE_RELATIVE, kGenericUsb, kHost, std::string(255, '\x04'));
    const std::string input = vel16 + kReqInfo + mmi38 + abs8 + rel255 + move_absolute(1);
    const std::vector<std::string> expected{"0413 d=50 s=01 [" + hex(std::string(16, '\x02')) + "]", kReqInfoSeen,
                                            "0520 d=50 s=01 [" + hex(std::string(38, '\x03')) + "]",
                                            "0453 d=50 s=01 [01 00 10 00 00 00 EE EE]",
                                            "0448 d=50 s=01 [" + hex(std::string(255, '\x04')) + "]",
                                            "0453 d=50 s=01 [01 00 01 00 00 00]"};
    for (std::size_t chunk = 1; chunk <= input.size(); ++chunk) {
        INFO("chunk " << chunk);
        std::size_t dropped = 0;
        CHECK(frame(input, chunk, &dropped) == expected);
        CHECK(dropped == 0);
    }
}

TEST_CASE("apt framer takes the bytes after a garbage header of a plausible length as its data, requests included",
          "[unit][apt][framer]")
{
    // Noise that reads as a header (SET_VELPARAMS to 0x50, 12 data bytes) holds the next 12 bytes
    // as its packet, as a real unit believes the length: the two REQ_INFOs behind it are data,
    // unanswered; the third is a frame. Before lengths past the layout were framed, the 14 bytes
    // of VELPARAMS bounded what noise could swallow; now 255 do (frame_framer.hpp).
    const std::string noise = bytes({0x13, 0x04, 0x0C, 0x00, 0xD0, 0x01});
    const std::string input = noise + kReqInfo + kReqInfo + kReqInfo;
    for (std::size_t chunk = 1; chunk <= input.size(); ++chunk) {
        INFO("chunk " << chunk);
        std::size_t dropped = 0;
        CHECK(frame(input, chunk, &dropped)
              == std::vector<std::string>{"0413 d=50 s=01 [05 00 00 00 50 01 05 00 00 00 50 01]", kReqInfoSeen});
        CHECK(dropped == 0);
    }
    // A length past what follows: the framer waits for the rest with the request inside it,
    // until the session's inter-byte timeout discards the lot (discard_partial, counted as
    // garbage); the request sent again is framed.
    FrameFramer f;
    CHECK(frame(f, bytes({0x13, 0x04, 0xFF, 0x00, 0xD0, 0x01}) + kReqInfo, 100).empty());
    CHECK(f.in_frame());
    CHECK(f.buffered() == 12);
    CHECK(f.discard_partial() == 12);
    CHECK(hex(f.take_dropped().bytes) == "13 04 FF 00 D0 01 " + hex(kReqInfo));
    CHECK(frame(f, kReqInfo, 100) == std::vector<std::string>{kReqInfoSeen});
}

TEST_CASE("apt framer seeds: random frames of every length up to 255 among garbage keep their boundaries",
          "[unit][apt][framer]")
{
    // Deterministic fuzzing of the header's length: data messages of the table at random lengths,
    // half of them 0..layout and half past the layout up to 255, separated by runs of bytes that
    // can start no header (0x00: ID 0x0000 and address 0x00 are none), split at random. Every
    // frame comes out whole, in order, nothing of a frame is dropped, and every garbage byte is.
    std::mt19937 rng(2024);
    std::vector<const MessageInfo*> data_messages;
    for (const auto& m : all_messages())
        if (!m.header_only())
            data_messages.push_back(&m);
    for (int round = 0; round < 200; ++round) {
        std::string input;
        std::vector<std::string> expected;
        std::size_t garbage = 0;
        for (int k = 0; k < 8; ++k) {
            const std::size_t run = rng() % 4;
            input.append(run, '\0');
            garbage += run;
            const auto& m = *data_messages[rng() % data_messages.size()];
            const auto layout = static_cast<std::size_t>(m.data_length);
            const std::size_t length =
                rng() % 2 ? rng() % (layout + 1) : layout + 1 + rng() % (kMaxDataLength - layout);
            std::string data(length, '\0');
            for (auto& c : data)
                c = static_cast<char>(rng() & 0xFF);
            const std::string f = encode_with_data(m.id, kGenericUsb, kHost, data);
            input += f;
            char head[32];
            std::snprintf(head, sizeof head, "%04X d=50 s=01 ", m.id);
            expected.push_back(head + ("[" + hex(data) + "]"));
        }
        FrameFramer f;
        std::size_t dropped = 0;
        std::vector<std::string> got;
        std::size_t pos = 0;
        while (pos < input.size()) {
            const std::size_t n = 1 + rng() % 40;
            auto part = frame(f, input.substr(pos, n), n, &dropped);
            got.insert(got.end(), part.begin(), part.end());
            pos += n;
        }
        INFO("round " << round);
        CHECK(got == expected);
        CHECK(dropped == garbage);
        CHECK(f.buffered() == 0);
    }
}

TEST_CASE("apt framer holds a frame until its data has arrived", "[unit][apt][framer]")
{
    FrameFramer f;
    const std::string m = move_absolute(0x01020304);
    auto r = f.parse(std::string_view(m).substr(0, 8));
    CHECK(r.status == FrameFramer::Status::NeedMore);
    CHECK(f.in_frame());
    CHECK(f.buffered() == 8);
    r = f.parse(std::string_view(m).substr(8));
    REQUIRE(r.status == FrameFramer::Status::Frame);
    CHECK(r.consumed == 4);
    CHECK_FALSE(f.in_frame());
    // The data lives in the framer until the next parse().
    CHECK(hex(r.frame.data) == "01 00 04 03 02 01");
    r = f.parse(kReqInfo);
    CHECK(r.status == FrameFramer::Status::Frame);
    CHECK(f.buffered() == 0);
}

TEST_CASE("apt framer accepts both forms of MOVE_RELATIVE and MOVE_ABSOLUTE", "[unit][apt][framer]")
{
    std::string data;
    put_u16(data, 1);
    put_i32(data, -20000);
    const std::string input = encode_header_only(MGMSG_MOT_MOVE_RELATIVE, 1, 0, kGenericUsb, kHost)
        + encode_with_data(MGMSG_MOT_MOVE_RELATIVE, kGenericUsb, kHost, data)
        + encode_header_only(MGMSG_MOT_MOVE_ABSOLUTE, 1, 0, kGenericUsb, kHost)
        + encode_with_data(MGMSG_MOT_MOVE_ABSOLUTE, kGenericUsb, kHost, data);
    for (std::size_t chunk = 1; chunk <= input.size(); ++chunk)
        CHECK(frame(input, chunk) == std::vector<std::string>{
                  "0448 d=50 s=01 p=01,00", "0448 d=50 s=01 [01 00 E0 B1 FF FF]",
                  "0453 d=50 s=01 p=01,00", "0453 d=50 s=01 [01 00 E0 B1 FF FF]"});
}

TEST_CASE("apt framer recognises piezo and strain gauge frames", "[unit][apt][framer]")
{
    // Until the table had the piezo chapter, these were dropped as garbage.
    std::string status;
    put_u16(status, 1);
    put_i16(status, 0x7777);   // OPVoltage
    put_i16(status, 0x1333);   // Position
    put_u32(status, 0x00000401);
    const std::string garbage = bytes({0x00, 0x07, 0xFF});
    // 0x0660 (PZ_REQ_PZSTATUSUPDATE, later issues) is a frame too, 0x0663 is not.
    const std::string input = garbage + encode_header_only(MGMSG_PZ_REQ_OUTPUTVOLTS, 1, 0, kGenericUsb, kHost)
        + encode_with_data(MGMSG_PZ_GET_PZSTATUSUPDATE, kHost, kGenericUsb, status) + garbage
        + encode_header_only(MGMSG_PZ_REQ_TSG_READING, 1, 0, kGenericUsb, kHost) + kReqInfo
        + encode_header_only(MGMSG_PZ_REQ_PZSTATUSUPDATE, 1, 0, kGenericUsb, kHost)
        + encode_header_only(0x0663, 1, 0, kGenericUsb, kHost);
    const std::vector<std::string> expected{"0644 d=50 s=01 p=01,00",
                                            "0661 d=01 s=50 [01 00 77 77 33 13 01 04 00 00]",
                                            "07DD d=50 s=01 p=01,00", kReqInfoSeen, "0660 d=50 s=01 p=01,00"};
    for (std::size_t chunk = 1; chunk <= input.size(); ++chunk) {
        INFO("chunk " << chunk);
        std::size_t dropped = 0;
        CHECK(frame(input, chunk, &dropped) == expected);
        CHECK(dropped == 2 * garbage.size() + 5);   // 0x0663 is no message; its last byte may start one
    }
}

TEST_CASE("apt framer keeps the bytes it drops for the wire log, in order, the first 256 of them",
          "[unit][apt][framer]")
{
    FrameFramer f;
    // "hi" before a frame, held bytes that turn out to be garbage, then a frame.
    CHECK(frame(f, "hi" + kReqInfo + bytes({0x05, 0x00, 0x00, 0x00}), 100) == std::vector<std::string>{kReqInfoSeen});
    CHECK(frame(f, bytes({0x30}) + kReqInfo, 100) == std::vector<std::string>{kReqInfoSeen});
    auto d = f.take_dropped();
    CHECK(d.count == 7);
    CHECK(hex(d.bytes) == "68 69 05 00 00 00 30");
    CHECK(f.take_dropped().count == 0);
    // A partial frame the session discards (the inter-byte timeout).
    CHECK(frame(f, bytes({0x13, 0x04, 0x0E, 0x00, 0xD0, 0x01, 0x01}), 100).empty());
    CHECK(f.discard_partial() == 7);
    d = f.take_dropped();
    CHECK(hex(d.bytes) == "13 04 0E 00 D0 01 01");
    // A long run: counted in full, the first kKeptDropped kept.
    CHECK(frame(f, std::string(1000, 'Z') + kReqInfo, 64) == std::vector<std::string>{kReqInfoSeen});
    d = f.take_dropped();
    CHECK(d.count == 1000);
    CHECK(d.bytes == std::string(FrameFramer::kKeptDropped, 'Z'));
}

TEST_CASE("apt framer survives 10 MB of garbage", "[unit][apt][framer]")
{
    SECTION("one repeated byte")
    {
        FrameFramer f;
        const std::string chunk(64 * 1024, 'Z');   // 0x5A5A is no message
        for (int i = 0; i < 160; ++i) {            // 10 MiB
            const auto r = f.parse(chunk);
            CHECK(r.status == FrameFramer::Status::NeedMore);
            CHECK(r.consumed == chunk.size());
            CHECK(f.buffered() <= 1);
        }
        CHECK(frame(f, kReqInfo, 100) == std::vector<std::string>{kReqInfoSeen});
        CHECK(f.dropped_bytes() == 160u * chunk.size());
        CHECK(f.garbage_runs() == 1);
    }
    SECTION("random bytes")
    {
        FrameFramer f;
        std::mt19937 rng(12345);
        std::string chunk(64 * 1024, '\0');
        for (int i = 0; i < 160; ++i) {
            for (auto& c : chunk)
                c = static_cast<char>(rng() & 0xFF);
            std::string_view piece = chunk;
            while (!piece.empty()) {
                const auto r = f.parse(piece);
                REQUIRE(r.consumed > 0);
                piece.remove_prefix(r.consumed);
                REQUIRE(f.buffered() <= kMaxFrameSize);
            }
        }
        // Random bytes hold a plausible header now and then; whatever is held, at most one
        // frame of zeros completes it, and the zeros after that are dropped.
        CHECK(f.dropped_bytes() > 10u * 1000 * 1000);
        const auto frames = frame(f, std::string(kMaxFrameSize, '\0') + kReqInfo, 7);
        REQUIRE_FALSE(frames.empty());
        CHECK(frames.back() == kReqInfoSeen);
        CHECK(f.buffered() == 0);
    }
}

TEST_CASE("discard_partial drops a frame short of its data or a partial header, then frames resume", "[unit][apt][framer]")
{
    FrameFramer f;
    const auto set_vel = rigsim::test::bytes("13 04 0E 00 D0 01 01 00 00 00 00 00 F4 01 00 00 40 42 0F 00");
    const auto req_pos = rigsim::test::bytes("11 04 01 00 50 01");
    CHECK(f.discard_partial() == 0);
    CHECK(frame(f, set_vel.substr(0, 10), 10).empty());
    CHECK(f.in_frame());
    CHECK(f.discard_partial() == 10);
    CHECK(f.buffered() == 0);
    CHECK(f.dropped_bytes() == 10);
    CHECK(frame(f, req_pos, 6) == std::vector<std::string>{"0411 d=50 s=01 p=01,00"});
    CHECK(frame(f, req_pos.substr(0, 3), 3).empty());
    CHECK(f.discard_partial() == 3);
    CHECK(frame(f, set_vel, 1) == std::vector<std::string>{"0413 d=50 s=01 [01 00 00 00 00 00 F4 01 00 00 40 42 0F 00]"});
    CHECK(f.discard_partial() == 0);   // the last frame is not a partial one
}

} // namespace test_frame_framer
