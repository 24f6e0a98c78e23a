#include "emulator/core/kinematics_config.hpp"

#include "emulator/core/config_reader.hpp"
#include "emulator/core/rig_config.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

namespace rigsim {

namespace {

using nlohmann::json;

/// A unit quaternion's norm may be off by this much (rounding in the file).
constexpr double kQuaternionTolerance = 1e-6;
/// Lengths (offsets, joint points, box corners) are at most 1 km in magnitude, so that poses
/// stay finite however the frames are chained.
constexpr long kMaxLengthMm = 1000000;

constexpr std::array<std::string_view, 3> kKinematicsKeys{"frames", "tools", "collisions"};
constexpr std::array<std::string_view, 6> kFrameKeys{"name", "parent", "offset", "axis", "joint", "box_mm"};
constexpr std::array<std::string_view, 4> kToolKeys{"name", "parent", "offset", "box_mm"};
constexpr std::array<std::string_view, 3> kOffsetKeys{"translation_mm", "rpy_deg", "quaternion"};
constexpr std::array<std::string_view, 2> kAxisKeys{"device", "channel"};
constexpr std::array<std::string_view, 2> kBoxKeys{"min", "max"};
constexpr std::array<std::string_view, 1> kFixedJointKeys{"type"};
constexpr std::array<std::string_view, 2> kPrismaticJointKeys{"type", "axis"};
constexpr std::array<std::string_view, 3> kRevoluteJointKeys{"type", "axis", "point_mm"};
constexpr std::array<std::string_view, 3> kGoniometerJointKeys{"type", "axis", "centre_mm"};

std::string vector_text(const double* v, std::size_t n)
{
    return dump(json(std::vector<double>(v, v + n)));
}

/// Reads one "kinematics" object into a KinematicsConfig.
class KinematicsLoader {
public:
    KinematicsLoader(const ConfigReader& reader, const std::vector<DeviceConfig>& devices)
        : r_(reader), devices_(devices)
    {
    }

    KinematicsConfig load(const json& value)
    {
        const std::string top = "/kinematics";
        r_.check_keys(value, top, kKinematicsKeys);
        const auto& frames = r_.require(value, top, "frames");
        const auto* tools = ConfigReader::find(value, "tools");
        if (!frames.is_array() || frames.empty())
            r_.fail(top + "/frames", "expected a non-empty array of frames, got " + describe(frames));
        if (tools && !tools->is_array())
            r_.fail(top + "/tools", "expected an array of tool points, got " + describe(*tools));
        const std::size_t total = frames.size() + (tools ? tools->size() : 0);
        if (total > kMaxFrames)
            r_.fail(top, "at most " + std::to_string(kMaxFrames) + " frames and tools together, got " +
                             std::to_string(total));

        for (std::size_t i = 0; i < frames.size(); ++i)
            load_frame(frames[i], pointer_to(top + "/frames", i), false);
        if (tools)
            for (std::size_t i = 0; i < tools->size(); ++i)
                load_frame((*tools)[i], pointer_to(top + "/tools", i), true);

        resolve_parents();
        const auto root = find_root();
        check_cycles();
        KinematicsConfig out;
        out.frames = parent_first(root);
        if (const auto* c = ConfigReader::find(value, "collisions"))
            out.collisions = load_collisions(*c, out.frames);
        else
            out.collisions = auto_collisions(out.frames);
        return out;
    }

private:
    /// A frame as read, before the tree is ordered.
    struct Entry {
        FrameConfig frame;
        std::string parent_name;     ///< empty: none given
        std::size_t parent = 0;      ///< index into entries_
    };

    void load_frame(const json& v, const std::string& pointer, bool tool)
    {
        if (tool)
            r_.check_keys(v, pointer, kToolKeys);
        else
            r_.check_keys(v, pointer, kFrameKeys);
        Entry e;
        e.frame.pointer = pointer;
        e.frame.tool = tool;
        const auto name_pointer = pointer_to(pointer, "name");
        e.frame.name = load_name(r_.require(v, pointer, "name"), name_pointer);
        const auto [it, fresh] = names_.emplace(e.frame.name, entries_.size());
        if (!fresh)
            r_.fail(name_pointer, "name " + quote(e.frame.name) + " is already used by " +
                                      entries_[it->second].frame.pointer);
        const auto* parent = ConfigReader::find(v, "parent");
        if (tool && !parent)
            r_.fail(pointer_to(pointer, "parent"), "required key missing (a tool point sits on a frame)");
        if (parent)
            e.parent_name = r_.get_string(*parent, pointer_to(pointer, "parent"), "the name of a frame");
        else
            check_root_keys(v, pointer);
        if (const auto* o = ConfigReader::find(v, "offset"))
            load_offset(*o, pointer_to(pointer, "offset"), e.frame);
        if (!tool)
            load_joint(v, pointer, e.frame);
        if (const auto* b = ConfigReader::find(v, "box_mm"))
            e.frame.box_mm = load_box(*b, pointer_to(pointer, "box_mm"));
        entries_.push_back(std::move(e));
    }

