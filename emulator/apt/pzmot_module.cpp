#include "emulator/apt/pzmot_module.hpp"
#include "emulator/apt/wire.hpp"
#include "emulator/core/log_format.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>

namespace rigsim::apt {

namespace {

constexpr std::uint32_t kPzMovingForward = 0x00000010;
constexpr std::uint32_t kPzMovingReverse = 0x00000020;
constexpr std::uint32_t kPzJoggingForward = 0x00000040;
constexpr std::uint32_t kPzJoggingReverse = 0x00000080;
constexpr std::uint32_t kPzConnected = 0x00000100;
constexpr std::uint32_t kPzEnabled = 0x80000000;

/// The sub-messages of each model (issue 37 p. 371).
constexpr std::uint16_t kTimSubs[] = {0x05, 0x07, 0x09, 0x11, 0x13};
constexpr std::uint16_t kKimSubs[] = {0x05, 0x07, 0x0B, 0x0F, 0x15, 0x17, 0x19, 0x2B, 0x2D, 0x30, 0x32, 0x34};

/// The channels of ChanEnableMode `mode` (p. 394) as bits, and back (a set no mode names: none).
constexpr std::uint16_t kModeMasks[] = {0x0, 0x1, 0x2, 0x4, 0x8, 0x3, 0xC};

std::uint16_t mode_of_mask(std::uint16_t mask)
{
    for (std::uint16_t mode = 0; mode < std::size(kModeMasks); ++mode)
        if (kModeMasks[mode] == mask)
            return mode;
    return 0;
}

/// The power-up block of sub-message `sub` for the channel of bit `bits` (the examples of issue 37
/// p. 372-401: no public reading of a unit's defaults).
template <class... Blocks> msg::PzmotBlock default_block(std::uint16_t sub, std::uint16_t bits, const std::variant<Blocks...>*)
{
    msg::PzmotBlock out;
    (
        [&] {
            if (Blocks::sub_id != sub)
                return;
            Blocks b{};
            if constexpr (!std::is_same_v<Blocks, msg::PzmotChanEnableMode> && !std::is_same_v<Blocks, msg::PzmotTrigIoConfig>)
                b.chan_ident = bits;
            out = b;
        }(),
        ...);
    return out;
}

/// The blocks kept once for the unit (no channel word).
bool unit_wide(std::uint16_t sub)
{
    return sub == msg::PzmotChanEnableMode::sub_id || sub == msg::PzmotTrigIoConfig::sub_id;
}

} // namespace

PzMotorModule::PzMotorModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address,
                             std::vector<models::InertialDrive*> drives, spdlog::logger& log, SaveToEeprom save)
    : Module(unit, bay, address, log, std::move(save)), drives_(std::move(drives))
{
    for (std::size_t c = 0; c < drives_.size(); ++c) {
        counter_base_[c] = drives_[c]->pulses();   // the counter reads 0 at power-up
        drives_[c]->set_listener(this, [this, c](Ticks) { arrived(c); });
    }
}

PzMotorModule::~PzMotorModule()
{
    for (auto* drive : drives_)
        drive->clear_listener(this);   // the world outlives its devices
}

void PzMotorModule::handle(const msg::Message& m, Request& r)
{
    visit_as(*this, m, r);
}

bool PzMotorModule::kim() const
{
    return unit_.model.name == "KIM101";
}

std::optional<std::size_t> PzMotorModule::channel_of_bit(std::uint16_t bits)
{
    switch (bits) {
    case 0x1:
        return 0;
    case 0x2:
        return 1;
    case 0x4:
        return 2;
    case 0x8:
        return 3;
    default:
        return std::nullopt;
    }
}

std::optional<std::size_t> PzMotorModule::channel_or_ignore(std::uint16_t bits, std::string_view what)
{
    if (const auto c = channel_of_bit(bits))
        return c;
    ignore(fmt::format("{}: {} with {} {}: the channels are bits 0x01, 0x02, 0x04, 0x08 (issue 37 p. 372): ignored",
                       request_->peer, request_->frame.info->name, what, bits));
    return std::nullopt;
}

