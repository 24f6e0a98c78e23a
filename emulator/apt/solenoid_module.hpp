#pragma once
// The solenoid module of a TSC001/KSC101 (module.hpp; APT manual p. 84-92). It keeps the
// protocol state (operating mode, cycle parameters, interlock mode, the ON/OFF command, the
// triggered mode's priming, the interlock plug and the TRIG IN level) and drives the output
// through models::Solenoid, the body in the world that times the on/off cycles.

#include "emulator/apt/kcube_params.hpp"
#include "emulator/apt/module.hpp"
#include "models/clock.hpp"
#include "models/solenoid.hpp"

#include <cstdint>
#include <string>

namespace rigsim::apt {

/// The solenoid driver's one channel: the Solenoid family and the Motor-family messages of
/// its cross-reference table (p. 138).
class SolenoidModule final : public Module {
public:
    /// The solenoid SETs MOT_SET_EEPROMPARAMS saves (D-14), with the LED and button blocks
    /// it keeps as a motor module does.
    using Saved = SavedSets<msg::SetSolCycleParams, msg::SolSetOperatingMode, msg::SolSetInterlockMode,
                            msg::SetAvModes, msg::SetButtonParams>;

    /// SET_SOL_OPERATINGMODE's modes (p. 85).
    enum class Mode : std::uint8_t { Manual = 1, Single = 2, Auto = 3, Triggered = 4 };

    SolenoidModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address, models::Solenoid& output,
                   const Clock& clock, bool interlock_fitted, spdlog::logger& log, SaveToEeprom save);

    static constexpr bool handles(msg::Family f)
    {
        return f == msg::Family::Solenoid || f == msg::Family::Motor || f == msg::Family::KCubeMotor;
    }
    void handle(const msg::Message& m, Request& r) override;
    std::string status_update(std::uint8_t host) const override;
    void power_down(bool restore_positions) override;
    /// The output's next edge: the shell wakes then so that the "solenoid" event has its tick.
    Ticks next_change(Ticks now) const override;
    void tick(Ticks now) override;
    bool saves(std::uint16_t id) const override { return Saved::saves(id) || kcube_.saves(id); }
    std::size_t fields_read(std::uint16_t id) const override { return kcube_.fields_read(id); }
    std::optional<std::string> saved_data(const msg::Message& m) const override
    {
        return Saved::saves(msg::message_id(m)) ? Saved::data(m) : kcube_.saved_data(m);
    }
    void describe(nlohmann::json& out) const override;
    Refused patch(const nlohmann::json& body) override;

    /// The interlock plug is in (it outlives a power cycle: the shell hands it to the new module).
    bool interlock_fitted() const { return interlock_fitted_; }
    /// MOT_GET_STATUSUPDATE's status bits (p. 77; D-4): 0x1 output on, 0x1000 interlock enabled;
    /// a KSC101 of the later generation also 0x2000, its key switch unlocked ("K-Cube units").
    std::uint32_t status_bits() const;

