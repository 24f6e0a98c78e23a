#pragma once
// The faults injected through the control API (docs/control-api.md "Faults"): ids, the record
// GET /api/faults lists, and where each kind acts: a body of the world (stall, slip,
// limit_switch, sensor_failure: models::World::add_fault on the body the device names, the same
// for every family), the device (ControlSurface::add_fault: reference_lost), the link between
// the device and its clients (Link), or a power cycle.

#include "emulator/daemon/rig.hpp"
#include "models/clock.hpp"
#include "models/world.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace rigsim::control {

/// Starts device fault `f` (parsed: parse_device_fault): a physical one on the body of `world`
/// that `surface` names (ControlSurface::fault_body, then models::World::add_fault, then
/// ControlSurface::faults_changed), the same for every family; reference_lost on the device
/// (ControlSurface::add_fault). `*on_body` says which; `*kept` is false for a one-off fault.
/// A refusal names the field; `world` may be nullptr (physical faults are then refused).
Refused start_device_fault(ControlSurface& surface, models::World* world, const DeviceFault& f, bool* kept,
                           bool* on_body);
/// Ends device fault `id` that start_device_fault started (`on_body` as it said).
void end_device_fault(ControlSurface& surface, models::World* world, std::uint64_t id, bool on_body);

class FaultBook {
public:
    /// Kinds that act inside the device (its ControlSurface), on the wire (the Link), and at once.
    static const std::vector<std::string>& device_kinds();
    static const std::vector<std::string>& link_kinds();
    /// Active faults one device may have (each byte fault filters every byte it carries).
    static constexpr std::size_t kMaxFaultsPerDevice = 64;

    /// `world`: where the physical faults act (nullptr: a rig without bodies; they are refused).
    FaultBook(const Clock& clock, std::vector<ControlledDevice>& devices, models::World* world);

    /// POST /api/faults: validates and starts the fault; returns its record (201). Throws
    /// BadRequest naming the field.
    nlohmann::json add(const nlohmann::json& body);
    /// DELETE /api/faults/{id}; false if no such fault is active.
    bool remove(std::uint64_t id);
    /// Ends every fault (of one device, if given); returns their ids.
    std::vector<std::uint64_t> remove_all(const std::string* device = nullptr);
    /// The active faults (of one device, if given), oldest first.
    nlohmann::json list(const std::string* device = nullptr) const;

private:
    enum class Where { Body, Device, Link };
    struct Record {
        std::size_t device;   ///< index into devices_
        Where where;
        nlohmann::json json;
    };
    std::size_t device_index(const nlohmann::json& body) const;
    /// Starts a link fault from its params; throws BadRequest.
    void add_link(std::uint64_t id, const std::string& kind, const nlohmann::json& params, Link& link,
                  std::size_t device);
    /// 409 for a second fault of `kind` on the device's link (drop and corrupt bytes excepted).
    void refuse_second(const std::string& kind, const Link& link, std::size_t device) const;
    /// add_link() of the kinds that end a connection; false for another kind.
    bool add_close(std::uint64_t id, const std::string& kind, const nlohmann::json& params, Link& link);

    const Clock& clock_;
    std::vector<ControlledDevice>& devices_;
    models::World* world_;
    std::map<std::uint64_t, Record> active_;
    std::uint64_t next_id_ = 1;
};

} // namespace rigsim::control
