#include "emulator/apt/piezo_module.hpp"
#include "emulator/core/log_format.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace rigsim::apt {

namespace {

/// p. 100's example: the power-up PI constants.
constexpr int kPowerUpProp = 100;
constexpr int kPowerUpInt = 15;
/// D-18: a smooth mode change moves the output to the new demand over this long.
constexpr int kSmoothMs = 500;
/// p. 123: slew rate in V/ms = value × Vmax / 19000.
constexpr double kSlewDivisor = 19000.0;

// PZSTATUSBITS (p. 101-102) besides codec.hpp's msg::kPzConnected, msg::kPzZeroed, msg::kPzZeroing.
constexpr std::uint32_t kGaugeConnected = 0x00000100;
constexpr std::uint32_t kClosedLoop = 0x00000400;
constexpr std::uint32_t kHw75V = 0x00001000;
constexpr std::uint32_t kHw100V = 0x00002000;
constexpr std::uint32_t kHw150V = 0x00004000;
constexpr std::uint32_t kActive = 0x20000000;
constexpr std::uint32_t kEnabled = 0x80000000;

/// TPZ_IOSETTINGS VoltageLimit (p. 115): 1 75 V, 2 100 V, 3 150 V.
double limit_v(std::uint16_t code)
{
    return code == 3 ? 150.0 : code == 2 ? 100.0 : 75.0;
}

std::uint16_t limit_code(double v)
{
    return v >= 150 ? 3 : v >= 100 ? 2 : 1;
}

models::LutPlayer::Params player_params(const msg::PzOutputLutParams& p)
{
    return {p.mode,           p.cycle_length,   p.num_cycles,    p.delay_time,       p.pre_cycle_rest,
            p.post_cycle_rest, p.op_trig_start, p.op_trig_width, p.trig_repeat_cycle};
}

} // namespace

PiezoModule::PiezoModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address, const PiezoSetup& setup,
                         spdlog::logger& log, SaveToEeprom save)
    : Module(unit, bay, address, log, std::move(save)), actuator_(setup.actuator), clock_(setup.clock),
      strain_gauge_(setup.strain_gauge), bpc_(unit.model.rack), hardware_max_v_(setup.hardware_max_voltage_v),
      zero_time_ms_(setup.zero_time_ms), pi_(std::max<std::uint32_t>(1, unit.model.loop_rate_hz)),
      lut_(setup.clock, static_cast<std::size_t>(unit.model.lut_max_index) + 1)
{
    const models::LutPlayer::Params p;
    lut_params_ = {kChan1, p.mode, p.cycle_length, p.num_cycles, p.delay_time, p.pre_cycle_rest, p.post_cycle_rest,
                   p.op_trig_start, p.op_trig_width, p.trig_repeat_cycle};
    restore_power_up_settings();
    last_tick_ = clock_.now();
    ramp_ = {actuator_.voltage(), actuator_.voltage(), last_tick_, 0};
}

void PiezoModule::restore_power_up_settings()
{
    pi_.set_gains(kPowerUpProp, kPowerUpInt);
    slew_open_ = 0;
    slew_closed_ = 0;
    // TPZ/KPZ: the limit is the actuator's rating at power-up; BPC: the rating within the
    // amplifier's maximum.
    const double rating = actuator_.config().max_voltage_v;
    max_v_ = bpc_ ? std::min<double>(rating, hardware_max_v_) : rating;
    voltage_limit_ = limit_code(max_v_);
}

void PiezoModule::handle(const msg::Message& m, Request& r)
{
    const Ticks now = clock_.now();
    check_lut_end(now);
    visit_as(*this, m, r);
    record_trace(now);
}

// ---- the amplifier ----

double PiezoModule::output_at(Ticks t) const
{
    if (ramp_.rate_v_per_tick <= 0)
        return ramp_.target_v;
    const double step = ramp_.rate_v_per_tick * static_cast<double>(std::max<Ticks>(0, t - ramp_.start));
    return ramp_.target_v >= ramp_.from_v ? std::min(ramp_.target_v, ramp_.from_v + step)
                                          : std::max(ramp_.target_v, ramp_.from_v - step);
}

