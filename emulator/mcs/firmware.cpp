#include "emulator/mcs/firmware.hpp"

#include <array>
#include <utility>

namespace rigsim::mcs {
namespace {

constexpr std::array<std::pair<Firmware, std::string_view>, 1> kNames{{
    {Firmware::V1_2_44, "1.2.44"},
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
    return "\"1.2.44\"";
}

} // namespace rigsim::mcs
