#include "emulator/mcs/firmware.hpp"

#include <string>

namespace rigsim::mcs {
namespace {

struct Generation {
    Firmware firmware;
    std::string_view name;
    std::array<std::int64_t, 3> version;
};

/// Oldest first.
constexpr std::array<Generation, 2> kGenerations{{
    {Firmware::V1_2_44, "1.2.44", {1, 2, 44}},
    {Firmware::V2_0_1, "2.0.1", {2, 0, 1}},
}};

const Generation& generation(Firmware f)
{
    for (const auto& g : kGenerations)
        if (g.firmware == f)
            return g;
    return kGenerations.front();
}

} // namespace

std::string_view firmware_name(Firmware f)
{
    return generation(f).name;
}

std::optional<Firmware> find_firmware(std::string_view name)
{
    for (const auto& g : kGenerations)
        if (g.name == name)
            return g.firmware;
    return std::nullopt;
}

std::string_view firmware_names()
{
    // Built once from the table, so the message never drifts from the names.
    static const std::string names = [] {
        std::string out;
        for (const auto& g : kGenerations)
            out += (out.empty() ? "\"" : ", \"") + std::string(g.name) + "\"";
        return out;
    }();
    return names;
}

std::array<std::int64_t, 3> firmware_version(Firmware f)
{
    return generation(f).version;
}

Firmware firmware_of_version(const std::array<std::int64_t, 3>& version)
{
    Firmware newest = kGenerations.front().firmware;
    for (const auto& g : kGenerations)
        if (g.version <= version)   // lexicographic: high, then low, then update
            newest = g.firmware;
    return newest;
}

std::optional<FrmDirection> frm_direction(Firmware f, std::int32_t direction)
{
    // Manual 3.3 FRM: "Must be either 0 (forward) or 1 (backward)".
    const std::int32_t known = f == Firmware::V1_2_44 ? 1 : 7;
    if (direction < 0 || direction > known)
        return std::nullopt;
    // MCSControl.h 2.0.1: SA_FORWARD_DIRECTION 0, SA_BACKWARD_DIRECTION 1,
    // SA_FORWARD_BACKWARD_DIRECTION 2, SA_BACKWARD_FORWARD_DIRECTION 3, and 4..7 the same
    // four with _ABORT_ON_ENDSTOP: the low bit names the first direction of 1 and 3 (and 5,
    // 7), 4 the abort (docs/protocol/mcs.md, "Firmware generations").
    FrmDirection d;
    d.backward = direction % 2 == 1;
    d.abort_on_end_stop = direction >= 4;
    return d;
}

} // namespace rigsim::mcs
