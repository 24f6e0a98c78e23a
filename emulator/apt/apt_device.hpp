#pragma once
// A single-unit APT motor controller (T-Cube/K-Cube DC servo) as a rig device: a framer per
// connection, one handler function per message of the manual, the motor channel, and the
// status updates it sends by itself (manual section 5 (c)).

#include "emulator/apt/catalogue.hpp"
#include "emulator/apt/frame_framer.hpp"
#include "emulator/apt/motor_channel.hpp"
#include "emulator/core/clock.hpp"
#include "emulator/core/device.hpp"

#include <spdlog/logger.h>

#include <memory>
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

    AptDevice(const DeviceConfig& config, Clock& clock, std::shared_ptr<spdlog::logger> log);
    ~AptDevice() override;
    AptDevice(const AptDevice&) = delete;
    AptDevice& operator=(const AptDevice&) = delete;

    const DeviceConfig& config() const override { return config_; }
    std::unique_ptr<Session> open_session(SendFn send, std::string peer) override;

    /// Handle one frame from a connection; answers go to `reply`.
    void handle(const Frame& frame, std::string_view peer, std::string& reply);

    MotorChannel& channel() { return channel_; }
    std::uint32_t serial_number() const { return serial_; }
    int identify_count() const { return identify_count_; }

    void attach(AptSession* s) { sessions_.push_back(s); }
    void detach(AptSession* s);

    Ticks next_change(Ticks now) const override;
    void tick(Ticks now) override;

    /// Send end-of-move messages and due status updates to every connection.
    void flush();

private:
    std::string info_packet() const;
    std::string status_packet() const;      ///< 14 bytes: MOT_GET_STATUSUPDATE layout
    std::string dc_status_packet() const;   ///< 14 bytes: MOT_GET_DCSTATUSUPDATE layout
    void broadcast(const std::string& frame);

    DeviceConfig config_;
    Clock& clock_;
    std::shared_ptr<spdlog::logger> log_;
    const ControllerModel& model_;
    const StageModel& stage_;
    MotorChannel channel_;
    std::uint32_t serial_;
    std::vector<AptSession*> sessions_;
    bool updates_ = false;                  ///< after HW_START_UPDATEMSGS
    Ticks next_update_ = kNever;
    int updates_since_ack_ = 0;
    bool end_of_move_messages_ = true;      ///< MOT_SUSPEND/RESUME_ENDOFMOVEMSGS
    int identify_count_ = 0;
    std::uint8_t host_ = 0x01;              ///< where replies go (the last requester's source)
};

} // namespace rigsim::apt
