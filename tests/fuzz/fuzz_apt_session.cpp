// Fuzz target: bytes through whole APT devices on a stepped clock, as clients' connections deliver
// them (frame framer, codec, unit shell, modules, motor channels, status updates, EEPROM saves).
// Input: a header line (a rig JSON on one line; empty: a TDC001 with an MTS50-Z8) and a stream of
// client bytes, clock advances and session switches (tests/fuzz/fuzz_rig.hpp).
#include "tests/fuzz/fuzz_rig.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace {

constexpr std::string_view kDefaultRig =
    R"({"devices":[{"name":"tdc001","protocol":"apt","model":"TDC001","apt":{"stage":"MTS50-Z8"}}]})";

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    rigsim::fuzz::run_session_input(std::string_view(reinterpret_cast<const char*>(data), size), kDefaultRig);
    return 0;
}
