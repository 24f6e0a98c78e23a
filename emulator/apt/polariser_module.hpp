#pragma once
// The polarisation controller module of an MPC320 (three paddles) or MPC220 (two) (module.hpp;
// units of today, docs/protocol/apt.md). Issue 37 p. 29's list: the paddles are addressed as bits
// 1, 2, 4 of the channel byte (QuTech-Delft/QMI mpc320.py, moonshot-nagayama-pj/PnPQ, yaq's
// yaqd-thorlabs: "channels go as 0x01, 0x02, 0x04"); MOVE_ABSOLUTE, MOVE_JOG (POL_PARAMS' jog step
// of the paddle), MOVE_HOME (POL_PARAMS' home position, for every paddle of the mask) and MOVE_STOP
// move them at POL_PARAMS' velocity (10..100 % of 400 deg/s); 0..1370 counts are 0..170 degrees
// (issue 37 p. 408). A move ends with the header-only MOVE_COMPLETED (or MOVE_HOMED), param1 the
// paddle (PnPQ reads 6 bytes); REQ_DCSTATUSUPDATE answers a paddle's position and status
// (pyLabLib, QMI and PnPQ read them so). MOD_SET_CHANENABLESTATE enables the paddles of its mask
// and disables the others ("set the enabled set", QMI); a disabled paddle does not move.
// Each paddle is a models::Paddle, a body of the world.

#include "emulator/apt/module.hpp"
#include "models/clock.hpp"
#include "models/paddle.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace rigsim::apt {

class PolariserModule final : public Module {
public:
    /// The SET MOT_SET_EEPROMPARAMS saves: POL_PARAMS.
    using Saved = SavedSets<msg::SetPolParams>;
    /// 0..170 degrees in 0..1370 counts (issue 37 p. 408).
    static constexpr double kCountsPerDeg = 1370.0 / 170.0;
    static constexpr double kMaxDeg = 170.0;
    /// POL_PARAMS' velocity is a percentage of this (issue 37 p. 408).
    static constexpr double kFullSpeedDegPerS = 400.0;

    PolariserModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address, std::vector<models::Paddle*> paddles,
                    const Clock& clock, spdlog::logger& log, SaveToEeprom save);
    ~PolariserModule() override;

    static constexpr bool handles(msg::Family f)
    {
        // Motor: moves, counters; DcServo: REQ_DCSTATUSUPDATE; Piezo: 0x0686 (the rest is off its list).
        return f == msg::Family::Motor || f == msg::Family::DcServo || f == msg::Family::Polariser
            || f == msg::Family::Piezo;
    }
    void handle(const msg::Message& m, Request& r) override;
    Ticks next_change(Ticks now) const override;
    void tick(Ticks now) override;
    std::vector<std::string> take_unprompted(std::uint8_t host) override;
    void power_down(bool restore_positions) override;
    bool saves(std::uint16_t id) const override { return Saved::saves(id); }
    std::optional<std::string> saved_data(const msg::Message& m) const override { return Saved::data(m); }
    void describe(nlohmann::json& out) const override;
    bool takes_channel(std::uint16_t sent) const override;

    /// A paddle's status word (MOT_GET_DCSTATUSUPDATE, p. 125's bits): 0x10/0x20 moving up/down,
    /// 0x200 homing, 0x400 homed, 0x80000000 enabled.
    std::uint32_t status_bits(std::size_t paddle) const;

    using Module::on;
    void on(const msg::ModSetChanEnableState& m);   ///< the paddles of its mask enabled, the others not
    void on(const msg::ModReqChanEnableState& m);   ///< param2 1 enabled, 0 not (QMI: the MPC320 answers 0)
    void on(const msg::SetPosCounter& m);           ///< MGMSG_MOT_SET_POSCOUNTER: the paddle's counter reads this here
    void on(const msg::ReqPosCounter& m);           ///< MGMSG_MOT_REQ_POSCOUNTER
    void on(const msg::MoveAbsolute& m);            ///< MGMSG_MOT_MOVE_ABSOLUTE: counts 0..1370
    void on(const msg::MoveJog& m);                 ///< MGMSG_MOT_MOVE_JOG: the paddle's jog step up (1) or down (2)
    void on(const msg::MoveHome& m);                ///< MGMSG_MOT_MOVE_HOME: to the home position
    void on(const msg::MoveStop& m);                ///< MGMSG_MOT_MOVE_STOP: stops where they are, MOVE_STOPPED
    void on(const msg::ReqDcStatusUpdate& m);       ///< MGMSG_MOT_REQ_DCSTATUSUPDATE
    void on(const msg::SetEepromParams& m);         ///< MGMSG_MOT_SET_EEPROMPARAMS
    void on(const msg::SetPolParams& m);            ///< MGMSG_MOT_SET_POLPARAMS (issue 37 p. 408)
    void on(const msg::ReqPolParams& m);            ///< MGMSG_MOT_REQ_POLPARAMS
    void on(const msg::MotSetPzStageParamDefaults& m);   ///< 0x0686, RESTOREFACTORYSETTINGS: POL_PARAMS' defaults
    template <class T> void on(const T&) { not_mine(); }

private:
    struct Ended {
        std::uint16_t id;   ///< MOVE_COMPLETED, MOVE_HOMED or MOVE_STOPPED
        std::size_t paddle;
    };
    /// The paddles of channel mask `mask` (bits 1, 2, 4), in order.
    std::vector<std::size_t> paddles_of(std::uint16_t mask) const;
    /// Move paddle `p` to `counts` at POL_PARAMS' velocity; `homing` marks the end as MOVE_HOMED.
    void move(std::size_t p, double counts, bool homing);
    double counts_at(std::size_t p) const;
    void arrived(std::size_t p);

    std::vector<models::Paddle*> paddles_;
    const Clock& clock_;
    msg::PolParams params_{};
    std::vector<bool> paddle_enabled_;
    std::vector<bool> homing_;
    std::vector<bool> homed_;
    std::vector<double> counter_offset_;   ///< counts the counter reads less than the paddle's angle
    std::vector<Ended> ended_;             ///< end-of-move messages not yet sent
};

} // namespace rigsim::apt
