/*
 * rigsim_bench_kinematics: what the kinematic chains (models/kinematics) cost per tick, issue
 * 13's closing figure. In one process, no daemon: a rig of 100 stages in 20 chains of depth 5
 * on a table (mixed joints: prismatic x, y, z, revolute, goniometer), a tool point at the end
 * of each chain (20), 121 frames. Each joint's reader returns its axis's position now: a
 * moving axis samples a smooth out-and-back profile (a table, one value per tick), a still
 * one its rest position. A tick is one Kinematics::update() and a read of every tool's world
 * pose. Variants, each its own rig, run in alternating blocks in the same process:
 *   bare   the loop and the tool reads without update() (the floor);
 *   still  nothing moves: update() reads the 100 joints and recomputes nothing;
 *   one    one chain's first joint moves: its 5 frames and its tool are recomputed;
 *   all    every axis moves: 100 frames and 20 tools recomputed.
 * A measurement, not a test: exit 0 whatever the figures, 1 if a tick recomputed another count
 * of frames than its variant's or the lazily updated poses differ from a full recomputation,
 * 2 on bad flags. See bench/README.md.
 */
#include "models/kinematics.hpp"
#include "tick_bench.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace kinematics_bench {

using rigsim::models::Joint;
using rigsim::models::JointType;
using rigsim::models::Kinematics;

constexpr int kChains = 20;
constexpr int kDepth = 5;
constexpr std::int64_t kProfileTicks = 4000;   ///< one out-and-back move: 4 s at 1 kHz

struct Options {
    std::int64_t ticks = 20000;   ///< ticks per block
    int blocks = 10;
};

enum class Variant { Bare, Still, One, All };
const std::vector<std::string> kVariantNames = {"bare", "still", "one", "all"};

const char* name(Variant v)
{
    return kVariantNames[static_cast<std::size_t>(v)].c_str();
}

/// Frames update() recomputes per tick in each variant.
std::size_t expected_recomputed(Variant v)
{
    switch (v) {
    case Variant::Bare:
    case Variant::Still:
        return 0;
    case Variant::One:
        return kDepth + 1;
    case Variant::All:
        return kChains * (kDepth + 1);
    }
    return 0;
}

/// One stage axis as a joint reader sees it.
struct AxisSim {
    const std::vector<double>* profile = nullptr;   ///< position per tick of the move
    std::int64_t phase = 0;
    bool moving = false;
    double rest = 0;

    double position(std::int64_t now) const
    {
        return moving ? (*profile)[static_cast<std::size_t>((now + phase) % kProfileTicks)] : rest;
    }
};

/// An out-and-back move of `amplitude`: amplitude (1 - cos(2π t / T)) / 2, sampled per tick.
std::vector<double> profile(double amplitude)
{
    std::vector<double> p(kProfileTicks);
    for (std::int64_t t = 0; t < kProfileTicks; ++t)
        p[static_cast<std::size_t>(t)] = amplitude * (1 - std::cos(6.283185307179586 * t / kProfileTicks)) / 2;
    return p;
}

/// The rig of one variant: its tick, axes, frames and tools.
struct Setup {
    Variant variant;
    std::int64_t now = 0;
    std::vector<double> mm_profile = profile(10);     // prismatic, mm
    std::vector<double> deg_profile = profile(90);    // revolute, degrees
    std::vector<double> tilt_profile = profile(10);   // goniometer, degrees
    std::vector<std::unique_ptr<AxisSim>> axes;
    std::vector<std::size_t> tools;
    Kinematics kinematics{"table"};
    double sum = 0;                ///< of the tool poses read, so the reads are not optimised out
    std::uint64_t wrong_ticks = 0;   ///< ticks that recomputed another count than expected

    explicit Setup(Variant v) : variant(v) { build(kinematics); }

    /// Adds the 20 chains and 20 tools to `k`, reading this rig's axes.
    void build(Kinematics& k)
    {
        const bool fresh = axes.empty();
        std::size_t axis = 0;
        for (int c = 0; c < kChains; ++c) {
            std::size_t parent = 0;
            for (int level = 0; level < kDepth; ++level, ++axis) {
                Joint joint;
                const std::vector<double>* table = &mm_profile;
                switch ((c + level) % kDepth) {
                case 0:
                    joint.type = JointType::Prismatic;
                    joint.axis = Eigen::Vector3d::UnitX();
                    break;
                case 1:
                    joint.type = JointType::Prismatic;
                    joint.axis = Eigen::Vector3d::UnitY();
                    break;
                case 2:
                    joint.type = JointType::Revolute;
                    joint.axis = Eigen::Vector3d::UnitZ();
                    joint.point_mm = Eigen::Vector3d(5, 0, 0);
                    table = &deg_profile;
                    break;
                case 3:
                    joint.type = JointType::Prismatic;
                    joint.axis = Eigen::Vector3d::UnitZ();
                    break;
                case 4:
                    joint.type = JointType::Goniometer;
                    joint.axis = Eigen::Vector3d::UnitX();
                    joint.point_mm = Eigen::Vector3d(0, 0, 40);
                    table = &tilt_profile;
                    break;
                }
                if (fresh) {
                    auto a = std::make_unique<AxisSim>();
                    a->profile = table;
                    a->phase = static_cast<std::int64_t>(axis) * 37 % kProfileTicks;
                    a->moving = variant == Variant::All || (variant == Variant::One && c == 0 && level == 0);
                    a->rest = (*table)[static_cast<std::size_t>(a->phase)];
                    axes.push_back(std::move(a));
                }
                Eigen::Isometry3d offset(Eigen::Translation3d(level == 0 ? (c % 5) * 200.0 : 0,
                                                              level == 0 ? (c / 5) * 200.0 : 0, 30));
                offset.linear() = rigsim::models::quaternion_from_rpy_deg(0, 0, 3.0 * c).toRotationMatrix();
                const AxisSim* sim = axes[axis].get();
                const std::int64_t* clock = &now;
                parent = k.add_frame("c" + std::to_string(c) + "_" + std::to_string(level), parent, offset, joint,
                                     [sim, clock] { return sim->position(*clock); });
            }
            const std::size_t tool = k.add_tool("tool" + std::to_string(c), parent,
                                                Eigen::Isometry3d(Eigen::Translation3d(0, 0, 25)));
            if (&k == &kinematics)
                tools.push_back(tool);
        }
    }
};

