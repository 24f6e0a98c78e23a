#pragma once
// Gives the memory the daemon freed back to the system a while after a client went. glibc keeps
// what a program frees in its heap for later allocations, so the buffers of a burst of clients
// (answers queued for clients that did not read, event streams behind) would stay resident after
// they are gone; malloc_trim(0) returns the free pages. It walks the heap, so it runs at most once
// per interval, on the loop, after the connections' last handlers have run.

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include <chrono>
#include <cstddef>

namespace rigsim {

class MemoryTrim {
public:
    /// A trim runs `delay` after the first request since the last one.
    explicit MemoryTrim(boost::asio::io_context& io, std::chrono::milliseconds delay = kDefaultDelay);
    MemoryTrim(const MemoryTrim&) = delete;
    MemoryTrim& operator=(const MemoryTrim&) = delete;

    /// A client went: trim soon (requests until then are one trim).
    void request();
    /// Trims run so far.
    std::size_t trims() const { return trims_; }

    static constexpr std::chrono::milliseconds kDefaultDelay{500};

private:
    boost::asio::steady_timer timer_;
    std::chrono::milliseconds delay_;
    bool armed_ = false;
    std::size_t trims_ = 0;
};

} // namespace rigsim
