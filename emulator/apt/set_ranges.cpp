#include "emulator/apt/set_ranges.hpp"

#include <cstdint>
#include <string_view>
#include <vector>

namespace rigsim::apt {

namespace {

struct FieldRange {
    std::string_view name;
    std::int64_t value;
    std::int64_t min;
    std::int64_t max;
};
using Ranges = std::vector<FieldRange>;

constexpr std::int64_t kMaxLong = 2'147'483'647;

template <class P> Ranges ranges(const P&)
{
    return {};   // the manual gives this block no ranges rigsim checks
}

Ranges ranges(const msg::VelParams& p)
{
    // p. 30: acceleration and maximum velocity are unsigned longs; a zero would never move.
    return {{"minimum velocity", p.min_velocity, 0, kMaxLong},
            {"acceleration", p.acceleration, 1, kMaxLong},
            {"maximum velocity", p.max_velocity, 1, kMaxLong}};
}

Ranges ranges(const msg::JogParams& p)
{
    // p. 32: jog mode 1 continuous, 2 single step; stop mode 1 immediate, 2 profiled.
    return {{"jog mode", p.jog_mode, 1, 2},
            {"jog step size", p.jog_step_size, 0, kMaxLong},
            {"jog minimum velocity", p.jog_min_velocity, 0, kMaxLong},
            {"jog acceleration", p.jog_acceleration, 1, kMaxLong},
            {"jog maximum velocity", p.jog_max_velocity, 1, kMaxLong},
            {"stop mode", p.jog_stop_mode, 1, 2}};
}

Ranges ranges(const msg::DcPidParams& p)
{
    // p. 51: proportional, integral, differential and integral limit 0..32767.
    return {{"proportional", p.proportional, 0, 32767},
            {"integral", p.integral, 0, 32767},
            {"differential", p.differential, 0, 32767},
            {"integral limit", p.integral_limit, 0, 32767}};
}

Ranges ranges(const msg::ButtonParams& p)
{
    return {{"mode", p.mode, 1, 2}};   // p. 58: mode 1 jog, 2 go to position
}

Ranges ranges(const msg::PmdPositionLoopParams& p)
{
    // p. 61. The PosErrLim text says "0 to 7FFFFFF" (seven Fs); the dword's other limit
    // field, Integral Limit, says 7FFFFFFF: taken for both.
    return {{"Kp", p.kp_pos, 0, 32767},
            {"Ki", p.ki_pos, 0, 32767},
            {"integral limit", p.integral_limit, 0, kMaxLong},
            {"Kd", p.kd_pos, 0, 32767},
            {"KdTimePos", p.kd_time_pos, 1, 32767},
            {"KvffPos", p.kvff_pos, 0, 32767},
            {"KaffPos", p.kaff_pos, 0, 32767},
            {"PosErrLim", p.pos_err_lim, 0, kMaxLong}};
}

Ranges ranges(const msg::PmdMotorOutputParams& p)
{
    // p. 63-64: MotorBias "-32767 to 32768" in a signed word: -32767..32767.
    return {{"ContCurrentLim", p.cont_current_lim, 0, 32767},
            {"EnergyLim", p.energy_lim, 0, 32767},
            {"MotorLim", p.motor_lim, 0, 32767},
            {"MotorBias", p.motor_bias, -32767, 32767}};
}

Ranges ranges(const msg::PmdTrackSettleParams& p)
{
    // p. 66: settle time 0..32767 cycles; both windows 0..65535 (any word).
    return {{"settle time", p.time_cycles, 0, 32767}};
}

Ranges ranges(const msg::PmdProfileModeParams& p)
{
    // p. 69: mode 0 trapezoidal, 2 S-curve (1 is no mode); jerk 0..4294967295 (any dword).
    return {{"mode", p.mode, 0, 2}};
}

Ranges ranges(const msg::PmdCurrentLoopParams& p)
{
    // p. 71: phase 0 A, 1 B, 2 A and B; gains, limit, dead band, feed-forward 0..32767.
    return {{"phase", p.phase, 0, 2},          {"KpCurrent", p.kp_current, 0, 32767},
            {"KiCurrent", p.ki_current, 0, 32767}, {"ILimCurrent", p.i_lim_current, 0, 32767},
            {"IDeadBand", p.i_dead_band, 0, 32767}, {"Kff", p.kff, 0, 32767}};
}

Ranges ranges(const msg::PmdSettledCurrentLoopParams& p)
{
    // p. 73: as the current loop's.
    return {{"phase", p.phase, 0, 2},
            {"KpSettled", p.kp_settled, 0, 32767},
            {"KiSettled", p.ki_settled, 0, 32767},
            {"ILimSettled", p.i_lim_settled, 0, 32767},
            {"IDeadBandSettled", p.i_dead_band_settled, 0, 32767},
            {"KffSettled", p.kff_settled, 0, 32767}};
}

Ranges ranges(const msg::SolCycleParams& p)
{
    // p. 87: OnTime and OffTime in 250 us steps, 100 ms..10,000 s; NumCycles 0 (forever)..1,000,000.
    return {{"OnTime", p.on_time_250us, 400, 40'000'000},
            {"OffTime", p.off_time_250us, 400, 40'000'000},
            {"NumCycles", p.num_cycles, 0, 1'000'000}};
}

// ---- Piezo (p. 93-125) ----

Ranges ranges(const msg::PzOutputPos& p)
{
    return {{"PositionSW", p.position_sw, 0, 32767}};   // p. 97: 0..32767 = 0..100 % of the travel
}

Ranges ranges(const msg::PzInputVoltsSrc& p)
{
    return {{"VoltSrc", p.volt_src, 0, 3}};   // p. 98: software, + external input (1), + potentiometer (2)
}

Ranges ranges(const msg::PzPiConsts& p)
{
    return {{"PropConst", p.prop_const, 0, 255}, {"IntConst", p.int_const, 0, 255}};   // p. 100
}

Ranges ranges(const msg::TpzDispSettings& p)
{
    return {{"DispIntensity", p.disp_intensity, 0, 255}};   // p. 114
}

Ranges ranges(const msg::TpzIoSettings& p)
{
    // p. 115: VoltageLimit 1 75 V, 2 100 V, 3 150 V; HubAnalogInput 1 hub A, 2 hub B, 3 SMA.
    return {{"VoltageLimit", p.voltage_limit, 1, 3}, {"HubAnalogInput", p.hub_analog_input, 1, 3}};
}

Ranges ranges(const msg::PzOutputMaxVolts& p)
{
    return {{"Voltage", p.voltage, 0, 1500}};   // p. 121: 0.1 V steps, up to 150 V
}

Ranges ranges(const msg::TpzSlewRates& p)
{
    return {{"SlewOpen", p.slew_open, 0, 32767}, {"SlewClosed", p.slew_closed, 0, 32767}};   // p. 123
}

// ---- Strain gauge (p. 127-129) ----

Ranges ranges(const msg::TsgIoSettings& p)
{
    // p. 127: HubAnalogueOutput 1 hub A, 2 hub B pairs; DisplayMode 1 position, 2 voltage, 3 force.
    // ForceCalib "between 1 and 1000" N in 0.001 N steps does not fit its word: 1..65535 (D-22).
    return {{"HubAnalogueOutput", p.hub_analogue_output, 1, 2},
            {"DisplayMode", p.display_mode, 1, 3},
            {"ForceCalib", p.force_calib, 1, 65535}};
}

// ---- Later protocol issues: motor blocks (codec_kcube.hpp; sources in messages.def) ----

Ranges ranges(const msg::PowerParams& p)
{
    // Issue 16 p. 44: "in the range 1 to 100 (i.e. 1% to 100% of full power)".
    return {{"RestFactor", p.rest_factor, 1, 100}, {"MoveFactor", p.move_factor, 1, 100}};
}

Ranges ranges(const msg::KCubeMmiParams& p, bool wheel)
{
    // quantumion/thorlabs_cube kdc.py (and the issue 37 client's checks): JSMode 1 velocity,
    // 2 jog, 3 go to position; DirSense 0..2; DispBrightness 0..100; DispTimeout 0..480
    // minutes; DispDimLevel 0..10.
    Ranges r{{"DispBrightness", p.disp_brightness, 0, 100},
             {"DispTimeout", p.disp_timeout, 0, 480},
             {"DispDimLevel", p.disp_dim_level, 0, 10}};
    // The wheel's words are the motor cubes'. A KSC101 has no wheel: Kinesis' KSC_MMIParams
    // calls the ten words before the display "unused", and MSLNZ/msl-equipment thorlabs/ksc.py
    // sends them as 0 (JSMode 0), which the unit takes.
    if (wheel)
        r.insert(r.begin(), {{"JSMode", p.js_mode, 1, 3}, {"DirSense", p.dir_sense, 0, 2}});
    return r;
}

Ranges ranges(const msg::KCubeTrigIoConfig& p)
{
    // Polarity 1 active high, 2 active low (Kinesis' KMOT_TRIG_POLHIGH / KMOT_TRIG_POLLOW). The
    // modes are a set, not a range: KCubeParams checks them.
    return {{"Trig1Polarity", p.trig1_polarity, 1, 2}, {"Trig2Polarity", p.trig2_polarity, 1, 2}};
}

Ranges ranges(const msg::KCubePosTrigParams& p)
{
    // quantumion kdc.py: pulse width "from 1 us to 1000000 us"; counts of pulses and cycles.
    return {{"NumPulsesFwd", p.num_pulses_fwd, 0, kMaxLong},
            {"NumPulsesRev", p.num_pulses_rev, 0, kMaxLong},
            {"PulseWidth", p.pulse_width, 1, 1'000'000},
            {"NumCycles", p.num_cycles, 0, kMaxLong}};
}

Ranges ranges(const msg::KCubeKstLoopParams& p)
{
    return {{"LoopMode", p.loop_mode, 1, 2}};   // KMOT_KST_OPENLOOP 1, KMOT_KST_CLOSEDLOOP 2
}

std::optional<std::string> first_out_of_range(const Ranges& fields)
{
    for (const auto& r : fields)
        if (r.value < r.min || r.value > r.max)
            return std::string(r.name) + " " + std::to_string(r.value) + " (" + std::to_string(r.min) + ".."
                   + std::to_string(r.max) + ")";
    return std::nullopt;
}

template <class T> struct IsSet : std::false_type {};
template <class P> struct IsSet<msg::Set<P>> : std::true_type {};

} // namespace

std::optional<std::string> out_of_range(const msg::Message& m, bool mmi_wheel)
{
    return msg::visit(
        [mmi_wheel](const auto& typed) -> std::optional<std::string> {
            using T = std::decay_t<decltype(typed)>;
            if constexpr (std::is_same_v<T, msg::SetKCubeMmiParams>)
                return first_out_of_range(ranges(typed.params, mmi_wheel));
            else if constexpr (IsSet<T>::value)
                return first_out_of_range(ranges(typed.params));
            else
                return std::nullopt;
        },
        m);
}

} // namespace rigsim::apt
