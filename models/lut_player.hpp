#pragma once
// The waveform generator of a piezo channel (APT manual p.106-112, "WGM"): a table of up to
// 8000 samples (PZ_SET_OUTPUTLUT) clocked out as PZ_SET_OUTPUTLUTPARAMS says, from
// PZ_START_LUTOUTPUT to the end of its cycles or PZ_STOP_LUTOUTPUT. No protocol here: the
// piezo module decodes the messages, decides when a start happens (input triggers, p.109) and
// turns samples into volts or position (p.106).
//
// Like PiezoScanner, the output is a function of clock time, counted in base sample
// intervals b (1 ms BPC, 0.25 ms TPZ: p.109, passed to start()). From p.109-110:
// - DelayTime "specifies the time interval between neighbouring samples, i.e. for how long the
//   sample will remain at its present value" (range 1..2147483648): each sample is output for
//   D = max(1, DelayTime) intervals, so DelayTime 1 is the full bandwidth. The same paragraph's
//   "set the DelayTime parameter to the required additional delay" is not read as D + 1: the
//   range starts at 1 and the default is the full bandwidth (plan D-8); 0 is taken as 1.
// - PreCycleRest: "the system then outputs the first value in the LUT until the PreCycleRest
//   time has expired" (0..2147483648 sample intervals): each cycle opens with Pre intervals of
//   LUT[0], before LUT[0] itself is output for its D intervals.
// - PostCycleRest: "the system then outputs the last value in the cycle until the
//   PostCycleRest time has expired": each cycle closes with Post intervals of LUT[L-1].
// - Rests are in base sample intervals, not in D-stretched ones ("independently of the
//   DelayTime parameter", p.110). A cycle lasts Pre + L·D + Post intervals, L = CycleLength.
// - OUTPUTLUT_FIXED outputs NumCycles cycles; OUTPUTLUT_CONTINUOUS runs until stop() (p.108).
// - After the last cycle or a stop, the output holds the last value output: LUT[L-1] at the
//   end of a fixed run, the sample of the stop instant after a stop. The manual does not say
//   what follows the last cycle; this is its "remain at the last position" of the post-rest
//   (p.110) carried on, as a DAC holds its last code (plan §3).
// - CycleLength may be the whole table (8000 BPC, 513 TPZ: p.106 "a maximum of 8000 samples"):
//   p.109's "0 to 7999 ... 0 to 512" is the index range of PZ_SET_OUTPUTLUT repeated.
// Sub-tick intervals are exact: at tick t, floor(elapsed_µs / b) intervals have passed, and the
// value is the sample the schedule gives at that instant (a 1 kHz tick sees every fourth sample
// of a 0.25 ms schedule). The parameters and the table are copied at start(): a SET during a
// run changes the next run, and the run stays a pure function of time.
//
// The trigger fields (OPTrigStart, OPTrigWidth, TrigRepeatCycle, mode bits 0x04-0x80) are kept
// and checked, not interpreted here.

#include "models/clock.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace rigsim::models {

class LutPlayer {
public:
    using Table = Eigen::Array<std::int16_t, Eigen::Dynamic, 1>;

    static constexpr std::size_t kMaxSamples = 8000;   ///< p.106: "a maximum of 8000 samples"
    /// Mode bits of PZ_SET_OUTPUTLUTPARAMS (p.108-109).
    static constexpr std::uint16_t kContinuous = 0x01;
    static constexpr std::uint16_t kFixed = 0x02;
    static constexpr std::uint16_t kOutputTrig = 0x04;
    static constexpr std::uint16_t kInputTrig = 0x08;
    static constexpr std::uint16_t kOutputTrigSenseHi = 0x10;
    static constexpr std::uint16_t kInputTrigSenseHi = 0x20;
    static constexpr std::uint16_t kGated = 0x40;
    static constexpr std::uint16_t kOutputTrigRepeat = 0x80;
    static constexpr std::uint16_t kTriggerBits = 0xFC;   ///< "not applicable to the TPZ001" (p.108)

    /// The fields of PZ_SET_OUTPUTLUTPARAMS (p.108-110), as on the wire.
    struct Params {
        std::uint16_t mode = kContinuous;
        std::uint16_t cycle_length = 0;      ///< samples per cycle, L
        std::int32_t num_cycles = 1;         ///< fixed mode only
        std::int32_t delay_time = 1;         ///< base intervals per sample (0 taken as 1)
        std::int32_t pre_cycle_rest = 0;     ///< base intervals of LUT[0] before each cycle
        std::int32_t post_cycle_rest = 0;    ///< base intervals of LUT[L-1] after each cycle
        std::uint16_t op_trig_start = 0;
        std::int32_t op_trig_width = 0;
        std::uint16_t trig_repeat_cycle = 0;
        bool operator==(const Params& o) const;
        bool operator!=(const Params& o) const { return !(*this == o); }
    };