void PiezoModule::demand(double v, Ticks now)
{
    // D-17: the amplifier is unipolar; a negative demand gives 0 V, one above the limit the limit.
    const double target = std::clamp(v, 0.0, max_v_);
    const std::uint16_t slew = closed_loop() ? slew_closed_ : slew_open_;
    const double v_per_ms = slew * max_v_ / kSlewDivisor;
    ramp_ = {output_at(now), target, now, v_per_ms * 1000.0 / clock_.tick_hz()};
    const double out = output_at(now);
    if (out != actuator_.voltage())
        actuator_.set_voltage(out);
}

double PiezoModule::volts_of(std::int16_t code) const
{
    return code / msg::kPzFullScale * max_v_;
}

std::int16_t PiezoModule::code_of(double v) const
{
    if (max_v_ <= 0)   // OUTPUTMAXVOLTS 0 (p. 121 allows it): the output is 0 V, 0 % of any maximum
        return 0;
    return static_cast<std::int16_t>(std::clamp(std::lround(v / max_v_ * msg::kPzFullScale), -32768L, 32767L));
}

std::optional<double> PiezoModule::fed_back_um(Ticks t) const
{
    return feedback_ ? feedback_(t, hub_analog_input_) : std::nullopt;
}

bool PiezoModule::has_feedback() const
{
    return strain_gauge_ || fed_back_um(clock_.now()).has_value();
}

double PiezoModule::position_frac(Ticks t) const
{
    if (strain_gauge_)
        return (actuator_.extension_um() - zero_offset_um_) / actuator_.config().travel_um;
    // A TPZ/KPZ knows its position only through the gauge reader wired to its feedback input.
    return fed_back_um(t).value_or(0.0) / actuator_.config().travel_um;
}

std::uint16_t PiezoModule::position_word(Ticks t) const
{
    if (!has_feedback())
        return position_code_;
    return static_cast<std::uint16_t>(std::clamp(std::lround(position_frac(t) * msg::kPzFullScale), 0L, 32767L));
}

double PiezoModule::smoothed(double v, Ticks now) const
{
    if (smooth_start_ == kNever)
        return v;
    const double w = std::min(1.0, static_cast<double>(now - smooth_start_) / clock_.ticks_from_ms(kSmoothMs));
    return smooth_from_v_ + (v - smooth_from_v_) * w;
}

void PiezoModule::apply_closed_loop(Ticks now, Ticks elapsed)
{
    const double out = pi_.run(position_code_ / msg::kPzFullScale, position_frac(now), elapsed, clock_.tick_hz());
    demand(smoothed(out * max_v_, now), now);
}

void PiezoModule::apply_lut(Ticks now)
{
    const auto value = lut_.value_at(now);
    if (!value)
        return;
    // D-7: LUT samples are volts in open loop and positions in closed loop (p. 106).
    if (closed_loop() && has_feedback()) {
        position_code_ = static_cast<std::uint16_t>(std::max<std::int16_t>(0, *value));
        return;
    }
    demand(volts_of(*value), now);
}

void PiezoModule::finish_zeroing(Ticks)
{
    // p. 117: with 0 V applied the position read becomes the zero reference (D-13).
    zero_offset_um_ = actuator_.extension_um();
    zeroed_ = true;
    zero_end_ = kNever;
}

Ticks PiezoModule::next_change(Ticks now) const
{
    Ticks next = kNever;
    // A closed loop also ticks once when its feedback comes or goes, to note it (resume_loop()).
    if (output_at(now) != ramp_.target_v || (closed_loop() && (has_feedback() || fed_)))
        next = now + 1;
    if (smooth_start_ != kNever)
        next = now + 1;
    if (zero_end_ != kNever)
        next = std::min(next, std::max(zero_end_, now + 1));
    if (lut_.started())
        next = std::min(next, lut_.next_change(now));
    return next;
}

bool PiezoModule::busy(Ticks now) const
{
    if (smooth_start_ != kNever || zero_end_ != kNever || (lut_.started() && lut_.next_change(now) != kNever))
        return true;   // a run's held value after its end changes nothing
    if (!(closed_loop() && has_feedback()))
        return output_at(now) != ramp_.target_v;
    // Settled: the position read is the demand to the count, or the output stands at a rail.
    const double out = output_at(now);
    const long error = std::lround(position_frac(now) * msg::kPzFullScale) - static_cast<long>(position_code_);
    return std::abs(error) > 1 && out > 0 && out < max_v_;
}