/// `ticks` ticks of `s`: one update() (but bare) and every tool's pose read per tick. Not
/// inlined: callgrind counts inside it (--toggle-collect).
__attribute__((noinline)) void run_ticks(Setup& s, std::int64_t ticks)
{
    const bool update = s.variant != Variant::Bare;
    const std::size_t expected = expected_recomputed(s.variant);
    for (std::int64_t t = 0; t < ticks; ++t) {
        ++s.now;
        if (update && s.kinematics.update() != expected)
            ++s.wrong_ticks;
        for (std::size_t tool : s.tools) {
            const Eigen::Isometry3d& pose = s.kinematics.world_pose(tool);
            s.sum += pose.translation().sum() + pose.linear()(0, 0);
        }
    }
}

/// Whether the lazily updated poses equal those of a rig built now and updated once.
bool poses_match(Setup& s)
{
    Kinematics fresh("table");
    s.build(fresh);
    fresh.update();
    for (std::size_t i = 0; i < fresh.size(); ++i)
        if (!fresh.world_pose(i).isApprox(s.kinematics.world_pose(i), 1e-12))
            return false;
    return true;
}

constexpr const char* kUsage =
    "usage: rigsim_bench_kinematics [--ticks N] [--blocks N] [--only bare|still|one|all]\n"
    "  --ticks N    ticks per block and variant (default 20000)\n"
    "  --blocks N   alternating blocks per variant (default 10)\n"
    "  --only V     run one variant only (for callgrind)\n";

} // namespace kinematics_bench

int main(int argc, char** argv)
{
    using namespace kinematics_bench;
    using namespace rigsim::bench;
    Options o;
    std::vector<Variant> variants;
    for (std::size_t i : parse_command_line(argc, argv, "rigsim_bench_kinematics", kUsage,
                                            {{"--ticks", 1, 100'000'000, [&](long n) { o.ticks = n; }},
                                             {"--blocks", 1, 1000, [&](long n) { o.blocks = static_cast<int>(n); }}},
                                            kVariantNames))
        variants.push_back(static_cast<Variant>(i));

    std::vector<std::unique_ptr<Setup>> setups;
    std::vector<std::function<void()>> blocks;
    for (Variant v : variants) {
        setups.push_back(std::make_unique<Setup>(v));
        setups.back()->kinematics.update();   // the first update computes every frame
        blocks.push_back([s = setups.back().get(), &o] { run_ticks(*s, o.ticks); });
    }
    const std::vector<BlockTimes> cpu = run_alternating(o.blocks, blocks);

    int rc = 0;
    for (auto& s : setups) {
        if (s->wrong_ticks) {
            std::fprintf(stderr, "rigsim_bench_kinematics: %s: %llu ticks did not recompute %zu frames\n",
                         name(s->variant), static_cast<unsigned long long>(s->wrong_ticks),
                         expected_recomputed(s->variant));
            rc = 1;
        }
        if (s->variant != Variant::Bare && !poses_match(*s)) {
            std::fprintf(stderr, "rigsim_bench_kinematics: %s: the lazily updated poses differ from a full update\n",
                         name(s->variant));
            rc = 1;
        }
    }

    std::printf("kinematics: %d chains x %d stages + %d tools = %zu frames; a tick = update() + %d tool poses read; "
                "%d blocks of %lld ticks per variant\n",
                kChains, kDepth, kChains, setups.front()->kinematics.size(), kChains, o.blocks,
                static_cast<long long>(o.ticks));
    const Table table({{"variant", 7}, {"recomputed", 12}, {"ns/tick (med)", 14}, {"ns/tick (min)", 14},
                       {"- bare (ns)", 12}, {"% of 1 ms tick", 14}});
    table.header();
    double bare_ns = -1;
    for (std::size_t i = 0; i < variants.size(); ++i) {
        const double med_ns = cpu[i].median() / static_cast<double>(o.ticks) * 1e9;
        const double min_ns = cpu[i].min() / static_cast<double>(o.ticks) * 1e9;
        if (variants[i] == Variant::Bare)
            bare_ns = med_ns;
        const std::string over = bare_ns < 0 || variants[i] == Variant::Bare
                                     ? std::string("-")
                                     : std::to_string(std::lround(med_ns - bare_ns));
        table.row({name(variants[i]), std::to_string(expected_recomputed(variants[i])), fixed(med_ns, 1),
                   fixed(min_ns, 1), over, fixed(med_ns / 1e6 * 100, 3)});
    }
    std::printf("  (CPU of this thread per tick, median and minimum over the blocks; recomputed: frames per tick)\n");
    return rc;
}
