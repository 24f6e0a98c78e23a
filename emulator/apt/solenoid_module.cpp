#include "emulator/apt/solenoid_module.hpp"
#include "emulator/core/log_format.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

namespace rigsim::apt {

namespace {

/// The only channel of a module: P_MOD_CHAN1.

/// MOT_GET_STATUSUPDATE bits (D-4): the output, as Kinesis reads a KSC101's status word.
constexpr std::uint32_t kOutputOn = 0x00000001;
/// p. 77 table: "interlock state (1 = enabled)".
constexpr std::uint32_t kInterlockEnabled = 0x00001000;
/// A KSC101's key switch unlocked (MSLNZ/msl-equipment thorlabs/ksc.py is_key_unlocked: bit 13).
/// rigsim has no key: the key of a unit whose output works is unlocked.
constexpr std::uint32_t kKeyUnlocked = 0x00002000;

/// MOT_GET_SOL_STATE's state byte (p. 91: 1 on, 2 off).
constexpr std::uint8_t kSolOn = 1;
constexpr std::uint8_t kSolOff = 2;
/// A KSC101's firmware reports the output off as 0, not 2 (amsikking/thorlabs_KSC101
/// thorlabs_KSC101.py reads 0 closed, 1 open, "error in docs?"; Kinesis' SC_OperatingStates
/// names the 0 it "sometimes" returns, msl-equipment kinesis/enums.py).
constexpr std::uint8_t kKCubeSolOff = 0;

const char* mode_name(SolenoidModule::Mode m)
{
    switch (m) {
    case SolenoidModule::Mode::Manual:
        return "manual";
    case SolenoidModule::Mode::Single:
        return "single";
    case SolenoidModule::Mode::Auto:
        return "auto";
    case SolenoidModule::Mode::Triggered:
        return "triggered";
    }
    return "manual";
}

} // namespace

SolenoidModule::SolenoidModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address,
                               models::Solenoid& output, const Clock& clock, bool interlock_fitted,
                               spdlog::logger& log, SaveToEeprom save)
    : Module(unit, bay, address, log, std::move(save)), output_(output), clock_(clock),
      interlock_fitted_(interlock_fitted), published_active_(output.active_at(clock.now())),
      kcube_(unit.model_name, unit.firmware)
{
}

void SolenoidModule::handle(const msg::Message& m, Request& r)
{
    visit_as(*this, m, r);
    note_output(clock_.now());
}

Ticks SolenoidModule::next_change(Ticks now) const
{
    const Ticks edge = output_.next_event(now);
    return edge == kNever ? kNever : std::max(edge, now + 1);
}

void SolenoidModule::tick(Ticks now)
{
    note_output(now);
}

void SolenoidModule::note_output(Ticks now)
{
    const bool active = output_.active_at(now);
    if (active == published_active_)
        return;
    published_active_ = active;
    publish("solenoid", {{"output", active ? "on" : "off"}, {"cycles_done", output_.cycles_done(now)}});
}

void SolenoidModule::power_down(bool)
{
    output_.close(clock_.now());   // the driver's output is off while the unit is
    note_output(clock_.now());
}

std::uint32_t SolenoidModule::status_bits() const
{
    std::uint32_t bits = 0;
    if (output_.active_at(clock_.now()))
        bits |= kOutputOn;
    if (interlock_mode_ == 1)
        bits |= kInterlockEnabled;
    if (kcube_firmware())
        bits |= kKeyUnlocked;
    return bits;
}

std::string SolenoidModule::status_update(std::uint8_t host) const
{
    // p. 77: position and encoder count 0 (a solenoid has neither).
    return msg::encode(msg::GetStatusUpdate{msg::MotStatus{kChan1, 0, 0, status_bits()}}, host, address_);
}

Ticks SolenoidModule::ticks_of(std::int32_t units_250us) const
{
    const auto ticks = std::llround(static_cast<double>(units_250us) * clock_.tick_hz() / 4000.0);
    return std::max<Ticks>(1, ticks);
}

void SolenoidModule::close_output()
{
    output_.close(clock_.now());
    commanded_on_ = false;
    primed_ = false;
}

void SolenoidModule::start_cycles(std::int64_t cycles)
{
    output_.start_cycles(clock_.now(), ticks_of(cycle_.on_time_250us), ticks_of(cycle_.off_time_250us), cycles);
}

