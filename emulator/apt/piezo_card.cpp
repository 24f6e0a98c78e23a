#include "emulator/apt/piezo_card.hpp"
#include "emulator/apt/piezo_module.hpp"
#include "emulator/apt/wire.hpp"
#include "emulator/core/log_format.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>

namespace rigsim::apt {

namespace {

/// The channel word a message carries: param1 of a header-only one, else its first data word.
std::uint16_t sent_channel(const Frame& f)
{
    if (!f.has_data)
        return f.param1;
    return f.data.size() >= 2 ? get_u16(f.data, 0) : 0;
}

} // namespace

PiezoCard::PiezoCard(const UnitIdentity& unit, std::size_t bay, std::uint8_t address,
                     std::array<std::unique_ptr<Module>, kChannels> channels, spdlog::logger& log)
    : Module(unit, bay, address, log, {}), channels_(std::move(channels))
{
}

std::string PiezoCard::rechannel(std::string_view frames, std::uint16_t to)
{
    std::string out(frames);
    for (std::size_t at = 0; at + kHeaderSize <= out.size();) {
        const bool data = (static_cast<unsigned char>(out[at + 4]) & kDataFlag) != 0;
        const std::size_t length = data ? get_u16(out, at + 2) : 0;
        if (data && length >= 2 && get_u16(out, at + kHeaderSize) == 1) {
            out[at + kHeaderSize] = static_cast<char>(to & 0xFF);
            out[at + kHeaderSize + 1] = static_cast<char>(to >> 8);
        } else if (!data && static_cast<unsigned char>(out[at + 2]) == 1) {
            out[at + 2] = static_cast<char>(to);
        }
        at += kHeaderSize + length;
    }
    return out;
}

void PiezoCard::handle(const msg::Message& m, Request& r)
{
    // The card's own questions: its channel 1 answers them as the card.
    if (msg::holds<msg::HwReqInfo>(m) || msg::holds<msg::HubReqBayUsed>(m))
        return channels_[0]->handle(m, r);
    // PZ_SET_LUTVALUETYPE has no channel (param1 is the type, p. 126): the card's, both channels.
    if (msg::holds<msg::PzSetLutValueType>(m)) {
        channels_[0]->handle(m, r);
        std::string reply;
        Request r2{r.frame, r.peer, reply, r.host};
        channels_[1]->handle(m, r2);
        return;
    }
    const std::uint16_t sent = sent_channel(r.frame);
    if (sent == 1)
        return channels_[0]->handle(m, r);
    if (sent != 2) {
        r.ignored = true;
        r.why = fmt::format("{} for channel {}: an {} has channels 1 and 2", r.frame.info->name, sent,
                            unit_.model.bay_model_name);
        log_.warn("{}: {}, ignored", r.peer, r.why);
        return;
    }
    // Channel 2 sees the message as its channel 1, and its answers go out as channel 2's.
    Frame as_one = r.frame;
    std::string data(r.frame.data);
    if (as_one.has_data) {
        data[0] = 1;
        data[1] = 0;
        as_one.data = data;
    } else {
        as_one.param1 = 1;
    }
    as_one.bytes = {};
    const auto m1 = msg::decode(as_one);
    std::string reply;
    Request r1{as_one, r.peer, reply, r.host};
    channels_[1]->handle(m1, r1);
    r.ignored = r1.ignored;
    r.why = r1.why;
    r.reply += rechannel(reply, 2);
}

std::string PiezoCard::status_update(std::uint8_t host) const
{
    return channels_[0]->status_update(host) + rechannel(channels_[1]->status_update(host), 2);
}

Ticks PiezoCard::next_change(Ticks now) const
{
    return std::min(channels_[0]->next_change(now), channels_[1]->next_change(now));
}

bool PiezoCard::busy(Ticks now) const
{
    return channels_[0]->busy(now) || channels_[1]->busy(now);
}

void PiezoCard::tick(Ticks now)
{
    for (auto& c : channels_)
        c->tick(now);
}

std::vector<std::string> PiezoCard::take_unprompted(std::uint8_t host)
{
    auto frames = channels_[0]->take_unprompted(host);
    for (const auto& f : channels_[1]->take_unprompted(host))
        frames.push_back(rechannel(f, 2));
    return frames;
}

void PiezoCard::power_down(bool restore_positions)
{
    for (auto& c : channels_)
        c->power_down(restore_positions);
}

void PiezoCard::describe(nlohmann::json& out) const
{
    auto channels = nlohmann::json::array();
    for (std::size_t c = 0; c < kChannels; ++c) {
        nlohmann::json one{{"card_channel", c + 1}};
        if (const auto* piezo = dynamic_cast<const PiezoModule*>(channels_[c].get()))
            one["body"] = piezo->actuator().key();   // the world body it drives
        channels_[c]->describe(one);
        channels.push_back(std::move(one));
    }
    out["card_channels"] = std::move(channels);
}

Refused PiezoCard::patch(const nlohmann::json& body)
{
    // {"card_channel": 1 or 2, ...the piezo channel's keys}
    const auto it = body.find("card_channel");
    if (it == body.end() || !it->is_number_integer() || (*it != 1 && *it != 2))
        return Refusal{400, "\"card_channel\": 1 or 2 is required (an " + std::string(unit_.model.bay_model_name)
                                + " has two channels)"};
    nlohmann::json rest = body;
    rest.erase("card_channel");
    return channels_[it->get<int>() - 1]->patch(rest);
}

Refused PiezoCard::trace(Ticks from, std::size_t max, nlohmann::json& out) const
{
    // Both channels' traces, each under its channel.
    auto traces = nlohmann::json::array();
    for (std::size_t c = 0; c < kChannels; ++c) {
        nlohmann::json one{{"card_channel", c + 1}};
        if (auto refused = channels_[c]->trace(from, max, one))
            return refused;
        traces.push_back(std::move(one));
    }
    out["card_channels"] = std::move(traces);
    return std::nullopt;
}

void PiezoCard::set_event_sink(EventSink sink)
{
    for (std::size_t c = 0; c < kChannels; ++c)
        channels_[c]->set_event_sink([sink, c](std::string_view type, const nlohmann::json& data) {
            nlohmann::json with = data;
            with["card_channel"] = c + 1;
            if (sink)
                sink(type, with);
        });
}

} // namespace rigsim::apt
