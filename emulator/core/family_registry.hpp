#pragma once
// The protocol families a rig may name ("mcs", "apt"), as core sees them: a name, the loader
// of a device's section and the factory of its Device. Core knows no family; the daemon layer
// (emulator/daemon/rig_families.cpp) registers them.

#include "emulator/core/rig_config.hpp"

#include <nlohmann/json_fwd.hpp>

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace spdlog {
class logger;
}

namespace rigsim {

namespace models {
class World;
}
class ConfigReader;
class Device;
class StateStore;
class EventBus;

/// What a family's factory may hand its device: the rig's world, the device's logger, the
/// non-volatile store and the control API's event stream.
struct DeviceContext {
    models::World& world;
    std::shared_ptr<spdlog::logger> log;
    StateStore& store;
    EventBus* events = nullptr;
};

/// One protocol family.
struct Family {
    std::string name;          ///< "protocol" value and section key: "mcs"
    std::string device_noun;   ///< for messages: "an MCS device"
    /// Validates the family's keys of the device object `device` at `pointer` into
    /// `config.section` (and the family's defaults of generic fields, such as the model);
    /// throws ConfigError through `reader`.
    std::function<void(const ConfigReader& reader, const nlohmann::json& device, const std::string& pointer,
                       DeviceConfig& config)>
        load;
    /// The device of a loaded config.
    std::function<std::unique_ptr<Device>(const DeviceConfig& config, const DeviceContext& context)> make;
    /// Checks across devices once every device of `rig` is loaded (one device naming
    /// another); throws ConfigError through `reader`. Empty: none.
    std::function<void(const ConfigReader& reader, const RigConfig& rig)> validate_rig = nullptr;
};

/// The families of a rig, in registration order (the order messages list them in).
class FamilyRegistry {
public:
    /// Add a family; throws std::invalid_argument if its name is taken.
    void add(Family family);
    /// The family with this name, or nullptr.
    const Family* find(std::string_view name) const;
    const std::vector<Family>& all() const { return families_; }
    /// The names as a message lists them: "\"mcs\" or \"apt\"".
    std::string quoted_names() const;

private:
    std::vector<Family> families_;
};

} // namespace rigsim
