#include "proc_cpu.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rigsim::bench {

std::optional<std::string> read_file(const std::string& path)
{
    std::ifstream in{path, std::ios::binary};
    if (!in)
        return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

double stat_tick_s()
{
    return 1.0 / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

namespace {

/// utime + stime and stime in seconds from a /proc/.../stat file (process or thread).
void read_stat(const std::string& path, CpuSample& sample)
{
    const auto stat = read_file(path);
    if (!stat)
        throw std::runtime_error("cannot read " + path + ": is the daemon still running?");
    // comm (field 2) may hold spaces and parentheses: fields 3.. start after the last ')'.
    const auto paren = stat->rfind(')');
    if (paren == std::string::npos)
        throw std::runtime_error("cannot parse " + path);
    std::istringstream fields{stat->substr(paren + 1)};
    std::string field;
    unsigned long long utime = 0;
    unsigned long long stime = 0;
    for (int number = 3; number <= 15 && fields >> field; ++number) {
        if (number == 14)
            utime = std::stoull(field);
        else if (number == 15)
            stime = std::stoull(field);
    }
    if (!fields)
        throw std::runtime_error("cannot parse " + path);
    sample.stat_s = static_cast<double>(utime + stime) * stat_tick_s();
    sample.system_s = static_cast<double>(stime) * stat_tick_s();
}

/// Time on CPU in ns, the first field of a /proc/.../schedstat file.
std::optional<std::int64_t> schedstat_ns(const std::string& path)
{
    const auto schedstat = read_file(path);
    if (!schedstat)
        return std::nullopt;
    std::istringstream in{*schedstat};
    long long on_cpu_ns = 0;
    if (!(in >> on_cpu_ns))
        return std::nullopt;
    return on_cpu_ns;
}

}  // namespace

CpuSample read_process_cpu(pid_t pid)
{
    CpuSample sample;
    sample.wall = std::chrono::steady_clock::now();
    const std::string dir = "/proc/" + std::to_string(pid);
    read_stat(dir + "/stat", sample);

    // /proc/<pid>/schedstat is the main thread alone: sum over the tasks.
    std::error_code ec;
    std::int64_t total_ns = 0;
    bool any = false;
    for (const auto& task : std::filesystem::directory_iterator{dir + "/task", ec}) {
        // A thread may exit while we iterate: skip what cannot be read.
        if (const auto ns = schedstat_ns(task.path().string() + "/schedstat")) {
            total_ns += *ns;
            any = true;
        }
    }
    if (any)
        sample.schedstat_ns = total_ns;
    return sample;
}

CpuSample read_thread_cpu(pid_t tid)
{
    CpuSample sample;
    sample.wall = std::chrono::steady_clock::now();
    const std::string dir = "/proc/self/task/" + std::to_string(tid);
    read_stat(dir + "/stat", sample);
    sample.schedstat_ns = schedstat_ns(dir + "/schedstat");
    return sample;
}

}  // namespace rigsim::bench
