#pragma once
// Non-volatile memory of the rig's devices (APT MOT_SET_EEPROMPARAMS, ...), kept in a JSON
// state file so that what a device saved survives a daemon restart (--state-file). Without a
// file, saves last until the daemon exits.

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace rigsim {

class StateStore {
public:
    /// In memory only.
    StateStore() = default;
    /// Backed by `path`: loaded now if it exists (a broken file is an error: throws
    /// std::runtime_error naming it), rewritten atomically on every save.
    explicit StateStore(std::string path);

    /// What device `device` saved under `key`, or null.
    const nlohmann::json* get(const std::string& device, const std::string& key) const;
    /// Save and, with a file, write it (throws std::system_error if it cannot).
    void set(const std::string& device, const std::string& key, nlohmann::json value);
    const nlohmann::json& device_state(const std::string& device) const;

private:
    std::optional<std::string> path_;
    nlohmann::json state_ = nlohmann::json::object();
};

} // namespace rigsim