// ---- Solenoid family ----

void SolenoidModule::on(const msg::SolSetOperatingMode& m)
{
    if (m.operating_mode < 1 || m.operating_mode > 4)
        return ignore(fmt::format("{}: MOT_SET_SOL_OPERATINGMODE mode {} (1..4): ignored", request_->peer,
                                  m.operating_mode));
    const auto mode = static_cast<Mode>(m.operating_mode);
    if (mode != mode_ && (commanded_on_ || output_.active_at(clock_.now()) || running())) {
        log_.info("{}: MOT_SET_SOL_OPERATINGMODE {} while the output runs: closed first", request_->peer,
                  mode_name(mode));
        close_output();
    }
    mode_ = mode;
}

void SolenoidModule::on(const msg::SolReqOperatingMode&)
{
    answer(msg::SolGetOperatingMode{kChan1, static_cast<std::uint8_t>(mode_)});
}

void SolenoidModule::on(const msg::SetSolCycleParams& m)
{
    // The ranges (p. 87) are set_ranges.cpp's; a new cycle applies from the next start.
    cycle_ = m.params;
    cycle_.chan_ident = kChan1;
}

void SolenoidModule::on(const msg::ReqSolCycleParams&)
{
    answer(msg::GetSolCycleParams{cycle_});
}

void SolenoidModule::on(const msg::SolSetInterlockMode& m)
{
    if (m.interlock_mode != 1 && m.interlock_mode != 2)
        return ignore(fmt::format("{}: MOT_SET_SOL_INTERLOCKMODE mode {} (1 enabled, 2 disabled): ignored",
                                  request_->peer, m.interlock_mode));
    interlock_mode_ = m.interlock_mode;
    if (interlock_blocks() && (commanded_on_ || running())) {
        log_.warn("{}: interlock enabled without the interlock plug: the output closes", request_->peer);
        close_output();
    }
}

void SolenoidModule::on(const msg::SolReqInterlockMode&)
{
    answer(msg::SolGetInterlockMode{kChan1, interlock_mode_});
}

void SolenoidModule::on(const msg::SolSetState& m)
{
    if (m.state == 2)
        return close_output();
    if (m.state != 1)
        return ignore(fmt::format("{}: MOT_SET_SOL_STATE state {} (1 on, 2 off): ignored", request_->peer, m.state));
    // p. 89: with the interlock enabled the output opens only while the plug is fitted.
    if (interlock_blocks())
        return ignore(fmt::format("{}: MOT_SET_SOL_STATE ON with the interlock enabled and its plug not fitted: "
                                  "ignored",
                                  request_->peer));
    if (running())
        return ignore(fmt::format("{}: MOT_SET_SOL_STATE ON during a {} cycle run: ignored", request_->peer,
                                  mode_name(mode_)));
    commanded_on_ = true;
    switch (mode_) {
    case Mode::Manual:
        return output_.open(clock_.now());
    case Mode::Single:
        return start_cycles(1);
    case Mode::Auto:
        return start_cycles(cycle_.num_cycles);
    case Mode::Triggered:
        primed_ = true;   // p. 85: the cycles run on each TRIG IN edge once primed
        return;
    }
}

void SolenoidModule::on(const msg::SolReqState&)
{
    const std::uint8_t off = kcube_firmware() ? kKCubeSolOff : kSolOff;
    answer(msg::SolGetState{kChan1, output_.active_at(clock_.now()) ? kSolOn : off});
}

// ---- Motor family (p. 138) ----

void SolenoidModule::on(const msg::SetAvModes& m)
{
    if ((m.params.mode_bits & ~0x000Bu) != 0)   // p. 52-53: bits 1, 2, 8 only
        return ignore(fmt::format("{}: MOT_SET_AVMODES mode bits 0x{:04x} (bits of 0x000b only): ignored",
                                  request_->peer, m.params.mode_bits));
    av_modes_ = m.params;
    av_modes_.chan_ident = kChan1;
}

void SolenoidModule::on(const msg::ReqAvModes&)
{
    answer(msg::GetAvModes{av_modes_});
}

