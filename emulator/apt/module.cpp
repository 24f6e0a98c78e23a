#include "emulator/apt/module.hpp"
#include "emulator/core/log_format.hpp"

#include "emulator/apt/set_ranges.hpp"


#include <cassert>

namespace rigsim::apt {

namespace {

/// The only channel of a module: P_MOD_CHAN1.

template <std::size_t N> std::array<char, N> padded(std::string_view s)
{
    std::array<char, N> a{};
    s.substr(0, N).copy(a.data(), N);
    return a;
}

/// Channel addressing: header-only messages carry it in param1, others as the first word.
std::uint16_t sent_channel(const Frame& f)
{
    return f.has_data ? get_u16(f.data, 0) : f.param1;
}

} // namespace

msg::HwGetInfo hw_get_info(const UnitIdentity& unit, std::optional<std::size_t> bay)
{
    // p. 21. In a rack, the motherboard (type 45) reports its bays; each bay's card (type 44
    // for a brushless card) reports one channel and a serial with the card prefix.
    const auto& model = unit.model;
    const bool card = model.rack && bay;
    msg::HwGetInfo info;
    info.serial_number =
        card ? model.bay_serial_prefix * 1'000'000 + (unit.serial % 1'000'000) * 10 % 1'000'000
                   + static_cast<std::uint32_t>(*bay)
             : unit.serial;
    info.model_number = padded<8>(card && !model.bay_model_name.empty() ? std::string(model.bay_model_name)
                                  : model.reported_name.empty()        ? unit.model_name
                                                                       : std::string(model.reported_name));
    info.type = card ? model.bay_hw_type : model.hw_type;
    for (std::size_t i = 0; i < info.firmware_version.size(); ++i)   // minor, interim, major, 0 (p. 21)
        info.firmware_version[i] = static_cast<char>((model.firmware_version >> (8 * i)) & 0xFF);
    info.notes = padded<64>(model.notes);
    info.nchs = static_cast<std::uint16_t>(model.rack && !bay ? unit.built_in_bays : 1);
    if (model.later_info_fields) {
        // The later issue's layout of the manual's 64 bytes of notes (data 18..81): notes
        // char[48], 12 bytes whose last word is the stage type (data 76), the hardware version
        // (78) and the modification state (80) (yaq-project/thorlabs-apt-protocol parsing.py,
        // pyLabLib kinesis.py get_device_info). Hardware version 1 (3 for the units that report
        // it, catalogue.cpp), state 0: the values the manual's own example (p. 22) carries there.
        constexpr std::size_t kNotesAt = 18;
        const auto put = [&info](std::size_t data_offset, std::uint16_t v) {
            info.notes[data_offset - kNotesAt] = static_cast<char>(v & 0xff);
            info.notes[data_offset - kNotesAt + 1] = static_cast<char>(v >> 8);
        };
        put(76, card ? std::uint16_t{0} : unit.stage_type);
        put(78, model.hardware_version);
        put(80, 0);
    }
    return info;
}

Module::Module(const UnitIdentity& unit, std::size_t bay, std::uint8_t address, spdlog::logger& log,
               SaveToEeprom save)
    : unit_(unit), bay_(bay), address_(address), log_(log), save_to_eeprom_(std::move(save))
{
}

Refused Module::patch(const nlohmann::json&)
{
    return Refusal{400, "the channels of a " + unit_.model_name + " take no PATCH keys"};
}

Refused Module::trace(Ticks, std::size_t, nlohmann::json&) const
{
    return Refusal{404, "no trace for this channel"};
}

void Module::ignore(const std::string& text)
{
    assert(request_ != nullptr && "a module answers or ignores only while it handles a message");
    request_->ignored = true;
    const auto prefix = std::string(request_->peer) + ": ";
    request_->why = text.compare(0, prefix.size(), prefix) == 0 ? text.substr(prefix.size()) : text;
    log_.warn("{}", text);
}

void Module::not_mine()
{
    ignore(fmt::format("{}: {} is not a message a {} acts on: ignored", request_->peer, request_->frame.info->name,
                       unit_.model_name));
}

bool Module::taken()
{
    const auto& model = unit_.model;
    const auto id = request_->frame.id;
    if (model.takes.empty() || model.takes.contains(id) || (later_generation() && model.later_takes.contains(id)))
        return true;
    not_mine();
    return false;
}

std::size_t Module::fields_read(std::uint16_t id) const
{
    const auto* info = find_message(id);
    return info ? info->min_data_length() : 0;
}

bool Module::long_enough()
{
    const Frame& f = request_->frame;
    if (!f.has_data || f.data.size() >= fields_read(f.id))
        return true;
    // A later issue's message on a unit of the manual's generation is one it does not know,
    // whatever its length (KCubeParams::takes says the same of a whole one).
    if (f.info->later_issue && !later_generation()) {
        ignore(fmt::format("{}: {} is a message of later protocol issues: a {} of the issue-3 generation (the "
                           "2012 manual) does not know it: ignored",
                           request_->peer, f.info->name, unit_.model_name));
        return false;
    }
    ignore(fmt::format("{}: {} with {} data byte(s), short of the {} a {} reads: ignored", request_->peer,
                       f.info->name, f.data.size(), fields_read(f.id), unit_.model_name));
    return false;
}

std::uint16_t Module::channel() const
{
    const auto sent = sent_channel(request_->frame);
    // The manual says the channel must be 1, but T-Cube and K-Cube firmware takes channel 0
    // as its one channel too (public drivers send 0 and work); rack bays keep the manual's rule.
    return !unit_.model.rack && sent == 0 ? kChan1 : sent;
}

void Module::wrong_channel()
{
    ignore(fmt::format("{}: {} for channel {}: a module has only channel 1, ignored", request_->peer,
                       request_->frame.info->name, sent_channel(request_->frame)));
}

bool Module::channel_ok()
{
    if (takes_channel(channel()))
        return true;
    wrong_channel();
    return false;
}

bool Module::in_range()
{
    // A later issue's message on a unit of the manual's generation: the handler ignores it as a
    // message the unit does not know, whatever its values.
    if (request_->frame.info->later_issue && !later_generation())
        return true;
    const auto bad = out_of_range(*message_, unit_.model.mmi_wheel);
    if (bad)
        ignore(fmt::format("{}: {} with {}: ignored", request_->peer, request_->frame.info->name, *bad));
    return !bad;
}

// ---- Bay family ----

void Module::on(const msg::ModSetChanEnableState& m)
{
    if (channel() == kChan1 && (m.enable_state == 1 || m.enable_state == 2))
        return set_enabled(m.enable_state == 1);
    wrong_channel();
}

void Module::on(const msg::ModReqChanEnableState&)
{
    if (!channel_ok())
        return;
    answer(msg::ModGetChanEnableState{kChan1, static_cast<std::uint8_t>(enabled() ? 1 : 2)});
}

void Module::on(const msg::HwReqInfo&)
{
    answer(hw_get_info(unit_, unit_.model.rack ? std::optional<std::size_t>(bay_) : std::nullopt));
}

void Module::on(const msg::HubReqBayUsed&)
{
    if (unit_.model.rack) {   // a hub question for a rack bay
        if (channel_ok())
            not_mine();
        return;
    }
    answer(msg::HubGetBayUsed{0xFF});   // p. 24: -0x01 (0xFF) means a standalone T-/K-Cube, off any hub
}

} // namespace rigsim::apt
