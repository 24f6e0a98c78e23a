#include "emulator/core/frame_queue.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <new>

namespace rigsim {

namespace {

constexpr std::size_t kLengthBytes = sizeof(std::uint32_t);

std::size_t page_size()
{
    static const std::size_t size = [] {
        const long n = ::sysconf(_SC_PAGESIZE);
        return n > 0 ? static_cast<std::size_t>(n) : std::size_t{4096};
    }();
    return size;
}

} // namespace

FrameQueue::~FrameQueue()
{
    clear();
}

FrameQueue::Block FrameQueue::allocate(std::size_t capacity)
{
    const auto page = page_size();
    capacity = (capacity + page - 1) / page * page;
    void* p = ::mmap(nullptr, capacity, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED)
        throw std::bad_alloc();
    Block block;
    block.data = static_cast<char*>(p);
    block.capacity = capacity;
    return block;
}

void FrameQueue::release(Block& block)
{
    if (block.data)
        ::munmap(block.data, block.capacity);
    block = Block{};
}

void FrameQueue::push_back(std::string_view frame)
{
    const std::size_t need = kLengthBytes + frame.size();
    if (blocks_.empty() || blocks_.back().capacity - blocks_.back().tail < need) {
        // A queue that emptied reuses its block from the start, or gives it back for a larger one.
        if (frames_ == 0 && !blocks_.empty() && blocks_.back().capacity >= need) {
            blocks_.back().head = blocks_.back().tail = 0;
        } else {
            if (frames_ == 0)
                clear();
            blocks_.reserve(blocks_.size() + 1);   // no block is lost if the vector cannot grow
            blocks_.push_back(allocate(need > kBlockBytes ? need : kBlockBytes));
        }
    }
    auto& block = blocks_.back();
    const auto length = static_cast<std::uint32_t>(frame.size());
    std::memcpy(block.data + block.tail, &length, kLengthBytes);
    if (!frame.empty())
        std::memcpy(block.data + block.tail + kLengthBytes, frame.data(), frame.size());
    block.tail += need;
    ++block.count;
    ++frames_;
}

std::string_view FrameQueue::frame_at(const Block& block, std::size_t at)
{
    std::uint32_t length = 0;
    std::memcpy(&length, block.data + at, kLengthBytes);
    return {block.data + at + kLengthBytes, length};
}

std::string_view FrameQueue::front() const
{
    const auto& block = blocks_.front();
    return frame_at(block, block.head);
}

void FrameQueue::pop_front()
{
    auto& block = blocks_.front();
    block.head += kLengthBytes + front().size();
    --block.count;
    --frames_;
    if (block.count > 0)
        return;
    if (blocks_.size() == 1) {   // empty now: kept for the next frames
        block.head = block.tail = 0;
        return;
    }
    release(block);
    blocks_.erase(blocks_.begin());
}

void FrameQueue::keep_front_only()
{
    if (frames_ <= 1)
        return;
    while (blocks_.size() > 1) {
        release(blocks_.back());
        blocks_.pop_back();
    }
    auto& block = blocks_.front();
    block.tail = block.head + kLengthBytes + front().size();
    block.count = 1;
    frames_ = 1;
}

void FrameQueue::clear()
{
    for (auto& block : blocks_)
        release(block);
    blocks_.clear();
    frames_ = 0;
}

} // namespace rigsim