void PiezoModule::resume_loop(Ticks now)
{
    const bool fed = has_feedback();
    if (closed_loop() && fed && !fed_) {
        last_tick_ = now;
        pi_.reset(output_at(now) / max_v_, position_code_ / msg::kPzFullScale, position_frac(now));
    }
    fed_ = fed;
}

void PiezoModule::tick(Ticks now)
{
    // The feedback came back (TPZ_IOSETTINGS or the reader's own hub output): the loop resumes
    // bumpless from now, the output held while it was away.
    resume_loop(now);
    const Ticks elapsed = now - last_tick_;
    last_tick_ = now;
    if (zero_end_ != kNever && now >= zero_end_)
        finish_zeroing(now);
    const bool smoothing = smooth_start_ != kNever;   // the last tick of a smooth change meets the demand
    if (smoothing && now - smooth_start_ >= clock_.ticks_from_ms(kSmoothMs))
        smooth_start_ = kNever;
    if (zero_end_ == kNever) {
        if (lut_.started())
            apply_lut(now);
        if (closed_loop() && has_feedback())
            apply_closed_loop(now, elapsed);
        else if (smoothing && !lut_.started())
            demand(smoothed(volts_of(volts_code_), now), now);
    }
    const double out = output_at(now);
    if (out != actuator_.voltage())
        actuator_.set_voltage(out);
    check_lut_end(now);
    record_trace(now);
}

void PiezoModule::power_down(bool)
{
    if (lut_live_)
        end_lut(clock_.now(), "power_cycle");
    actuator_.set_voltage(0);   // the amplifier's output off; the stack relaxes (models/piezo_actuator.hpp)
}

std::uint32_t PiezoModule::status_bits() const
{
    std::uint32_t bits = msg::kPzConnected;
    if (zeroed_)
        bits |= msg::kPzZeroed;
    if (zero_end_ != kNever)
        bits |= msg::kPzZeroing;
    if (has_feedback())
        bits |= kGaugeConnected;
    if (closed_loop())
        bits |= kClosedLoop;
    if (bpc_) {
        bits |= hardware_max_v_ >= 150 ? kHw150V : hardware_max_v_ >= 100 ? kHw100V : kHw75V;
        bits |= kActive;
        if (enabled())
            bits |= kEnabled;
    }
    return bits;
}

std::string PiezoModule::status_update(std::uint8_t host) const
{
    const Ticks now = clock_.now();
    const msg::PzGetPzStatusUpdate u{kChan1, code_of(output_at(now)),
                                     static_cast<std::int16_t>(has_feedback() ? position_word(now) : 0),
                                     status_bits()};
    return msg::encode(u, host, address_);
}

// ---- Control API: LUT runs and their events, the trace ring (the rest: piezo_control.cpp) ----

bool PiezoModule::start_lut(Ticks now, const char* by, std::string* why)
{
    const bool was_running = lut_live_ && lut_.running_at(now);
    const std::int64_t cycles = was_running ? lut_.cycle_at(now) : 0;
    if (auto refused = lut_.start(now, unit_.model.lut_base_interval_us)) {
        *why = *refused;
        return false;
    }
    if (was_running)
        publish("lut_ended", {{"reason", "restarted"}, {"cycles", cycles}});
    lut_live_ = true;
    publish("lut_started", {{"by", by},
                            {"cycle_length", lut_.params().cycle_length},
                            {"num_cycles", (lut_.params().mode & models::LutPlayer::kFixed) ? nlohmann::json(lut_.params().num_cycles) : nlohmann::json(nullptr)}});
    last_tick_ = now;
    apply_lut(now);
    return true;
}

void PiezoModule::end_lut(Ticks now, const char* reason)
{
    lut_live_ = false;
    publish("lut_ended", {{"reason", reason}, {"cycles", lut_.cycle_at(now)}});
}

