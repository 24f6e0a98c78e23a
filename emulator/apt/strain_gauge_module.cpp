#include "emulator/apt/strain_gauge_module.hpp"

#include "models/piezo_actuator.hpp"

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

namespace rigsim::apt {

WiredStrainGauge* find_mounted_gauge(const models::World& world, const models::PiezoActuator& actuator)
{
    for (const auto& key : world.keys())
        if (auto* gauge = world.find_as<WiredStrainGauge>(key); gauge && gauge->actuator() == &actuator)
            return gauge;
    return nullptr;
}

std::function<std::optional<double>(Ticks, std::uint16_t)> gauge_feedback(const models::World& world,
                                                                          const models::PiezoActuator& actuator)
{
    // Looked up once: a body stays in its world for the world's life.
    const WiredStrainGauge* gauge = find_mounted_gauge(world, actuator);
    if (!gauge)
        return [](Ticks, std::uint16_t) -> std::optional<double> { return std::nullopt; };
    return [gauge](Ticks now, std::uint16_t input) -> std::optional<double> {
        if (!gauge->reaches(input))
            return std::nullopt;
        return gauge->reading_um(now);
    };
}

StrainGaugeModule::StrainGaugeModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address,
                                     WiredStrainGauge* gauge, const Clock& clock, const StrainGaugeConfig& config,
                                     spdlog::logger& log, SaveToEeprom save)
    : Module(unit, bay, address, log, std::move(save)), gauge_(gauge), clock_(clock),
      stiffness_n_per_um_(config.stiffness_n_per_um), zero_time_ms_(config.zero_time_ms),
      hub_output_(config.route == GaugeRoute::HubB ? 2 : 1)
{
    // The rig's route is the power-up HubAnalogueOutput of a reader on the hub (docs/config.md).
    if (gauge_)
        gauge_->set_hub_output(hub_output_);
}

void StrainGaugeModule::handle(const msg::Message& m, Request& r)
{
    visit_as(*this, m, r);
}

double StrainGaugeModule::travel_um() const
{
    return linked() ? gauge_->actuator()->config().travel_um : 0.0;
}

std::int16_t StrainGaugeModule::code_of(double um, std::uint16_t mode) const
{
    if (!linked())
        return 0;
    // D-15: +-32767 is +-100 % of the mode's full scale (p. 129): the travel (MAXTRAVEL) in
    // position mode; +-10 V in voltage mode, where the reader's output is 10 V at full travel;
    // +-ForceCalib x 0.001 N in force mode, the force being the rig's stiffness x extension.
    double frac = um / travel_um();
    if (mode == 3)
        frac = um * stiffness_n_per_um_ / (force_calib_ * 0.001);
    return static_cast<std::int16_t>(std::clamp(std::lround(frac * msg::kPzFullScale), -32767L, 32767L));
}

std::int16_t StrainGaugeModule::reading_code(Ticks now) const
{
    return linked() ? code_of(gauge_->reading_um(now), display_mode_) : 0;
}

std::uint32_t StrainGaugeModule::status_bits() const
{
    std::uint32_t bits = linked() ? msg::kPzConnected : 0;
    if (zeroed_)
        bits |= msg::kPzZeroed;
    if (zero_end_ != kNever)
        bits |= msg::kPzZeroing;
    return bits;
}

std::string StrainGaugeModule::status_update(std::uint8_t host) const
{
    // The reader drives no output (OPVoltage 0); Position is the reading on the position scale,
    // 0..32767 (p. 103; below the zero reads 0, TSG_READING keeps the sign).
    const Ticks now = clock_.now();
    const std::int16_t position = linked() ? std::max<std::int16_t>(0, code_of(gauge_->reading_um(now), 1)) : 0;
    return msg::encode(msg::PzGetPzStatusUpdate{kChan1, 0, position, status_bits()}, host, address_);
}

void StrainGaugeModule::power_down(bool)
{
    if (gauge_)
        gauge_->clear_zero();
}

