// The frames a transport holds for a slow client: in order, whole, in pages of the queue's own
// that go back to the system as soon as they are read (emulator/core/frame_queue.*).
#include "emulator/core/frame_queue.hpp"

#include <catch2/catch.hpp>

#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <string>
#include <vector>

namespace test_frame_queue {

using rigsim::FrameQueue;

/// Whether the page holding `p` is mapped in this process (mincore fails with ENOMEM for an
/// address no mapping holds). Counting /proc/self/maps lines would not do: the kernel merges
/// neighbouring anonymous mappings.
bool mapped(const void* p)
{
    static const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
    auto* start = reinterpret_cast<void*>(reinterpret_cast<std::uintptr_t>(p) & ~(page - 1));
    unsigned char resident = 0;
    return ::mincore(start, 1, &resident) == 0;
}

TEST_CASE("frame queue: frames come out in order and whole, across blocks", "[unit][core]")
{
    FrameQueue q;
    CHECK(q.empty());
    CHECK(q.blocks() == 0);
    // 3,000 frames of 1..97 bytes: about 150 KB, three blocks of 64 KiB.
    std::size_t bytes = 0;
    for (int i = 0; i < 3000; ++i) {
        const std::string frame(static_cast<std::size_t>(1 + i % 97), static_cast<char>('a' + i % 26));
        q.push_back(frame);
        bytes += frame.size();
    }
    CHECK(q.size() == 3000);
    CHECK(q.blocks() == (bytes + 4 * 3000) / FrameQueue::kBlockBytes + 1);
    for (int i = 0; i < 3000; ++i) {
        REQUIRE(q.front() == std::string(static_cast<std::size_t>(1 + i % 97), static_cast<char>('a' + i % 26)));
        q.pop_front();
    }
    CHECK(q.empty());
    CHECK(q.blocks() == 1);   // the last one, kept for the next frames
}

TEST_CASE("frame queue: read blocks go back to the system at once, and every one when it goes",
          "[unit][core]")
{
    const void* first = nullptr;
    const void* last = nullptr;
    {
        FrameQueue q;
        const std::string frame(1000, 'x');
        for (int i = 0; i < 1000; ++i)   // about 1 MB: 16 blocks
            q.push_back(frame);
        CHECK(q.blocks() == 16);
        first = q.front().data();
        CHECK(mapped(first));
        for (int i = 0; i < 990; ++i)
            q.pop_front();
        CHECK(q.blocks() == 1);
        CHECK(q.size() == 10);
        CHECK_FALSE(mapped(first));   // the read blocks are unmapped
        last = q.front().data();
        CHECK(mapped(last));
    }
    CHECK_FALSE(mapped(last));   // and the last one with the queue
}

TEST_CASE("frame queue: an empty frame, a frame larger than a block, an emptied queue reused",
          "[unit][core]")
{
    FrameQueue q;
    q.push_back("");
    const std::string big(3 * FrameQueue::kBlockBytes + 5, 'b');
    q.push_back(big);
    q.push_back("after");   // in the big frame's block, whose last page has room
    CHECK(q.blocks() == 2);
    CHECK(q.front().empty());
    q.pop_front();
    CHECK(q.front() == big);
    q.pop_front();
    CHECK(q.front() == "after");
    q.pop_front();
    CHECK(q.blocks() == 1);
    // Emptied: the next frame starts its block again; one larger than it replaces it.
    q.push_back("again");
    CHECK(q.blocks() == 1);
    CHECK(q.front() == "again");
    q.pop_front();
    q.push_back(big);
    CHECK(q.blocks() == 1);
    CHECK(q.front() == big);
}

TEST_CASE("frame queue: keep_front_only drops the rest, the front stays where it is, clear gives all back",
          "[unit][core]")
{
    FrameQueue q;
    const std::string frame(40000, 'f');
    for (int i = 0; i < 5; ++i)
        q.push_back(frame + std::to_string(i));
    const auto* where = q.front().data();
    CHECK(q.blocks() == 5);
    q.keep_front_only();
    CHECK(q.size() == 1);
    CHECK(q.blocks() == 1);
    CHECK(q.front().data() == where);
    CHECK(q.front() == frame + "0");
    q.push_back("next");   // after the front, in its block
    q.pop_front();
    CHECK(q.front() == "next");
    q.clear();
    CHECK(q.empty());
    CHECK(q.blocks() == 0);
    q.keep_front_only();   // nothing to keep
    CHECK(q.empty());
}

TEST_CASE("frame queue: for_each_front visits the oldest frames in order, across blocks", "[unit][core]")
{
    FrameQueue q;
    const std::string filler(FrameQueue::kBlockBytes - 100, '.');
    q.push_back(filler);
    q.push_back("one");
    q.push_back(std::string(200, '2'));   // no room left in the first block
    q.push_back("three");
    REQUIRE(q.blocks() == 2);
    std::vector<std::string> seen;
    q.for_each_front(3, [&](std::string_view f) { seen.emplace_back(f); });
    CHECK(seen == std::vector<std::string>{filler, "one", std::string(200, '2')});
    q.pop_front();
    seen.clear();
    q.for_each_front(10, [&](std::string_view f) { seen.emplace_back(f); });
    CHECK(seen == std::vector<std::string>{"one", std::string(200, '2'), "three"});
    seen.clear();
    q.for_each_front(0, [&](std::string_view f) { seen.emplace_back(f); });
    CHECK(seen.empty());
}

} // namespace test_frame_queue
