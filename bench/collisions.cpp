/*
 * rigsim_bench_collisions: what the collision watch (models/collision_watch) costs per tick. In
 * one process, no daemon, on a stepped clock: N stages side by side on a table, 10 mm apart,
 * each a models::Axis driving a prismatic joint along z with a 2 mm box on it, the pairs of
 * "auto" (every two boxes: N(N-1)/2 pairs, none ever touching). Variants, each its own world, run
 * in alternating blocks in the same process:
 *   bare   the same axes moving, no watch (the floor: the clock, the world, the axes' reads);
 *   still  the watch, nothing moves: it sleeps, no tick runs;
 *   one    the watch, one axis moves: every tick the watch updates the frames and tests every pair;
 *   all    the watch, every axis moves.
 * A measurement, not a test: exit 0 whatever the figures, 1 if a variant's watch did not check
 * on every tick it should have (or did while still), 2 on bad flags. See bench/README.md.
 */
#include "models/axis.hpp"
#include "models/clock.hpp"
#include "models/collision_watch.hpp"
#include "models/kinematics.hpp"
#include "models/world.hpp"
#include "tick_bench.hpp"

#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace collisions_bench {

using namespace rigsim;
using namespace rigsim::models;

enum class Variant { Bare, Still, One, All };
const std::vector<std::string> kVariantNames = {"bare", "still", "one", "all"};

const char* name(Variant v)
{
    return kVariantNames[static_cast<std::size_t>(v)].c_str();
}

constexpr const char* kUsage =
    "usage: rigsim_bench_collisions [--stages N] [--ticks N] [--blocks N]\n"
    "  --stages N   stages side by side, each a box, every two a pair (default 20)\n"
    "  --ticks N    ticks per block and variant (default 5000)\n"
    "  --blocks N   alternating blocks per variant (default 5)\n";

/// One world: the stages, and the watch unless bare.
struct Rig {
    Rig(int stages, Variant v) : world(clock), kin("table")
    {
        std::vector<JointDrive> drives(1);
        for (int i = 0; i < stages; ++i) {
            AxisConfig c;
            c.travel_min_counts = -1e12;
            c.travel_max_counts = 1e12;
            Axis& a = world.emplace<Axis>("stage/" + std::to_string(i), clock, c);
            axes.push_back(&a);
            Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
            offset.translation() = Eigen::Vector3d(10.0 * i, 0, 0);
            const std::size_t f = kin.add_frame("s" + std::to_string(i), 0, offset,
                                                Joint{JointType::Prismatic, Eigen::Vector3d::UnitZ(), {}},
                                                [&a] { return a.position_counts() * 1e-3; });
            kin.set_box(f, Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1)));
            JointDrive d;
            d.body_key = a.key();
            d.velocity = [&a] { return a.velocity_counts_per_s() * 1e-3; };
            d.set_obstacles = [&a](std::optional<double> lo, std::optional<double> hi) {
                a.set_obstacles(lo ? std::optional<double>(*lo * 1e3) : std::nullopt,
                                hi ? std::optional<double>(*hi * 1e3) : std::nullopt);
            };
            drives.push_back(std::move(d));
        }
        if (v != Variant::Bare) {
            watch = &world.emplace<CollisionWatch>("rig/collisions", kin, auto_collision_pairs(kin), std::move(drives));
            watch->link(world);
        }
        clock.advance(1);   // the watch's first check, at power-up
        const int moving = v == Variant::Still ? 0 : v == Variant::One ? 1 : stages;
        for (int i = 0; i < moving; ++i)
            axes[static_cast<std::size_t>(i)]->move_to(1e11, 10'000, 0);   // 10 mm/s, for ever
    }

    Clock clock;
    World world;
    Kinematics kin;
    std::vector<Axis*> axes;
    CollisionWatch* watch = nullptr;
};

/// The ticks, one at a time as the daemon's ticker runs them.
void run_ticks(Rig& r, std::int64_t ticks)
{
    for (std::int64_t i = 0; i < ticks; ++i)
        r.clock.advance(1);
}

int run(int argc, char** argv)
{
    int stages = 20;
    std::int64_t ticks = 5000;
    int blocks = 5;
    rigsim::bench::parse_command_line(argc, argv, "rigsim_bench_collisions", kUsage,
                                      {{"--stages", 2, 100'000, [&](long n) { stages = static_cast<int>(n); }},
                                       {"--ticks", 1, 100'000'000, [&](long n) { ticks = n; }},
                                       {"--blocks", 1, 1000, [&](long n) { blocks = static_cast<int>(n); }}},
                                      {});
    std::vector<std::unique_ptr<Rig>> rigs;
    std::vector<std::function<void()>> block;
    for (std::size_t k = 0; k < kVariantNames.size(); ++k) {
        rigs.push_back(std::make_unique<Rig>(stages, static_cast<Variant>(k)));
        block.push_back([r = rigs.back().get(), ticks] { run_ticks(*r, ticks); });
    }
    const std::vector<rigsim::bench::BlockTimes> cpu = rigsim::bench::run_alternating(blocks, block);
    int status = 0;
    const auto pairs = static_cast<std::uint64_t>(stages) * static_cast<std::uint64_t>(stages - 1) / 2;
    std::printf("%d stages, %llu pairs, %d blocks of %lld ticks\n", stages, static_cast<unsigned long long>(pairs),
                blocks, static_cast<long long>(ticks));
    double bare = 0;
    for (std::size_t k = 0; k < rigs.size(); ++k) {
        const auto variant = static_cast<Variant>(k);
        const double median = cpu[k].median() / static_cast<double>(ticks) * 1e9;   // ns per tick
        const double min = cpu[k].min() / static_cast<double>(ticks) * 1e9;
        if (variant == Variant::Bare)
            bare = median;
        const Rig& r = *rigs[k];
        const std::uint64_t expected = variant == Variant::Bare    ? 0
                                       : variant == Variant::Still ? 1
                                                                   : 1 + static_cast<std::uint64_t>(ticks) * blocks;
        const std::uint64_t checks = r.watch ? r.watch->checks() : 0;
        if (checks != expected) {
            std::fprintf(stderr, "%s: %llu checks, expected %llu\n", name(variant),
                         static_cast<unsigned long long>(checks), static_cast<unsigned long long>(expected));
            status = 1;
        }
        std::printf("%-6s median %9.3f us/tick  min %9.3f  over bare %9.3f us = %6.2f %% of the 1 ms tick\n",
                    name(variant), median / 1e3, min / 1e3, (median - bare) / 1e3,
                    (median - bare) / 1e4);
    }
    return status;
}

} // namespace collisions_bench

int main(int argc, char** argv)
{
    return collisions_bench::run(argc, argv);
}
