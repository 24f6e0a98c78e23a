#pragma once
// The piezo module of an APT unit (module.hpp): a TPZ001/KPZ101's channel or a BPC30x bay. It
// owns the amplifier: the demand (PZ_SET_OUTPUTVOLTS in open loop, the PI filter on the strain
// gauge in closed loop, the LUT while it runs), clipped to 0..the voltage limit and slewed
// (p. 123), drives the bay's PiezoActuator (models/piezo_actuator.hpp, world key
// "<device>/<bay+1>"). The actuator integrates the motion; this module only sets its voltage.
// Choices the manual leaves open: docs/protocol/errata.md (D-7, D-9, D-11, D-13, D-17..D-19).

#include "emulator/apt/kcube_units.hpp"
#include "emulator/apt/module.hpp"
#include "emulator/apt/output_trace.hpp"
#include "models/lut_player.hpp"
#include "models/pi_loop.hpp"
#include "models/piezo_actuator.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace rigsim::apt {

/// What a piezo module is built with: its actuator and the unit's set-up of it.
struct PiezoSetup {
    models::PiezoActuator& actuator;
    const Clock& clock;
    bool strain_gauge = false;         ///< a BPC bay's stage feeds back its extension
    int hardware_max_voltage_v = 150;  ///< BPC30x amplifier maximum (TPZ/KPZ: the actuator's rating)
    int zero_time_ms = 2000;           ///< PZ_SET_ZERO's duration (D-13)
};

/// TPZ001, KPZ101 and the BPC30x bays.
class PiezoModule final : public Module {
public:
    /// What PZ_SET_EEPROMPARAMS saves (p. 113): the settings of the channel, not its output.
    using Saved = SavedSets<msg::PzSetPosControlMode, msg::SetPzInputVoltsSrc, msg::SetPzPiConsts,
                            msg::SetPzOutputLutParams, msg::SetTpzDispSettings, msg::SetTpzIoSettings,
                            msg::SetPzOutputMaxVolts, msg::SetTpzSlewRates>;
    /// What it also saves on a KPZ101 of the later generation: its own blocks (piezo_kcube.cpp).
    using LaterSaved = SavedSets<msg::SetKpzMmiParams, msg::SetKpzTrigIoConfig>;

    /// A TPZ/KPZ's position feedback: the reading (µm from its zero) that reaches input
    /// `hub_analog_input` (TPZ_IOSETTINGS, p. 115) at `now`, or nullopt if none does.
    using Feedback = std::function<std::optional<double>(Ticks now, std::uint16_t hub_analog_input)>;

    PiezoModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address, const PiezoSetup& setup,
                spdlog::logger& log, SaveToEeprom save);

    static constexpr bool handles(msg::Family f) { return f == msg::Family::Piezo; }
    void handle(const msg::Message& m, Request& r) override;
    std::string status_update(std::uint8_t host) const override;
    Ticks next_change(Ticks now) const override;
    /// Slewing, smoothing, zeroing, running a LUT, or a closed loop not yet settled on its
    /// demand (a settled loop keeps ticking but changes nothing a client reads).
    bool busy(Ticks now) const override;
    void tick(Ticks now) override;
    void power_down(bool restore_positions) override;
    bool saves(std::uint16_t id) const override;
    std::optional<std::string> saved_data(const msg::Message& m) const override;
    void describe(nlohmann::json& out) const override;
    /// `{"trig_in": true|false|"pulse"}`: the TRIG IN level of a BPC30x bay (the LUT's input
    /// trigger, p. 108); a TPZ001/KPZ101 has none (400).
    Refused patch(const nlohmann::json& body) override;
    Refused trace(Ticks from, std::size_t max, nlohmann::json& out) const override;
    /// The actuator the bay drives: a body of the world (a kinematic joint reads its extension).
    const models::PiezoActuator& actuator() const { return actuator_; }

    /// The amplifier's output now (V), after clip and slew.
    double output_v() const { return output_at(clock_.now()); }
    /// The voltage limit in force (V): TPZ_IOSETTINGS' VoltageLimit or OUTPUTMAXVOLTS.
    double max_v() const { return max_v_; }
    /// Where a TPZ/KPZ reads its position in closed loop (a strain gauge reader of the world,
    /// set by the unit shell; a BPC bay reads its own stage's gauge).
    void set_feedback(Feedback feedback) { feedback_ = std::move(feedback); }
    /// The PZSTATUSBITS word (p. 101-102).
    std::uint32_t status_bits() const;

    using Module::on;
    void on(const msg::PzSetPosControlMode& m);        ///< MGMSG_PZ_SET_POSCONTROLMODE (p. 94)
    void on(const msg::PzReqPosControlMode& m);        ///< MGMSG_PZ_REQ_POSCONTROLMODE (p. 94)
    void on(const msg::SetPzOutputVolts& m);           ///< MGMSG_PZ_SET_OUTPUTVOLTS (p. 96)
    void on(const msg::ReqPzOutputVolts& m);           ///< MGMSG_PZ_REQ_OUTPUTVOLTS (p. 96)
    void on(const msg::SetPzOutputPos& m);             ///< MGMSG_PZ_SET_OUTPUTPOS (p. 97)
    void on(const msg::ReqPzOutputPos& m);             ///< MGMSG_PZ_REQ_OUTPUTPOS (p. 97)
    void on(const msg::SetPzInputVoltsSrc& m);         ///< MGMSG_PZ_SET_INPUTVOLTSSRC (p. 98)
    void on(const msg::ReqPzInputVoltsSrc& m);         ///< MGMSG_PZ_REQ_INPUTVOLTSSRC (p. 98)
    void on(const msg::SetPzPiConsts& m);              ///< MGMSG_PZ_SET_PICONSTS (p. 100)
    void on(const msg::ReqPzPiConsts& m);              ///< MGMSG_PZ_REQ_PICONSTS (p. 100)
    void on(const msg::PzReqPzStatusBits& m);          ///< MGMSG_PZ_REQ_PZSTATUSBITS (p. 101)
    void on(const msg::PzAckPzStatusUpdate& m);        ///< MGMSG_PZ_ACK_PZSTATUSUPDATE (p. 105)
    void on(const msg::SetPzOutputLut& m);             ///< MGMSG_PZ_SET_OUTPUTLUT (p. 106)
    void on(const msg::ReqPzOutputLut& m);             ///< MGMSG_PZ_REQ_OUTPUTLUT (p. 106)
    void on(const msg::SetPzOutputLutParams& m);       ///< MGMSG_PZ_SET_OUTPUTLUTPARAMS (p. 108)
    void on(const msg::ReqPzOutputLutParams& m);       ///< MGMSG_PZ_REQ_OUTPUTLUTPARAMS (p. 108)
    void on(const msg::PzStartLutOutput& m);           ///< MGMSG_PZ_START_LUTOUTPUT (p. 112)
    void on(const msg::PzStopLutOutput& m);            ///< MGMSG_PZ_STOP_LUTOUTPUT (p. 112)
    void on(const msg::PzSetEepromParams& m);          ///< MGMSG_PZ_SET_EEPROMPARAMS (p. 113)
    void on(const msg::SetTpzDispSettings& m);         ///< MGMSG_PZ_SET_TPZ_DISPSETTINGS (p. 114)
    void on(const msg::ReqTpzDispSettings& m);         ///< MGMSG_PZ_REQ_TPZ_DISPSETTINGS (p. 114)
    void on(const msg::SetTpzIoSettings& m);           ///< MGMSG_PZ_SET_TPZ_IOSETTINGS (p. 115)
    void on(const msg::ReqTpzIoSettings& m);           ///< MGMSG_PZ_REQ_TPZ_IOSETTINGS (p. 115)
    void on(const msg::PzSetZero& m);                  ///< MGMSG_PZ_SET_ZERO (p. 117)
    void on(const msg::PzReqMaxTravel& m);             ///< MGMSG_PZ_REQ_MAXTRAVEL (p. 118)
    void on(const msg::SetPzIoSettings& m);            ///< MGMSG_PZ_SET_IOSETTINGS (p. 119, MPZ601 only)
    void on(const msg::ReqPzIoSettings& m);            ///< MGMSG_PZ_REQ_IOSETTINGS (p. 119, MPZ601 only)
    void on(const msg::SetPzOutputMaxVolts& m);        ///< MGMSG_PZ_SET_OUTPUTMAXVOLTS (p. 121)
    void on(const msg::ReqPzOutputMaxVolts& m);        ///< MGMSG_PZ_REQ_OUTPUTMAXVOLTS (p. 121)
    void on(const msg::SetTpzSlewRates& m);            ///< MGMSG_PZ_SET_TPZ_SLEWRATES (p. 123)
    void on(const msg::ReqTpzSlewRates& m);            ///< MGMSG_PZ_REQ_TPZ_SLEWRATES (p. 123)
    void on(const msg::MotSetPzStageParamDefaults& m); ///< MGMSG_MOT_SET_PZSTAGEPARAMDEFAULTS (p. 125)
    void on(const msg::PzSetLutValueType& m);          ///< MGMSG_PZ_SET_LUTVALUETYPE (p. 126, MPZ601 only)
    // The KPZ101's own messages of the later protocol issues (piezo_kcube.cpp).
    void on(const msg::PzReqPzStatusUpdate& m);        ///< MGMSG_PZ_REQ_PZSTATUSUPDATE (later issue)
    void on(const msg::SetKpzMmiParams& m);            ///< MGMSG_KPZ_SET_KCUBEMMIPARAMS (later issue)
    void on(const msg::ReqKpzMmiParams& m);            ///< MGMSG_KPZ_REQ_KCUBEMMIPARAMS (later issue)
    void on(const msg::SetKpzTrigIoConfig& m);         ///< MGMSG_KPZ_SET_KCUBETRIGIOCONFIG (later issue)
    void on(const msg::ReqKpzTrigIoConfig& m);         ///< MGMSG_KPZ_REQ_KCUBETRIGIOCONFIG (later issue)

