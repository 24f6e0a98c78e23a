#pragma once
// The piezo inertia motor module of a KIM101 (K-Cube) or TIM101 (T-Cube): four channels, each a
// PIA actuator driven open loop (module.hpp; units of today, docs/protocol/apt.md), after Thorlabs'
// "Motion Controllers Host-Controller Communications Protocol" issue 37 p. 370-406:
// - the channel words of the data are bits 1, 2, 4, 8 (p. 372-405), and so is PZMOT_MOVE_JOG's
//   param1, as the units answer (InstrumentKit issue 372; docs/protocol/errata.md "Units of today");
//   a channel word that is no single bit of the four is ignored and logged;
// - PZMOT_SET/REQ/GET_PARAMS' sub-messages: each model takes its own (p. 371: the TIM101 0x05,
//   0x07, 0x09, 0x11, 0x13; the KIM101 0x05, 0x07, 0x0B, 0x0F (no SET), 0x15, 0x17, 0x19, 0x2B,
//   0x2D, 0x30, 0x32, 0x34); the blocks are kept per channel (0x17 and 0x2B per unit) and answered
//   as set; 0x05 sets and reads the position counter;
// - only the enabled channels move (p. 370; infn-epics thorlabs-apt-motor: "the KIM101 can only move
//   the currently selected channel"; foxtrot's TIM101: "nothing will happen"): the KIM101's
//   ChanEnableMode (0x2B: none, one channel, or the pairs 1+2 and 3+4) or, on both models,
//   MOD_SET_CHANENABLESTATE, which selects its channel (state 1) or disables it (state 2); channel 1
//   at power-up;
// - PZMOT_MOVE_ABSOLUTE drives the pulses from the counter to the target at DriveOPParams' step rate
//   and acceleration; PZMOT_MOVE_JOG a jog step (the KIM101's KCubeJogParams: a step count for each
//   direction; the TIM101's TIM_JogParams: one) or, in continuous mode, until MOT_MOVE_STOP or a
//   MOVE_JOG with direction 0 (InstrumentKit's stop); each end, and each stop, sends
//   PZMOT_MOVE_COMPLETED (p. 403: channel, counter, two unused words);
// - PZMOT_GET_STATUSUPDATE (p. 405) every 100 ms after HW_START_UPDATEMSGS and on
//   PZMOT_REQ_STATUSUPDATE: the four channels' counters and status bits (moving 0x10/0x20, jogging
//   0x40/0x80, connected 0x100, enabled 0x80000000).
// Each channel's actuator is a models::InertialDrive, a body of the world: its counter counts
// pulses, the screw moves by their lengths (forward and reverse differ).

#include "emulator/apt/module.hpp"
#include "models/clock.hpp"
#include "models/inertial_drive.hpp"

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace rigsim::apt {

class PzMotorModule final : public Module {
public:
    static constexpr std::size_t kChannels = 4;

    PzMotorModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address,
                  std::vector<models::InertialDrive*> drives, spdlog::logger& log, SaveToEeprom save);
    ~PzMotorModule() override;

    static constexpr bool handles(msg::Family f)
    {
        // PzMotor: the PZMOT family; Motor: MOVE_STOP and SET_EEPROMPARAMS (its list, kPzmot);
        // Untyped: a PZMOT_SET_PARAMS whose sub-message it does not know, logged as such.
        return f == msg::Family::PzMotor || f == msg::Family::Motor || f == msg::Family::Untyped;
    }
    void handle(const msg::Message& m, Request& r) override;
    std::string status_update(std::uint8_t host) const override;
    Ticks next_change(Ticks now) const override;
    void tick(Ticks now) override;
    std::vector<std::string> take_unprompted(std::uint8_t host) override;
    void power_down(bool restore_positions) override;
    bool saves(std::uint16_t) const override { return false; }
    std::optional<std::string> saved_data(const msg::Message&) const override { return std::nullopt; }
    void describe(nlohmann::json& out) const override;
    /// Every channel word reaches the handlers, which check it where the message carries it.
    bool takes_channel(std::uint16_t) const override { return true; }

    /// Channel `c`'s (0..3) position counter, in pulses.
    std::int32_t counter(std::size_t c) const;
    /// Channel `c`'s status bits (p. 405).
    std::uint32_t status_bits(std::size_t c) const;
    /// The enabled channels as bits 1, 2, 4, 8.
    std::uint16_t enabled_mask() const { return enabled_mask_; }
    const models::InertialDrive& drive(std::size_t c) const { return *drives_[c]; }

    using Module::on;
    void on(const msg::ModSetChanEnableState& m);   ///< selects (1) or disables (2) the channel of its bit
    void on(const msg::ModReqChanEnableState& m);   ///< 1 enabled, 2 not
    void on(const msg::PzmotSetParams& m);          ///< MGMSG_PZMOT_SET_PARAMS (p. 371)
    void on(const msg::PzmotReqParams& m);          ///< MGMSG_PZMOT_REQ_PARAMS: GET_PARAMS with the block
    void on(const msg::PzmotMoveAbsolute& m);       ///< MGMSG_PZMOT_MOVE_ABSOLUTE (p. 402)
    void on(const msg::PzmotMoveJog& m);            ///< MGMSG_PZMOT_MOVE_JOG (p. 404)
    void on(const msg::PzmotReqStatusUpdate& m);    ///< MGMSG_PZMOT_REQ_STATUSUPDATE (p. 405)
    void on(const msg::MoveStop& m);                ///< MGMSG_MOT_MOVE_STOP: stops the channel of param1's bit
    void on(const msg::SetEepromParams& m);         ///< MGMSG_MOT_SET_EEPROMPARAMS: nothing a public source names
    void on(const msg::Untyped& m);                 ///< a sub-message it does not know, or short of its block
    template <class T> void on(const T&) { not_mine(); }

private:
    enum class Motion { None, Move, Jog };
    /// The channel (0..3) of channel word `bits`, if it is one of the bits 1, 2, 4, 8.
    static std::optional<std::size_t> channel_of_bit(std::uint16_t bits);
    /// Whether this model takes sub-message `sub` (p. 371); `set`: as a SET (0x0F is REQ/GET only).
    bool takes_sub(std::uint16_t sub, bool set) const;
    /// The block the unit keeps for sub-message `sub` on channel `c` (unit-wide blocks: c ignored).
    msg::PzmotBlock& block(std::uint16_t sub, std::size_t c);
    /// The channel word's channel, or log and ignore the message (`what` names the word).
    std::optional<std::size_t> channel_or_ignore(std::uint16_t bits, std::string_view what);
    /// Enable the channels of `mask` only; a channel that is no longer enabled stops.
    void enable_only(std::uint16_t mask);
    /// Drive channel `c`: `pulses` in `direction` (nullopt: until stopped).
    void run(std::size_t c, Motion motion, int direction, std::optional<std::int64_t> pulses, std::int32_t rate,
             std::int32_t accn);
    /// Stop channel `c` where it is; MOVE_COMPLETED follows if it was moving.
    void stop(std::size_t c);
    void arrived(std::size_t c);
    bool kim() const;

    std::vector<models::InertialDrive*> drives_;   ///< each reads the world's clock
    std::map<std::pair<std::uint16_t, std::size_t>, msg::PzmotBlock> blocks_;
    std::array<std::int64_t, kChannels> counter_base_{};   ///< drive pulses at counter 0
    std::array<Motion, kChannels> motion_{};
    std::uint16_t enabled_mask_ = 0x01;
    std::vector<std::size_t> ended_;   ///< channels whose MOVE_COMPLETED is not yet sent
};

} // namespace rigsim::apt