void PiezoModule::check_lut_end(Ticks now)
{
    if (lut_live_ && !lut_.running_at(now))
        end_lut(now, "cycles_done");
}

void PiezoModule::record_trace(Ticks now)
{
    const double v = output_at(now);
    const auto index = lut_.index_at(now);
    const bool running = lut_.running_at(now);
    trace_.record({now, v, actuator_.extension_um(), code_of(v),
                   static_cast<std::int16_t>(running && index ? static_cast<std::int16_t>(*index) : -1)},
                  running);
}

// ---- Piezo family: mode and output ----

void PiezoModule::on(const msg::PzSetPosControlMode& m)
{
    if (m.mode < 1 || m.mode > 4)
        return ignore(fmt::format("{}: PZ_SET_POSCONTROLMODE with mode {} (1..4): ignored", request_->peer, m.mode));
    const bool closed = m.mode == 2 || m.mode == 4;
    if (closed && !has_feedback())   // D-19
        return ignore(fmt::format("{}: PZ_SET_POSCONTROLMODE {}: the {} has no position feedback connected, closed "
                                  "loop ignored",
                                  request_->peer, m.mode, unit_.model_name));
    const Ticks now = clock_.now();
    if (closed && !closed_loop())
        pi_.reset(output_at(now) / max_v_);   // bumpless
    if (m.mode == 3 || m.mode == 4) {
        smooth_start_ = now;
        smooth_from_v_ = output_at(now);
    }
    mode_ = m.mode;
    last_tick_ = now;
    fed_ = has_feedback();
    if (!closed && smooth_start_ == kNever && !lut_.started())
        demand(volts_of(volts_code_), now);
}

void PiezoModule::on(const msg::PzReqPosControlMode&)
{
    answer(msg::PzGetPosControlMode{kChan1, mode_});
}

void PiezoModule::on(const msg::SetPzOutputVolts& m)
{
    if (closed_loop())   // p. 96
        return ignore(fmt::format("{}: PZ_SET_OUTPUTVOLTS in closed loop: ignored", request_->peer));
    const Ticks now = clock_.now();
    if (lut_.running_at(now))
        return ignore(fmt::format("{}: PZ_SET_OUTPUTVOLTS while the LUT output runs: ignored", request_->peer));
    if (zero_end_ != kNever)
        return ignore(fmt::format("{}: PZ_SET_OUTPUTVOLTS while zeroing: ignored", request_->peer));
    lut_.reset();
    volts_code_ = m.params.voltage;
    demand(volts_of(volts_code_), now);
}

void PiezoModule::on(const msg::ReqPzOutputVolts&)
{
    answer(msg::GetPzOutputVolts{{kChan1, code_of(output_v())}});
}

void PiezoModule::on(const msg::SetPzOutputPos& m)
{
    if (!closed_loop())   // p. 97
        return ignore(fmt::format("{}: PZ_SET_OUTPUTPOS in open loop: ignored", request_->peer));
    if (lut_.running_at(clock_.now()))
        return ignore(fmt::format("{}: PZ_SET_OUTPUTPOS while the LUT output runs: ignored", request_->peer));
    lut_.reset();
    position_code_ = m.params.position_sw;
}

void PiezoModule::on(const msg::ReqPzOutputPos&)
{
    answer(msg::GetPzOutputPos{{kChan1, position_word(clock_.now())}});
}

void PiezoModule::on(const msg::SetPzInputVoltsSrc& m)
{
    volt_src_ = m.params.volt_src;   // no external or potentiometer input is modelled: they add 0 V
}

void PiezoModule::on(const msg::ReqPzInputVoltsSrc&)
{
    answer(msg::GetPzInputVoltsSrc{{kChan1, volt_src_}});
}

void PiezoModule::on(const msg::SetPzPiConsts& m)
{
    pi_.set_gains(m.params.prop_const, m.params.int_const);
}

void PiezoModule::on(const msg::ReqPzPiConsts&)
{
    answer(msg::GetPzPiConsts{{kChan1, static_cast<std::uint16_t>(pi_.prop()),
                               static_cast<std::uint16_t>(pi_.integral())}});
}

void PiezoModule::on(const msg::PzReqPzStatusBits&)
{
    answer(msg::PzGetPzStatusBits{kChan1, status_bits()});
}

