// MemoryTrim: requests while one is due make one trim, run on the loop after the delay.

#include "emulator/daemon/memory_trim.hpp"

#include <catch2/catch.hpp>

#include <boost/asio/io_context.hpp>

#include <chrono>

namespace test_memory_trim {

using namespace rigsim;

TEST_CASE("memory trim: requests while one is due are one trim, a later request another", "[unit][daemon]")
{
    boost::asio::io_context io;
    MemoryTrim trim(io, std::chrono::milliseconds(1));
    trim.request();
    trim.request();
    trim.request();
    CHECK(trim.trims() == 0);   // not inside the request: on the loop, after the delay
    io.run();
    CHECK(trim.trims() == 1);
    trim.request();
    io.restart();
    io.run();
    CHECK(trim.trims() == 2);
}

TEST_CASE("memory trim: destroyed with a trim due, nothing runs", "[unit][daemon]")
{
    boost::asio::io_context io;
    {
        MemoryTrim trim(io, std::chrono::seconds(60));
        trim.request();
    }
    io.run();   // the cancelled wait ends at once
    SUCCEED();
}

} // namespace test_memory_trim
