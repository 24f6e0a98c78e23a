#pragma once

#include <optional>
#include <string>

namespace rigsim::bench {

/*
 * Where the client and the servers run. On a small machine the round trip depends
 * mostly on whether client and server share a CPU (a direct switch) or not (a
 * cross-CPU wake-up): for the ratio to mean anything, rigsimd and its floor must be
 * placed alike, so by default both are pinned the same way.
 */
enum class Pinning { Same, Split, None };

/// Parses "split", "same" or "none".
std::optional<Pinning> parse_pinning(const std::string& text);

/// The CPUs chosen for a pinning; absent: left to the scheduler.
struct Placement {
    std::optional<int> client_cpu;
    std::optional<int> server_cpu;
};

/// The first CPU(s) of this process's affinity mask: Split wants two, Same one.
/// Split falls back to Same when only one CPU is allowed.
Placement choose_placement(Pinning pinning);

/// Describes a placement for the report, e.g. "client on CPU 0, servers on CPU 1".
std::string describe(const Placement& placement);

/// Pins the calling thread to `cpu`; throws on failure.
void pin_this_thread(int cpu);

}  // namespace rigsim::bench