void PiezoModule::on(const msg::PzAckPzStatusUpdate&)
{
    // The unit shell takes the model's server-alive acknowledgement before any module.
}

// ---- Piezo family: LUT (p. 106-112) ----

void PiezoModule::on(const msg::SetPzOutputLut& m)
{
    if (auto why = models::LutPlayer::check_index(m.params.index, lut_.capacity()))
        return ignore(fmt::format("{}: PZ_SET_OUTPUTLUT: {}: ignored", request_->peer, *why));
    lut_.set_sample(m.params.index, m.params.output);
    last_lut_ = m.params;
    last_lut_.chan_ident = kChan1;
}

void PiezoModule::on(const msg::ReqPzOutputLut&)
{
    answer(msg::GetPzOutputLut{last_lut_});   // D-9: the REQ names no index
}

void PiezoModule::on(const msg::SetPzOutputLutParams& m)
{
    const auto p = player_params(m.params);
    if (auto why = models::LutPlayer::check_params(p, lut_.capacity(), bpc_))
        return ignore(fmt::format("{}: PZ_SET_OUTPUTLUTPARAMS: {}: ignored", request_->peer, *why));
    lut_.set_params(p);
    lut_params_ = m.params;
    lut_params_.chan_ident = kChan1;
}

void PiezoModule::on(const msg::ReqPzOutputLutParams&)
{
    answer(msg::GetPzOutputLutParams{lut_params_});
}

void PiezoModule::on(const msg::PzStartLutOutput&)
{
    const Ticks now = clock_.now();
    if (lut_.params().mode & models::LutPlayer::kInputTrig) {
        // p. 109: with the input trigger mode, START arms the output; a TRIG IN edge starts it.
        lut_armed_ = true;
        log_.info("{}: PZ_START_LUTOUTPUT: armed, the LUT output starts at the next TRIG IN edge", request_->peer);
        return;
    }
    std::string why;
    if (!start_lut(now, "start", &why))
        return ignore(fmt::format("{}: PZ_START_LUTOUTPUT: {}: ignored", request_->peer, why));
}

void PiezoModule::on(const msg::PzStopLutOutput&)
{
    const Ticks now = clock_.now();
    lut_armed_ = false;
    if (lut_live_ && lut_.running_at(now))
        end_lut(now, "stop");
    lut_.stop(now);
}

// ---- Piezo family: settings ----

void PiezoModule::on(const msg::PzSetEepromParams& m)
{
    save_to_eeprom_(m.msg_id, request_->peer);
}

void PiezoModule::on(const msg::SetTpzDispSettings& m)
{
    disp_intensity_ = m.params.disp_intensity;
}

void PiezoModule::on(const msg::ReqTpzDispSettings&)
{
    answer(msg::GetTpzDispSettings{{disp_intensity_}});
}

void PiezoModule::on(const msg::SetTpzIoSettings& m)
{
    const Ticks now = clock_.now();
    const bool fed = has_feedback();
    voltage_limit_ = m.params.voltage_limit;
    hub_analog_input_ = m.params.hub_analog_input;
    max_v_ = limit_v(voltage_limit_);   // p. 115: the output is clipped to the new limit
    demand(ramp_.target_v, now);
    // A closed loop idles while its input is switched away; it resumes bumpless from now, not
    // integrating the time it stood.
    if (closed_loop() && has_feedback() != fed) {
        last_tick_ = now;
        pi_.reset(output_at(now) / max_v_, position_code_ / msg::kPzFullScale, position_frac(now));
    }
    fed_ = has_feedback();
}

void PiezoModule::on(const msg::ReqTpzIoSettings&)
{
    answer(msg::GetTpzIoSettings{{kChan1, voltage_limit_, hub_analog_input_, 0, 0}});
}

void PiezoModule::on(const msg::PzSetZero&)
{
    const Ticks now = clock_.now();
    // p. 117, D-13: 0 V out, "zeroing" for zero_time_ms, then the position read is the zero.
    zeroed_ = false;
    volts_code_ = 0;
    position_code_ = 0;
    if (lut_live_ && lut_.running_at(now))
        end_lut(now, "set_zero");
    lut_.reset();
    zero_end_ = now + clock_.ticks_from_ms(zero_time_ms_);
    demand(0, now);
}