Ticks StrainGaugeModule::next_change(Ticks now) const
{
    return zero_end_ == kNever ? kNever : std::max(zero_end_, now + 1);
}

void StrainGaugeModule::tick(Ticks now)
{
    if (zero_end_ == kNever || now < zero_end_)
        return;
    // p. 117, D-13: the position read at the end of zeroing is the new zero reference.
    if (linked())
        gauge_->zero(now);
    zeroed_ = true;
    zero_end_ = kNever;
}

void StrainGaugeModule::describe(nlohmann::json& out) const
{
    const Ticks now = clock_.now();
    static constexpr const char* kUnits[] = {"um", "V", "N"};
    const std::int16_t code = reading_code(now);
    const double um = linked() ? gauge_->reading_um(now) : 0.0;
    // The reading as the display mode shows it (D-15): µm from the zero, the ±10 V output, or
    // the force through the rig's stiffness.
    const double value = display_mode_ == 2 ? code / msg::kPzFullScale * 10.0 : display_mode_ == 3 ? um * stiffness_n_per_um_ : um;
    out["display_mode"] = display_mode_;
    out["reading_code"] = code;
    out["reading"] = {{"value", value}, {"unit", kUnits[std::clamp<int>(display_mode_, 1, 3) - 1]}};
    out["reading_um"] = um;
    // The world: where the actuator the gauge is mounted on physically is.
    out["position_um"] = linked() ? nlohmann::json(gauge_->actuator()->extension_um()) : nlohmann::json(nullptr);
    out["mounted_on"] = linked() ? nlohmann::json(gauge_->config().actuator_key) : nlohmann::json(nullptr);
    out["zeroed"] = zeroed_;
    out["zeroing"] = zero_end_ != kNever;
    out["noise_um"] = gauge_ ? gauge_->noise_um() : 0.0;
    out["status"] = status_bits();
}

Refused StrainGaugeModule::patch(const nlohmann::json& body)
{
    for (const auto& [key, value] : body.items()) {
        if (key != "noise_um")
            return Refusal{400, "unknown key \"" + key + "\" for a strain gauge channel (noise_um)"};
        if (!value.is_number() || !std::isfinite(value.get<double>()) || value.get<double>() < 0)
            return Refusal{400, "\"noise_um\" is a number >= 0 (the sigma of one sample, um), got " + value.dump()};
        if (!gauge_)
            return Refusal{400, "\"noise_um\": the " + unit_.model_name + " has no gauge fitted (mounted_on \"\")"};
    }
    if (const auto it = body.find("noise_um"); it != body.end())
        gauge_->set_noise_um(it->get<double>());
    return std::nullopt;
}

// ---- StrainGauge family (p. 127-129) ----

void StrainGaugeModule::on(const msg::SetTsgIoSettings& m)
{
    hub_output_ = m.params.hub_analogue_output;
    if (gauge_)
        gauge_->set_hub_output(hub_output_);   // p. 127: where the reading goes to the driver
    display_mode_ = m.params.display_mode;
    force_calib_ = m.params.force_calib;
}

void StrainGaugeModule::on(const msg::ReqTsgIoSettings&)
{
    answer(msg::GetTsgIoSettings{{kChan1, hub_output_, display_mode_, force_calib_, 0, 0, 0}});
}

void StrainGaugeModule::on(const msg::TsgReqReading&)
{
    const Ticks now = clock_.now();
    // D-16: Smoothed is the mean of the last 8 samples, on the Reading's scale (a negative one
    // as its two's complement: the field is a word).
    const std::int16_t smoothed = linked() ? code_of(gauge_->smoothed_um(now), display_mode_) : 0;
    answer(msg::TsgGetReading{kChan1, reading_code(now), static_cast<std::uint16_t>(smoothed)});
}

// ---- Piezo family messages of the TSG001 (p. 134) ----

void StrainGaugeModule::on(const msg::PzAckPzStatusUpdate&)
{
    // The unit shell takes the model's server-alive acknowledgement before any module.
}

void StrainGaugeModule::on(const msg::PzSetEepromParams& m)
{
    save_to_eeprom_(m.msg_id, request_->peer);
}

