// rigsim_bench_json: the JSON reader of rig files, stage files, state files and control-API bodies
// (parse_json_text, emulator/core/json_text.*) against the nlohmann callback parser it replaced,
// side by side in one run on the input that parser took quadratic time over: an array of N empty
// objects. Prints milliseconds per parse (the best of 3) for each N and their ratio.
// Usage: rigsim_bench_json [N...]   (default 5000 21000 42000: 15 KB, a 63 KB API body, 126 KB)
#include "emulator/core/json_text.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

std::string objects(long n)
{
    std::string text = "{\"a\":[";
    for (long i = 0; i < n; ++i)
        text += i == 0 ? "{}" : ",{}";
    return text + "]}";
}

template <class Parse>
double best_ms(const std::string& text, Parse parse)
{
    double best = 1e300;
    for (int run = 0; run < 3; ++run) {
        const auto t0 = Clock::now();
        const json v = parse(text);
        const auto t1 = Clock::now();
        if (v.at("a").empty())
            std::abort();
        best = std::min(best, std::chrono::duration<double, std::milli>(t1 - t0).count());
    }
    return best;
}

} // namespace

int main(int argc, char** argv)
{
    std::vector<long> sizes;
    for (int i = 1; i < argc; ++i)
        sizes.push_back(std::strtol(argv[i], nullptr, 10));
    if (sizes.empty())
        sizes = {5000, 21000, 42000};
    std::printf("%10s %10s %14s %14s %8s\n", "objects", "bytes", "callback ms", "linear ms", "ratio");
    for (const long n : sizes) {
        const auto text = objects(n);
        // What rig_config.cpp and json_reply.cpp did before issue 27: a callback for the checks.
        const double old_ms = best_ms(text, [](const std::string& t) {
            return json::parse(t.begin(), t.end(), [](int depth, json::parse_event_t, json&) { return depth <= 64; });
        });
        const double new_ms = best_ms(text, [](const std::string& t) { return rigsim::parse_json_text(t); });
        std::printf("%10ld %10zu %14.2f %14.2f %8.3f\n", n, text.size(), old_ms, new_ms, new_ms / old_ms);
    }
    return 0;
}