void PiezoModule::on(const msg::PzReqMaxTravel&)
{
    answer(msg::PzGetMaxTravel{kChan1, max_travel_word()});
}

std::uint16_t PiezoModule::max_travel_word() const
{
    return static_cast<std::uint16_t>(std::lround(actuator_.config().travel_um * 10));   // 100 nm steps (p. 118)
}

void PiezoModule::on(const msg::SetPzIoSettings& m)
{
    // MPZ601 only (p. 135: only its takes list, kMpz, lets it reach here). p. 119: current limit
    // 0..2, low-pass filter 0..3, the BNC mode 0x0000 (trigger) or 0xFFFF (LV output); FeedbackSig
    // "for future use", kept as sent. Stored: rigsim's amplifier has no current limit or filter.
    const auto& p = m.params;
    if (p.amp_current_lim > 2 || p.amp_lp_filter > 3 || (p.bnc_trig_or_lv_out != 0 && p.bnc_trig_or_lv_out != 0xFFFF))
        return ignore(fmt::format("{}: PZ_SET_IOSETTINGS AmpCurrentLim {} (0..2), AmpLPFilter {} (0..3), BNCTrigORLVOut "
                                  "0x{:04x} (0x0000 or 0xFFFF): ignored",
                                  request_->peer, p.amp_current_lim, p.amp_lp_filter, p.bnc_trig_or_lv_out));
    io_settings_ = p;
    io_settings_.chan_ident = kChan1;
}

void PiezoModule::on(const msg::ReqPzIoSettings&)
{
    answer(msg::GetPzIoSettings{io_settings_});
}

msg::GetPzOutputMaxVolts PiezoModule::max_volts_message() const
{
    // D-11: flags 0x02/0x04/0x08 name the amplifier's 75/100/150 V hardware limit.
    const std::uint16_t flags = hardware_max_v_ >= 150 ? 0x08 : hardware_max_v_ >= 100 ? 0x04 : 0x02;
    return {{kChan1, static_cast<std::uint16_t>(std::lround(max_v_ * 10)), flags}};
}

void PiezoModule::on(const msg::SetPzOutputMaxVolts& m)
{
    if (m.params.voltage > hardware_max_v_ * 10)
        return ignore(fmt::format("{}: PZ_SET_OUTPUTMAXVOLTS {} V above the amplifier's {} V: ignored",
                                  request_->peer, m.params.voltage / 10.0, hardware_max_v_));
    max_v_ = m.params.voltage / 10.0;
    demand(ramp_.target_v, clock_.now());
    // p. 121: the unit answers with the new maximum and the travel it gives.
    answer(max_volts_message());
    answer(msg::PzGetMaxTravel{kChan1, max_travel_word()});
}

void PiezoModule::on(const msg::ReqPzOutputMaxVolts&)
{
    answer(max_volts_message());
}

void PiezoModule::on(const msg::SetTpzSlewRates& m)
{
    slew_open_ = m.params.slew_open;
    slew_closed_ = m.params.slew_closed;
}

void PiezoModule::on(const msg::ReqTpzSlewRates&)
{
    answer(msg::GetTpzSlewRates{{kChan1, slew_open_, slew_closed_}});
}

void PiezoModule::on(const msg::MotSetPzStageParamDefaults&)
{
    restore_power_up_settings();   // p. 125: the stage's default parameters
    demand(ramp_.target_v, clock_.now());
}

void PiezoModule::on(const msg::PzSetLutValueType& m)
{
    // MPZ601 only (p. 135, kMpz). p. 126: 1 the LUT's values are volts, 2 positions; "must be called
    // BEFORE the LUT values are downloaded". Stored (the control API shows it); the samples are read
    // by the loop mode they run in, as the BPC's are.
    if (m.lut_type != 1 && m.lut_type != 2)
        return ignore(fmt::format("{}: PZ_SET_LUTVALUETYPE {} (1 volts, 2 position): ignored", request_->peer,
                                  m.lut_type));
    lut_value_type_ = m.lut_type;
}

} // namespace rigsim::apt
