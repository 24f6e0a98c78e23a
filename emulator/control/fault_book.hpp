#pragma once
// The faults injected through the control API (docs/control-api.md "Faults"): ids, the record
// GET /api/faults lists, and where each kind acts: the device (ControlSurface::add_fault), the
// link between the device and its clients (Link), or a power cycle.

#include "emulator/daemon/rig.hpp"
#include "models/clock.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace rigsim::control {

class FaultBook {
public:
    /// Kinds that act inside the device (its ControlSurface), on the wire (the Link), and at once.
    static const std::vector<std::string>& device_kinds();
    static const std::vector<std::string>& link_kinds();
    /// Active faults one device may have (each byte fault filters every byte it carries).
    static constexpr std::size_t kMaxFaultsPerDevice = 64;

    FaultBook(const Clock& clock, std::vector<ControlledDevice>& devices);

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
    struct Record {
        std::size_t device;   ///< index into devices_
        bool link;
        nlohmann::json json;
    };
    std::size_t device_index(const nlohmann::json& body) const;
    /// Starts a link fault from its params; throws BadRequest.
    void add_link(std::uint64_t id, const std::string& kind, const nlohmann::json& params, Link& link);

    const Clock& clock_;
    std::vector<ControlledDevice>& devices_;
    std::map<std::uint64_t, Record> active_;
    std::uint64_t next_id_ = 1;
};

} // namespace rigsim::control
