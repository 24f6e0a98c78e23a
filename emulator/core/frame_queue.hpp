#pragma once
// The frames the daemon holds for a client that reads slower than they come, in order, until
// its socket or pty takes them: a transport's answers (emulator/transport/) and an event stream's
// backlog (emulator/control/http_session.cpp).
//
// They live in blocks of whole pages taken from the system (mmap) and given back to it as soon
// as the client has read them or goes, never in the allocator's heap: a client that stops
// reading may pile up megabytes of small answers, and were they small heap objects, whatever
// else the daemon allocated meanwhile (wire log entries, events) would sit among them, so that
// the pages they shared stayed resident after they were freed (the soak bench measured 1.11 to
// 1.17 times the starting RSS after such clients went, bench/README.md). Each frame is stored as
// its length (4 bytes) and its bytes, contiguous; a frame larger than a block gets a block of
// its own. A queue that empties keeps its one block for the next frames (an answer paced at a
// serial baud rate is queued every time), and releases it when it is destroyed.

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace rigsim {

class FrameQueue {
public:
    /// Bytes of a block (16 pages of 4 KiB): the frames of most queues fit in one.
    static constexpr std::size_t kBlockBytes = 64 * 1024;

    FrameQueue() = default;
    ~FrameQueue();
    FrameQueue(const FrameQueue&) = delete;
    FrameQueue& operator=(const FrameQueue&) = delete;

    /// Appends a copy of `frame`. Throws std::bad_alloc when the system has no pages to give.
    void push_back(std::string_view frame);
    /// The oldest frame (the queue must not be empty); valid until it is popped.
    std::string_view front() const;
    /// Calls `visit(std::string_view)` on the oldest frames in order, at most `max` of them.
    template <typename Visit>
    void for_each_front(std::size_t max, Visit&& visit) const;
    /// Removes the oldest frame.
    void pop_front();
    /// Removes every frame but the oldest (kept where it is: a write of it may be under way).
    void keep_front_only();
    /// Removes every frame and gives back every block.
    void clear();

    bool empty() const { return frames_ == 0; }
    /// Frames held.
    std::size_t size() const { return frames_; }
    /// Blocks held (one may be held while empty).
    std::size_t blocks() const { return blocks_.size(); }

private:
    struct Block {
        char* data = nullptr;
        std::size_t capacity = 0;
        std::size_t head = 0;    ///< first byte of the oldest frame not yet popped
        std::size_t tail = 0;    ///< end of the newest frame
        std::size_t count = 0;   ///< frames in it
    };

    static Block allocate(std::size_t capacity);
    static std::string_view frame_at(const Block& block, std::size_t at);
    static void release(Block& block);

    std::vector<Block> blocks_;   ///< oldest first
    std::size_t frames_ = 0;
};

template <typename Visit>
void FrameQueue::for_each_front(std::size_t max, Visit&& visit) const
{
    for (const auto& block : blocks_) {
        for (std::size_t at = block.head, n = 0; n < block.count; ++n) {
            if (max-- == 0)
                return;
            const auto frame = frame_at(block, at);
            visit(frame);
            at += sizeof(std::uint32_t) + frame.size();
        }
    }
}

} // namespace rigsim
