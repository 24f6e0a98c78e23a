#include "emulator/apt/firmware.hpp"

#include <array>
#include <string>
#include <utility>

namespace rigsim::apt {
namespace {

constexpr std::array<std::pair<Firmware, std::string_view>, 2> kNames{{
    {Firmware::Issue3, "issue-3"},
    {Firmware::Issue44_1, "issue-44.1"},
}};

} // namespace

std::string_view firmware_name(Firmware f)
{
    for (const auto& [value, name] : kNames)
        if (value == f)
            return name;
    return kNames.front().second;
}

std::optional<Firmware> find_firmware(std::string_view name)
{
    for (const auto& [value, n] : kNames)
        if (n == name)
            return value;
    return std::nullopt;
}

std::string_view firmware_names()
{
    // Built once from the table, so the message never drifts from the names.
    static const std::string names = [] {
        std::string out;
        for (const auto& g : kNames)
            out += (out.empty() ? "\"" : ", \"") + std::string(g.second) + "\"";
        return out;
    }();
    return names;
}

} // namespace rigsim::apt
