#include "emulator/daemon/memory_trim.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace rigsim {

MemoryTrim::MemoryTrim(boost::asio::io_context& io, std::chrono::milliseconds delay) : timer_(io), delay_(delay)
{
}

void MemoryTrim::request()
{
    if (armed_)
        return;
    armed_ = true;
    timer_.expires_after(delay_);
    timer_.async_wait([this](const boost::system::error_code& ec) {
        if (ec)   // cancelled: this object is being destroyed
            return;
        armed_ = false;
        ++trims_;
#if defined(__GLIBC__)
        ::malloc_trim(0);
#endif
    });
}

} // namespace rigsim
