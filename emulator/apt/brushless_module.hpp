#pragma once
// The brushless DC module (a BBD203 bay's card driving an MLS203 axis or a DDSM100): the DC
// motor messages and the PMD parameter trios of the manual's p. 61-76.

#include "emulator/apt/motor_module.hpp"

namespace rigsim::apt {

class BrushlessModule final : public DcMotorModule {
public:
    BrushlessModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address, MotorChannel& channel,
                    spdlog::logger& log, SaveToEeprom save);
    using DcMotorModule::on;
    static constexpr bool handles(msg::Family f)
    {
        return f == msg::Family::Motor || f == msg::Family::DcServo || f == msg::Family::Pmd
               || f == msg::Family::KCubeMotor;
    }
    void handle(const msg::Message& m, Request& r) override;

    void on(const msg::SetPmdPositionLoopParams& m);          ///< MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS (p. 61)
    void on(const msg::ReqPmdPositionLoopParams& m);          ///< MGMSG_MOT_REQ_PMDPOSITIONLOOPPARAMS (p. 61)
    void on(const msg::SetPmdMotorOutputParams& m);           ///< MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS (p. 64)
    void on(const msg::ReqPmdMotorOutputParams& m);           ///< MGMSG_MOT_REQ_PMDMOTOROUTPUTPARAMS (p. 64)
    void on(const msg::SetPmdTrackSettleParams& m);           ///< MGMSG_MOT_SET_PMDTRACKSETTLEPARAMS (p. 66)
    void on(const msg::ReqPmdTrackSettleParams& m);           ///< MGMSG_MOT_REQ_PMDTRACKSETTLEPARAMS (p. 66)
    void on(const msg::SetPmdProfileModeParams& m);           ///< MGMSG_MOT_SET_PMDPROFILEMODEPARAMS (p. 69)
    void on(const msg::ReqPmdProfileModeParams& m);           ///< MGMSG_MOT_REQ_PMDPROFILEMODEPARAMS (p. 69)
    void on(const msg::SetPmdCurrentLoopParams& m);           ///< MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS (p. 71)
    void on(const msg::ReqPmdCurrentLoopParams& m);           ///< MGMSG_MOT_REQ_PMDCURRENTLOOPPARAMS (p. 71)
    void on(const msg::SetPmdSettledCurrentLoopParams& m);    ///< MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS (p. 73)
    void on(const msg::ReqPmdSettledCurrentLoopParams& m);    ///< MGMSG_MOT_REQ_PMDSETTLEDCURRENTLOOPPARAMS (p. 73)
    void on(const msg::SetPmdStageAxisParams& m);             ///< MGMSG_MOT_SET_PMDSTAGEAXISPARAMS (p. 75)
    void on(const msg::ReqPmdStageAxisParams& m);             ///< MGMSG_MOT_REQ_PMDSTAGEAXISPARAMS (p. 75)

private:
    /// MOT_GET_PMDSTAGEAXISPARAMS of the bay's stage (p. 75).
    msg::PmdStageAxisParams stage_axis_params() const;

    // What the SETs stored, zeros until then (p. 61-73: the unit keeps them as sent).
    msg::PmdPositionLoopParams position_loop_{};
    msg::PmdMotorOutputParams motor_output_{};
    msg::PmdTrackSettleParams track_settle_{};
    msg::PmdProfileModeParams profile_mode_{};
    msg::PmdCurrentLoopParams current_loop_{};
    msg::PmdSettledCurrentLoopParams settled_current_loop_{};
};

} // namespace rigsim::apt
