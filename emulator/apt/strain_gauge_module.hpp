#pragma once
// The strain gauge module of an APT unit (module.hpp): a TSG001/KSG101 reader. Its gauge is a
// body of the world (models/strain_gauge.hpp, key "<device>/1") mounted on the actuator of the
// piezo driver the rig names ("mounted_on": "<piezo device>/1"): it reads the world, never the
// piezo driver's protocol state. A reader without a gauge fitted (no mounted_on) answers with
// status bit 0x1 clear and readings of 0.
//
// The piezo driver's closed loop reads the same gauge body through the world
// (gauge_feedback), never this module: the gauge's wiring (the rig's "route": on the hub or
// the SMA cable; on the hub, the channel of the reader's HubAnalogueOutput) must reach the
// driver's TPZ_IOSETTINGS HubAnalogInput (p. 115, p. 127).
// Choices the manual leaves open: docs/protocol/errata.md (D-15, D-16, D-22).

#include "emulator/apt/config.hpp"
#include "emulator/apt/kcube_units.hpp"
#include "emulator/apt/module.hpp"
#include "models/strain_gauge.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace rigsim::models {
class PiezoActuator;
}

namespace rigsim::apt {

/// A strain gauge and how its reader is cabled to the piezo driver: on the hub, where the
/// reader's TSG_IOSETTINGS HubAnalogueOutput (p. 127: 1 hub A, 2 hub B) picks the hub channel
/// the signal goes to, or over the SMA cable. The reader module writes its output here; the
/// driver's feedback reads it from the world.
class WiredStrainGauge final : public models::StrainGauge {
public:
    WiredStrainGauge(const Clock& clock, models::StrainGaugeConfig config, bool on_hub)
        : StrainGauge(clock, std::move(config)), on_hub_(on_hub)
    {
    }
    /// Whether the signal reaches driver input `input` (TPZ_IOSETTINGS HubAnalogInput, p. 115:
    /// 1 hub A, 2 hub B, 3 SMA).
    bool reaches(std::uint16_t input) const { return on_hub_ ? input == hub_output_ : input == 3; }
    /// The reader's HubAnalogueOutput (1 hub A, 2 hub B); the reading driver hears of it.
    void set_hub_output(std::uint16_t output)
    {
        hub_output_ = output;
        if (route_changed_)
            route_changed_();
    }
    /// Called after every set_hub_output() (empty: nobody): the driver whose feedback input reads
    /// this gauge (AptDevice::connect_feedback) tells its clock that whether its closed loop is
    /// fed may have changed (models/clock.hpp, "The schedule").
    void on_route_change(std::function<void()> f) { route_changed_ = std::move(f); }

private:
    bool on_hub_;
    std::uint16_t hub_output_ = 1;
    std::function<void()> route_changed_;
};

/// The gauge of the world mounted on `actuator`, or nullptr (none, or not linked yet).
WiredStrainGauge* find_mounted_gauge(const models::World& world, const models::PiezoActuator& actuator);

/// A TPZ001/KPZ101's feedback input (PiezoModule::Feedback): the reading (µm from the gauge's
/// zero, p. 129's 500 Hz sample) of the gauge mounted on `actuator` when its signal reaches
/// input `feedback_input` (HubAnalogInput), else nullopt. The gauge is looked up once, now:
/// call it after World::link_all().
std::function<std::optional<double>(Ticks now, std::uint16_t feedback_input)>
gauge_feedback(const models::World& world, const models::PiezoActuator& actuator);

/// TSG001 and KSG101.
class StrainGaugeModule final : public Module {
public:
    /// What PZ_SET_EEPROMPARAMS saves (p. 113) on a gauge reader.
    using Saved = SavedSets<msg::SetTsgIoSettings, msg::SetTpzDispSettings>;
    /// What it also saves on a KSG101 of the later generation: its own blocks.
    using LaterSaved = SavedSets<msg::SetKsgMmiParams, msg::SetKsgTrigIoConfig>;

    /// `gauge` is nullptr when no gauge is fitted (no mounted_on).
    StrainGaugeModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address, WiredStrainGauge* gauge,
                      const Clock& clock, const StrainGaugeConfig& config, spdlog::logger& log, SaveToEeprom save);

    static constexpr bool handles(msg::Family f) { return f == msg::Family::StrainGauge || f == msg::Family::Piezo; }
    void handle(const msg::Message& m, Request& r) override;
    std::string status_update(std::uint8_t host) const override;
    /// The zero is lost with the power, as the zeroed bit is (the gauge body outlives the module).
    void power_down(bool restore_positions) override;
    Ticks next_change(Ticks now) const override;
    void tick(Ticks now) override;
    bool saves(std::uint16_t id) const override;
    std::optional<std::string> saved_data(const msg::Message& m) const override;
    void describe(nlohmann::json& out) const override;
    /// `{"noise_um": x}`: the gauge's noise sigma from now on (x >= 0, finite).
    Refused patch(const nlohmann::json& body) override;

