// AptDevice's non-volatile memory (docs/protocol/apt.md, "EEPROM"): the last accepted SET of
// each block a bay saves, MOT_SET_EEPROMPARAMS (PZ_, ..._SET_EEPROMPARAMS) writing it to the
// state store, and its replay at power-up.

#include "emulator/apt/apt_device.hpp"
#include "emulator/apt/eeprom_entries.hpp"
#include "emulator/apt/messages.hpp"
#include "emulator/apt/wire_decode.hpp"
#include "emulator/core/config_reader.hpp"
#include "emulator/core/log_format.hpp"
#include "emulator/core/rig_config.hpp"
#include "emulator/core/state_store.hpp"

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <optional>
#include <string>

namespace rigsim::apt {

void AptDevice::save_to_eeprom(std::size_t bay, std::uint16_t id, std::string_view peer)
{
    const char* const name = eeprom_message(model_.kind);
    if (!modules_[bay]->saves(id)) {
        log_->warn("{}: {} for 0x{:04x} ({}): not a parameter SET it saves, nothing saved", peer, name, id,
                   message_name(id));
        return;
    }
    const auto it = last_set_.find({bay, id});
    if (it == last_set_.end()) {
        log_->warn("{}: {} for 0x{:04x}: no such parameters were set, nothing saved", peer, name, id);
        return;
    }
    if (!store_) {
        log_->info("{}: {} for 0x{:04x}: kept until the daemon exits (no --state-file)", peer, name, id);
        return;
    }
    store_->set(config_.name, eeprom_key(bay, id), to_hex(it->second));
    log_->info("{}: {} for 0x{:04x}: saved", peer, name, id);
}

void AptDevice::remember(std::size_t bay, const msg::Message& m)
{
    // Most messages are no SET the bay saves (a request): known from the id alone.
    if (!modules_[bay]->saves(msg::message_id(m)))
        return;
    if (auto data = modules_[bay]->saved_data(m))
        last_set_.insert_or_assign({bay, msg::message_id(m)}, std::move(*data));
}

std::optional<std::string> AptDevice::restore_entry(const std::string& key, const std::string& hex, const char* from)
{
    // What this device's non-volatile memory can hold: a parameter SET that the bay's
    // EEPROMPARAMS saves, of one of its bays, as long as the table says, for the bay's channel,
    // and accepted by the bay as if a client had sent it. Returns why an entry is none of that.
    const auto parsed = parse_eeprom_key(key);
    if (!parsed)
        return "the key is not bay<N>/0x<4 lower-case hex digits>";
    const auto [bay, id] = *parsed;
    if (bay >= modules_.size())
        return "no bay " + std::to_string(bay) + " (the " + config_.model
               + (modules_.size() == 1 ? " has bay 0 only)" : " has bays 0 to " + std::to_string(modules_.size() - 1) + ")");
    if (!modules_[bay]->saves(id))
        return message_name(id) + " is not a parameter SET that " + eeprom_message(model_.kind) + " saves";
    std::string data;
    std::string why;
    if (!from_hex(hex, data, why))
        return why;
    const auto* info = find_message(id);
    // A header-only SET is stored as its param1 and param2 (SavedSets).
    const auto length = info->header_only() ? std::size_t{2} : static_cast<std::size_t>(info->data_length);
    if (data.size() != length)
        return std::to_string(data.size()) + " data bytes, " + std::string(info->name) + " has " + std::to_string(length);
    const Frame f = saved_frame(*info, address_of(bay), data);
    const auto m = msg::decode(f);
    // The stored form differs from the data only in a channel other than 1.
    if (const auto stored = modules_[bay]->saved_data(m); stored && *stored != data) {
        // TSTACTUATORTYPE's param1 is the actuator, not a channel: only its param2 can differ.
        if (id == MGMSG_MOT_SET_TSTACTUATORTYPE)
            return "param2 " + std::to_string(f.param2) + "; MGMSG_MOT_SET_TSTACTUATORTYPE's param2 is 0";
        return "channel " + std::to_string(f.has_data ? get_u16(data, 0) : f.param1) + " in the data; bay "
               + std::to_string(bay) + " is channel 1";
    }
    last_set_.erase({bay, id});
    std::string ignored;
    Request r{f, from, ignored, host_};
    handle_bay(bay, m, r);
    const auto accepted = last_set_.find({bay, id});
    if (accepted == last_set_.end() || accepted->second != data)
        return "the bay ignores this " + std::string(info->name) + " (its warning says why)";
    log_->info("restored {} of bay {} from the {}", info->name, bay, from);
    return std::nullopt;
}

void AptDevice::restore_from_eeprom(bool first)
{
    // Keys sort by message ID, but a mode may need a setting of a higher ID: a closed loop
    // (PZ_SET_POSCONTROLMODE 0x0640) its feedback input (TPZ_IOSETTINGS 0x07D4, p. 115; D-19).
    // Mode SETs go last.
    const auto is_mode = [](const std::string& key) {
        const auto parsed = parse_eeprom_key(key);
        return parsed && parsed->second == msg::PzSetPosControlMode::id;
    };
    // The unit's own memory as the rig gives it (a learnt rig's power-up parameters), then what
    // clients saved into the state file over it.
    for (const bool modes : {false, true})
        for (const auto& [key, hex] : config_of(config_).eeprom)
            if (is_mode(key) == modes)
                if (const auto why = restore_entry(key, hex, "rig")) {
                    const auto where = config_.source + ": " + pointer_to(config_.pointer + "/apt/eeprom", key);
                    if (first)
                        throw ConfigError(where + ": " + *why);
                    // A power cycle: the rig was taken at start, and a client changed what this
                    // entry needs (a gauge's routing): the unit comes back without it.
                    log_->warn("{}: not restored at this power cycle: {}", where, *why);
                }
    if (!store_)
        return;
    // A copy: reject() drops the entry from the store.
    const nlohmann::json entries = store_->device_state(config_.name);
    for (const bool modes : {false, true})
        for (const auto& [key, value] : entries.items())
            if (is_mode(key) == modes) {
                const auto why = value.is_string()
                                     ? restore_entry(key, value.get<std::string>(), "state file")
                                     : std::optional<std::string>(std::string("expected a string of hex digits, got ")
                                                                  + value.type_name());
                if (why)
                    store_->reject(config_.name, key, *why);
            }
}

} // namespace rigsim::apt
