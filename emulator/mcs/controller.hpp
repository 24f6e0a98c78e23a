#pragma once
// An MCS controller: system-wide settings and its channels. No I/O.

#include "emulator/mcs/config.hpp"
#include "emulator/mcs/channel.hpp"
#include "emulator/mcs/commands.hpp"
#include "emulator/mcs/end_effector.hpp"
#include "models/clock.hpp"
#include "models/world.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace rigsim::mcs {

/// A version triple: GIV's interface version (RS232 form, manual 3.1), GFV's firmware versions (3.5).
struct InterfaceVersion {
    std::int64_t high = 1;
    std::int64_t low = 2;
    std::int64_t update = 44;
};

enum class CommunicationMode : int { Sync = 0, Async = 1 };

class Controller : public Tickable {
public:
    static constexpr std::int32_t kDefaultBaudrate = 9600;   ///< factory default (1.2)

    /// Channel n's positioner joins `world` under "<device>/<n>".
    Controller(const McsConfig& config, models::World& world, const std::string& device);

    std::size_t channel_count() const { return channels_.size(); }
    /// The positioners (channels that are no end effector), in index order.
    const std::vector<Channel*>& positioners() const { return positioners_; }
    /// The positioner with this index, or nullptr (out of range, or an end effector).
    Channel* channel(std::int32_t index) { return valid_index(index) ? channels_[static_cast<std::size_t>(index)].get() : nullptr; }
    const Channel* channel(std::int32_t index) const { return const_cast<Controller*>(this)->channel(index); }
    /// The end effector with this index, or nullptr.
    EndEffector* effector(std::int32_t index);
    const EndEffector* effector(std::int32_t index) const;
    bool valid_index(std::int32_t index) const
    {
        return index >= 0 && static_cast<std::size_t>(index) < channels_.size();
    }
    /// SRC for an end effector channel.
    void set_effector_report(std::int32_t index, bool report);

    std::uint32_t system_id() const { return system_id_; }
    /// GIV: the configured interface version (default 1.2.44, the manual's title page).
    InterfaceVersion interface_version() const { return interface_version_; }
    /// GFV: signal controller and generator firmware (the manual documents no number).
    InterfaceVersion firmware_version() const { return {1, 5, 0}; }

    CommunicationMode communication_mode() const { return mode_; }
    void set_communication_mode(CommunicationMode m) { mode_ = m; }

    /// SSE: system-wide sensor mode; stops every positioner.
    void set_sensor_mode(SensorMode mode);
    SensorMode sensor_mode() const { return sensor_mode_; }

    /// SHE: hand control module mode 0..2 (no HCM is attached to an emulated controller).
    void set_hcm_mode(std::int32_t mode) { hcm_mode_ = mode; }

    /// K: timeout in ms (0 = off); resets the timeout counter.
    void set_keep_alive(std::int32_t timeout_ms);
    /// Any command that could be parsed resets the keep-alive counter (K).
    void note_command();

    /// CB: stores the baud rate for the next reset; returns the rate the controller's baud
    /// rate generator really produces (CB57600 -> BR57142).
    std::int32_t configure_baudrate(std::int32_t baudrate);
    /// Baud rate of the serial interface since the last reset.
    std::int32_t baudrate() const { return baudrate_; }

    /// R: power-down/power-up: channels back to their power-up state, synchronous mode,
    /// keep-alive off; non-volatile settings (sensor types and mode, scales, baud rate) kept.
    void reset();
    /// Non-volatile settings back to the config (sensor types and mode, scales, safe
    /// directions, baud rate, end effector types): a power cycle that erases them.
    void restore_defaults();
    /// Every stage back at its configured start position.
    void place_at_start();
    /// The keep-alive timeout expired since the last call (K).
    bool take_keep_alive_expired()
    {
        const bool e = keep_alive_expired_;
        keep_alive_expired_ = false;
        return e;
    }
    std::int32_t keep_alive_ms() const { return keep_alive_ms_; }
    std::int32_t hcm_mode() const { return hcm_mode_; }
    /// The baud rate CB stored for the next reset.
    std::int32_t configured_baudrate() const { return configured_baudrate_; }

    void stop_all();

    /// GESM/SESM (deprecated system-wide emergency stop mode, 3.2).
    std::int32_t emergency_stop_mode() const { return esm_mode_; }
    void set_emergency_stop_mode(std::int32_t mode);
    /// A pulse on the ES line: every channel reacts per its emergency stop mode (2.2.1).
    void emergency_stop_pulse();
    /// An event of a trigger source reaches every channel's receivers (2.4, TC).
    void trigger(std::int32_t source);

    /// Messages sent by the controller by itself, to every connection: filled during
    /// tick() (asynchronous mode only), emptied by the device.
    std::vector<Reply>& outbox() { return outbox_; }
    /// Move channel events to the outbox (asynchronous mode) or drop them (sync mode).
    void collect_events();

    Ticks next_change(Ticks now) const override;
    void tick(Ticks now) override;
    /// Some channel or end effector changes by itself after `now` (the keep-alive deadline aside).
    bool busy(Ticks now) const;

private:
    const Clock& clock_;
    std::uint32_t system_id_;
    InterfaceVersion interface_version_;
    std::vector<std::unique_ptr<Channel>> channels_;   ///< one per index; nullptr at an end effector's
    std::vector<Channel*> positioners_;               ///< the positioners of channels_, in index order
    std::vector<std::unique_ptr<EndEffector>> effectors_;   ///< non-null for end effector indices
    bool any_effector_ = false;                       ///< some entry of effectors_ is non-null
    std::vector<bool> effector_report_;
    CommunicationMode mode_ = CommunicationMode::Sync;
    SensorMode sensor_mode_ = SensorMode::Enabled;
    std::int32_t hcm_mode_ = 1;
    std::int32_t esm_mode_ = 0;
    std::int32_t keep_alive_ms_ = 0;
    Ticks keep_alive_deadline_ = kNever;
    bool keep_alive_expired_ = false;
    std::int32_t baudrate_ = kDefaultBaudrate;
    std::int32_t configured_baudrate_ = kDefaultBaudrate;
    std::vector<Reply> outbox_;
};

} // namespace rigsim::mcs