private:
    /// The slewed output ramp: from `from_v` at `start` towards `target_v` at `rate_v_per_tick`
    /// (0: no limit, the output is the target at once).
    struct Ramp {
        double from_v = 0;
        double target_v = 0;
        Ticks start = 0;
        double rate_v_per_tick = 0;
    };
    bool closed_loop() const { return mode_ == 2 || mode_ == 4; }
    /// Closed loop has a position to act on (D-19: a TPZ/KPZ needs a linked gauge on the
    /// input HubAnalogInput selects).
    bool has_feedback() const;
    /// The feedback reading of a TPZ/KPZ's gauge at `t` (µm), if one reaches the selected input.
    std::optional<double> fed_back_um(Ticks t) const;
    double output_at(Ticks t) const;
    /// A new demand for the amplifier at `now`: clipped to 0..max (D-17), then slewed.
    void demand(double v, Ticks now);
    /// The open-loop demand (V) of `code` (-32768..32767 of the limit).
    double volts_of(std::int16_t code) const;
    std::int16_t code_of(double v) const;
    /// The measured position as a fraction of the travel, from the zero (0 without feedback).
    double position_frac(Ticks t) const;
    /// GET_OUTPUTPOS and the status update's Position: the measured position with feedback,
    /// else the set point.
    std::uint16_t position_word(Ticks t) const;
    /// `v` shaped by a smooth mode change in progress (D-18).
    double smoothed(double v, Ticks now) const;
    void apply_lut(Ticks now);
    void apply_closed_loop(Ticks now, Ticks elapsed);
    void restore_power_up_settings();
    /// A LUT run starts at `now` (START, or TRIG IN on an armed bay): lut_ended "restarted" for
    /// one in progress, then lut_started. False (logged) if the player refused the parameters.
    bool start_lut(Ticks now, const char* by, std::string* why);
    /// The run in progress ends at `now` for `reason`: the lut_ended event.
    void end_lut(Ticks now, const char* reason);
    /// A run whose cycles are all out by `now` ends ("cycles_done").
    void check_lut_end(Ticks now);
    /// The TRIG IN level changes: an edge into the active state (p. 108, 0x20 sense) starts an
    /// armed LUT; in gated mode (0x40) the edge out of it stops the run.
    void set_trig_in(bool level, Ticks now);
    /// The trace's sample of `now` (output_trace.hpp).
    void record_trace(Ticks now);
    void finish_zeroing(Ticks now);
    /// A closed loop whose feedback came back since the last tick restarts bumpless at `now`.
    void resume_loop(Ticks now);
    std::uint16_t max_travel_word() const;
    msg::GetPzOutputMaxVolts max_volts_message() const;

    models::PiezoActuator& actuator_;
    const Clock& clock_;
    bool strain_gauge_;
    Feedback feedback_;
    bool bpc_;                        ///< a BPC30x bay (OUTPUTMAXVOLTS, SET_ZERO, triggers)
    int hardware_max_v_;
    int zero_time_ms_;
    models::PiLoop pi_;
    models::LutPlayer lut_;

    std::uint8_t mode_ = 1;           ///< POSCONTROLMODE: 1 open, 2 closed, 3/4 smooth
    std::int16_t volts_code_ = 0;     ///< the last accepted SET_OUTPUTVOLTS
    std::uint16_t position_code_ = 0; ///< the closed-loop set point (SET_OUTPUTPOS)
    std::uint16_t volt_src_ = 0;
    std::uint16_t disp_intensity_ = 255;
    std::uint16_t voltage_limit_ = 1; ///< TPZ_IOSETTINGS VoltageLimit: 1 75 V, 2 100 V, 3 150 V
    std::uint16_t hub_analog_input_ = 1;
    std::uint16_t slew_open_ = 0;
    std::uint16_t slew_closed_ = 0;
    /// PZ_SET_IOSETTINGS (p. 119, the MPZ601's): as set; power-up 0s (no public reading).
    msg::PzIoSettings io_settings_{};
    /// PZ_SET_LUTVALUETYPE (p. 126, the MPZ601's): 1 volts, 2 position; as set.
    std::uint8_t lut_value_type_ = 1;
    double max_v_ = 75;
    msg::PzOutputLut last_lut_{1, 0, 0};
    msg::PzOutputLutParams lut_params_{};
    bool lut_armed_ = false;          ///< START with the input trigger mode: waits for TRIG IN
    bool lut_live_ = false;           ///< a run was started and its lut_ended not published yet
    bool trig_in_ = false;            ///< the TRIG IN level (BPC30x; the control API sets it)
    OutputTrace trace_;
    Ramp ramp_;
    Ticks smooth_start_ = kNever;     ///< a smooth mode change ramps from here for 500 ms (D-18)
    double smooth_from_v_ = 0;
    Ticks zero_end_ = kNever;         ///< SET_ZERO in progress until this tick
    bool zeroed_ = false;
    double zero_offset_um_ = 0;
    Ticks last_tick_ = 0;
    bool fed_ = false;                ///< has_feedback() at the last tick or feedback change seen
    msg::KpzMmiParams kcube_mmi_ = kpz_mmi_power_up();      ///< KPZ101, later generation
    msg::KpzTrigIoConfig kcube_trig_ = kpz_trig_power_up(); ///< KPZ101, later generation
};

} // namespace rigsim::apt
