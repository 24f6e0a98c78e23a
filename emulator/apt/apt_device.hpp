#pragma once
// An APT controller as a rig device: a single unit (T-Cube/K-Cube, answering as 0x50) or a
// card-slot system (motherboard at 0x11, bays at 0x21 + n). A framer per connection, the
// System messages, one module per bay of the model's kind (module.hpp; a motor kind's bay
// also has its motor channel), and the status updates the unit sends by itself (manual
// sections 4 and 5 (c)).

#include "emulator/apt/catalogue.hpp"
#include "emulator/apt/codec.hpp"
#include "emulator/apt/frame_framer.hpp"
#include "emulator/apt/motor_channel.hpp"
#include "emulator/apt/module.hpp"
#include "emulator/apt/motor_module.hpp"
#include "emulator/apt/rack_modules.hpp"
#include "emulator/core/control_surface.hpp"
#include "emulator/core/device.hpp"
#include "emulator/core/rig_config.hpp"
#include "emulator/core/wire_log.hpp"
#include "models/clock.hpp"
#include "models/world.hpp"

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace spdlog {
class logger;
}

namespace rigsim {
class EventBus;     // emulator/core/event_bus.hpp
class StateStore;   // emulator/core/state_store.hpp (nlohmann/json, spdlog: kept out of this header)
}

namespace rigsim::apt {

class AptSession;
class WiredStrainGauge;   // strain_gauge_module.hpp

class AptDevice : public Device, public Tickable, public ControlSurface {
public:
    /// Status updates every 100 ms of clock time (section 5 (c)).
    static constexpr std::int64_t kUpdatePeriod_ms = 100;
    /// USB units stop their update messages after this many without the model's acknowledgement
    /// (ControllerModel::ack_id: MOT_ACK_DCSTATUSUPDATE p. 80, PZ_ACK_PZSTATUSUPDATE p. 105: 50;
    /// PZMOT_ACK_STATUSUPDATE, issue 37 p. 406: 10).
    int updates_without_ack() const { return model_.updates_without_ack; }
    /// The wire log warns when this many went unacknowledged, four fifths of the cut-off (40 of
    /// 50; docs/control-api/apt.md "Notes").
    int updates_warn_at() const { return model_.updates_without_ack * 4 / 5; }
    /// A frame whose bytes stop for longer than this (clock time) is dropped when the next bytes
    /// arrive. The manual gives no serial timing beyond 115200 baud (2.3), at which a whole
    /// frame of 261 bytes takes 23 ms.
    static constexpr std::int64_t kInterByteTimeout_ms = 50;
    /// HW_RICHRESPONSE code of rigsim's one modelled fault (Thorlabs publishes no code list).
    static constexpr std::uint16_t kFaultCodeStalled = 0x0001;
    /// The serial line of every APT unit: 115200 baud, 8 data bits, 1 stop bit, no parity
    /// (2.1, the FTDI chip's set-up; 2.3, the RS-232 port): 10 bits a byte.
    static constexpr std::uint32_t kBaudRate = 115200;

    /// The device's bodies join `world` under "<device name>/<bay>". `store` keeps what MOT_SET_EEPROMPARAMS saves (nullptr: nothing survives the device).
    AptDevice(const DeviceConfig& config, models::World& world, std::shared_ptr<spdlog::logger> log,
              StateStore* store = nullptr, EventBus* events = nullptr);
    ~AptDevice() override;
    AptDevice(const AptDevice&) = delete;
    AptDevice& operator=(const AptDevice&) = delete;

    std::unique_ptr<Session> open_session(SendFn send, std::string peer) override;
    /// With the rig's `faithful_timing`, the pty's line runs at kBaudRate (the link paces it on
    /// the clock, as for an MCS); without it, 0: unpaced.
    std::uint32_t serial_baud() const override { return config_.faithful_timing ? kBaudRate : 0; }
    /// The unit's serial port runs at kBaudRate, paced or not.
    std::uint32_t line_baud() const override { return kBaudRate; }
    /// After World::link_all(): a piezo driver finds the gauge mounted on its actuator, then the
    /// device replays what the state file holds, as the unit loads its EEPROM at power-up.
    void power_up() override;
    /// A strain gauge reader powers up first: a piezo driver's saved closed loop reads the hub
    /// output the reader restores (TSG_IOSETTINGS, p. 127).
    int power_up_phase() const override;

    /// Handle one frame from a connection; answers go to `reply`.
    void handle(const Frame& frame, std::string_view peer, std::string& reply);

    /// The motor channel of a single unit, or of bay `bay` of a rack (motor kinds only).
    MotorChannel& channel(std::size_t bay = 0) { return *channels_.at(bay); }
    /// The module of a single unit, or of bay `bay` of a rack.
    Module& module(std::size_t bay = 0) { return *modules_.at(bay); }
    std::size_t bay_count() const { return modules_.size(); }
    const Clock& clock() const { return clock_; }
    std::uint32_t serial_number() const { return serial_; }
    int identify_count() const { return identify_count_; }

