#include "tick_bench.hpp"

#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace rigsim::bench {

namespace {

[[noreturn]] void usage_exit(const char* program, const char* usage, const std::string& why)
{
    if (!why.empty())
        std::fprintf(stderr, "%s: %s\n", program, why.c_str());
    std::fputs(usage, why.empty() ? stdout : stderr);
    std::exit(why.empty() ? 0 : 2);
}

double thread_cpu_s()
{
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

}  // namespace

Chosen parse_command_line(int argc, char** argv, const char* program, const char* usage,
                          const std::vector<IntFlag>& flags, const std::vector<std::string>& variants)
{
    Chosen chosen;
    for (int i = 1; i < argc; ++i) {
        const std::string flag = argv[i];
        if (flag == "-h" || flag == "--help")
            usage_exit(program, usage, {});
        if (i + 1 >= argc)
            usage_exit(program, usage, "missing value or unknown flag: " + flag);
        const std::string v = argv[++i];
        const auto f = std::find_if(flags.begin(), flags.end(), [&](const IntFlag& f) { return flag == f.flag; });
        const auto named = std::find(variants.begin(), variants.end(), v);
        if (f != flags.end()) {
            char* end = nullptr;
            const long n = std::strtol(v.c_str(), &end, 10);
            if (v.empty() || *end || n < f->lo || n > f->hi)
                usage_exit(program, usage,
                           flag + " wants an integer in " + std::to_string(f->lo) + ".." + std::to_string(f->hi));
            f->set(n);
        } else if (flag == "--only" && named != variants.end()) {
            chosen = {static_cast<std::size_t>(named - variants.begin())};
        } else {
            usage_exit(program, usage, "unknown flag or value: " + flag + " " + v);
        }
    }
    if (chosen.empty())
        for (std::size_t i = 0; i < variants.size(); ++i)
            chosen.push_back(i);
    return chosen;
}

std::vector<BlockTimes> run_alternating(int blocks, const std::vector<std::function<void()>>& block)
{
    std::vector<BlockTimes> times(block.size());
    for (int b = 0; b < blocks; ++b)
        for (std::size_t i = 0; i < block.size(); ++i) {
            const double before = thread_cpu_s();
            block[i]();
            times[i].cpu_s.push_back(thread_cpu_s() - before);
        }
    for (BlockTimes& t : times)
        std::sort(t.cpu_s.begin(), t.cpu_s.end());
    return times;
}

std::string fixed(double value, int decimals)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
    return buf;
}

void Table::header() const
{
    std::vector<std::string> cells;
    for (const Column& c : columns_)
        cells.emplace_back(c.header);
    row(cells);
}

void Table::row(const std::vector<std::string>& cells) const
{
    std::string line = " ";
    for (std::size_t i = 0; i < columns_.size(); ++i) {
        const int w = columns_[i].width;
        const std::string& cell = i < cells.size() ? cells[i] : std::string();
        const int pad = std::max(0, w - static_cast<int>(cell.size()));
        line += ' ';
        line += i == 0 ? cell + std::string(static_cast<std::size_t>(pad), ' ')
                       : std::string(static_cast<std::size_t>(pad), ' ') + cell;
    }
    std::puts(line.c_str());
}

}  // namespace rigsim::bench