bool PzMotorModule::takes_sub(std::uint16_t sub, bool set) const
{
    if (set && sub == msg::PzmotHomeParams::sub_id)
        return false;   // "Request/Get" only (p. 383)
    const auto* first = kim() ? std::begin(kKimSubs) : std::begin(kTimSubs);
    const auto* last = kim() ? std::end(kKimSubs) : std::end(kTimSubs);
    return std::find(first, last, sub) != last;
}

msg::PzmotBlock& PzMotorModule::block(std::uint16_t sub, std::size_t c)
{
    const std::pair<std::uint16_t, std::size_t> key{sub, unit_wide(sub) ? 0 : c};
    auto it = blocks_.find(key);
    if (it == blocks_.end())
        it = blocks_
                 .emplace(key, default_block(sub, static_cast<std::uint16_t>(1u << key.second),
                                             static_cast<const msg::PzmotBlock*>(nullptr)))
                 .first;
    return it->second;
}

std::int32_t PzMotorModule::counter(std::size_t c) const
{
    return static_cast<std::int32_t>(drives_[c]->pulses() - counter_base_[c]);
}

std::uint32_t PzMotorModule::status_bits(std::size_t c) const
{
    std::uint32_t bits = kPzConnected;
    const int dir = drives_[c]->direction();
    if (dir != 0 && motion_[c] == Motion::Move)
        bits |= dir > 0 ? kPzMovingForward : kPzMovingReverse;
    if (dir != 0 && motion_[c] == Motion::Jog)
        bits |= dir > 0 ? kPzJoggingForward : kPzJoggingReverse;
    if (enabled_mask_ & (1u << c))
        bits |= kPzEnabled;
    return bits;
}

std::string PzMotorModule::status_update(std::uint8_t host) const
{
    msg::PzmotGetStatusUpdate st;
    const auto put = [&](std::size_t c, std::uint16_t& chan, std::int32_t& position, std::uint32_t& bits) {
        chan = static_cast<std::uint16_t>(1u << c);
        position = counter(c);
        bits = status_bits(c);
    };
    put(0, st.chan_ident1, st.position1, st.status_bits1);
    put(1, st.chan_ident2, st.position2, st.status_bits2);
    put(2, st.chan_ident3, st.position3, st.status_bits3);
    put(3, st.chan_ident4, st.position4, st.status_bits4);
    return msg::encode(st, host, address_);
}

Ticks PzMotorModule::next_change(Ticks now) const
{
    return next_body_event(drives_, now, !ended_.empty());
}

void PzMotorModule::tick(Ticks now)
{
    for (auto* drive : drives_)
        drive->on_event(now);
}

std::vector<std::string> PzMotorModule::take_unprompted(std::uint8_t host)
{
    std::vector<std::string> frames;
    for (const auto c : ended_)
        frames.push_back(msg::encode(msg::PzmotMoveCompleted{static_cast<std::uint16_t>(1u << c), counter(c), 0, 0},
                                     host, address_));
    ended_.clear();
    return frames;
}

void PzMotorModule::arrived(std::size_t c)
{
    motion_[c] = Motion::None;
    ended_.push_back(c);
    publish("pzmot", {{"actuator", c + 1}, {"position", counter(c)}, {"screw_m", drives_[c]->position_m()}});
}

void PzMotorModule::power_down(bool restore_positions)
{
    for (auto* drive : drives_) {
        drive->stop();
        if (restore_positions)
            drive->place(drive->config().start_nm);
    }
    ended_.clear();
}

void PzMotorModule::enable_only(std::uint16_t mask)
{
    for (std::size_t c = 0; c < drives_.size(); ++c)
        if ((mask & (1u << c)) == 0 && drives_[c]->running())
            stop(c);   // a disabled channel does not move
    enabled_mask_ = mask;
}

void PzMotorModule::run(std::size_t c, Motion motion, int direction, std::optional<std::int64_t> pulses,
                        std::int32_t rate, std::int32_t accn)
{
    const auto& drive = std::get<msg::PzmotDriveOpParams>(block(msg::PzmotDriveOpParams::sub_id, c));
    motion_[c] = motion;
    drives_[c]->run(direction, pulses, rate, accn, drive.max_voltage);
}

void PzMotorModule::stop(std::size_t c)
{
    if (!drives_[c]->running())
        return;
    drives_[c]->stop();
    motion_[c] = Motion::None;
    ended_.push_back(c);
}

