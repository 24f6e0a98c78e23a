#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

namespace rigsim::bench {

/// CPU time a process or thread has used so far, with the wall time it was read at.
struct CpuSample {
    std::chrono::steady_clock::time_point wall;
    /// utime + stime from /proc/.../stat, in seconds (resolution: one clock tick).
    double stat_s = 0;
    /// stime alone: the part spent in the kernel on the process's behalf.
    double system_s = 0;
    /// Time on CPU from /proc/.../schedstat, in ns; absent if the kernel lacks schedstat.
    std::optional<std::int64_t> schedstat_ns;
};

/// The whole content of a file, or nothing if it cannot be opened.
std::optional<std::string> read_file(const std::string& path);

/// Reads the CPU time of every thread of process `pid` from /proc.
CpuSample read_process_cpu(pid_t pid);

/// Reads the CPU time of thread `tid` of this process from /proc.
CpuSample read_thread_cpu(pid_t tid);

/// Seconds per clock tick of /proc/<pid>/stat, i.e. its resolution.
double stat_tick_s();

}  // namespace rigsim::bench
