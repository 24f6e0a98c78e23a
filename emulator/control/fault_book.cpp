#include "emulator/control/fault_book.hpp"

#include "emulator/control/json_reply.hpp"
#include "emulator/core/control_surface.hpp"

#include <algorithm>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace rigsim::control {

using nlohmann::json;

namespace {

std::string joined(const std::vector<std::string>& names)
{
    std::string out;
    for (const auto& n : names)
        out += (out.empty() ? "" : ", ") + n;
    return out;
}

/// Refuses keys of `params` other than `allowed`.
void only_keys(const json& params, const std::string& kind, std::initializer_list<const char*> allowed)
{
    for (const auto& item : params.items()) {
        const std::string& key = item.key();
        const bool known = std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; });
        if (!known) {
            std::string list;
            for (const auto* a : allowed)
                list += (list.empty() ? "" : ", ") + std::string(a);
            throw BadRequest{400, "\"" + key + "\": not a parameter of a " + kind + " fault"
                                      + (list.empty() ? " (it takes none)" : " (it takes " + list + ")")};
        }
    }
}

/// The "direction" parameter: {inbound, outbound}; `allow_both` false for a one-way kind.
std::pair<bool, bool> direction_of(const json& params, const char* fallback, bool allow_both = true)
{
    const json d = params.contains("direction") ? params.at("direction") : json(fallback);
    if (d == "in")
        return {true, false};
    if (d == "out")
        return {false, true};
    if (allow_both && d == "both")
        return {true, true};
    throw BadRequest{400, std::string("\"direction\": expected ") + (allow_both ? "\"in\", \"out\" or \"both\"" : "\"in\" or \"out\"")
                              + ", got " + dump(d)};
}

/// A required parameter's presence.
void required(const json& params, const char* key, const std::string& kind)
{
    if (!params.contains(key))
        throw BadRequest{400, "\"" + std::string(key) + "\": required for a " + kind + " fault"};
}

std::uint32_t seed_of(const json& params)
{
    return params.contains("seed") ? static_cast<std::uint32_t>(require_int(params, "seed", 0, 0xFFFFFFFF)) : 1;
}

models::PhysicalFault physical_fault(FaultKind kind)
{
    switch (kind) {
    case FaultKind::Stall:
        return models::PhysicalFault::Stall;
    case FaultKind::Slip:
        return models::PhysicalFault::Slip;
    case FaultKind::LimitSwitch:
        return models::PhysicalFault::LimitSwitch;
    case FaultKind::SensorFailure:
        return models::PhysicalFault::SensorFailure;
    case FaultKind::ReferenceLost:
        break;
    }
    throw std::logic_error("reference_lost is the device's fault, not a body's");
}

} // namespace

Refused start_device_fault(ControlSurface& surface, models::World* world, const DeviceFault& f, bool* kept,
                           bool* on_body)
{
    *on_body = false;
    if (!physical(f.kind))
        return surface.add_fault(f, kept);
    // A physical fault acts on the body the device names, through the world: the same for every
    // family; the body says whether it can suffer it.
    std::string key;
    if (auto refused = surface.fault_body(f, key))
        return refused;
    if (!world)
        return Refusal{400, "\"kind\": " + std::string(fault_name(f.kind)) + ": this rig has no world for it to act in"};
    models::BodyFault body_fault;
    body_fault.kind = physical_fault(f.kind);
    body_fault.slip_steps = f.slip_counts;
    body_fault.slip_fraction = f.slip_fraction;
    body_fault.switch_side = f.limit_side;
    try {
        world->add_fault(f.id, key, body_fault);
    } catch (const std::invalid_argument& e) {
        return Refusal{400, e.what()};
    }
    surface.faults_changed();
    *on_body = true;
    *kept = true;
    return std::nullopt;
}

void end_device_fault(ControlSurface& surface, models::World* world, std::uint64_t id, bool on_body)
{
    if (!on_body) {
        surface.remove_fault(id);
        return;
    }
    if (world && world->remove_fault(id))
        surface.faults_changed();
}

