#include "cpu_placement.hpp"

#include "unique_fd.hpp"

#include <sched.h>

#include <stdexcept>
#include <vector>

namespace rigsim::bench {

std::optional<Pinning> parse_pinning(const std::string& text)
{
    if (text == "same")
        return Pinning::Same;
    if (text == "split")
        return Pinning::Split;
    if (text == "none")
        return Pinning::None;
    return std::nullopt;
}

Placement choose_placement(Pinning pinning)
{
    cpu_set_t set;
    CPU_ZERO(&set);
    if (::sched_getaffinity(0, sizeof set, &set) < 0)
        throw std::runtime_error(errno_message("sched_getaffinity"));
    std::vector<int> cpus;
    for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
        if (CPU_ISSET(cpu, &set))
            cpus.push_back(cpu);
    if (cpus.empty())
        return {};

    switch (pinning) {
    case Pinning::Same:
        return {cpus[0], cpus[0]};
    case Pinning::Split:
        if (cpus.size() >= 2)
            return {cpus[0], cpus[1]};
        return {cpus[0], cpus[0]};
    case Pinning::None:
        return {};
    }
    return {};
}

std::string describe(const Placement& placement)
{
    if (!placement.client_cpu || !placement.server_cpu)
        return "not pinned (left to the scheduler)";
    if (*placement.client_cpu == *placement.server_cpu)
        return "client and servers on CPU " + std::to_string(*placement.client_cpu);
    return "client on CPU " + std::to_string(*placement.client_cpu) + ", servers on CPU " +
           std::to_string(*placement.server_cpu);
}

void pin_this_thread(int cpu)
{
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    // pid 0: the calling thread only; threads started later inherit its mask.
    if (::sched_setaffinity(0, sizeof set, &set) < 0)
        throw std::runtime_error(errno_message("sched_setaffinity CPU " + std::to_string(cpu)));
}

}  // namespace rigsim::bench