    /// `capacity`: samples the unit holds (8000 BPC, 513 TPZ: indices 0..512, p.106).
    explicit LutPlayer(const Clock& clock, std::size_t capacity = kMaxSamples);

    /// Why the unit ignores PZ_SET_OUTPUTLUT at `index`, or nullopt.
    static std::optional<std::string> check_index(std::size_t index, std::size_t capacity);
    /// Why the unit ignores PZ_SET_OUTPUTLUTPARAMS `p`, or nullopt; `has_triggers`: false on
    /// the TPZ001, which has no trigger I/O (p.108).
    static std::optional<std::string> check_params(const Params& p, std::size_t capacity, bool has_triggers);
    /// Why PZ_START_LUTOUTPUT is ignored with `p`, `loaded` samples and the base interval, or nullopt.
    static std::optional<std::string> check_start(const Params& p, std::size_t loaded,
                                                  std::uint32_t base_interval_us);

    std::size_t capacity() const { return static_cast<std::size_t>(table_.size()); }
    /// Sets one sample (PZ_SET_OUTPUTLUT); false, and nothing changes, past the capacity.
    bool set_sample(std::size_t index, std::int16_t value);
    /// A sample of the table (0 past the capacity).
    std::int16_t sample(std::size_t index) const;
    /// Loads `table` from index 0 (cut at the capacity): the bench and tests.
    void set_table(const Table& table);
    const Table& table() const { return table_; }
    /// Samples loaded since power-up: the highest index set + 1 (p.109: CycleLength <= this).
    std::size_t loaded() const { return loaded_; }

    /// Takes `p` for the next start (the module checks it first: check_params()).
    void set_params(const Params& p) { params_ = p; }
    const Params& params() const { return params_; }

    /// Starts the waveform at `now`, every sample `base_interval_us` × max(1, DelayTime) long,
    /// restarting a run in progress. Returns why it did not start (check_params with
    /// triggers, check_start), or nullopt.
    std::optional<std::string> start(Ticks now, std::uint32_t base_interval_us);
    /// Stops a run at `now`: the output holds the value of that instant. No-op when not running.
    void stop(Ticks now);
    /// Forgets the run and its held value: value_at() is nullopt again.
    void reset();

    /// A run was started (and not reset): value_at() has a value.
    bool started() const { return started_; }
    /// Samples are being clocked out at `t` (from the start tick up to end_tick()).
    bool running_at(Ticks t) const { return started_ && t >= start_ && t < end_; }
    /// The output at `t`: the schedule's sample while running, the held value after; nullopt
    /// before any start.
    std::optional<std::int16_t> value_at(Ticks t) const;
    /// The table index being output at `t` (0 in the pre-rest, L-1 in the post-rest), nullopt
    /// when not running.
    std::optional<std::size_t> index_at(Ticks t) const;
    /// Cycles completed by `t` (so the 0-based number of the cycle in progress while running);
    /// NumCycles after a fixed run's end.
    std::int64_t cycle_at(Ticks t) const;
    Ticks start_tick() const { return start_; }
    /// First tick at which the run is over: kNever while a continuous run goes on; the stop
    /// tick after stop(); 0 before any start.
    Ticks end_tick() const { return end_; }
    /// First tick after `now` at which the output may take another sample or the run ends,
    /// kNever when not running: a module may sleep until then.
    Ticks next_change(Ticks now) const;

private:
    /// Where the schedule is after `n` base intervals of a run.
    struct Where {
        std::int64_t cycle;
        std::size_t index;
    };
    /// Base intervals completed between the start and tick `t` (t >= start).
    std::int64_t intervals_at(Ticks t) const;
    /// First tick at which `n` intervals have passed; kNever if that is past the tick range.
    Ticks tick_of_interval(std::int64_t n) const;
    Where where(std::int64_t n) const;
    std::int64_t delay_intervals() const;

    const Clock& clock_;
    Table table_;
    std::size_t loaded_ = 0;
    Params params_;

    // The run, fixed at start().
    bool started_ = false;
    Params run_;
    Table run_table_;
    std::uint32_t base_interval_us_ = 1000;
    std::int64_t cycle_intervals_ = 1;   ///< Pre + L·D + Post
    Ticks start_ = 0;
    Ticks end_ = 0;
    std::int16_t held_ = 0;              ///< the output from end_ on
};

} // namespace rigsim::models
