#pragma once
// An MCS2 device's section of the rig ("mcs2": firmware, serial number, channels): its structs with
// every default (docs/config.md), and its loader.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rigsim::mcs2 {

/// One channel and the positioner connected to it. Lengths in the channel's base unit: pm on a
/// linear positioner, n° (nano-degree) on a rotary one or a goniometer (guide 2.6, 4.4.10).
struct ChannelConfig {
    std::int32_t positioner_type = 300;   ///< a code of the Positioner Types document (Table 1.1)
    /// Mechanical end stops (physical position); none on a rotary stage referenced by a mark,
    /// which turns endlessly. Unset: ±10.5 mm linear, ±10° goniometer, none rotary.
    std::optional<std::int64_t> travel_min;
    std::optional<std::int64_t> travel_max;
    std::int64_t start_position = 0;          ///< physical position at power-up (reads as 0)
    std::int64_t reference_position = 0;      ///< physical position of the (first) reference mark
    std::int64_t coded_mark_spacing = 2'000'000'000;   ///< distance-coded marks: their spacing
    std::int64_t max_speed = 10'000'000'000;  ///< fastest closed-loop speed (velocity control off), unit/s
    std::int64_t step_width = 1'000'000;      ///< one open-loop step at full amplitude (65535 = 100 V)
    std::int64_t step_jitter_percent = 3;     ///< each step's width varies by up to this
    std::int64_t scan_range = 1'500'000;      ///< the piezo's deflection at 100 V (scan 65535)
    std::int64_t calibration_ms = 3000;       ///< how long :CAL# takes ("a few seconds", 2.6.1)
    std::int64_t drift = 0;                   ///< open-loop creep at rest, unit/s, signed
    std::int64_t temperature_c = 28;          ///< what :CHAN#:TEMP? and :MOD#:TEMP? read
    /// The positioner has its sensor (every MCS2 positioner type does); false: open loop only
    /// (SENSOR_PRESENT 0, closed-loop commands fail with NO_SENSOR_PRESENT).
    bool sensor = true;
};

/// The interface generations rigsim answers as (the device's "firmware").
enum class Firmware {
    Guide106,   ///< "1.0.6": the keywords and state bits of Programmer's Guide 1.0.6 only
    /// "current" (the default): also what units in the field answer and public drivers rely on
    /// (EPICS motorSmarAct, BLISS): `:CHAN#:SENS:MODE`, `:CHAN#:SENS:DEL`, `:MOD:STAT?` without an
    /// index, and channel state bit 18 AMPLIFIER_ENABLED.
    Current,
};

struct Config {
    Firmware firmware = Firmware::Current;
    std::string serial_number = "MCS2-00001234";   ///< :DEV:SNUM? (4.2.4)
    /// The unit has the optional I/O module (User Manual 2): the device's trigger input (emergency
    /// stop, external stream and command-group triggers), the modules' digital and analog I/O and the
    /// channels' output triggers. Without it their properties answer 257 NO_IOM_PRESENT.
    bool io_module = false;
    std::vector<ChannelConfig> channels;           ///< 1..12 (3 per driver module)
};

} // namespace rigsim::mcs2
