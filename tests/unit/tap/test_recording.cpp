// The tap's recording (emulator/tap/recording.hpp): each reply found for its request, however
// the requests and the unit's unprompted frames interleave.
#include "emulator/tap/recording.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <stdlib.h>
#include <unistd.h>

namespace test_recording {

using namespace rigsim::tap;
using nlohmann::json;

namespace {

/// A recording in a fresh temporary file; its lines once written.
class TempRecording {
public:
    TempRecording()
    {
        char path[] = "/tmp/rigsim-recording-XXXXXX";
        const int fd = ::mkstemp(path);
        REQUIRE(fd >= 0);
        ::close(fd);
        path_ = path;
    }
    ~TempRecording() { std::remove(path_.c_str()); }
    const std::string& path() const { return path_; }
    std::vector<json> lines() const
    {
        std::vector<json> out;
        std::ifstream in(path_);
        for (std::string line; std::getline(in, line);)
            out.push_back(json::parse(line));
        return out;
    }

private:
    std::string path_;
};

std::string bytes(std::initializer_list<int> b)
{
    std::string out;
    for (const int c : b)
        out.push_back(static_cast<char>(c));
    return out;
}

/// An APT header-only frame (a request) of message `id`.
std::string apt_header(int id)
{
    return bytes({id & 0xFF, id >> 8, 1, 0, 0x50, 0x01});
}

/// An APT frame of message `id` with `n` data bytes (a reply, a status update).
std::string apt_long(int id, int n)
{
    return bytes({id & 0xFF, id >> 8, n & 0xFF, n >> 8, 0x81, 0x50}) + std::string(static_cast<std::size_t>(n), '\0');
}

} // namespace

TEST_CASE("recording: APT replies find their requests by message ID, unprompted frames none", "[unit][tap]")
{
    TempRecording file;
    {
        Recorder r(file.path(), Protocol::Apt, json::object());
        r.bytes(1, Direction::In, apt_header(0x0411), 1000);      // seq 0: MOT_REQ_POSCOUNTER
        r.bytes(1, Direction::In, apt_header(0x0005), 1100);      // seq 1: HW_REQ_INFO
        r.bytes(1, Direction::In, apt_header(0x0492), 1150);      // seq 2: MOT_ACK_DCSTATUSUPDATE: asks nothing
        r.bytes(1, Direction::Out, apt_long(0x0491, 14), 2000);   // seq 3: a status update
        r.bytes(1, Direction::Out, apt_long(0x0006, 84), 3000);   // seq 4: HW_GET_INFO
        r.bytes(1, Direction::Out, apt_long(0x0412, 6), 5000);    // seq 5: MOT_GET_POSCOUNTER
        r.bytes(1, Direction::Out, apt_long(0x0412, 6), 6000);    // seq 6: asked by nobody
    }
    const auto lines = file.lines();
    REQUIRE(lines.size() == 8);
    CHECK_FALSE(lines[4].contains("reply_to"));
    CHECK(lines[5]["reply_to"] == 1);
    CHECK(lines[5]["latency_us"] == 1900);
    CHECK(lines[6]["reply_to"] == 0);
    CHECK(lines[6]["latency_us"] == 4000);
    CHECK_FALSE(lines[7].contains("reply_to"));
}

TEST_CASE("recording: MCS answers go to their commands in order, and a new connection forgets the old one's",
          "[unit][tap]")
{
    TempRecording file;
    {
        Recorder r(file.path(), Protocol::Mcs, json::object());
        r.bytes(1, Direction::In, ":GP0\n:GP1\n", 100);           // seq 0, 1
        r.bytes(1, Direction::Out, ":P0,5\n", 300);                // seq 2
        r.bytes(1, Direction::Out, ":P1,7\n", 400);                // seq 3
        r.bytes(1, Direction::In, ":GS0\n", 500);                  // seq 4: never answered here
        r.event("disconnect", 1, 600, json{{"reason", "test"}});   // seq 5
        r.bytes(2, Direction::Out, ":S0,0\n", 700);                // seq 6: not the old connection's reply
    }
    const auto lines = file.lines();
    REQUIRE(lines.size() == 8);
    CHECK(lines[3]["reply_to"] == 0);
    CHECK(lines[3]["latency_us"] == 200);
    CHECK(lines[4]["reply_to"] == 1);
    CHECK(lines[4]["latency_us"] == 300);
    CHECK_FALSE(lines[7].contains("reply_to"));
}

} // namespace test_recording
