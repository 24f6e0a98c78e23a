// The USB-serial chip's buffer on its own (emulator/daemon/usb_serial.hpp): packets at the
// latency timer or when full, on USB frames, the timer restarted by every packet.
#include "emulator/daemon/usb_serial.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

namespace test_usb_serial {

using namespace rigsim;

namespace {

/// The packets due by `now`.
std::vector<std::string> packets(UsbSerialBuffer& chip, Ticks now)
{
    std::vector<std::string> out;
    chip.release(now, [&](const std::string& p) { out.push_back(p); });
    return out;
}

constexpr UsbSerialTiming kFtdi{16, 1, 62};   // 16 ms timer, 1 ms frames, at 1 kHz

} // namespace

TEST_CASE("usb serial: a 12-byte answer waits for the latency timer, then goes whole", "[unit][daemon][usb]")
{
    UsbSerialBuffer chip(kFtdi, 0);
    CHECK(chip.next_packet() == kNever);
    chip.feed(1, 0, std::string(12, 'a'));
    CHECK(chip.next_packet() == 16);
    CHECK(packets(chip, 15).empty());
    const auto out = packets(chip, 16);
    REQUIRE(out.size() == 1);
    CHECK(out[0] == std::string(12, 'a'));
    CHECK(chip.bytes() == 0);
    CHECK(chip.pieces() == 0);
    CHECK(chip.next_packet() == kNever);
}

TEST_CASE("usb serial: a 90-byte answer goes in two packets, 62 bytes at the next frame and 28 one timer period later",
          "[unit][daemon][usb]")
{
    SECTION("all bytes at once")
    {
        UsbSerialBuffer chip(kFtdi, 0);
        chip.feed(0.5, 0, std::string(62, 'a') + std::string(28, 'b'));
        CHECK(chip.next_packet() == 1);
        auto out = packets(chip, 1);
        REQUIRE(out.size() == 1);
        CHECK(out[0] == std::string(62, 'a'));
        CHECK(chip.next_packet() == 17);   // the full packet restarted the timer at 1
        CHECK(packets(chip, 16).empty());
        out = packets(chip, 17);
        REQUIRE(out.size() == 1);
        CHECK(out[0] == std::string(28, 'b'));
    }
    SECTION("at 115200 baud: the 62nd byte comes at 5.38 ms")
    {
        UsbSerialBuffer chip(kFtdi, 0);
        const double per_byte = 10.0 * 1000 / 115200;
        chip.feed(per_byte, per_byte, std::string(90, 'x'));
        CHECK(chip.next_packet() == 6);
        CHECK(packets(chip, 6).at(0).size() == 62);
        CHECK(chip.next_packet() == 22);
        CHECK(packets(chip, 22).at(0).size() == 28);
    }
}

TEST_CASE("usb serial: the timer runs from the last packet, status-only packets included", "[unit][daemon][usb]")
{
    UsbSerialBuffer chip(kFtdi, 0);
    chip.feed(40, 0, "abc");            // status packets went at 16 and 32: the next at 48
    CHECK(chip.next_packet() == 48);
    CHECK(packets(chip, 48).at(0) == "abc");
    chip.feed(64, 0, "d");              // exactly at an expiry: it goes then
    CHECK(chip.next_packet() == 64);
    chip.clear();
    CHECK(chip.bytes() == 0);
    chip.feed(65, 0, "e");              // the phase is kept: 48, 64, 80
    CHECK(chip.next_packet() == 80);
}

TEST_CASE("usb serial: bytes that fill a packet before the timer send it at once, the rest waits a whole period",
          "[unit][daemon][usb]")
{
    UsbSerialBuffer chip(kFtdi, 0);
    chip.feed(1, 0, std::string(28, 'a'));
    CHECK(chip.next_packet() == 16);
    chip.feed(9.5, 0, std::string(40, 'b'));   // 68 bytes: a full packet at frame 10
    CHECK(chip.next_packet() == 10);
    const auto out = packets(chip, 30);
    REQUIRE(out.size() == 2);
    CHECK(out[0] == std::string(28, 'a') + std::string(34, 'b'));
    CHECK(out[1] == std::string(6, 'b'));
    CHECK(chip.next_packet() == kNever);
}

TEST_CASE("usb serial: only the bytes come by the timer's expiry go with it", "[unit][daemon][usb]")
{
    UsbSerialBuffer chip(kFtdi, 0);
    chip.feed(10, 2, "0123456");        // bytes at 10, 12, ..., 22
    CHECK(chip.next_packet() == 16);
    auto out = packets(chip, 16);
    REQUIRE(out.size() == 1);
    CHECK(out[0] == "0123");            // 10, 12, 14, 16
    CHECK(chip.next_packet() == 32);
    CHECK(packets(chip, 32).at(0) == "456");
}

TEST_CASE("usb serial: times in ticks of another clock rate are rounded up to whole ticks", "[unit][daemon][usb]")
{
    // 100 Hz: a tick is 10 ms, a frame 0.1 tick, the timer 1.6 ticks.
    UsbSerialBuffer chip(UsbSerialTiming{1.6, 0.1, 62}, 0);
    chip.feed(0.05, 0, "ab");
    CHECK(chip.next_packet() == 2);
    CHECK(packets(chip, 1).empty());
    CHECK(packets(chip, 2).at(0) == "ab");
    // 1 ms timer at 1 kHz: the first frame at or after the byte.
    UsbSerialBuffer fast(UsbSerialTiming{1, 1, 62}, 0);
    fast.feed(3.5, 0, "c");
    CHECK(fast.next_packet() == 4);
}

TEST_CASE("usb serial: feeds keep their order even when one claims an earlier time", "[unit][daemon][usb]")
{
    UsbSerialBuffer chip(kFtdi, 0);
    chip.feed(20, 0, "late");
    chip.feed(5, 0, "r");               // comes after "late" all the same
    CHECK(chip.next_packet() == 32);
    CHECK(packets(chip, 32).at(0) == "later");
}

TEST_CASE("usb serial: a byte a hair after an expiry, at a fine clock, still goes at the next one", "[unit][daemon][usb]")
{
    // 1 MHz ticks: a 16 ms timer is 16,000 ticks, a frame 1,000.
    UsbSerialBuffer chip(UsbSerialTiming{16'000, 1'000, 62}, 0);
    chip.feed(16'000 + 1e-8, 0, "x");
    CHECK(chip.next_packet() == 32'000);
    std::vector<std::string> out;
    chip.release(32'000, [&](const std::string& p) { out.push_back(p); });
    CHECK(out == std::vector<std::string>{"x"});
}

TEST_CASE("usb serial: random feeds at any clock rate come out whole, in order, in packets no larger than full",
          "[unit][daemon][usb]")
{
    std::mt19937 rng(20261206);
    for (const double hz : {1.0, 100.0, 1000.0, 48'000.0, 1'000'000.0}) {
        INFO("tick_hz " << hz);
        for (int round = 0; round < 20; ++round) {
            const double latency_ms = 1 + rng() % 255;
            const double frame_us = 125 + rng() % 876;
            const std::size_t packet = 1 + rng() % 64;
            UsbSerialBuffer chip(UsbSerialTiming{latency_ms * hz / 1e3, frame_us * hz / 1e6, packet}, rng() % 1000);
            std::string in;
            std::string out;
            Ticks last_release = 0;
            double t = 0;
            for (int op = 0; op < 200; ++op) {
                if (rng() % 3 != 0) {
                    t += std::uniform_real_distribution<double>(0, 50 * hz / 1e3)(rng);
                    const std::string bytes(1 + rng() % 100, static_cast<char>('a' + op % 26));
                    const double per_byte = rng() % 2 ? 0.0 : 10.0 * hz / 115200;
                    chip.feed(t, per_byte, bytes);
                    in += bytes;
                } else {
                    const Ticks now = last_release + static_cast<Ticks>(rng() % static_cast<unsigned>(1 + 40 * hz / 1e3));
                    REQUIRE((chip.bytes() == 0 || chip.next_packet() != kNever));
                    chip.release(now, [&](const std::string& p) {
                        CHECK(!p.empty());
                        CHECK(p.size() <= packet);
                        out += p;
                    });
                    last_release = now;
                }
            }
            // Everything goes in the end, however far its timer.
            for (int guard = 0; chip.bytes() > 0 && guard < 100'000; ++guard) {
                const auto next = chip.next_packet();
                REQUIRE(next != kNever);
                const Ticks at = std::max(next, last_release);
                const auto before = chip.bytes();
                chip.release(at, [&](const std::string& p) { out += p; });
                REQUIRE(chip.bytes() < before);   // a packet went at the time it named
                last_release = at;
            }
            CHECK(chip.bytes() == 0);
            CHECK(chip.pieces() == 0);
            CHECK(out == in);
        }
    }
}

} // namespace test_usb_serial
