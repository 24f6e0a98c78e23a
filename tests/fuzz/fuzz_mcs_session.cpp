// Fuzz target: bytes through a whole MCS device on a stepped clock, as a client's connections
// deliver them (line framer, codec, handlers, controller, channels, event system, end effectors).
// Input: a header line (a rig JSON on one line; empty: the default rig's mcs0) and a stream of
// client bytes, clock advances and session switches (tests/fuzz/fuzz_rig.hpp).
#include "tests/fuzz/fuzz_rig.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace {

/// The default rig's MCS (config/default.json, mcs0): three linear S channels.
constexpr std::string_view kDefaultRig =
    R"({"devices":[{"name":"mcs0","protocol":"mcs","model":"MCS-3D","mcs":{"system_id":3118100,"channels":[)"
    R"({"sensor_type":"S","travel_nm":[-10500000,10500000],"start_position_nm":-2500000},)"
    R"({"sensor_type":"S","travel_nm":[-10500000,10500000],"start_position_nm":4000000},)"
    R"({"sensor_type":"S","travel_nm":[-10500000,10500000],"start_position_nm":3000000}]}}]})";

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    rigsim::fuzz::run_session_input(std::string_view(reinterpret_cast<const char*>(data), size), kDefaultRig);
    return 0;
}
