#pragma once
// The flip mount module of an MFF101/MFF102 (module.hpp; units of today, docs/protocol/apt.md).
// Its list (Thorlabs' later protocol issue 37, p. 20) is short: MOT_MOVE_JOG takes the arm to
// position 1 or 2, MOT_REQ_STATUSBITS says where it is, MFF_OPERPARAMS holds the transit time and
// the two digital I/O ports' set-up, MOT_SET_EEPROMPARAMS saves that block. The arm is
// models::Flipper, the body in the world that times the transit; on arrival the unit sends
// MOT_MOVE_COMPLETED with its status (amsikking/thorlabs_MFF101 reads 20 bytes after a jog).

#include "emulator/apt/module.hpp"
#include "models/clock.hpp"
#include "models/flipper.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace rigsim::apt {

class FlipperModule final : public Module {
public:
    /// The SET MOT_SET_EEPROMPARAMS saves: the operating parameters.
    using Saved = SavedSets<msg::SetMffOperParams>;

    /// `power_up_position`: where the rig puts the arm (1 or 2), where a power cycle that
    /// restores the mechanics puts it back.
    FlipperModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address, models::Flipper& arm,
                  int power_up_position, const Clock& clock, spdlog::logger& log, SaveToEeprom save);
    ~FlipperModule() override;

    static constexpr bool handles(msg::Family f) { return f == msg::Family::Motor || f == msg::Family::Flipper; }
    void handle(const msg::Message& m, Request& r) override;
    Ticks next_change(Ticks now) const override;
    void tick(Ticks now) override;
    std::vector<std::string> take_unprompted(std::uint8_t host) override;
    void power_down(bool restore_positions) override;
    bool saves(std::uint16_t id) const override { return Saved::saves(id); }
    std::optional<std::string> saved_data(const msg::Message& m) const override { return Saved::data(m); }
    void describe(nlohmann::json& out) const override;

    /// MOT_GET_STATUSBITS: 0x01 at position 1, 0x02 at position 2 (the limit bits, as every
    /// driver reads them: MSLNZ/msl-equipment mff.py, QuTech-Delft/QMI mff10x.py, pyLabLib); while
    /// the arm travels, 0x10 toward position 1 and 0x20 toward position 2 (the jog's direction
    /// 1 forward, 2 reverse; pyLabLib reads any of 0x2F0 as moving, msl-equipment 0x10).
    std::uint32_t status_bits() const;

    using Module::on;
    void on(const msg::MoveJog& m);                ///< MGMSG_MOT_MOVE_JOG: direction 1 or 2 is the position
    void on(const msg::ReqStatusBits& m);          ///< MGMSG_MOT_REQ_STATUSBITS
    void on(const msg::SetEepromParams& m);        ///< MGMSG_MOT_SET_EEPROMPARAMS
    void on(const msg::SetMffOperParams& m);       ///< MGMSG_MOT_SET_MFF_OPERPARAMS (issue 37 p. 182)
    void on(const msg::ReqMffOperParams& m);       ///< MGMSG_MOT_REQ_MFF_OPERPARAMS
    /// Every other message of the Motor and Flipper families is off the MFF's list (the module's
    /// taken() has logged and ignored it before): nothing to do.
    template <class T> void on(const T&) { not_mine(); }

private:
    /// Publish "flipper" and queue MOVE_COMPLETED for the arrival at `position`.
    void arrived(int position);

    models::Flipper& arm_;
    int power_up_position_;
    const Clock& clock_;
    msg::MffOperParams params_{};   ///< issue 37's example values: 500 ms, toggle inputs on buttons, 200 ms
    std::vector<int> arrivals_;     ///< arrivals not yet reported
};

} // namespace rigsim::apt
