#include "models/collision_watch.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rigsim::models {

namespace {

int sign_of(double x)
{
    return (x > 0) - (x < 0);
}

/// A contact is deeper than at the last check by more than this (rounding of the poses).
constexpr double kDeeper_mm = 1e-9;

/// How far two overlapping boxes go into each other: the least overlap of their projections on
/// the 15 axes of the separating-axis test (the boxes as in boxes_overlap(); negative: apart).
double penetration_mm(const Eigen::AlignedBox3d& a, const Eigen::Isometry3d& world_T_a, const Eigen::AlignedBox3d& b,
                      const Eigen::Isometry3d& world_T_b)
{
    const Eigen::Vector3d ea = a.sizes() / 2;
    const Eigen::Vector3d eb = b.sizes() / 2;
    const Eigen::Matrix3d ra_world = world_T_a.linear();
    const Eigen::Matrix3d r = ra_world.transpose() * world_T_b.linear();
    const Eigen::Vector3d t = ra_world.transpose() * (world_T_b * b.center() - world_T_a * a.center());
    const Eigen::Matrix3d abs_r = r.cwiseAbs();
    double depth = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i)   // a's face normals
        depth = std::min(depth, ea(i) + eb.dot(abs_r.row(i)) - std::abs(t(i)));
    for (int j = 0; j < 3; ++j)   // b's face normals
        depth = std::min(depth, ea.dot(abs_r.col(j)) + eb(j) - std::abs(t.dot(r.col(j))));
    for (int i = 0; i < 3; ++i) {   // a's edge i x b's edge j, of length sqrt(1 - r(i,j)^2)
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
        for (int j = 0; j < 3; ++j) {
            const double length = std::sqrt(std::max(0.0, 1 - r(i, j) * r(i, j)));
            if (length < 1e-6)
                continue;   // parallel edges: the face normals cover them
            const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            const double rad_a = ea(i1) * abs_r(i2, j) + ea(i2) * abs_r(i1, j);
            const double rad_b = eb(j1) * abs_r(i, j2) + eb(j2) * abs_r(i, j1);
            const double dist = std::abs(t(i2) * r(i1, j) - t(i1) * r(i2, j));
            depth = std::min(depth, (rad_a + rad_b - dist) / length);
        }
    }
    return depth;
}

std::string frame_pair_name(const Kinematics& k, const FramePair& p)
{
    const auto name = [&](std::size_t f) { return f < k.size() ? "\"" + k.name(f) + "\"" : std::to_string(f); };
    return "collision pair (" + name(p.first) + ", " + name(p.second) + ")";
}

} // namespace

std::vector<std::size_t> joints_between(const Kinematics& kinematics, std::size_t a, std::size_t b)
{
    // Frames come parent first: of two frames the later is never an ancestor of the earlier,
    // so walking the later up meets the common ancestor.
    std::vector<std::size_t> from_a, from_b;
    while (a != b) {
        std::size_t& up = a > b ? a : b;
        if (kinematics.joint(up).type != JointType::Fixed)
            (&up == &a ? from_a : from_b).push_back(up);
        up = kinematics.parent(up);
    }
    from_a.insert(from_a.end(), from_b.begin(), from_b.end());
    return from_a;
}

std::vector<FramePair> auto_collision_pairs(const Kinematics& kinematics)
{
    std::vector<FramePair> pairs;
    for (std::size_t a = 0; a < kinematics.size(); ++a) {
        if (!kinematics.box(a))
            continue;
        for (std::size_t b = a + 1; b < kinematics.size(); ++b)
            if (kinematics.box(b) && kinematics.parent(b) != a && !joints_between(kinematics, a, b).empty())
                pairs.emplace_back(a, b);
    }
    return pairs;
}

CollisionWatch::CollisionWatch(Kinematics& kinematics, std::vector<FramePair> pairs, std::vector<JointDrive> drives)
    : kinematics_(kinematics), pairs_(std::move(pairs)), drives_(std::move(drives)),
      direction_(kinematics.size(), 0), last_q_(kinematics.size(), 0), pairs_of_(kinematics.size()),
      pair_due_(pairs_.size(), false), live_(pairs_.size()), depth_mm_(pairs_.size(), 0)
{
    if (drives_.size() != kinematics_.size())
        throw std::invalid_argument("collision watch: " + std::to_string(drives_.size()) + " joint drives for " +
                                    std::to_string(kinematics_.size()) + " frames");
    std::vector<bool> seen(kinematics_.size(), false);
    for (const FramePair& p : pairs_) {
        if (p.first >= kinematics_.size() || p.second >= kinematics_.size())
            throw std::invalid_argument(frame_pair_name(kinematics_, p) + ": no such frame");
        if (p.first == p.second)
            throw std::invalid_argument(frame_pair_name(kinematics_, p) + ": a frame cannot collide with itself");
        for (const std::size_t f : {p.first, p.second})
            if (!kinematics_.box(f))
                throw std::invalid_argument(frame_pair_name(kinematics_, p) + ": frame \"" + kinematics_.name(f) +
                                            "\" has no box");
        radius_mm_.push_back((kinematics_.box(p.first)->sizes().norm() + kinematics_.box(p.second)->sizes().norm()) / 2
                             * (1 + 1e-9));
        paths_.push_back(joints_between(kinematics_, p.first, p.second));
        for (const std::size_t f : paths_.back()) {
            if (!seen[f]) {
                seen[f] = true;
                watched_.push_back(f);
            }
            pairs_of_[f].push_back(paths_.size() - 1);
        }
    }
}