// ---- Bay family: the enabled channels ----

void PzMotorModule::on(const msg::ModSetChanEnableState& m)
{
    // Issue 37 p. 47: "0x04 channel 3, 0x08 channel 4" for this unit: the bits. The unit moves the
    // channel it has selected (foxtrot TIM101.cpp; infn-epics drvAptPzMot.cpp): state 1 selects it.
    const auto c = channel_or_ignore(m.chan_ident == 0 ? kChan1 : m.chan_ident, "channel");
    if (!c)
        return;
    if (m.enable_state != 1 && m.enable_state != 2)
        return ignore(fmt::format("{}: MOD_SET_CHANENABLESTATE state {} (1 enable, 2 disable): ignored", request_->peer,
                                  m.enable_state));
    const auto bit = static_cast<std::uint16_t>(1u << *c);
    enable_only(m.enable_state == 1 ? bit : static_cast<std::uint16_t>(enabled_mask_ & ~bit));
}

void PzMotorModule::on(const msg::ModReqChanEnableState& m)
{
    const auto c = channel_or_ignore(m.chan_ident == 0 ? kChan1 : m.chan_ident, "channel");
    if (!c)
        return;
    const bool on = (enabled_mask_ & (1u << *c)) != 0;
    const auto chan = static_cast<std::uint8_t>(m.chan_ident == 0 ? kChan1 : m.chan_ident);
    answer(msg::ModGetChanEnableState{chan, static_cast<std::uint8_t>(on ? 1 : 2)});
}

// ---- The PZMOT family ----

void PzMotorModule::on(const msg::PzmotSetParams& m)
{
    const auto sub = msg::sub_id_of(m.block);
    if (!takes_sub(sub, true))
        return ignore(fmt::format("{}: PZMOT_SET_PARAMS sub-message 0x{:02x}: not one a {} sets (issue 37 p. 371): ignored",
                                  request_->peer, sub, unit_.model_name));
    std::size_t c = 0;
    if (!unit_wide(sub)) {
        const auto ch = channel_or_ignore(msg::channel_of(m.block), "ChanIdent");
        if (!ch)
            return;
        c = *ch;
    }
    if (const auto* counts = std::get_if<msg::PzmotPosCounts>(&m.block)) {
        counter_base_[c] = drives_[c]->pulses() - counts->position;   // the counter reads Position from here
        return;
    }
    if (const auto* mode = std::get_if<msg::PzmotChanEnableMode>(&m.block))
        enable_only(kModeMasks[mode->mode]);   // 0..6, checked with the ranges
    block(sub, c) = m.block;
}

void PzMotorModule::on(const msg::PzmotReqParams& m)
{
    const std::uint16_t sub = m.sub_msg_id;
    if (!takes_sub(sub, false))
        return ignore(fmt::format("{}: PZMOT_REQ_PARAMS sub-message 0x{:02x}: not one a {} has (issue 37 p. 371): ignored",
                                  request_->peer, sub, unit_.model_name));
    std::size_t c = 0;
    if (!unit_wide(sub)) {
        const auto ch = channel_or_ignore(m.chan_ident == 0 ? kChan1 : m.chan_ident, "param2 (channel)");
        if (!ch)
            return;
        c = *ch;
    }
    if (sub == msg::PzmotPosCounts::sub_id)
        return answer(msg::PzmotGetParams{msg::PzmotPosCounts{static_cast<std::uint16_t>(1u << c), counter(c), 0}});
    if (sub == msg::PzmotChanEnableMode::sub_id)
        return answer(msg::PzmotGetParams{msg::PzmotChanEnableMode{mode_of_mask(enabled_mask_)}});
    answer(msg::PzmotGetParams{block(sub, c)});
}

