#include "emulator/mcs2/errors.hpp"

#include <array>
#include <utility>

namespace rigsim::mcs2 {

std::string_view error_text(std::int32_t code)
{
    // Table A.1, the codes the device reports (not the PC library's 0xf0xx; nor 0x7ffe, which
    // a unit answers for a feature its firmware lacks and rigsim never does).
    static constexpr std::array<std::pair<std::int32_t, std::string_view>, 61> kTexts{{
        {0x0000, "No error"},
        {0x0001, "Unknown command"},
        {0x0002, "Invalid packet size"},
        {0x0004, "Timeout"},
        {0x0005, "Invalid protocol"},
        {0x000c, "Buffer underflow"},
        {0x000d, "Buffer overflow"},
        {0x000e, "Invalid frame size"},
        {0x0010, "Invalid packet"},
        {0x0012, "Invalid key"},
        {0x0013, "Invalid parameter"},
        {0x0016, "Invalid data type"},
        {0x0017, "Invalid data"},
        {0x0018, "Handle limit reached"},
        {0x0019, "Aborted"},
        {0x0020, "Invalid device index"},
        {0x0021, "Invalid module index"},
        {0x0022, "Invalid channel index"},
        {0x0023, "Permission denied"},
        {0x0024, "Command not groupable"},
        {0x0025, "Movement locked"},
        {0x0026, "Sync failed"},
        {0x0027, "Invalid array size"},
        {0x0028, "Overrange"},
        {0x0029, "Invalid configuration"},
        {0x0100, "No hand control module present"},
        {0x0101, "No IO module present"},
        {0x0102, "No sensor module present"},
        {0x0103, "No sensor present"},
        {0x0104, "Sensor disabled"},
        {0x0105, "Power supply disabled"},
        {0x0106, "Amplifier disabled"},
        {0x0107, "Invalid sensor mode"},
        {0x0108, "Invalid actuator mode"},
        {0x0109, "Invalid input trigger mode"},
        {0x010a, "Invalid control options"},
        {0x010b, "Invalid reference type"},
        {0x010c, "Invalid adjustment state"},
        {0x010e, "No full access"},
        {0x010f, "Adjustment failed"},
        {0x0110, "Movement overridden"},
        {0x0111, "Not calibrated"},
        {0x0112, "Not referenced"},
        {0x0113, "Not adjusted"},
        {0x0114, "Sensor type not supported"},
        {0x0115, "Control loop input disabled"},
        {0x0116, "Invalid control loop input"},
        {0x0117, "Unexpected sensor data"},
        {0x0150, "Busy moving"},
        {0x0151, "Busy calibrating"},
        {0x0152, "Busy referencing"},
        {0x0153, "Busy adjusting"},
        {0x0200, "End stop reached"},
        {0x0201, "Following error limit"},
        {0x0202, "Range limit reached"},
        {0x0300, "Invalid stream handle"},
        {0x0301, "Invalid stream configuration"},
        {0x0302, "Insufficient frames"},
        {0x0303, "Busy streaming"},
        {0x0500, "Internal communication"},
        {0x7ffd, "Feature not supported"},
    }};
    for (const auto& [c, text] : kTexts)
        if (c == code)
            return text;
    return "Unknown error";
}

} // namespace rigsim::mcs2
