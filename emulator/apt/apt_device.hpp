#pragma once
// An APT motor controller as a rig device: a single unit (T-Cube/K-Cube, answering as 0x50)
// or a card-slot system (motherboard at 0x11, bays at 0x21 + n). A framer per connection, a
// handler for every message of the manual, one motor channel per bay, and the status updates
// the unit sends by itself (manual sections 4 and 5 (c)).

#include "emulator/apt/catalogue.hpp"
#include "emulator/apt/frame_framer.hpp"
#include "emulator/apt/motor_channel.hpp"
#include "models/clock.hpp"
#include "models/world.hpp"
#include "emulator/core/device.hpp"
#include "emulator/core/rig_config.hpp"
#include "emulator/core/state_store.hpp"

#include <spdlog/logger.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace rigsim::apt {

class AptSession;

class AptDevice : public Device, public Tickable {
public:
    /// Status updates every 100 ms of clock time (section 5 (c)).
    static constexpr std::int64_t kUpdatePeriod_ms = 100;
    /// USB units stop their update messages after 50 without MOT_ACK_DCSTATUSUPDATE.
    static constexpr int kUpdatesWithoutAck = 50;
    /// A frame whose bytes stop for longer than this (clock time) is dropped when the next bytes
    /// arrive. The manual gives no serial timing beyond 115200 baud (2.3), at which a whole
    /// frame of 261 bytes takes 23 ms.
    static constexpr std::int64_t kInterByteTimeout_ms = 50;
    /// HW_RICHRESPONSE code of rigsim's one modelled fault (Thorlabs publishes no code list).
    static constexpr std::uint16_t kFaultCodeStalled = 0x0001;

    /// The device's bodies join `world` under "<device name>/<bay>". `store` keeps what MOT_SET_EEPROMPARAMS saves (nullptr: nothing survives the device).
    AptDevice(const DeviceConfig& config, models::World& world, std::shared_ptr<spdlog::logger> log,
              StateStore* store = nullptr);
    ~AptDevice() override;
    AptDevice(const AptDevice&) = delete;
    AptDevice& operator=(const AptDevice&) = delete;

    std::unique_ptr<Session> open_session(SendFn send, std::string peer) override;

    /// Handle one frame from a connection; answers go to `reply`.
    void handle(const Frame& frame, std::string_view peer, std::string& reply);

    /// The motor channel of a single unit, or of bay `bay` of a rack.
    MotorChannel& channel(std::size_t bay = 0) { return *channels_.at(bay); }
    std::size_t bay_count() const { return channels_.size(); }
    const Clock& clock() const { return clock_; }
    std::uint32_t serial_number() const { return serial_; }
    int identify_count() const { return identify_count_; }

    void attach(AptSession* s) { sessions_.push_back(s); }
    void detach(AptSession* s);

    Ticks next_change(Ticks now) const override;
    void tick(Ticks now) override;

    /// Send end-of-move messages and due status updates to every connection.
    void flush();

private:
    /// The module address a bay answers from: 0x50 for a single unit, 0x21 + bay in a rack.
    std::uint8_t address_of(std::size_t bay) const;
    /// Module-wide messages a motherboard and a bay (or single unit) handle alike: identify,
    /// disconnect, update messages, server alive, flash programming. False if `f` is another.
    bool handle_system(const Frame& f, std::string_view peer);
    void handle_motherboard(const Frame& f, std::string_view peer, std::string& reply);
    void handle_bay(std::size_t bay, const Frame& f, std::string_view peer, std::string& reply);
    /// A rack's built-in channel card with no stage configured: info and status only.
    void handle_empty_bay(std::size_t bay, const Frame& f, std::string_view peer, std::string& reply);
    /// Bays whose channel card is built in (all of a BBD203's or BSC203's).
    std::size_t built_in_bays() const;
    std::string info_packet(std::optional<std::size_t> bay) const;
    std::string status_packet(std::size_t bay) const;      ///< 14 bytes: MOT_GET_STATUSUPDATE layout
    std::string dc_status_packet(std::size_t bay) const;   ///< 14 bytes: MOT_GET_DCSTATUSUPDATE layout
    void start_updates();
    /// Brushless (PMD) parameter trios of a bay: SET stores, REQ answers GET (manual p. 61-76).
    /// Returns false if `f` is not one of them.
    bool handle_pmd(std::size_t bay, const Frame& f, std::string& reply);
    /// MOT_GET_PMDSTAGEAXISPARAMS of a bay's stage (p. 75), without the channel word.
    std::string stage_axis_block(std::size_t bay) const;
    /// MOT_SET_EEPROMPARAMS: save the last SET of message `id` on bay `bay`.
    void save_to_eeprom(std::size_t bay, std::uint16_t id, std::string_view peer);
    /// Replay what the state file holds for this device (power-up from non-volatile memory).
    void restore_from_eeprom();
    void broadcast(const std::string& frame);
    /// The SET being handled was ignored: MOT_SET_EEPROMPARAMS must not save it.
    void forget_set();
    /// HW_RESPONSE or HW_RICHRESPONSE for a fault of bay `bay` (p. 19).
    std::string fault_report(std::size_t bay) const;

    DeviceConfig config_;
    Clock& clock_;
    std::shared_ptr<spdlog::logger> log_;
    const ControllerModel& model_;
    std::vector<std::unique_ptr<MotorChannel>> channels_;
    std::uint32_t serial_;
    std::vector<AptSession*> sessions_;
    bool updates_ = false;                  ///< after HW_START_UPDATEMSGS
    Ticks next_update_ = kNever;
    int updates_since_ack_ = 0;
    bool end_of_move_messages_ = true;      ///< MOT_SUSPEND/RESUME_ENDOFMOVEMSGS
    int identify_count_ = 0;
    std::uint8_t host_ = 0x01;              ///< where replies go (the last requester's source)
    StateStore* store_;
    std::map<std::pair<std::size_t, std::uint16_t>, std::string> pmd_blocks_;   ///< (bay, SET id) -> data after the channel word
    std::map<std::pair<std::size_t, std::uint16_t>, std::string> last_set_;   ///< (bay, SET id) -> data
    std::vector<std::uint16_t> last_move_;  ///< per bay: the message that started its last move
    struct SetUndo {
        std::pair<std::size_t, std::uint16_t> key;
        std::optional<std::string> previous;
    };
    std::optional<SetUndo> set_undo_;       ///< how to take back the SET being handled
    std::map<std::uint8_t, std::uint8_t> digital_outputs_;   ///< rack: bay address (0: motherboard) -> outputs

};

} // namespace rigsim::apt
