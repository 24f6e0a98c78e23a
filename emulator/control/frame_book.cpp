#include "emulator/control/frame_book.hpp"

#include <map>
#include <string>
#include <utility>

namespace rigsim::control {

namespace {

/// The highest channel a joint's axis names (docs/config.md "Kinematics": 0..255).
constexpr std::size_t kMaxJointChannel = 255;

bool same(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b)
{
    return a.matrix() == b.matrix();
}

} // namespace

std::vector<std::optional<JointAxis>> joint_axes(const std::vector<JointBinding>& bindings,
                                                 const std::vector<ControlledDevice>& devices)
{
    // Each device's channels, asked once which body they drive (the world's keys are the
    // families' own: an APT bay's is 1-based, an MCS channel's 0-based), from channel 0 up to the
    // first the device does not have (404): a joint's channel, which on a KIM101 or an MMR601
    // numbers actuators beyond the channel objects of describe().
    std::map<std::string, JointAxis, std::less<>> by_body;
    for (const auto& d : devices) {
        if (!d.surface)
            continue;
        for (std::size_t index = 0; index <= kMaxJointChannel; ++index) {
            std::string key;
            if (const auto refused = d.surface->axis_body_key(index, key)) {
                if (refused->status == 404)
                    break;
                continue;
            }
            if (!key.empty())
                by_body.emplace(key, JointAxis{d.endpoints.name, index});
        }
    }
    std::vector<std::optional<JointAxis>> out;
    out.reserve(bindings.size());
    for (const auto& b : bindings) {
        const auto it = b.body_key.empty() ? by_body.end() : by_body.find(b.body_key);
        out.push_back(it == by_body.end() ? std::nullopt : std::optional<JointAxis>(it->second));
    }
    return out;
}

FrameBook::FrameBook(FrameSource source) : source_(std::move(source))
{
    rebase();
}

void FrameBook::rebase()
{
    published_world_.clear();
    published_local_.clear();
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