    void attach(AptSession* s) { sessions_.push_back(s); }
    void detach(AptSession* s);

    Ticks next_change(Ticks now) const override;
    void tick(Ticks now) override;
    /// Its next change may have moved outside a tick (a session's messages handled, a session
    /// opened or closed): tell the clock (models/clock.hpp, "The schedule").
    void announce_change() { clock_.changed(*this); }

    /// Send end-of-move messages and what the modules sent by themselves to every connection.
    void flush();

    // ---- Control API (docs/control-api/apt.md); apt_control.cpp ----
    /// The device is its own control surface (apt_control.cpp).
    ControlSurface* control() override { return this; }
    void describe(nlohmann::json& out) const override;
    Refused patch_channel(std::size_t index, const nlohmann::json& body) override;
    /// reference_lost: the bay's motor is no longer homed.
    Refused add_fault(const DeviceFault& f, bool* kept) override;
    /// A motor bay's stage; the other kinds of unit have no motor for a physical fault to act on.
    Refused fault_body(const DeviceFault& f, std::string& out) const override;
    /// Each motor bay reads its stage's faults (a failed encoder freezes its counters).
    void faults_changed() override;
    void power_cycle(const PowerCycle& how) override;
    /// A module busy (Module::busy(): a piezo settling or running its LUT, a solenoid cycling, a
    /// gauge zeroing) or a motor's end-of-move not yet sent; status updates do not count.
    bool busy() const override;
    Refused trace(std::size_t index, std::int64_t from_tick, std::size_t max, nlohmann::json& out) const override;
    /// A motor bay's stage, a piezo bay's actuator; solenoid outputs and gauges move nothing (400).
    Refused axis_body_key(std::size_t index, std::string& out) const override;
    Refused channel_body_key(std::size_t index, std::string& out) const override;
    WireLog& wire_log() override { return wire_log_; }
    /// Record one frame crossing the wire of connection `peer` (notes: the client's mistakes).
    void record(bool inbound, std::string_view peer, std::string_view frame, std::vector<std::string> notes = {},
                bool unprompted = false);

private:
    /// handle() without the wire log: the frame to its module.
    void route(const Frame& frame, std::string_view peer, std::string& reply);
    /// The module address a bay answers from: 0x50 for a single unit, 0x21 + bay in a rack.
    std::uint8_t address_of(std::size_t bay) const;
    /// The module of this controller's unit kind (ControllerModel::kind) for bay `bay`.
    std::unique_ptr<Module> make_module(std::size_t bay);
    /// The solenoid module of bay `bay` over its output in the world (TSC001, KSC101).
    std::unique_ptr<Module> make_solenoid_module(std::size_t bay, Module::SaveToEeprom save);
    /// Bays with a module: a rack's configured bays (stages or piezo bays), else 1.
    std::size_t rack_bays() const;
    /// The piezo module of bay `bay` over its actuator (world key "<device>/<bay+1>").
    std::unique_ptr<Module> make_piezo_module(std::size_t bay, Module::SaveToEeprom save);
    /// One piezo channel of `bay` (`card_channel` 0 but on a two-channel card) over its world body.
    std::unique_ptr<Module> make_piezo_channel(std::size_t bay, std::size_t card_channel, Module::SaveToEeprom save);
    /// The world key of the actuator of `bay`'s channel `card_channel`.
    std::string piezo_key(std::size_t bay, std::size_t card_channel) const;
    /// A TPZ/KPZ's feedback: the gauge of the (linked) world mounted on its actuator, if any.
    void connect_feedback(std::size_t bay);
    /// The module of this controller's motor kind for bay `bay`.
    std::unique_ptr<MotorModule> make_motor_module(std::size_t bay, Module::SaveToEeprom save);
    /// The motor module of bay `bay` (motor kinds: every bay with a channel has one).
    MotorModule& motor_module(std::size_t bay) const { return static_cast<MotorModule&>(*modules_[bay]); }
    /// A message for bay `bay` (or a single unit): the shell's System messages, else the
    /// bay's module; a SET it accepts is kept for MOT_SET_EEPROMPARAMS.
    void handle_bay(std::size_t bay, const msg::Message& m, Request& r);
    /// Module-wide messages (the System family and the model's server-alive acknowledgement)
    /// every module address acts on alike: identify, disconnect, update messages, server alive,
    /// end-of-move messages, flash programming. False if `m` is another.
    bool handle_system(const msg::Message& m, std::string_view peer);
    void on(const msg::ModIdentify& m, std::string_view peer);            ///< MGMSG_MOD_IDENTIFY (p. 16)
    void on(const msg::HwDisconnect& m, std::string_view peer);           ///< MGMSG_HW_DISCONNECT (p. 19)
    void on(const msg::HwStartUpdateMsgs& m, std::string_view peer);      ///< MGMSG_HW_START_UPDATEMSGS (p. 20)
    void on(const msg::HwStopUpdateMsgs& m, std::string_view peer);       ///< MGMSG_HW_STOP_UPDATEMSGS (p. 20)
    void on(const msg::HwYesFlashProgramming& m, std::string_view peer);  ///< MGMSG_HW_YES_FLASH_PROGRAMMING
    void on(const msg::HwNoFlashProgramming& m, std::string_view peer);   ///< MGMSG_HW_NO_FLASH_PROGRAMMING
    void on(const msg::SuspendEndOfMoveMsgs& m, std::string_view peer);   ///< MGMSG_MOT_SUSPEND_ENDOFMOVEMSGS (p. 82)
    void on(const msg::ResumeEndOfMoveMsgs& m, std::string_view peer);    ///< MGMSG_MOT_RESUME_ENDOFMOVEMSGS (p. 83)
    void on(const msg::AckDcStatusUpdate& m, std::string_view peer);      ///< MGMSG_MOT_ACK_DCSTATUSUPDATE (p. 80)
    /// The host acknowledged the status updates (ControllerModel::ack_id).
    void server_alive();
    void start_updates();
    /// MOT_SET_EEPROMPARAMS (PZ_SET_EEPROMPARAMS): save the last SET of message `id` on bay `bay`.
    void save_to_eeprom(std::size_t bay, std::uint16_t id, std::string_view peer);
    /// Keep `m` if it is a SET that the bay's module saves (Module::saved_data).
    void remember(std::size_t bay, const msg::Message& m);
    /// Replay the rig's "eeprom" entries, then what the state file holds for this device
    /// (power-up from non-volatile memory). A rig entry the unit refuses is a ConfigError at the
    /// first power-up (`first`), a warning at a power cycle (the rig was taken at start).
    void restore_from_eeprom(bool first);
    /// Replays one entry (key "bay0/0x0413", its data in hex) from `from` ("rig", "state file":
    /// the peer of the request) as if a client had sent the SET; why it is not one the bay saves and takes, if not.
    std::optional<std::string> restore_entry(const std::string& key, const std::string& hex, const char* from);
    void broadcast(const std::string& frame, std::vector<std::string> notes = {});
    /// Note on the frame being handled (the wire log's entry for it).
    void note(std::string text) { notes_.push_back(std::move(text)); }
    /// The channel object of bay `bay` (docs/control-api/apt.md "Channels").
    nlohmann::json channel_json(std::size_t bay) const;
    /// Bay `bay`'s module publishes its events (lut_started, lut_ended, solenoid) on the stream.
    void connect_events(std::size_t bay);
    /// Events "move_started", "move_ended" and "status" for the control API's listeners.
    void publish_events(std::size_t bay, const std::vector<MotorEvent>& events);
    /// The notes a status update or end-of-move message earns (the unacknowledged count).
    std::vector<std::string> update_notes() const;
    /// HW_RESPONSE or HW_RICHRESPONSE for a fault of bay `bay` (p. 19).
    std::string fault_report(std::size_t bay) const;