void StrainGaugeModule::on(const msg::SetTpzDispSettings& m)
{
    disp_intensity_ = m.params.disp_intensity;
}

void StrainGaugeModule::on(const msg::ReqTpzDispSettings&)
{
    answer(msg::GetTpzDispSettings{{disp_intensity_}});
}

void StrainGaugeModule::on(const msg::PzSetZero&)
{
    if (!linked())
        return ignore(fmt::format("{}: PZ_SET_ZERO: the {} has no strain gauge fitted: ignored", request_->peer,
                                  unit_.model_name));
    // p. 117, D-13: "zeroing" for zero_time_ms, then the reading there is the zero.
    zeroed_ = false;
    zero_end_ = clock_.now() + clock_.ticks_from_ms(zero_time_ms_);
}

void StrainGaugeModule::on(const msg::PzReqMaxTravel&)
{
    // p. 118: the travel of the actuator the gauge is mounted on, in 100 nm steps (0 unfitted).
    answer(msg::PzGetMaxTravel{kChan1, static_cast<std::uint16_t>(std::lround(travel_um() * 10))});
}

// ---- The KSG101's own messages (later protocol issues; docs/protocol/apt.md "K-Cube units") ----

bool StrainGaugeModule::saves(std::uint16_t id) const
{
    return Saved::saves(id) || (takes_later(id) && LaterSaved::saves(id));
}

std::optional<std::string> StrainGaugeModule::saved_data(const msg::Message& m) const
{
    if (auto data = Saved::data(m))
        return data;
    return takes_later(msg::message_id(m)) ? LaterSaved::data(m) : std::nullopt;
}

void StrainGaugeModule::on(const msg::PzReqPzStatusUpdate&)
{
    request_->reply += status_update(request_->host);   // the 100 ms update, now
}

void StrainGaugeModule::on(const msg::SetKsgMmiParams& m)
{
    if (const auto bad = kcube_out_of_range(m.params))
        return ignore(fmt::format("{}: KSG_SET_KCUBEMMIPARAMS with {}: ignored", request_->peer, *bad));
    kcube_mmi_ = m.params;
    kcube_mmi_.chan_ident = kChan1;
}

void StrainGaugeModule::on(const msg::ReqKsgMmiParams&)
{
    answer(msg::GetKsgMmiParams{kcube_mmi_});
}

void StrainGaugeModule::on(const msg::SetKsgTrigIoConfig& m)
{
    if (const auto bad = kcube_out_of_range(m.params))
        return ignore(fmt::format("{}: KSG_SET_KCUBETRIGIOCONFIG with {}: ignored", request_->peer, *bad));
    kcube_trig_ = m.params;
    kcube_trig_.chan_ident = kChan1;
}

void StrainGaugeModule::on(const msg::ReqKsgTrigIoConfig&)
{
    answer(msg::GetKsgTrigIoConfig{kcube_trig_});
}

std::unique_ptr<Module> make_strain_gauge_module(const UnitIdentity& unit, std::uint8_t address,
                                                 const DeviceConfig& config, models::World& world,
                                                 spdlog::logger& log, Module::SaveToEeprom save)
{
    const auto& g = config_of(config).gauge;
    WiredStrainGauge* gauge = nullptr;
    if (!g.mounted_on.empty()) {
        // The gauge is the world's: a power cycle makes a new module over the same body. The
        // world links it to its actuator once every device exists (World::link_all()).
        const auto key = config.name + "/1";
        gauge = world.find_as<WiredStrainGauge>(key);
        if (!gauge) {
            models::StrainGaugeConfig m;
            m.actuator_key = g.mounted_on + "/1";
            m.noise_um = g.noise_um;
            m.seed = g.seed;
            gauge = &world.emplace<WiredStrainGauge>(key, world.clock(), m, g.route != GaugeRoute::Sma);
        }
    }
    return std::make_unique<StrainGaugeModule>(unit, 0, address, gauge, world.clock(), g, log, std::move(save));
}

} // namespace rigsim::apt
