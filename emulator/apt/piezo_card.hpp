#pragma once
// The MPZ601 piezo module of an MMR601 modular rack (units of today, docs/protocol/apt.md): one bay,
// two piezo channels (Thorlabs/Motion_Control_Examples MMR601: "Piezo and StepperMotor have 2"),
// each a PiezoModule, addressed by the channel word of the message (1 or 2: param1 of a header-only
// message, the first data word of the others), as the manual addresses the channels of its two- and
// three-channel units (p. 15). Each channel sees its messages as its channel 1 and answers so; the
// card puts its own channel back into the answers, its status updates and its unprompted frames.
// HW_REQ_INFO and HUB_REQ_BAYUSED are the card's (its channel 1 answers them); a channel word other
// than 1 or 2 is ignored and logged.

#include "emulator/apt/module.hpp"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace rigsim::apt {

class PiezoCard final : public Module {
public:
    static constexpr std::size_t kChannels = 2;

    PiezoCard(const UnitIdentity& unit, std::size_t bay, std::uint8_t address,
              std::array<std::unique_ptr<Module>, kChannels> channels, spdlog::logger& log);

    void handle(const msg::Message& m, Request& r) override;
    std::string status_update(std::uint8_t host) const override;
    Ticks next_change(Ticks now) const override;
    bool busy(Ticks now) const override;
    void tick(Ticks now) override;
    std::vector<std::string> take_unprompted(std::uint8_t host) override;
    void power_down(bool restore_positions) override;
    /// The MPZ601's list (issue 37 p. 7) has no EEPROMPARAMS: nothing is saved.
    bool saves(std::uint16_t) const override { return false; }
    std::optional<std::string> saved_data(const msg::Message&) const override { return std::nullopt; }
    std::size_t fields_read(std::uint16_t id) const override { return channels_[0]->fields_read(id); }
    void describe(nlohmann::json& out) const override;
    Refused patch(const nlohmann::json& body) override;
    Refused trace(Ticks from, std::size_t max, nlohmann::json& out) const override;
    void set_event_sink(EventSink sink) override;
    bool takes_channel(std::uint16_t sent) const override { return sent == 1 || sent == 2; }

    Module& card_channel(std::size_t c) { return *channels_[c]; }
    const Module& card_channel(std::size_t c) const { return *channels_[c]; }

    /// Frames `frames` (a reply stream) with the channel word of each (param1, or the first data
    /// word) 1 made `to`.
    static std::string rechannel(std::string_view frames, std::uint16_t to);

private:
    std::array<std::unique_ptr<Module>, kChannels> channels_;
};

} // namespace rigsim::apt
