#pragma once

/*
 * What the in-process tick benches (kinematics, collisions, lut_tick, lut_rig) share: their
 * command line (integer flags in a range, --only one of the variants, -h), the timed blocks run
 * in alternation so that drifts of the machine (frequency, cache, other load) fall on every
 * variant alike, and the table they print.
 */

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace rigsim::bench {

/// An integer flag of a bench's command line: its name, its range and what it sets.
struct IntFlag {
    const char* flag;   ///< "--ticks"
    long lo;
    long hi;
    std::function<void(long)> set;
};

/// The variants a command line chose, as indices into the bench's variant names: all of them
/// in order, or the one `--only` named.
using Chosen = std::vector<std::size_t>;

/// Parses a bench's command line: every flag takes a value. -h or --help prints `usage` to
/// stdout and exits 0; an unknown flag, a missing value or one out of its flag's range prints
/// "`program`: why" and `usage` to stderr and exits 2. `--only V` is accepted if `variants` is
/// not empty, V one of them.
Chosen parse_command_line(int argc, char** argv, const char* program, const char* usage,
                          const std::vector<IntFlag>& flags, const std::vector<std::string>& variants);

/// One variant's CPU time per block, in seconds, sorted ascending.
struct BlockTimes {
    std::vector<double> cpu_s;

    double median() const { return cpu_s[cpu_s.size() / 2]; }
    double min() const { return cpu_s.front(); }
};

/// Runs `blocks` rounds, each calling every variant's `block` once in turn, and returns the CPU
/// time of this thread each call took, per variant.
std::vector<BlockTimes> run_alternating(int blocks, const std::vector<std::function<void()>>& block);

/// `value` printed with `decimals` decimals ("%.*f").
std::string fixed(double value, int decimals);

/// A table of right-aligned columns but the first, each row indented by two spaces.
class Table {
public:
    struct Column {
        const char* header;
        int width;
    };

    explicit Table(std::vector<Column> columns) : columns_(std::move(columns)) {}

    /// Prints the headers.
    void header() const;
    /// Prints one row, a cell per column.
    void row(const std::vector<std::string>& cells) const;

private:
    std::vector<Column> columns_;
};

}  // namespace rigsim::bench