    /// The root is the table: fixed in the world where the world's origin is.
    void check_root_keys(const json& v, const std::string& pointer) const
    {
        for (const char* key : {"offset", "axis", "joint"})
            if (ConfigReader::find(v, key))
                r_.fail(pointer_to(pointer, key), std::string("the root frame (the one without \"parent\") is the "
                                                              "world's origin: it takes no ") + key);
    }

    std::string load_name(const json& v, const std::string& pointer) const
    {
        if (!is_name(v))
            r_.fail(pointer, "expected a frame name of 1.." + std::to_string(kMaxNameLength) +
                                 " characters [A-Za-z0-9_.-], got " + describe(v));
        const auto& s = v.get_ref<const std::string&>();
        if (s.find_first_not_of('.') == std::string::npos)
            r_.fail(pointer, "a frame name made only of dots is no URL path segment (/api/frames/<name>), got " +
                                 describe(v));
        return s;
    }

    double load_number(const json& v, const std::string& pointer) const
    {
        // JSON has no NaN or infinity; a number too large for a double is refused by the
        // parser. Strings such as "nan" or "inf" are type errors here.
        if (!v.is_number() || !std::isfinite(v.get<double>()))
            r_.fail(pointer, "expected a finite number, got " + describe(v));
        return v.get<double>();
    }

    template <std::size_t N>
    std::array<double, N> load_numbers(const json& v, const std::string& pointer) const
    {
        if (!v.is_array() || v.size() != N)
            r_.fail(pointer, "expected an array of " + std::to_string(N) + " numbers, got " + describe(v));
        std::array<double, N> out{};
        for (std::size_t i = 0; i < N; ++i)
            out[i] = load_number(v[i], pointer_to(pointer, i));
        return out;
    }

    /// N lengths in mm, each at most kMaxLengthMm in magnitude.
    template <std::size_t N>
    std::array<double, N> load_lengths(const json& v, const std::string& pointer) const
    {
        const auto out = load_numbers<N>(v, pointer);
        for (std::size_t i = 0; i < N; ++i)
            if (!(std::abs(out[i]) <= kMaxLengthMm))
                r_.fail(pointer_to(pointer, i), "expected a number of at most " + std::to_string(kMaxLengthMm) +
                                                    " mm in magnitude, got " + dump(json(out[i])));
        return out;
    }

    /// A direction: any non-zero length, made unit. Scaled by its largest component first, so
    /// that neither a huge nor a tiny vector overflows or underflows the norm.
    Vector3 load_direction(const json& v, const std::string& pointer) const
    {
        auto d = load_numbers<3>(v, pointer);
        const double largest = std::max({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])});
        if (!(largest > 0))
            r_.fail(pointer, "expected a non-zero vector, got " + vector_text(d.data(), 3));
        for (auto& x : d)
            x /= largest;
        const double norm = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (auto& x : d)
            x /= norm;
        return d;
    }