    using Module::on;
    void on(const msg::SolSetOperatingMode& m);   ///< MGMSG_MOT_SET_SOL_OPERATINGMODE (p. 85)
    void on(const msg::SolReqOperatingMode& m);   ///< MGMSG_MOT_REQ_SOL_OPERATINGMODE (p. 85)
    void on(const msg::SetSolCycleParams& m);     ///< MGMSG_MOT_SET_SOL_CYCLEPARAMS (p. 87)
    void on(const msg::ReqSolCycleParams& m);     ///< MGMSG_MOT_REQ_SOL_CYCLEPARAMS (p. 87)
    void on(const msg::SolSetInterlockMode& m);   ///< MGMSG_MOT_SET_SOL_INTERLOCKMODE (p. 89)
    void on(const msg::SolReqInterlockMode& m);   ///< MGMSG_MOT_REQ_SOL_INTERLOCKMODE (p. 89)
    void on(const msg::SolSetState& m);           ///< MGMSG_MOT_SET_SOL_STATE (p. 91)
    void on(const msg::SolReqState& m);           ///< MGMSG_MOT_REQ_SOL_STATE (p. 91)
    void on(const msg::SetAvModes& m);            ///< MGMSG_MOT_SET_AVMODES (p. 53)
    void on(const msg::ReqAvModes& m);            ///< MGMSG_MOT_REQ_AVMODES (p. 53)
    void on(const msg::SetButtonParams& m);       ///< MGMSG_MOT_SET_BUTTONPARAMS (p. 58)
    void on(const msg::ReqButtonParams& m);       ///< MGMSG_MOT_REQ_BUTTONPARAMS (p. 58)
    void on(const msg::SetEepromParams& m);       ///< MGMSG_MOT_SET_EEPROMPARAMS (p. 60)
    // A KSC101 of the later generation (messages.def's takes list kKscLater; the TSC001 ignores them, D-4).
    void on(const msg::ReqStatusBits& m);         ///< MGMSG_MOT_REQ_STATUSBITS (p. 81; KSC101, later generation)
    void on(const msg::ReqStatusUpdate& m);       ///< MGMSG_MOT_REQ_STATUSUPDATE (p. 78; KSC101, later generation)
    /// MGMSG_MOT_SET_KCUBETRIGIOCONFIG (later issue; KSC101): a solenoid cube's port modes first.
    void on(const msg::SetKCubeTrigIoConfig& m);
    /// The KCubeMotor family (later issues): the KSC101's display and trigger blocks, kept by
    /// KCubeParams (kcube_params.hpp) as a K-Cube motor module keeps them; the rest it ignores.
    template <class T, class = decltype(std::declval<KCubeParams&>().on(std::declval<const T&>(),
                                                                        std::declval<KCubeOutcome&>()))>
    void on(const T& m)
    {
        KCubeOutcome out;
        kcube_.on(m, out);
        finish(out);
    }
    /// Every other Motor-family message: no solenoid meaning (D-4), ignored and logged.
    template <class T, std::enable_if_t<T::family == msg::Family::Motor, int> = 0> void on(const T&) { not_mine(); }

private:
    bool running() const { return output_.running(clock_.now()); }
    bool interlock_blocks() const { return interlock_mode_ == 1 && !interlock_fitted_; }
    /// A K-Cube's firmware of the later generation: the KSC101's state encoding ("K-Cube units").
    bool kcube_firmware() const { return later_generation() && !unit_.model.later_takes.empty(); }
    /// Close the output and disarm the triggered mode; the command reads OFF.
    void close_output();
    /// Start the programmed cycles now (`cycles` of them, 0 = forever).
    void start_cycles(std::int64_t cycles);
    /// A rising edge on TRIG IN: a primed triggered mode runs its cycles.
    void trigger_rising();
    /// The plug pulled or refitted (PATCH interlock_fitted).
    void set_interlock_fitted(bool fitted);
    Ticks ticks_of(std::int32_t units_250us) const;
    /// Publish the "solenoid" event if the output changed since the last one.
    void note_output(Ticks now);
    /// Send KCubeParams's answer, or log why it ignored the message.
    void finish(const KCubeOutcome& out);

    models::Solenoid& output_;
    const Clock& clock_;
    Mode mode_ = Mode::Manual;                  ///< p. 86: the power-up mode is manual
    msg::SolCycleParams cycle_{1, 4000, 4000, 0};
    std::uint8_t interlock_mode_ = 1;           ///< 1 enabled (plug required), 2 disabled
    bool commanded_on_ = false;                 ///< the last SET_SOL_STATE (OFF at power-up)
    bool primed_ = false;                       ///< triggered mode: ON armed it
    bool interlock_fitted_;
    bool trig_in_ = false;
    bool published_active_ = false;             ///< the output as the last "solenoid" event said
    msg::AvModes av_modes_{1, 0x000B};
    msg::ButtonParams button_params_{};
    KCubeParams kcube_;                         ///< the KSC101's K-Cube blocks (later generation)
};

} // namespace rigsim::apt
