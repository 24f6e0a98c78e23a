#include "emulator/apt/polariser_module.hpp"
#include "emulator/apt/wire.hpp"
#include "emulator/core/log_format.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace rigsim::apt {

namespace {

constexpr std::uint32_t kPaddleMovingUp = 0x00000010;
constexpr std::uint32_t kPaddleMovingDown = 0x00000020;
constexpr std::uint32_t kPaddleHoming = 0x00000200;
constexpr std::uint32_t kPaddleHomed = 0x00000400;
constexpr std::uint32_t kPaddleEnabled = 0x80000000;

/// POL_PARAMS at power-up and after RESTOREFACTORYSETTINGS: issue 37's example (p. 408: 50 %,
/// home 0, "usually set to 0", jog steps 25 counts = 3 degrees); no reading of a unit's defaults.
constexpr msg::PolParams kPolFactory{0, 50, 0, 25, 25, 25};

} // namespace

PolariserModule::PolariserModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address,
                                 std::vector<models::Paddle*> paddles, const Clock& clock, spdlog::logger& log,
                                 SaveToEeprom save)
    : Module(unit, bay, address, log, std::move(save)), paddles_(std::move(paddles)), clock_(clock), params_(kPolFactory),
      paddle_enabled_(paddles_.size(), true), homing_(paddles_.size(), false), homed_(paddles_.size(), false),
      counter_offset_(paddles_.size(), 0.0)
{
    for (std::size_t p = 0; p < paddles_.size(); ++p)
        paddles_[p]->set_listener(this, [this, p](Ticks) { arrived(p); });
}

PolariserModule::~PolariserModule()
{
    for (auto* paddle : paddles_)
        paddle->clear_listener(this);   // the world outlives its devices
}

void PolariserModule::handle(const msg::Message& m, Request& r)
{
    visit_as(*this, m, r);
}

bool PolariserModule::takes_channel(std::uint16_t sent) const
{
    // Bits 1, 2, 4: the paddles (an MPC220's two: 1, 2).
    const std::uint16_t all = static_cast<std::uint16_t>((1u << paddles_.size()) - 1);
    return sent != 0 && (sent & ~all) == 0;
}

std::vector<std::size_t> PolariserModule::paddles_of(std::uint16_t mask) const
{
    std::vector<std::size_t> out;
    for (std::size_t p = 0; p < paddles_.size(); ++p)
        if (mask & (1u << p))
            out.push_back(p);
    return out;
}

double PolariserModule::counts_at(std::size_t p) const
{
    return paddles_[p]->angle_at(clock_.now()) * kCountsPerDeg - counter_offset_[p];
}

Ticks PolariserModule::next_change(Ticks now) const
{
    return next_body_event(paddles_, now, !ended_.empty());
}

void PolariserModule::tick(Ticks now)
{
    for (auto* paddle : paddles_)
        paddle->on_event(now);
}

std::vector<std::string> PolariserModule::take_unprompted(std::uint8_t host)
{
    std::vector<std::string> frames;
    for (const auto& e : ended_)
        frames.push_back(encode_header_only(e.id, static_cast<std::uint8_t>(1u << e.paddle), 0, host, address_));
    ended_.clear();
    return frames;
}

void PolariserModule::arrived(std::size_t p)
{
    const bool homing = homing_[p];
    homing_[p] = false;
    if (homing) {
        homed_[p] = true;
        counter_offset_[p] = 0;   // homed: the counter reads the home position's counts
    }
    ended_.push_back({homing ? MGMSG_MOT_MOVE_HOMED : MGMSG_MOT_MOVE_COMPLETED, p});
    publish("paddle", {{"paddle", p + 1}, {"angle_deg", paddles_[p]->angle_at(clock_.now())}});
}

void PolariserModule::power_down(bool restore_positions)
{
    const auto now = clock_.now();
    for (auto* paddle : paddles_)
        restore_positions ? paddle->place(0) : paddle->stop(now);
    ended_.clear();
}