void PzMotorModule::on(const msg::PzmotMoveAbsolute& m)
{
    const auto c = channel_or_ignore(m.chan_ident, "ChanIdent");
    if (!c)
        return;
    if ((enabled_mask_ & (1u << *c)) == 0)
        return ignore(fmt::format("{}: PZMOT_MOVE_ABSOLUTE for channel {}, which is not enabled (ChanEnableMode or "
                                  "MOD_SET_CHANENABLESTATE): ignored",
                                  request_->peer, *c + 1));
    const std::int64_t steps = static_cast<std::int64_t>(m.abs_position) - counter(*c);
    const auto& drive = std::get<msg::PzmotDriveOpParams>(block(msg::PzmotDriveOpParams::sub_id, *c));
    if (steps == 0) {
        // Already there (pyLabLib and infn-epics stop a channel so): a move under way ends here.
        drives_[*c]->stop();
        motion_[*c] = Motion::None;
        ended_.push_back(*c);
        return;
    }
    run(*c, Motion::Move, steps > 0 ? 1 : -1, std::llabs(steps), drive.step_rate, drive.step_accn);
}

void PzMotorModule::on(const msg::PzmotMoveJog& m)
{
    const auto c = channel_or_ignore(m.chan_ident, "param1 (channel)");
    if (!c)
        return;
    if (m.jog_dir == 0)   // InstrumentKit stops a jog so ("quite empirical", thorlabsapt.py)
        return stop(*c);
    if (m.jog_dir != 1 && m.jog_dir != 2)
        return ignore(fmt::format("{}: PZMOT_MOVE_JOG direction {} (1 forward, 2 reverse): ignored", request_->peer,
                                  m.jog_dir));
    if ((enabled_mask_ & (1u << *c)) == 0)
        return ignore(fmt::format("{}: PZMOT_MOVE_JOG for channel {}, which is not enabled (ChanEnableMode or "
                                  "MOD_SET_CHANENABLESTATE): ignored",
                                  request_->peer, *c + 1));
    const int dir = m.jog_dir == 1 ? 1 : -1;
    if (kim()) {
        const auto& jog = std::get<msg::PzmotKCubeJogParams>(block(msg::PzmotKCubeJogParams::sub_id, *c));
        const auto size = dir > 0 ? jog.jog_step_size_fwd : jog.jog_step_size_rev;
        run(*c, Motion::Jog, dir, jog.jog_mode == 1 ? std::nullopt : std::optional<std::int64_t>(size), jog.jog_step_rate,
            jog.jog_step_accn);
    } else {
        const auto& jog = std::get<msg::PzmotTimJogParams>(block(msg::PzmotTimJogParams::sub_id, *c));
        run(*c, Motion::Jog, dir, jog.jog_mode == 1 ? std::nullopt : std::optional<std::int64_t>(jog.jog_step_size),
            jog.jog_step_rate, jog.jog_step_accn);
    }
}

void PzMotorModule::on(const msg::PzmotReqStatusUpdate&)
{
    request_->reply += status_update(request_->host);   // the four channels, whatever param1 says
}

void PzMotorModule::on(const msg::MoveStop& m)
{
    const auto c = channel_or_ignore(m.chan_ident == 0 ? kChan1 : m.chan_ident, "param1 (channel)");
    if (c)
        stop(*c);
}

void PzMotorModule::on(const msg::SetEepromParams& m)
{
    save_to_eeprom_(m.msg_id, request_->peer);   // logged: no PZMOT block is one it saves (saves())
}

void PzMotorModule::on(const msg::Untyped& m)
{
    if (m.id == MGMSG_PZMOT_SET_PARAMS && m.has_data && m.data.size() >= 2)
        return ignore(fmt::format("{}: PZMOT_SET_PARAMS sub-message 0x{:02x} with {} data byte(s): no such block, or "
                                  "short of its fields (issue 37 p. 371-401): ignored",
                                  request_->peer, get_u16(m.data, 0), m.data.size()));
    ignore(fmt::format("{}: {} in a form the {} does not read ({} data byte(s)): ignored", request_->peer,
                       request_->frame.info->name, unit_.model_name, m.data.size()));
}

void PzMotorModule::describe(nlohmann::json& out) const
{
    auto channels = nlohmann::json::array();
    for (std::size_t c = 0; c < drives_.size(); ++c)
        channels.push_back({{"channel", c + 1},
                            {"position", counter(c)},
                            {"screw_m", drives_[c]->position_m()},
                            {"moving", drives_[c]->running()},
                            {"enabled", (enabled_mask_ & (1u << c)) != 0},
                            {"status", status_bits(c)}});
    out["actuators"] = std::move(channels);
    out["enable_mode"] = mode_of_mask(enabled_mask_);
}

} // namespace rigsim::apt