    void load_offset(const json& v, const std::string& pointer, FrameConfig& f) const
    {
        r_.check_keys(v, pointer, kOffsetKeys);
        if (const auto* t = ConfigReader::find(v, "translation_mm"))
            f.translation_mm = load_lengths<3>(*t, pointer_to(pointer, "translation_mm"));
        const auto* rpy = ConfigReader::find(v, "rpy_deg");
        const auto* q = ConfigReader::find(v, "quaternion");
        if (rpy && q)
            r_.fail(pointer, "rpy_deg and quaternion both give the rotation: keep one");
        if (rpy)
            f.rpy_deg = load_numbers<3>(*rpy, pointer_to(pointer, "rpy_deg"));
        if (q) {
            const auto qp = pointer_to(pointer, "quaternion");
            auto w = load_numbers<4>(*q, qp);
            const double norm = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2] + w[3] * w[3]);
            if (!(std::abs(norm - 1) <= kQuaternionTolerance))
                r_.fail(qp, "expected a unit quaternion [w, x, y, z] (norm within 1e-6 of 1), got " +
                                vector_text(w.data(), 4) + " (norm " + dump(json(norm)) + ")");
            for (auto& x : w)
                x /= norm;
            f.quaternion = w;
        }
    }

    void load_joint(const json& v, const std::string& pointer, FrameConfig& f)
    {
        const auto* axis = ConfigReader::find(v, "axis");
        const auto* joint = ConfigReader::find(v, "joint");
        const auto axis_pointer = pointer_to(pointer, "axis");
        const auto joint_pointer = pointer_to(pointer, "joint");
        if (joint) {
            if (!joint->is_object())
                r_.fail(joint_pointer, "expected an object, got " + describe(*joint));
            const auto type_pointer = pointer_to(joint_pointer, "type");
            const auto& type = r_.get_string(r_.require(*joint, joint_pointer, "type"), type_pointer,
                                             "a joint type");
            if (type == "fixed")
                f.joint = JointKind::Fixed;
            else if (type == "prismatic")
                f.joint = JointKind::Prismatic;
            else if (type == "revolute")
                f.joint = JointKind::Revolute;
            else if (type == "goniometer")
                f.joint = JointKind::Goniometer;
            else
                r_.fail(type_pointer, "unknown joint type " + quote(type) +
                                          " (expected \"fixed\", \"prismatic\", \"revolute\" or \"goniometer\")");
            switch (f.joint) {
            case JointKind::Fixed:
                r_.check_keys(*joint, joint_pointer, kFixedJointKeys);
                break;
            case JointKind::Prismatic:
                r_.check_keys(*joint, joint_pointer, kPrismaticJointKeys);
                break;
            case JointKind::Revolute:
                r_.check_keys(*joint, joint_pointer, kRevoluteJointKeys);
                if (const auto* p = ConfigReader::find(*joint, "point_mm"))
                    f.joint_point_mm = load_lengths<3>(*p, pointer_to(joint_pointer, "point_mm"));
                break;
            case JointKind::Goniometer:
                r_.check_keys(*joint, joint_pointer, kGoniometerJointKeys);
                f.joint_point_mm = load_lengths<3>(r_.require(*joint, joint_pointer, "centre_mm"),
                                                   pointer_to(joint_pointer, "centre_mm"));
                break;
            }
            if (f.joint != JointKind::Fixed)
                f.joint_axis = load_direction(r_.require(*joint, joint_pointer, "axis"),
                                              pointer_to(joint_pointer, "axis"));
        }
        const bool moving = f.joint != JointKind::Fixed;
        if (axis && !joint)
            r_.fail(joint_pointer, "required key missing (a frame with an \"axis\" has a moving joint: "
                                   "prismatic, revolute or goniometer)");
        if (axis && !moving)
            r_.fail(pointer_to(joint_pointer, "type"), "a fixed joint is driven by no axis (" + axis_pointer +
                                                           " is given): expected prismatic, revolute or goniometer");
        if (moving && !axis)
            r_.fail(axis_pointer, std::string("required key missing (a ") + joint_kind_name(f.joint) +
                                      " joint is driven by a device's channel)");
        if (axis)
            f.axis = load_axis(*axis, axis_pointer);
    }

    FrameAxisConfig load_axis(const json& v, const std::string& pointer)
    {
        r_.check_keys(v, pointer, kAxisKeys);
        FrameAxisConfig a;
        const auto device_pointer = pointer_to(pointer, "device");
        a.device = r_.get_string(r_.require(v, pointer, "device"), device_pointer, "a device name");
        const bool known = std::any_of(devices_.begin(), devices_.end(),
                                       [&](const DeviceConfig& d) { return d.name == a.device; });
        if (!known)
            r_.fail(device_pointer, "no device named " + quote(a.device) + " in the rig");
        a.channel = static_cast<std::size_t>(
            r_.get_int(r_.require(v, pointer, "channel"), pointer_to(pointer, "channel"), 0, 255));
        const auto [it, fresh] = axes_.emplace(std::make_pair(a.device, a.channel), pointer);
        if (!fresh)
            r_.fail(pointer, "device " + quote(a.device) + " channel " + std::to_string(a.channel) +
                                 " already drives " + it->second + ": one axis drives one frame");
        return a;
    }

    FrameBoxConfig load_box(const json& v, const std::string& pointer) const
    {
        r_.check_keys(v, pointer, kBoxKeys);
        FrameBoxConfig b;
        b.min = load_lengths<3>(r_.require(v, pointer, "min"), pointer_to(pointer, "min"));
        b.max = load_lengths<3>(r_.require(v, pointer, "max"), pointer_to(pointer, "max"));
        for (std::size_t i = 0; i < 3; ++i)
            if (b.min[i] > b.max[i])
                r_.fail(pointer, "expected min <= max in every coordinate, got min " + vector_text(b.min.data(), 3) +
                                     " and max " + vector_text(b.max.data(), 3));
        return b;
    }

    void resolve_parents()
    {
        for (auto& e : entries_) {
            if (e.parent_name.empty())
                continue;
            const auto it = names_.find(e.parent_name);
            if (it == names_.end())
                r_.fail(pointer_to(e.frame.pointer, "parent"), "no frame named " + quote(e.parent_name));
            e.parent = it->second;
        }
    }

    /// The one entry without a parent.
    std::size_t find_root() const
    {
        std::optional<std::size_t> root;
        for (std::size_t i = 0; i < entries_.size(); ++i) {
            if (!entries_[i].parent_name.empty())
                continue;
            if (root)
                r_.fail(entries_[i].frame.pointer, "a second root (a frame without \"parent\"): " +
                                                       entries_[*root].frame.pointer +
                                                       " is the root; every other frame names its parent");
            root = i;
        }
        if (!root)
            r_.fail("/kinematics/frames", "no root: every frame names a \"parent\"; exactly one (the table) "
                                          "must have none");
        return *root;
    }

    /// Every chain must end at the root: a chain that comes back to a frame is a mount cycle,
    /// reported at the first frame of the file that is on it.
    void check_cycles() const
    {
        // 0: unvisited, 1: on the chain being followed, 2: reaches the root.
        std::vector<int> state(entries_.size(), 0);
        for (std::size_t start = 0; start < entries_.size(); ++start) {
            std::vector<std::size_t> chain;
            std::size_t i = start;
            while (state[i] == 0 && !entries_[i].parent_name.empty()) {
                state[i] = 1;
                chain.push_back(i);
                i = entries_[i].parent;
            }
            if (state[i] == 1) {
                // i is on the chain: the cycle is chain[from i]; start it at its first frame in the file.
                const auto at = std::find(chain.begin(), chain.end(), i);
                std::vector<std::size_t> cycle(at, chain.end());
                const auto first = std::min_element(cycle.begin(), cycle.end());
                std::rotate(cycle.begin(), first, cycle.end());
                std::string names;
                for (auto c : cycle)
                    names += entries_[c].frame.name + " -> ";
                names += entries_[cycle.front()].frame.name;
                r_.fail(pointer_to(entries_[cycle.front()].frame.pointer, "parent"),
                        "mount cycle: " + names + " (each frame sits on the next)");
            }
            for (auto c : chain)
                state[c] = 2;
            state[i] = 2;
        }
    }

    /// The frames parent first (by depth, in file order within a depth: frames, then tools),
    /// with parents as indices into the result. Checks the depth limit.
    std::vector<FrameConfig> parent_first(std::size_t root) const
    {
        std::vector<std::size_t> depth(entries_.size(), 0);
        std::vector<bool> known(entries_.size(), false);
        known[root] = true;
        for (std::size_t i = 0; i < entries_.size(); ++i) {
            std::vector<std::size_t> chain;
            std::size_t j = i;
            while (!known[j]) {
                chain.push_back(j);
                j = entries_[j].parent;
            }
            for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
                depth[*it] = depth[entries_[*it].parent] + 1;
                known[*it] = true;
            }
        }
        for (std::size_t i = 0; i < entries_.size(); ++i)
            if (depth[i] > kMaxFrameDepth)
                r_.fail(pointer_to(entries_[i].frame.pointer, "parent"),
                        "frame " + quote(entries_[i].frame.name) + " is " + std::to_string(depth[i]) +
                            " mounts above the root (at most " + std::to_string(kMaxFrameDepth) + ")");
        std::vector<std::size_t> order(entries_.size());
        for (std::size_t i = 0; i < order.size(); ++i)
            order[i] = i;
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return depth[a] < depth[b]; });
        std::vector<std::size_t> index_of(entries_.size());
        for (std::size_t k = 0; k < order.size(); ++k)
            index_of[order[k]] = k;
        std::vector<FrameConfig> out;
        for (auto i : order) {
            out.push_back(entries_[i].frame);
            out.back().parent = i == root ? 0 : index_of[entries_[i].parent];
        }
        return out;
    }

    /// "auto": every pair of frames with boxes that a moving joint between them can bring
    /// together, a frame and its own parent aside.
    static std::vector<std::pair<std::size_t, std::size_t>> auto_collisions(const std::vector<FrameConfig>& frames)
    {
        std::vector<std::size_t> moving(frames.size(), 0);   // moving joints from the root to the frame
        std::vector<std::size_t> depth(frames.size(), 0);
        for (std::size_t i = 1; i < frames.size(); ++i) {
            moving[i] = moving[frames[i].parent] + (frames[i].joint != JointKind::Fixed ? 1 : 0);
            depth[i] = depth[frames[i].parent] + 1;
        }
        std::vector<std::size_t> boxed;
        for (std::size_t i = 0; i < frames.size(); ++i)
            if (frames[i].box_mm)
                boxed.push_back(i);
        std::vector<std::pair<std::size_t, std::size_t>> out;
        for (std::size_t x = 0; x < boxed.size(); ++x) {
            for (std::size_t y = x + 1; y < boxed.size(); ++y) {
                const auto a = boxed[x];
                const auto b = boxed[y];
                if (frames[b].parent == a || frames[a].parent == b)
                    continue;
                auto i = a;
                auto j = b;
                while (depth[i] > depth[j])
                    i = frames[i].parent;
                while (depth[j] > depth[i])
                    j = frames[j].parent;
                while (i != j) {
                    i = frames[i].parent;
                    j = frames[j].parent;
                }
                if (moving[a] + moving[b] > 2 * moving[i])
                    out.emplace_back(a, b);
            }
        }
        return out;
    }

    std::vector<std::pair<std::size_t, std::size_t>> load_collisions(const json& v,
                                                                      const std::vector<FrameConfig>& frames) const
    {
        const std::string pointer = "/kinematics/collisions";
        if (v.is_string() && v.get_ref<const std::string&>() == "auto")
            return auto_collisions(frames);
        if (!v.is_array())
            r_.fail(pointer, "expected \"auto\" or an array of pairs of frame names, got " + describe(v));
        std::map<std::string, std::size_t> index;
        for (std::size_t i = 0; i < frames.size(); ++i)
            index.emplace(frames[i].name, i);
        std::map<std::pair<std::size_t, std::size_t>, std::string> listed;
        std::vector<std::pair<std::size_t, std::size_t>> out;
        for (std::size_t k = 0; k < v.size(); ++k) {
            const auto pair_pointer = pointer_to(pointer, k);
            const auto& p = v[k];
            if (!p.is_array() || p.size() != 2)
                r_.fail(pair_pointer, "expected a pair of frame names, got " + describe(p));
            std::array<std::size_t, 2> ends{};
            for (std::size_t e = 0; e < 2; ++e) {
                const auto end_pointer = pointer_to(pair_pointer, e);
                const auto& name = r_.get_string(p[e], end_pointer, "the name of a frame");
                const auto it = index.find(name);
                if (it == index.end())
                    r_.fail(end_pointer, "no frame named " + quote(name));
                if (!frames[it->second].box_mm)
                    r_.fail(end_pointer, "frame " + quote(name) + " has no box_mm (" + frames[it->second].pointer + ")");
                ends[e] = it->second;
            }
            if (ends[0] == ends[1])
                r_.fail(pair_pointer, "a frame does not collide with itself");
            const std::pair<std::size_t, std::size_t> key = std::minmax(ends[0], ends[1]);
            const auto [it, fresh] = listed.emplace(key, pair_pointer);
            if (!fresh)
                r_.fail(pair_pointer, "the pair is already listed at " + it->second);
            out.push_back(key);
        }
        return out;
    }

    const ConfigReader& r_;
    const std::vector<DeviceConfig>& devices_;
    std::vector<Entry> entries_;                    ///< frames then tools, in file order
    std::map<std::string, std::size_t> names_;      ///< name -> entry
    std::map<std::pair<std::string, std::size_t>, std::string> axes_;   ///< (device, channel) -> axis pointer
};

} // namespace

const char* joint_kind_name(JointKind kind)
{
    switch (kind) {
    case JointKind::Fixed:
        return "fixed";
    case JointKind::Prismatic:
        return "prismatic";
    case JointKind::Revolute:
        return "revolute";
    case JointKind::Goniometer:
        return "goniometer";
    }
    return "fixed";
}

KinematicsConfig load_kinematics_config(const ConfigReader& reader, std::string_view source, const json& value,
                                        const std::vector<DeviceConfig>& devices)
{
    auto config = KinematicsLoader{reader, devices}.load(value);
    config.source = std::string(source);
    return config;
}

} // namespace rigsim