void PolariserModule::move(std::size_t p, double counts, bool homing)
{
    if (!paddle_enabled_[p]) {
        return ignore(fmt::format("{}: {} for paddle {}, which is disabled: ignored", request_->peer,
                                  request_->frame.info->name, p + 1));
    }
    const double deg_per_tick = params_.velocity / 100.0 * kFullSpeedDegPerS / static_cast<double>(clock_.tick_hz());
    homing_[p] = homing;
    paddles_[p]->move_to(clock_.now(), (counts + counter_offset_[p]) / kCountsPerDeg, deg_per_tick);
}

std::uint32_t PolariserModule::status_bits(std::size_t p) const
{
    const auto now = clock_.now();
    std::uint32_t bits = 0;
    const int dir = paddles_[p]->direction_at(now);
    if (dir > 0)
        bits |= kPaddleMovingUp;
    if (dir < 0)
        bits |= kPaddleMovingDown;
    if (homing_[p])
        bits |= kPaddleHoming;
    if (homed_[p])
        bits |= kPaddleHomed;
    if (paddle_enabled_[p])
        bits |= kPaddleEnabled;
    return bits;
}

void PolariserModule::on(const msg::ModSetChanEnableState& m)
{
    // QMI mpc320.py: the mask is the set of enabled paddles, the state 1; 0 with state 1 disables all.
    if (m.enable_state != 1 && m.enable_state != 2)
        return ignore(fmt::format("{}: MOD_SET_CHANENABLESTATE state {} (1 enable, 2 disable): ignored", request_->peer,
                                  m.enable_state));
    const std::uint16_t all = static_cast<std::uint16_t>((1u << paddles_.size()) - 1);
    if ((m.chan_ident & ~all) != 0)
        return ignore(fmt::format("{}: MOD_SET_CHANENABLESTATE for paddles 0x{:02x} (an {} has 0x{:02x}): ignored",
                                  request_->peer, m.chan_ident, unit_.model_name, all));
    const auto now = clock_.now();
    for (std::size_t p = 0; p < paddles_.size(); ++p) {
        const bool on = m.enable_state == 1 && (m.chan_ident & (1u << p)) != 0;
        if (!on && paddles_[p]->moving_at(now))
            paddles_[p]->stop(now);   // a disabled paddle does not move
        paddle_enabled_[p] = on;
    }
}

void PolariserModule::on(const msg::ModReqChanEnableState& m)
{
    if (!takes_channel(m.chan_ident == 0 ? 1 : m.chan_ident))
        return wrong_channel();
    const auto ps = paddles_of(m.chan_ident == 0 ? 1 : m.chan_ident);
    const bool on = std::all_of(ps.begin(), ps.end(), [this](std::size_t p) { return paddle_enabled_[p]; });
    answer(msg::ModGetChanEnableState{m.chan_ident, static_cast<std::uint8_t>(on ? 1 : 0)});
}

void PolariserModule::on(const msg::SetPosCounter& m)
{
    for (const auto p : paddles_of(channel()))
        counter_offset_[p] = paddles_[p]->angle_at(clock_.now()) * kCountsPerDeg - m.params.position;
}

void PolariserModule::on(const msg::ReqPosCounter&)
{
    const auto ps = paddles_of(channel());
    answer(msg::GetPosCounter{{channel(), static_cast<std::int32_t>(std::lround(counts_at(ps.front())))}});
}

