#include "emulator/core/control_surface.hpp"

#include <nlohmann/json.hpp>

#include <limits>
#include <string>
#include <vector>

namespace rigsim {

namespace {

/// The parameters a fault kind takes, as the API names them.
std::vector<std::string_view> parameters_of(FaultKind kind)
{
    switch (kind) {
    case FaultKind::Slip:
        return {"counts", "fraction"};
    case FaultKind::LimitSwitch:
        return {"side"};
    case FaultKind::Stall:
    case FaultKind::SensorFailure:
    case FaultKind::ReferenceLost:
        return {};
    }
    return {};
}

Refused bad(std::string message) { return Refusal{400, std::move(message)}; }

/// The number at `key` if the params have one, in [0, max] (`range` says so), or a 400 naming it.
Refused number_at(const nlohmann::json& params, const char* key, double max, const char* range,
                  std::optional<double>& out)
{
    const auto it = params.find(key);
    if (it == params.end())
        return std::nullopt;
    if (!it->is_number() || !(it->get<double>() >= 0) || !(it->get<double>() <= max))
        return bad("\"" + std::string(key) + "\": expected " + range + ", got " + it->dump());
    out = it->get<double>();
    return std::nullopt;
}

} // namespace

std::string_view fault_name(FaultKind kind)
{
    switch (kind) {
    case FaultKind::Stall:
        return "stall";
    case FaultKind::Slip:
        return "slip";
    case FaultKind::SensorFailure:
        return "sensor_failure";
    case FaultKind::ReferenceLost:
        return "reference_lost";
    case FaultKind::LimitSwitch:
        return "limit_switch";
    }
    return "stall";
}

Refused parse_device_fault(std::string_view kind, const nlohmann::json& params, DeviceFault& out)
{
    const FaultKind* found = nullptr;
    std::string names;
    for (const auto& k : kFaultKinds) {
        if (fault_name(k) == kind)
            found = &k;
        names += std::string(names.empty() ? "" : ", ") + std::string(fault_name(k));
    }
    if (!found)
        return bad("\"kind\": \"" + std::string(kind) + "\" is no device fault (" + names + ")");
    out.kind = *found;
    const auto takes = parameters_of(out.kind);
    if (!params.is_object())
        return bad("the fault's parameters must be an object");
    for (const auto& item : params.items()) {
        bool known = false;
        std::string list;
        for (const auto name : takes) {
            known = known || item.key() == name;
            list += std::string(list.empty() ? "" : ", ") + std::string(name);
        }
        if (!known)
            return bad("\"" + item.key() + "\": not a parameter of a " + std::string(kind) + " fault"
                       + (list.empty() ? " (it takes none)" : " (it takes " + list + ")"));
    }
    if (out.kind == FaultKind::Slip) {
        if (auto r = number_at(params, "counts", std::numeric_limits<double>::max(), "a number >= 0", out.slip_counts))
            return r;
        if (auto r = number_at(params, "fraction", 1, "a number from 0 to 1", out.slip_fraction))
            return r;
    }
    if (out.kind == FaultKind::LimitSwitch) {
        const auto side = params.find("side");
        if (side == params.end() || !side->is_string() || (*side != "forward" && *side != "reverse"))
            return bad("\"side\": \"forward\" or \"reverse\" is required"
                       + (side == params.end() ? std::string() : ", got " + side->dump()));
        out.limit_side = *side == "forward" ? 1 : -1;
    }
    return std::nullopt;
}

} // namespace rigsim
