// Fuzz target: bytes through a whole MCS2 device on a stepped clock, as its clients' connections
// deliver them (line framer, grammar, command tree, property table, controller, channels, command
// groups, streaming). Input: a header line (a rig JSON on one line; empty: three type-300
// channels) and a stream of client bytes, clock advances and session switches
// (tests/fuzz/fuzz_rig.hpp).
#include "tests/fuzz/fuzz_rig.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace {

/// tests/device/mcs2's harness: three linear positioners of type 300 without step jitter.
constexpr std::string_view kDefaultRig =
    R"({"devices":[{"name":"mcs2","protocol":"mcs2","mcs2":{"channels":[)"
    R"({"step_jitter_percent":0},{"step_jitter_percent":0},{"step_jitter_percent":0}]}}]})";

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    rigsim::fuzz::run_session_input(std::string_view(reinterpret_cast<const char*>(data), size), kDefaultRig);
    return 0;
}