const std::vector<std::string>& FaultBook::device_kinds()
{
    static const std::vector<std::string> kinds = [] {
        std::vector<std::string> names;
        for (const auto kind : kFaultKinds)
            names.emplace_back(fault_name(kind));
        return names;
    }();
    return kinds;
}

const std::vector<std::string>& FaultBook::link_kinds()
{
    static const std::vector<std::string> kinds{"unplugged",  "drop_bytes", "corrupt_bytes", "latency",
                                                "slicer",     "bandwidth",  "reset",         "slow_close",
                                                "hang_close", "cut_after",  "garbage_close", "overrun",
                                                "baud_mismatch"};
    return kinds;
}

FaultBook::FaultBook(const Clock& clock, std::vector<ControlledDevice>& devices, models::World* world)
    : clock_(clock), devices_(devices), world_(world)
{
}

std::size_t FaultBook::device_index(const json& body) const
{
    if (!body.contains("device"))
        throw BadRequest{400, "\"device\": required (the device's name)"};
    const auto& v = body.at("device");
    if (!v.is_string())
        throw BadRequest{400, "\"device\": expected a device name, got " + dump(v)};
    for (std::size_t i = 0; i < devices_.size(); ++i)
        if (devices_[i].endpoints.name == v.get<std::string>())
            return i;
    std::vector<std::string> names;
    for (const auto& d : devices_)
        names.push_back(d.endpoints.name);
    throw BadRequest{404, "\"device\": no device named " + dump(v) + " (devices: " + joined(names) + ")"};
}

json FaultBook::add(const json& body)
{
    const auto index = device_index(body);
    if (!body.contains("kind") || !body.at("kind").is_string())
        throw BadRequest{400, "\"kind\": required, one of " + joined(device_kinds()) + ", " + joined(link_kinds())
                                  + ", power_cycle"};
    const auto kind = body.at("kind").get<std::string>();
    const bool device_kind = std::count(device_kinds().begin(), device_kinds().end(), kind) > 0;
    const bool link_kind = std::count(link_kinds().begin(), link_kinds().end(), kind) > 0;
    if (!device_kind && !link_kind && kind != "power_cycle")
        throw BadRequest{400, "\"kind\": unknown fault " + dump(body.at("kind")) + " (expected one of "
                                  + joined(device_kinds()) + ", " + joined(link_kinds()) + ", power_cycle)"};
    json params = json::object();
    for (const auto& [key, value] : body.items())
        if (key != "device" && key != "kind" && key != "channel")
            params[key] = value;
    std::optional<std::size_t> channel;
    if (body.contains("channel")) {
        if (!device_kind)
            throw BadRequest{400, "\"channel\": a " + kind + " fault acts on the whole device"};
        channel = static_cast<std::size_t>(require_int(body, "channel", 0, 255));
    }
    auto& dev = devices_[index];
    const auto on_device = std::count_if(active_.begin(), active_.end(),
                                         [&](const auto& a) { return a.second.device == index; });
    if (on_device >= static_cast<std::ptrdiff_t>(kMaxFaultsPerDevice))
        throw BadRequest{409, "device \"" + dev.endpoints.name + "\" has " + std::to_string(kMaxFaultsPerDevice)
                                  + " active faults already: delete some first"};
    const std::uint64_t id = next_id_;
    bool kept = true;
    Where where = link_kind ? Where::Link : Where::Device;
    if (device_kind) {
        if (!dev.surface)
            throw BadRequest{400, "\"kind\": device \"" + dev.endpoints.name + "\" takes no device faults"};
        DeviceFault fault;
        if (auto refused = parse_device_fault(kind, params, fault))
            throw BadRequest{refused->status, refused->message};
        fault.id = id;
        fault.channel = channel;
        bool on_body = false;
        if (auto refused = start_device_fault(*dev.surface, world_, fault, &kept, &on_body))
            throw BadRequest{refused->status, refused->message};
        where = on_body ? Where::Body : Where::Device;
    } else if (link_kind) {
        if (!dev.link)
            throw BadRequest{400, "\"kind\": device \"" + dev.endpoints.name + "\" takes no wire faults"};
        add_link(id, kind, params, *dev.link, index);
    } else {
        only_keys(params, kind, {"keep_saved"});
        const bool keep = !params.contains("keep_saved") || require_bool(params, "keep_saved");
        if (dev.surface)
            dev.surface->power_cycle(PowerCycle{keep, false});
        kept = false;
    }
    ++next_id_;
    json record{{"id", id},
                {"device", dev.endpoints.name},
                {"channel", device_kind ? json(channel.value_or(0)) : json(nullptr)},
                {"kind", kind},
                {"params", params},
                {"active", kept},
                {"since_ms", clock_.seconds(clock_.now()) * 1000.0}};
    if (kept)
        active_.emplace(id, Record{index, where, record});
    return record;
}