void CollisionWatch::link(World& world)
{
    for (const std::size_t f : watched_) {
        const std::string& key = drives_[f].body_key;
        if (key.empty())
            continue;
        Body* body = world.find(key);
        if (!body)
            throw std::invalid_argument("collision watch: frame \"" + kinematics_.name(f) + "\": no body \"" + key +
                                        "\" in the world");
        world.watch(*body, *this);
    }
}

void CollisionWatch::on_watched(Body& /*body*/)
{
    if (awake_)
        return;
    awake_ = true;
    reschedule();
}

Ticks CollisionWatch::next_event(Ticks now) const
{
    return awake_ ? now + 1 : kNever;
}

void CollisionWatch::on_event(Ticks now)
{
    kinematics_.update();
    ++checks_;
    // The way each watched joint moves: the way it went since the check on the tick before
    // (what its velocity says may lag: a piezo creeping on), else its velocity's sign.
    const bool consecutive = last_check_ == now - 1;
    const bool first = checks_ == 1;
    bool moving = false;
    // Only a pair with a joint between its frames that went somewhere since the last check
    // can have come together or apart: the others keep their state untested.
    std::fill(pair_due_.begin(), pair_due_.end(), first);
    for (const std::size_t f : watched_) {
        const double q = kinematics_.joint_position(f);
        int dir = consecutive ? sign_of(q - last_q_[f]) : 0;
        if (dir == 0 && drives_[f].velocity)
            dir = sign_of(drives_[f].velocity());
        direction_[f] = dir;
        moving = moving || dir != 0;
        if (q != last_q_[f])
            for (const std::size_t p : pairs_of_[f])
                pair_due_[p] = true;
        last_q_[f] = q;
    }
    last_check_ = now;
    for (std::size_t i = 0; i < pairs_.size(); ++i) {
        if (!pair_due_[i])
            continue;
        const auto [a, b] = pairs_[i];
        const auto& box_a = *kinematics_.box(a);
        const auto& box_b = *kinematics_.box(b);
        const auto& pose_a = kinematics_.world_pose(a);
        const auto& pose_b = kinematics_.world_pose(b);
        // Two spheres round the boxes apart: the boxes are (most pairs, most ticks, cheaply).
        const double reach = radius_mm_[i];
        const bool touching = (pose_a * box_a.center() - pose_b * box_b.center()).squaredNorm() <= reach * reach
                              && boxes_overlap(box_a, pose_a, box_b, pose_b);
        if (touching && !live_[i]) {
            depth_mm_[i] = penetration_mm(box_a, pose_a, box_b, pose_b);
            begin_contact(i);
        } else if (touching) {
            // A joint that began to move during the contact and takes the boxes deeper is
            // stopped too; sliding along or parting is free.
            const double depth = penetration_mm(box_a, pose_a, box_b, pose_b);
            if (depth > depth_mm_[i] + kDeeper_mm)
                deepen_contact(i);
            depth_mm_[i] = depth;
        } else if (!touching && live_[i]) {
            end_contact(i);
        }
    }
    awake_ = moving;
}

void CollisionWatch::begin_contact(std::size_t pair)
{
    live_[pair] = Contact{pairs_[pair].first, pairs_[pair].second, {}, {}};
    const Contact c = stop_joints(pair);
    if (listener_)
        listener_(c);
}

void CollisionWatch::deepen_contact(std::size_t pair)
{
    const Contact c = stop_joints(pair);
    if (listener_ && (!c.stopped.empty() || !c.not_stopped.empty()))
        listener_(c);
}

Contact CollisionWatch::stop_joints(std::size_t pair)
{
    Contact& live = *live_[pair];
    Contact c{live.frame_a, live.frame_b, {}, {}};
    for (const std::size_t f : paths_[pair]) {
        const int dir = direction_[f];
        if (dir == 0)
            continue;
        const ContactJoint j{f, kinematics_.joint_position(f), dir};
        if (!drives_[f].set_obstacles) {
            // Reported once per contact and direction: it pushes on.
            const bool told = std::any_of(live.not_stopped.begin(), live.not_stopped.end(),
                                          [&](const ContactJoint& k) { return k.frame == f && k.direction == dir; });
            if (!told) {
                live.not_stopped.push_back(j);
                c.not_stopped.push_back(j);
            }
            continue;
        }
        const bool held = std::any_of(holds_.begin(), holds_.end(), [&](const Hold& h) {
            return h.pair == pair && h.frame == f && h.direction == dir;
        });
        if (held)
            continue;   // against its obstacle already
        holds_.push_back(Hold{pair, f, dir, j.position});
        apply_holds(f);
        live.stopped.push_back(j);
        c.stopped.push_back(j);
    }
    return c;
}

void CollisionWatch::end_contact(std::size_t pair)
{
    std::vector<std::size_t> released;
    for (const Hold& h : holds_)
        if (h.pair == pair)
            released.push_back(h.frame);
    holds_.erase(std::remove_if(holds_.begin(), holds_.end(), [&](const Hold& h) { return h.pair == pair; }),
                 holds_.end());
    for (const std::size_t f : released)
        apply_holds(f);
    live_[pair].reset();
}

void CollisionWatch::apply_holds(std::size_t frame)
{
    // Of the obstacles live contacts put on one side of a joint, the nearest holds it.
    std::optional<double> min, max;
    for (const Hold& h : holds_) {
        if (h.frame != frame)
            continue;
        if (h.direction > 0)
            max = max ? std::min(*max, h.position) : h.position;
        else
            min = min ? std::max(*min, h.position) : h.position;
    }
    drives_[frame].set_obstacles(min, max);
}

std::vector<Contact> CollisionWatch::contacts() const
{
    std::vector<Contact> out;
    for (const auto& c : live_)
        if (c)
            out.push_back(*c);
    return out;
}

} // namespace rigsim::models
