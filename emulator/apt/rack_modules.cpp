#include "emulator/apt/rack_modules.hpp"
#include "emulator/core/log_format.hpp"


#include <type_traits>

namespace rigsim::apt {

RackMotherboard::RackMotherboard(const UnitIdentity& unit, std::size_t present_bays, spdlog::logger& log)
    : Module(unit, 0, kRack, log, nullptr), present_bays_(present_bays)
{
}

void RackMotherboard::handle(const msg::Message& m, Request& r)
{
    request_ = &r;
    msg::visit(
        [this](const auto& typed) {
            using T = std::decay_t<decltype(typed)>;
            if constexpr (T::family == msg::Family::Rack || std::is_same_v<T, msg::HwReqInfo>)
                on(typed);
            else if constexpr (T::family != msg::Family::System) {   // another module's message
                log_.warn("{}: {} to the motherboard: it acts on no such message, ignored", request_->peer,
                          request_->frame.info->name);
                request_->ignored = true;
                request_->why = "the motherboard (0x11) acts on no such message";
            }
        },
        m);
}

void RackMotherboard::on(const msg::HwReqInfo&)
{
    answer(hw_get_info(unit_, std::nullopt));
}

void RackMotherboard::on(const msg::RackReqBayUsed& m)
{
    // p. 23: "Is controller bay #1 (i.e. bay 0) occupied": bays are numbered from 0 here.
    // The BBD203's and BSC203's channel cards are built in: every bay is occupied, with a
    // stage or not (a card without one reports its motor not connected).
    answer(msg::RackGetBayUsed{m.bay_ident, static_cast<std::uint8_t>(m.bay_ident < unit_.built_in_bays ? 1 : 2)});
}

void RackMotherboard::on(const msg::RackReqStatusBits&)
{
    answer(msg::RackGetStatusBits{0});   // digital inputs of the USER IO connector: all low
}

bool RackMotherboard::dig_outputs_ok(std::uint8_t outputs, std::uint8_t bay, bool set)
{
    // p. 26: header only; param1 the outputs (bits 0..3 for outputs 1..4), param2 the bay
    // whose card the outputs belong to ("28, 02, 01, 22, 11, 01": bay address 0x22), or 0
    // for the motherboard's own.
    const bool bay_ok = bay == 0 || (bay >= kBay0 && bay < kBay0 + present_bays_);
    if (bay_ok && !(set && outputs > 0x0F))
        return true;
    log_.warn("{}: {} for outputs 0x{:02x} of bay 0x{:02x} (outputs 0..0x0f; 0 or a present bay): ignored",
              request_->peer, request_->frame.info->name, outputs, bay);
    request_->ignored = true;
    request_->why = fmt::format("outputs 0x{:02x} of bay 0x{:02x} (outputs 0..0x0f; 0 or a present bay)", outputs, bay);
    return false;
}

void RackMotherboard::on(const msg::RackSetDigOutputs& m)
{
    if (dig_outputs_ok(m.dig_outputs, m.bay_ident, true))
        digital_outputs_[m.bay_ident] = m.dig_outputs;
}

void RackMotherboard::on(const msg::RackReqDigOutputs& m)
{
    if (dig_outputs_ok(m.dig_outputs, m.bay_ident, false))
        answer(msg::RackGetDigOutputs{digital_outputs_[m.bay_ident], m.bay_ident});
}

EmptyBay::EmptyBay(const UnitIdentity& unit, std::size_t bay, bool answers_dc_status, spdlog::logger& log)
    : Module(unit, bay, static_cast<std::uint8_t>(kBay0 + bay), log, nullptr), answers_dc_status_(answers_dc_status)
{
}

void EmptyBay::handle(const msg::Message& m, Request& r)
{
    request_ = &r;
    msg::visit(
        [this](const auto& typed) {
            using T = std::decay_t<decltype(typed)>;
            if constexpr (std::is_same_v<T, msg::HwReqInfo> || std::is_same_v<T, msg::ReqStatusBits>
                          || std::is_same_v<T, msg::ReqStatusUpdate> || std::is_same_v<T, msg::ReqDcStatusUpdate>)
                on(typed);
            else if constexpr (T::family != msg::Family::System)   // a motor's message: there is none
                no_stage();
        },
        m);
}

void EmptyBay::no_stage()
{
    log_.warn("{}: {} to bay {} (0x{:02x}): no stage is connected to it, ignored", request_->peer,
              request_->frame.info->name, bay_, address());
    request_->ignored = true;
    request_->why = fmt::format("bay {} (0x{:02x}) has no stage connected", bay_, address());
}

bool EmptyBay::channel1() const
{
    const auto& f = request_->frame;
    return (f.has_data ? get_u16(f.data, 0) : f.param1) == 1;
}

void EmptyBay::on(const msg::ReqStatusBits&)
{
    if (!channel1())
        return no_stage();
    answer(msg::GetStatusBits{1, 0});
}

void EmptyBay::on(const msg::ReqStatusUpdate&)
{
    if (!channel1())
        return no_stage();
    answer(msg::GetStatusUpdate{{1, 0, 0, 0}});
}

void EmptyBay::on(const msg::ReqDcStatusUpdate&)
{
    if (!channel1() || !answers_dc_status_)   // a DC message: a stepper card ignores it
        return no_stage();
    answer(msg::GetDcStatusUpdate{{1, 0, 0, 0, 0}});
}

} // namespace rigsim::apt