void SolenoidModule::on(const msg::SetButtonParams& m)
{
    button_params_ = m.params;
    button_params_.chan_ident = kChan1;
}

void SolenoidModule::on(const msg::ReqButtonParams&)
{
    answer(msg::GetButtonParams{button_params_});
}

void SolenoidModule::on(const msg::SetEepromParams& m)
{
    save_to_eeprom_(m.msg_id, request_->peer);
}

void SolenoidModule::on(const msg::ReqStatusBits&)
{
    answer(msg::GetStatusBits{kChan1, status_bits()});
}

void SolenoidModule::on(const msg::ReqStatusUpdate&)
{
    request_->reply += status_update(request_->host);   // the 100 ms update, now
}

void SolenoidModule::finish(const KCubeOutcome& out)
{
    if (!out.ignored.empty())
        return ignore(fmt::format("{}: {}", request_->peer, out.ignored));
    if (out.answer)
        answer(*out.answer);
}

void SolenoidModule::on(const msg::SetKCubeTrigIoConfig& m)
{
    // Kinesis' KSC_TriggerPortMode (msl-equipment kinesis/enums.py): 0 disabled, 1 input, 0x0A
    // output; the motor cubes' move and position modes have no solenoid meaning.
    for (const auto mode : {m.params.trig1_mode, m.params.trig2_mode})
        if (mode != 0 && mode != 1 && mode != 0x0A)
            return ignore(fmt::format("{}: MOT_SET_KCUBETRIGIOCONFIG with trigger mode {} (a KSC101: 0, 1 or 10): "
                                      "ignored",
                                      request_->peer, mode));
    KCubeOutcome out;
    kcube_.on(m, out);
    finish(out);
}

// ---- Control API ----

void SolenoidModule::trigger_rising()
{
    if (mode_ != Mode::Triggered || !primed_)
        return log_.info("control: TRIG IN rising edge with the {} mode {}: no cycles", mode_name(mode_),
                         primed_ ? "primed" : "not primed");
    if (running())
        return log_.info("control: TRIG IN rising edge during a cycle run: ignored");
    start_cycles(cycle_.num_cycles);
}

void SolenoidModule::set_interlock_fitted(bool fitted)
{
    interlock_fitted_ = fitted;
    if (interlock_blocks() && (commanded_on_ || output_.active_at(clock_.now()) || running())) {
        log_.warn("control: interlock plug pulled: the output closes (p. 89)");
        close_output();
    }
}

void SolenoidModule::describe(nlohmann::json& out) const
{
    const auto now = clock_.now();
    out["mode"] = mode_name(mode_);
    out["state"] = commanded_on_ ? "on" : "off";
    out["output_active"] = output_.active_at(now);
    out["cycles_done"] = output_.cycles_done(now);
    out["cycles_total"] = output_.cycles_total();
    out["primed"] = primed_;
    out["interlock_mode"] = interlock_mode_ == 1 ? "enabled" : "disabled";
    out["interlock_fitted"] = interlock_fitted_;
    out["trig_in"] = trig_in_;
    out["status"] = status_bits();
}

Refused SolenoidModule::patch(const nlohmann::json& body)
{
    if (!body.is_object())
        return Refusal{400, "a solenoid channel's PATCH is an object"};
    for (const auto& [key, value] : body.items()) {
        if (key == "interlock_fitted" && !value.is_boolean())
            return Refusal{400, "\"interlock_fitted\" is true or false"};
        if (key == "trig_in" && !value.is_boolean() && value != "pulse")
            return Refusal{400, "\"trig_in\" is true, false or \"pulse\""};
        if (key != "interlock_fitted" && key != "trig_in")
            return Refusal{400, "unknown key \"" + key + "\" for a solenoid channel (interlock_fitted, trig_in)"};
    }
    if (const auto it = body.find("interlock_fitted"); it != body.end())
        set_interlock_fitted(it->get<bool>());
    if (const auto it = body.find("trig_in"); it != body.end()) {
        const bool pulse = !it->is_boolean();
        const bool level = pulse || it->get<bool>();
        if (level && !trig_in_)
            trigger_rising();
        trig_in_ = pulse ? false : level;   // a pulse: rising then falling edge, in one tick
    }
    note_output(clock_.now());
    return std::nullopt;
}

} // namespace rigsim::apt