    /// The PZ_GET_PZSTATUSUPDATE status bits (p. 101-104): 0x1 a gauge linked, 0x10 zeroed, 0x20 zeroing.
    std::uint32_t status_bits() const;
    /// The TSG_READING Reading word at `now` in the display mode in force (p. 129, D-15).
    std::int16_t reading_code(Ticks now) const;

    using Module::on;
    void on(const msg::SetTsgIoSettings& m);     ///< MGMSG_PZ_SET_TSG_IOSETTINGS (p. 127)
    void on(const msg::ReqTsgIoSettings& m);     ///< MGMSG_PZ_REQ_TSG_IOSETTINGS (p. 128)
    void on(const msg::TsgReqReading& m);        ///< MGMSG_PZ_REQ_TSG_READING (p. 129)
    void on(const msg::PzAckPzStatusUpdate& m);  ///< MGMSG_PZ_ACK_PZSTATUSUPDATE (p. 105)
    void on(const msg::PzSetEepromParams& m);    ///< MGMSG_PZ_SET_EEPROMPARAMS (p. 113)
    void on(const msg::SetTpzDispSettings& m);   ///< MGMSG_PZ_SET_TPZ_DISPSETTINGS (p. 114)
    void on(const msg::ReqTpzDispSettings& m);   ///< MGMSG_PZ_REQ_TPZ_DISPSETTINGS (p. 114)
    void on(const msg::PzSetZero& m);            ///< MGMSG_PZ_SET_ZERO (p. 117)
    void on(const msg::PzReqMaxTravel& m);       ///< MGMSG_PZ_REQ_MAXTRAVEL (p. 118)
    // The KSG101's own messages of the later protocol issues: its display and trigger-port blocks,
    // kept and answered (rigsim drives no display or trigger port), and the status-update request.
    void on(const msg::PzReqPzStatusUpdate& m);  ///< MGMSG_PZ_REQ_PZSTATUSUPDATE (later issue)
    void on(const msg::SetKsgMmiParams& m);      ///< MGMSG_KSG_SET_KCUBEMMIPARAMS (later issue)
    void on(const msg::ReqKsgMmiParams& m);      ///< MGMSG_KSG_REQ_KCUBEMMIPARAMS (later issue)
    void on(const msg::SetKsgTrigIoConfig& m);   ///< MGMSG_KSG_SET_KCUBETRIGIOCONFIG (later issue)
    void on(const msg::ReqKsgTrigIoConfig& m);   ///< MGMSG_KSG_REQ_KCUBETRIGIOCONFIG (later issue)
    /// The other Piezo and StrainGauge messages: outside the TSG001's MessageSet (p. 134) and the
    /// KSG101's later_takes, so dispatch() never lets one reach here; a model without a set would
    /// log and ignore it.
    template <class T> void on(const T&) { not_mine(); }

private:
    bool linked() const { return gauge_ != nullptr && gauge_->actuator() != nullptr; }
    double travel_um() const;
    /// `um` from the zero as a Reading word in display mode `mode`.
    std::int16_t code_of(double um, std::uint16_t mode) const;

    WiredStrainGauge* gauge_;
    const Clock& clock_;
    double stiffness_n_per_um_;
    int zero_time_ms_;
    std::uint16_t hub_output_;          ///< HubAnalogueOutput: 1 hub A, 2 hub B pairs
    std::uint16_t display_mode_ = 1;    ///< 1 position, 2 voltage, 3 force
    std::uint16_t force_calib_ = 30000; ///< 0.001 N steps (p. 128's default, FSC102)
    std::uint16_t disp_intensity_ = 255;
    Ticks zero_end_ = kNever;           ///< SET_ZERO in progress until this tick
    bool zeroed_ = false;
    msg::KsgMmiParams kcube_mmi_ = ksg_mmi_power_up();      ///< KSG101, later generation
    msg::KsgTrigIoConfig kcube_trig_ = ksg_trig_power_up(); ///< KSG101, later generation
};

/// The gauge reader of device `config` at `address`: its gauge body ("<device>/1", made once,
/// kept across power cycles) mounted on "<mounted_on>/1" when the rig names a piezo driver.
std::unique_ptr<Module> make_strain_gauge_module(const UnitIdentity& unit, std::uint8_t address,
                                                 const DeviceConfig& config, models::World& world,
                                                 spdlog::logger& log, Module::SaveToEeprom save);

} // namespace rigsim::apt