    DeviceConfig config_;
    Clock& clock_;
    models::World& world_;   ///< where a module kind's bodies live (a solenoid's output)
    std::shared_ptr<spdlog::logger> log_;
    const ControllerModel& model_;
    std::uint32_t serial_;
    UnitIdentity unit_;
    std::vector<std::unique_ptr<MotorChannel>> channels_;  ///< per bay with a stage (motor kinds)
    std::vector<std::unique_ptr<Module>> modules_;         ///< per bay (with a stage, for a motor kind)
    std::unique_ptr<RackMotherboard> motherboard_;          ///< racks only
    std::vector<std::unique_ptr<EmptyBay>> empty_bays_;     ///< a rack's built-in bays past the last stage
    std::vector<AptSession*> sessions_;
    bool updates_ = false;                  ///< after HW_START_UPDATEMSGS
    Ticks next_update_ = kNever;
    int updates_since_ack_ = 0;
    bool end_of_move_messages_ = true;      ///< MOT_SUSPEND/RESUME_ENDOFMOVEMSGS
    /// Addressed as a single unit (ControllerModel::wrong_address_freezes): deaf until a power cycle.
    bool frozen_ = false;
    int identify_count_ = 0;
    std::uint8_t host_ = 0x01;              ///< where replies go (the last requester's source)
    bool linked_ = false;                   ///< power_up() ran: the world's bodies are linked
    WiredStrainGauge* routed_gauge_ = nullptr;   ///< the gauge whose route this TPZ/KPZ's input follows
    StateStore* store_;
    EventBus* events_;   ///< the control API's event stream, or nullptr
    /// (bay, SET id) -> the last accepted, as its module stores it (Module::saved_data).
    std::map<std::pair<std::size_t, std::uint16_t>, std::string> last_set_;

    WireLog wire_log_;
    std::vector<std::string> notes_;                 ///< on the frame being handled
    std::vector<std::uint32_t> published_status_;    ///< per bay: the status bits last published
    std::vector<bool> was_moving_;                   ///< per bay: moving after the last flush
    std::vector<bool> stalled_;                      ///< per bay: a Fault event waits for its Stopped
};

} // namespace rigsim::apt
