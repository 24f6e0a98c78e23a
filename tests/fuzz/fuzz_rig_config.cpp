// Fuzz target: the rig JSON loader (emulator/core/rig_config.*, config_reader.*,
// kinematics_config.*, and each family's section loader: emulator/mcs/config.*,
// emulator/apt/config.*, stage_file.*), then the rig it accepts.
// Input: the text of a rig file. A rig the loader accepts gets its pty paths resolved, is built as
// the daemon builds it (devices, links, world, frames; fuzz_rig.hpp) when it has at most
// kMaxDevices devices, and every device is asked for its identity and moved a little on the
// clock: a value the loader lets through must be one the devices live with.
// Checked beyond the sanitizers: the loader throws nothing but ConfigError, whose message names
// the source.
#include "tests/fuzz/fuzz_rig.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace {

using namespace std::string_view_literals;

void check(bool ok)
{
    if (!ok)
        __builtin_trap();
}

/// MCS: the channels, a move and a status on channel 0 (manual 3.1, 3.3).
constexpr std::string_view kMcsProbe = ":GNC\n:GSI\n:GCM\n:MPA0,1000000,0\n:MPR1,-500000,0\n:GS0\n:GP0\n"sv;
/// APT, to the unit (0x50) and the first bay (0x21): HW_REQ_INFO, MOVE_HOME, MOVE_ABSOLUTE to 34,304 counts,
/// REQ_DCSTATUSUPDATE, PZ_REQ_PZSTATUSUPDATE.
constexpr std::string_view kAptProbe =
    "\x05\x00\x00\x00\x50\x01" "\x43\x04\x01\x00\x50\x01" "\x53\x04\x06\x00\xD0\x01\x01\x00\x00\x86\x00\x00"
    "\x90\x04\x01\x00\x50\x01" "\x60\x06\x01\x00\x50\x01"
    "\x05\x00\x00\x00\x21\x01" "\x43\x04\x01\x00\x21\x01" "\x53\x04\x06\x00\xA1\x01\x01\x00\x00\x86\x00\x00"
    "\x90\x04\x01\x00\x21\x01"sv;

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    rigsim::fuzz::quiet_logging();
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    std::optional<rigsim::RigConfig> config;
    try {
        config = rigsim::parse_rig_config(text, "fuzz.json");
        rigsim::resolve_pty_paths(*config, "/nonexistent/rigsim-fuzz", "fuzz.json");
    } catch (const rigsim::ConfigError& e) {
        check(std::string_view(e.what()).substr(0, 9) == "fuzz.json");
        return 0;
    }
    if (config->devices.size() > rigsim::fuzz::kMaxDevices)
        return 0;
    std::unique_ptr<rigsim::fuzz::FuzzRig> rig;
    try {
        rig = std::make_unique<rigsim::fuzz::FuzzRig>(*config);
    } catch (const rigsim::ConfigError&) {
        return 0;   // a frame's joint the devices refuse: --check-config's error, not the loader's
    }
    rig->open_sessions();
    std::string stream;
    for (std::size_t d = 0; d < config->devices.size(); ++d) {
        stream += "\xFF";
        stream += static_cast<char>(0xF0 + d);
        for (char c : config->devices[d].protocol == "mcs" ? kMcsProbe : kAptProbe) {
            stream += c;
            if (c == '\xFF')
                stream += c;
        }
    }
    stream += "\xFF\x07\xD0";   // 2 s
    rig->play(stream + stream);
    return 0;
}
