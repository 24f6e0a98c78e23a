// The KPZ101's own messages of the later protocol issues (PiezoModule, piezo_module.hpp): its MMI
// (wheel and display) and trigger-port blocks, kept and answered, and PZ_REQ_PZSTATUSUPDATE. Only a
// KPZ101 of the later firmware generation takes them (messages.def's takes list kKpzLater); sources and
// layouts: docs/protocol/apt.md "K-Cube units". rigsim has no wheel, display or trigger ports to
// drive: the blocks change nothing physical.

#include "emulator/apt/piezo_module.hpp"

#include <spdlog/spdlog.h>

namespace rigsim::apt {

namespace {
} // namespace

bool PiezoModule::saves(std::uint16_t id) const
{
    return Saved::saves(id) || (takes_later(id) && LaterSaved::saves(id));
}

std::optional<std::string> PiezoModule::saved_data(const msg::Message& m) const
{
    if (auto data = Saved::data(m))
        return data;
    return takes_later(msg::message_id(m)) ? LaterSaved::data(m) : std::nullopt;
}

void PiezoModule::on(const msg::PzReqPzStatusUpdate&)
{
    // The update the unit sends every 100 ms, now (yaq pz_req_pzstatusupdate; pyLabLib reads it).
    request_->reply += status_update(request_->host);
}

void PiezoModule::on(const msg::SetKpzMmiParams& m)
{
    if (const auto bad = kcube_out_of_range(m.params))
        return ignore(fmt::format("{}: KPZ_SET_KCUBEMMIPARAMS with {}: ignored", request_->peer, *bad));
    kcube_mmi_ = m.params;
    kcube_mmi_.chan_ident = kChan1;
}

void PiezoModule::on(const msg::ReqKpzMmiParams&)
{
    answer(msg::GetKpzMmiParams{kcube_mmi_});
}

void PiezoModule::on(const msg::SetKpzTrigIoConfig& m)
{
    if (const auto bad = kcube_out_of_range(m.params))
        return ignore(fmt::format("{}: KPZ_SET_KCUBETRIGIOCONFIG with {}: ignored", request_->peer, *bad));
    kcube_trig_ = m.params;
    kcube_trig_.chan_ident = kChan1;
}

void PiezoModule::on(const msg::ReqKpzTrigIoConfig&)
{
    answer(msg::GetKpzTrigIoConfig{kcube_trig_});
}

} // namespace rigsim::apt
