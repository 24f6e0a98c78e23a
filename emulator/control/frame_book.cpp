#include "emulator/control/frame_book.hpp"

#include <utility>

namespace rigsim::control {

namespace {

bool same(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b)
{
    return a.matrix() == b.matrix();
}

} // namespace

FrameBook::FrameBook(FrameSource source) : source_(std::move(source))
{
    if (empty())
        return;
    auto& k = *source_.kinematics;
    k.update();
    for (std::size_t i = 0; i < k.size(); ++i) {
        published_world_.push_back(k.world_pose(i));
        published_local_.push_back(k.parent_pose(i));
    }
}

nlohmann::json FrameBook::all()
{
    if (empty())
        return no_frames_json();
    auto& k = *source_.kinematics;
    k.update();
    return frames_json(k, source_.axes, contacts_now(k, source_.collision_pairs));
}

std::optional<nlohmann::json> FrameBook::one(std::string_view name)
{
    if (empty())
        return std::nullopt;
    auto& k = *source_.kinematics;
    const auto frame = k.find(name);
    if (!frame)
        return std::nullopt;
    k.update();
    const auto& axes = source_.axes;
    const JointAxis* axis = *frame < axes.size() && axes[*frame] ? &*axes[*frame] : nullptr;
    return frame_json(k, *frame, axis);
}

nlohmann::json FrameBook::changed()
{
    auto out = nlohmann::json::array();
    if (empty())
        return out;
    auto& k = *source_.kinematics;
    k.update();   // GET /api/frames may have updated since: compare with what was published
    for (std::size_t i = 0; i < k.size(); ++i) {
        if (same(k.world_pose(i), published_world_[i]) && same(k.parent_pose(i), published_local_[i]))
            continue;
        published_world_[i] = k.world_pose(i);
        published_local_[i] = k.parent_pose(i);
        const JointAxis* axis = i < source_.axes.size() && source_.axes[i] ? &*source_.axes[i] : nullptr;
        out.push_back(frame_json(k, i, axis));
    }
    return out;
}

} // namespace rigsim::control