void PolariserModule::on(const msg::MoveAbsolute& m)
{
    if (!m.absolute_distance)
        return ignore(fmt::format("{}: MOT_MOVE_ABSOLUTE without a position (a paddle has no MOVEABSPARAMS): ignored",
                                  request_->peer));
    const auto ps = paddles_of(channel());
    if (ps.size() != 1)
        return ignore(fmt::format("{}: MOT_MOVE_ABSOLUTE for paddles 0x{:02x}: one paddle at a time: ignored",
                                  request_->peer, channel()));
    const auto target = *m.absolute_distance + counter_offset_[ps[0]];
    if (target < 0 || target > kMaxDeg * kCountsPerDeg + 0.5)
        return ignore(fmt::format("{}: MOT_MOVE_ABSOLUTE to {} counts, past 0..1370 (0..170 degrees): ignored",
                                  request_->peer, *m.absolute_distance));
    move(ps[0], *m.absolute_distance, false);
}

void PolariserModule::on(const msg::MoveJog& m)
{
    if (m.direction != 1 && m.direction != 2)
        return ignore(fmt::format("{}: MOT_MOVE_JOG direction {} (1 up, 2 down): ignored", request_->peer, m.direction));
    const std::uint16_t steps[] = {params_.jog_step1, params_.jog_step2, params_.jog_step3};
    for (const auto p : paddles_of(channel())) {
        const double step = m.direction == 1 ? steps[p] : -static_cast<double>(steps[p]);
        const double target = std::clamp(counts_at(p) + step + counter_offset_[p], 0.0, kMaxDeg * kCountsPerDeg);
        move(p, target - counter_offset_[p], false);
    }
}

void PolariserModule::on(const msg::MoveHome& m)
{
    for (const auto p : paddles_of(m.chan_ident == 0 ? 1 : m.chan_ident))
        move(p, params_.home_position - counter_offset_[p], true);
}

void PolariserModule::on(const msg::MoveStop& m)
{
    const auto now = clock_.now();
    for (const auto p : paddles_of(m.chan_ident == 0 ? 1 : m.chan_ident)) {
        if (!paddles_[p]->moving_at(now))
            continue;
        paddles_[p]->stop(now);
        homing_[p] = false;
        ended_.push_back({MGMSG_MOT_MOVE_STOPPED, p});
    }
}

void PolariserModule::on(const msg::ReqDcStatusUpdate&)
{
    const auto ps = paddles_of(channel());
    const auto p = ps.front();
    const double deg_per_s = paddles_[p]->moving_at(clock_.now())
                                 ? params_.velocity / 100.0 * kFullSpeedDegPerS * paddles_[p]->direction_at(clock_.now())
                                 : 0.0;
    msg::DcStatus st{channel(), static_cast<std::int32_t>(std::lround(counts_at(p))),
                     static_cast<std::int16_t>(std::lround(deg_per_s * kCountsPerDeg / 100.0)), 0, status_bits(p)};
    answer(msg::GetDcStatusUpdate{st});
}

void PolariserModule::on(const msg::SetEepromParams& m)
{
    save_to_eeprom_(m.msg_id, request_->peer);
}

void PolariserModule::on(const msg::SetPolParams& m)
{
    params_ = m.params;   // the ranges (issue 37 p. 408) were checked before
}

void PolariserModule::on(const msg::ReqPolParams&)
{
    answer(msg::GetPolParams{params_});
}

void PolariserModule::on(const msg::MotSetPzStageParamDefaults&)
{
    params_ = kPolFactory;
}

void PolariserModule::describe(nlohmann::json& out) const
{
    auto paddles = nlohmann::json::array();
    for (std::size_t p = 0; p < paddles_.size(); ++p)
        paddles.push_back({{"paddle", p + 1},
                           {"angle_deg", paddles_[p]->angle_at(clock_.now())},
                           {"position", std::lround(counts_at(p))},
                           {"moving", paddles_[p]->moving_at(clock_.now())},
                           {"enabled", static_cast<bool>(paddle_enabled_[p])},
                           {"status", status_bits(p)}});
    out["paddles"] = std::move(paddles);
    out["velocity_percent"] = params_.velocity;
    out["home_position"] = params_.home_position;
    out["jog_steps"] = {params_.jog_step1, params_.jog_step2, params_.jog_step3};
}

} // namespace rigsim::apt
