#include "emulator/apt/kcube_units.hpp"

#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <string_view>

namespace rigsim::apt {

namespace {

/// "<name> <value> (<min>..<max>)" if `value` is outside min..max.
std::optional<std::string> outside(std::string_view name, std::int64_t value, std::int64_t min, std::int64_t max)
{
    if (value >= min && value <= max)
        return std::nullopt;
    return std::string(name) + " " + std::to_string(value) + " (" + std::to_string(min) + ".." + std::to_string(max)
           + ")";
}

/// "<name> <value> (<allowed>)" if `value` is none of `allowed` (`listed` spells them).
std::optional<std::string> not_one_of(std::string_view name, std::uint16_t value,
                                      std::initializer_list<std::uint16_t> allowed, std::string_view listed)
{
    if (std::find(allowed.begin(), allowed.end(), value) != allowed.end())
        return std::nullopt;
    return std::string(name) + " " + std::to_string(value) + " (" + std::string(listed) + ")";
}

/// The first of `checks` that found a field out of range.
std::optional<std::string> first(std::initializer_list<std::optional<std::string>> checks)
{
    for (const auto& c : checks)
        if (c)
            return c;
    return std::nullopt;
}

/// The display fields every K-Cube shares: intensity 0..100 %, timeout 0..480 min, dimmed
/// level 0..10 (msl-equipment thorlabs/ksc.py set_display_parameters).
std::optional<std::string> display(std::uint16_t intensity, std::uint16_t timeout, std::uint16_t dim_level)
{
    return first({outside("display intensity", intensity, 0, 100), outside("display timeout", timeout, 0, 480),
                  outside("display dim level", dim_level, 0, 10)});
}

/// A trigger port's polarity: 1 active high, 2 active low (Kinesis KPZ/KSG_TriggerPortPolarity).
std::optional<std::string> polarity(std::string_view name, std::uint16_t value)
{
    return outside(name, value, 1, 2);
}

} // namespace

msg::KpzMmiParams kpz_mmi_power_up()
{
    msg::KpzMmiParams p;
    p.js_mode = 1;
    p.js_volt_gearbox = 1;
    p.js_volt_step = 1;
    p.dir_sense = 1;
    p.disp_brightness = 50;
    p.disp_timeout = 2;
    p.disp_dim_level = 5;
    return p;
}

msg::KpzTrigIoConfig kpz_trig_power_up()
{
    return msg::KpzTrigIoConfig{};   // both ports disabled, active high
}

msg::KsgMmiParams ksg_mmi_power_up()
{
    return msg::KsgMmiParams{1, 50, 2, 5};
}

msg::KsgTrigIoConfig ksg_trig_power_up()
{
    return msg::KsgTrigIoConfig{};   // both ports disabled, active high, no limits, 1 sample
}

std::optional<std::string> kcube_out_of_range(const msg::KpzMmiParams& p)
{
    // JSMode 1..3 and JSVoltGearbox 1..3: Kinesis' KPZ_WheelMode and KPZ_WheelChangeRate
    // (msl-equipment kinesis/enums.py). DirSense 1..2 there (KPZ_WheelDirectionSense); 0 is what
    // kptrofatter/kcube's KPZ101 session sends, so 0..2.
    return first({outside("JSMode", p.js_mode, 1, 3), outside("JSVoltGearbox", p.js_volt_gearbox, 1, 3),
                  outside("DirSense", p.dir_sense, 0, 2),
                  display(p.disp_brightness, p.disp_timeout, p.disp_dim_level)});
}

std::optional<std::string> kcube_out_of_range(const msg::KpzTrigIoConfig& p)
{
    // Kinesis' KPZ_TriggerPortMode: 0 disabled, 1 GPI, 2 voltage step up, 3 step down, 0x0A GPO.
    constexpr std::string_view kModes = "0, 1, 2, 3 or 10";
    return first({not_one_of("Trig1Mode", p.trig1_mode, {0, 1, 2, 3, 0x0A}, kModes),
                  polarity("Trig1Polarity", p.trig1_polarity),
                  not_one_of("Trig2Mode", p.trig2_mode, {0, 1, 2, 3, 0x0A}, kModes),
                  polarity("Trig2Polarity", p.trig2_polarity)});
}

std::optional<std::string> kcube_out_of_range(const msg::KsgMmiParams& p)
{
    return display(p.disp_intensity, p.disp_timeout, p.disp_dim_level);
}

std::optional<std::string> kcube_out_of_range(const msg::KsgTrigIoConfig& p)
{
    // Kinesis' KSG_TriggerPortMode: 0 disabled, 1 GPI, 0x0A GPO, 0x0B..0x10 outputs against the
    // limits (below lower, above lower, below upper, above upper, between, outside).
    constexpr std::string_view kModes = "0, 1 or 10..16";
    const std::initializer_list<std::uint16_t> modes{0, 1, 0x0A, 0x0B, 0x0C, 0x0D, 0x0E, 0x0F, 0x10};
    return first({not_one_of("Trig1Mode", p.trig1_mode, modes, kModes), polarity("Trig1Polarity", p.trig1_polarity),
                  not_one_of("Trig2Mode", p.trig2_mode, modes, kModes), polarity("Trig2Polarity", p.trig2_polarity)});
}

} // namespace rigsim::apt
