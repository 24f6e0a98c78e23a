#pragma once
// The modules of a card-slot (rack) system besides its motor cards (section 4): the
// motherboard at 0x11, and a built-in channel card without a stage.

#include "emulator/apt/module.hpp"

#include <map>

namespace rigsim::apt {

/// A rack's motherboard (0x11): its info, which bays are used, its USER IO connector.
class RackMotherboard final : public Module {
public:
    /// `present_bays`: bays with a stage (0x21 .. 0x21 + present_bays - 1).
    RackMotherboard(const UnitIdentity& unit, std::size_t present_bays, spdlog::logger& log);

    /// Act on a message to 0x11 (not a System one: the shell took those).
    void handle(const msg::Message& m, Request& r) override;
    bool saves(std::uint16_t) const override { return false; }
    std::optional<std::string> saved_data(const msg::Message&) const override { return std::nullopt; }

    void on(const msg::HwReqInfo& m);           ///< MGMSG_HW_REQ_INFO (p. 21)
    void on(const msg::RackReqBayUsed& m);      ///< MGMSG_RACK_REQ_BAYUSED (p. 23)
    void on(const msg::RackReqStatusBits& m);   ///< MGMSG_RACK_REQ_STATUSBITS (p. 25)
    void on(const msg::RackSetDigOutputs& m);   ///< MGMSG_RACK_SET_DIGOUTPUTS (p. 26)
    void on(const msg::RackReqDigOutputs& m);   ///< MGMSG_RACK_REQ_DIGOUTPUTS (p. 26)

private:
    /// A digital outputs message names outputs 0..0x0f (SET) of the motherboard (0) or a present bay.
    bool dig_outputs_ok(std::uint8_t outputs, std::uint8_t bay, bool set);

    std::size_t present_bays_;
    std::map<std::uint8_t, std::uint8_t> digital_outputs_;   ///< bay address (0: motherboard) -> outputs
};

/// A rack's built-in channel card with no stage configured: info and status only, with the
/// "motor connected" bit (0x100, p. 77) clear.
class EmptyBay final : public Module {
public:
    /// `answers_dc_status`: a DC card's (not a stepper card's) answers MOT_REQ_DCSTATUSUPDATE.
    EmptyBay(const UnitIdentity& unit, std::size_t bay, bool answers_dc_status, spdlog::logger& log);

    /// Act on a message to this bay (not a System one: the shell took those).
    void handle(const msg::Message& m, Request& r) override;
    bool saves(std::uint16_t) const override { return false; }
    std::optional<std::string> saved_data(const msg::Message&) const override { return std::nullopt; }

    using Module::on;                           ///< MGMSG_HW_REQ_INFO (p. 21)
    void on(const msg::ReqStatusBits& m);       ///< MGMSG_MOT_REQ_STATUSBITS (p. 81)
    void on(const msg::ReqStatusUpdate& m);     ///< MGMSG_MOT_REQ_STATUSUPDATE (p. 78)
    void on(const msg::ReqDcStatusUpdate& m);   ///< MGMSG_MOT_REQ_DCSTATUSUPDATE (p. 80)

private:
    void no_stage();
    bool channel1() const;

    bool answers_dc_status_;
};

} // namespace rigsim::apt