/// One cable, one delay: a second such fault would hide the first, and ending either would end
/// both. Likewise one of each kind but dropped and corrupted bytes.
void FaultBook::refuse_second(const std::string& kind, const Link& link, std::size_t device) const
{
    if (kind == "unplugged" && link.unplugged_id() != 0)
        throw BadRequest{409, "the device is unplugged already (fault " + std::to_string(link.unplugged_id()) + ")"};
    if (kind == "latency" && link.latency_id() != 0)
        throw BadRequest{409, "the device has a latency fault already (fault " + std::to_string(link.latency_id())
                                  + "): delete it first"};
    if (kind != "drop_bytes" && kind != "corrupt_bytes")
        for (const auto& [other, r] : active_)
            if (r.device == device && r.where == Where::Link && r.json.at("kind") == kind)
                throw BadRequest{409, "the device has a " + kind + " fault already (fault " + std::to_string(other)
                                          + "): delete it first"};
}

void FaultBook::add_link(std::uint64_t id, const std::string& kind, const json& params, Link& link,
                         std::size_t device)
{
    refuse_second(kind, link, device);
    if (kind == "unplugged") {
        only_keys(params, kind, {});
        link.set_unplugged(id, true);
        return;
    }
    if (kind == "latency") {
        only_keys(params, kind, {"latency_ms", "jitter_ms", "seed"});
        required(params, "latency_ms", kind);
        LatencyFault f;
        f.id = id;
        f.latency = clock_.ticks_from_ms(require_int(params, "latency_ms", 0, 600'000));
        f.jitter = params.contains("jitter_ms") ? clock_.ticks_from_ms(require_int(params, "jitter_ms", 0, 600'000)) : 0;
        f.seed = seed_of(params);
        link.add(f);
        return;
    }
    if (kind == "slicer") {
        only_keys(params, kind, {"slice_bytes", "gap_ms"});
        SliceFault f;
        f.id = id;
        f.slice_bytes = params.contains("slice_bytes")
                            ? static_cast<std::size_t>(require_int(params, "slice_bytes", 1, 65'536))
                            : 1;
        f.gap = params.contains("gap_ms") ? clock_.ticks_from_ms(require_int(params, "gap_ms", 0, 60'000)) : 0;
        link.add(f);
        return;
    }
    if (kind == "bandwidth") {
        only_keys(params, kind, {"bytes_per_s", "direction"});
        required(params, "bytes_per_s", kind);
        BandwidthFault f;
        f.id = id;
        f.bytes_per_s = static_cast<double>(require_int(params, "bytes_per_s", 1, 100'000'000));
        std::tie(f.inbound, f.outbound) = direction_of(params, "both");
        link.add(f);
        return;
    }
    if (kind == "overrun") {
        only_keys(params, kind, {"buffer_bytes", "drain_bytes_per_s"});
        OverrunFault f;
        f.id = id;
        if (params.contains("buffer_bytes"))
            f.buffer_bytes = static_cast<std::size_t>(require_int(params, "buffer_bytes", 1, 65'536));
        if (params.contains("drain_bytes_per_s"))
            f.drain_bytes_per_s = static_cast<double>(require_int(params, "drain_bytes_per_s", 1, 10'000'000));
        link.add(f);
        return;
    }
    if (kind == "baud_mismatch") {
        only_keys(params, kind, {"direction"});
        BaudMismatchFault f;
        f.id = id;
        std::tie(f.inbound, f.outbound) = direction_of(params, "both");
        link.add(f);
        return;
    }
    if (add_close(id, kind, params, link))
        return;
    only_keys(params, kind, {"direction", "probability", "seed"});
    ByteFault f;
    f.id = id;
    f.corrupt = kind == "corrupt_bytes";
    std::tie(f.inbound, f.outbound) = direction_of(params, "both");
    f.probability = params.contains("probability") ? require_number(params, "probability", 0, 1) : 1.0;
    f.seed = seed_of(params);
    link.add(f);
}

/// The faults that end a connection (reset, garbage_close, slow_close, hang_close, cut_after);
/// false for another kind.
bool FaultBook::add_close(std::uint64_t id, const std::string& kind, const json& params, Link& link)
{
    CloseFault close;
    close.id = id;
    if (kind == "reset" || kind == "garbage_close") {
        close.kind = kind == "reset" ? CloseKind::Reset : CloseKind::GarbageClose;
        if (kind == "reset") {
            only_keys(params, kind, {"after_ms"});
        } else {
            only_keys(params, kind, {"after_ms", "bytes", "seed"});
            close.bytes = params.contains("bytes") ? static_cast<std::uint64_t>(require_int(params, "bytes", 1, 65'536)) : 64;
            close.seed = seed_of(params);
        }
        close.delay = params.contains("after_ms") ? clock_.ticks_from_ms(require_int(params, "after_ms", 0, 600'000)) : 0;
        link.add(close);
        return true;
    }
    if (kind == "slow_close") {
        only_keys(params, kind, {"delay_ms"});
        required(params, "delay_ms", kind);
        close.kind = CloseKind::SlowClose;
        close.delay = clock_.ticks_from_ms(require_int(params, "delay_ms", 0, 600'000));
        link.add(close);
        return true;
    }
    if (kind == "hang_close") {
        only_keys(params, kind, {"close_after_ms"});
        required(params, "close_after_ms", kind);
        close.kind = CloseKind::HangClose;
        close.delay = clock_.ticks_from_ms(require_int(params, "close_after_ms", 0, 600'000));
        link.add(close);
        return true;
    }
    if (kind == "cut_after") {
        only_keys(params, kind, {"bytes", "direction"});
        required(params, "bytes", kind);
        close.kind = CloseKind::CutAfter;
        close.bytes = static_cast<std::uint64_t>(require_int(params, "bytes", 0, 1'000'000'000));
        close.inbound = direction_of(params, "out", false).first;
        link.add(close);
        return true;
    }
    return false;
}

bool FaultBook::remove(std::uint64_t id)
{
    const auto it = active_.find(id);
    if (it == active_.end())
        return false;
    auto& dev = devices_[it->second.device];
    switch (it->second.where) {
    case Where::Link:
        dev.link->remove(id);
        break;
    case Where::Device:
    case Where::Body:
        if (dev.surface)
            end_device_fault(*dev.surface, world_, id, it->second.where == Where::Body);
        break;
    }
    active_.erase(it);
    return true;
}

std::vector<std::uint64_t> FaultBook::remove_all(const std::string* device)
{
    std::vector<std::uint64_t> ids;
    for (const auto& [id, r] : active_)
        if (!device || devices_[r.device].endpoints.name == *device)
            ids.push_back(id);
    for (const auto id : ids)
        remove(id);
    return ids;
}

json FaultBook::list(const std::string* device) const
{
    auto out = json::array();
    for (const auto& [id, r] : active_)
        if (!device || devices_[r.device].endpoints.name == *device)
            out.push_back(r.json);
    return out;
}

} // namespace rigsim::control
