#include "emulator/core/state_store.hpp"

#include "emulator/core/rig.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rigsim {

StateStore::StateStore(std::string path) : path_(std::move(path))
{
    std::ifstream in(*path_);
    if (!in)
        return;   // no state yet: the first save creates the file
    std::stringstream text;
    text << in.rdbuf();
    try {
        state_ = nlohmann::json::parse(text.str());
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(*path_ + ": not a rigsim state file: " + e.what());
    }
    if (!state_.is_object())
        throw std::runtime_error(*path_ + ": not a rigsim state file: expected an object");
}

const nlohmann::json* StateStore::get(const std::string& device, const std::string& key) const
{
    const auto d = state_.find(device);
    if (d == state_.end() || !d->is_object())
        return nullptr;
    const auto k = d->find(key);
    return k == d->end() ? nullptr : &*k;
}

const nlohmann::json& StateStore::device_state(const std::string& device) const
{
    static const nlohmann::json kEmpty = nlohmann::json::object();
    const auto d = state_.find(device);
    return d == state_.end() || !d->is_object() ? kEmpty : *d;
}

void StateStore::set(const std::string& device, const std::string& key, nlohmann::json value)
{
    state_[device][key] = std::move(value);
    if (path_)
        write_file_atomically(*path_, state_.dump(2) + "\n");
}

} // namespace rigsim
