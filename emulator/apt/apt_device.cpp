#include "emulator/apt/apt_device.hpp"
#include "emulator/apt/config.hpp"
#include "emulator/core/state_store.hpp"

#include "emulator/apt/brushless_module.hpp"
#include "emulator/apt/messages.hpp"
#include "emulator/apt/wire.hpp"
#include "emulator/apt/wire_decode.hpp"

#include <spdlog/logger.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>

namespace rigsim::apt {

namespace {

/// The only channel of a module: P_MOD_CHAN1.
constexpr std::uint16_t kChan1 = 0x01;

} // namespace

/// One connection: its own framer; frames go to the device, answers come back.
class AptSession : public Session {
public:
    AptSession(AptDevice& device, SendFn send, std::string peer, spdlog::logger& log)
        : device_(device), send_(std::move(send)), peer_(std::move(peer)), log_(log)
    {
        device_.attach(this);
    }
    ~AptSession() override { device_.detach(this); }

    void receive(std::string_view bytes) override
    {
        const Ticks now = device_.clock().now();
        if (framer_.buffered() > 0
            && now - last_byte_ > device_.clock().ticks_from_ms(AptDevice::kInterByteTimeout_ms)) {
            const auto n = framer_.discard_partial();
            log_.warn("{}: dropped {} byte(s) of an unfinished APT message after {} ms without its rest", peer_, n,
                      AptDevice::kInterByteTimeout_ms);
            device_.record(true, peer_, {},
                           {std::to_string(n) + " byte(s) of an unfinished message dropped: the rest did not come within "
                            + std::to_string(AptDevice::kInterByteTimeout_ms) + " ms"});
        }
        if (!bytes.empty())
            last_byte_ = now;
        std::size_t dropped = 0;
        while (!bytes.empty()) {
            const auto r = framer_.parse(bytes);
            bytes.remove_prefix(r.consumed);
            dropped += r.dropped;
            if (r.status != FrameFramer::Status::Frame)
                continue;
            std::string reply;
            device_.handle(r.frame, peer_, reply);
            if (!reply.empty())
                send_(reply);   // one frame, one write
        }
        if (dropped > 0) {
            log_.warn("{}: skipped {} byte(s) that start no valid APT message", peer_, dropped);
            // The bytes are gone (the framer resyncs byte by byte); the entry says how many.
            device_.record(true, peer_, {},
                           {"ignored by the unit: " + std::to_string(dropped)
                            + " byte(s) that start no valid message (an unknown message ID, address or data length)"});
        }
        device_.flush();
    }

    void send(std::string_view frame) { send_(frame); }
    const std::string& peer() const { return peer_; }

private:
    AptDevice& device_;
    SendFn send_;
    std::string peer_;
    spdlog::logger& log_;
    FrameFramer framer_;
    Ticks last_byte_ = 0;   ///< clock tick of the last bytes received
};

AptDevice::AptDevice(const DeviceConfig& config, models::World& world, std::shared_ptr<spdlog::logger> log,
                     StateStore* store, EventBus* events)
    : config_(config), clock_(world.clock()), log_(std::move(log)), model_(*find_controller(config.model)),
      serial_(config_of(config).serial_number != 0 ? config_of(config).serial_number : model_.serial_prefix * 1'000'000 + 1),
      unit_{config.model, model_, serial_,
            std::max(model_.rack ? config_of(config).bays.size() : std::size_t{1}, static_cast<std::size_t>(model_.max_bays))},
      store_(store), events_(events), wire_log_(config.name, clock_.tick_hz(), events, log_)
{
    wire_log_.set_decoder([](const WireEntry& e, nlohmann::json& out) { decode_for_log(e.bytes, out); });
    // World keys number bays as the APT software does: channel 1 of a single unit, bays 1..n
    // of a rack (addresses 0x21..).
    const auto key = [&](std::size_t bay) { return config.name + "/" + std::to_string(bay + 1); };
    if (model_.rack)
        for (const auto& stage : config_of(config).bays)
            channels_.push_back(std::make_unique<MotorChannel>(model_, *find_stage(stage), world,
                                                               key(channels_.size())));
    else
        channels_.push_back(std::make_unique<MotorChannel>(model_, *find_stage(config_of(config).stage), world, key(0)));
    for (std::size_t bay = 0; bay < channels_.size(); ++bay)
        modules_.push_back(make_module(bay));
    patched_switch_.assign(channels_.size(), 0);
    published_status_.assign(channels_.size(), 0);
    was_moving_.assign(channels_.size(), false);
    stalled_.assign(channels_.size(), false);
    if (model_.rack) {
        motherboard_ = std::make_unique<RackMotherboard>(unit_, channels_.size(), *log_);
        for (std::size_t bay = channels_.size(); bay < unit_.built_in_bays; ++bay)
            empty_bays_.push_back(std::make_unique<EmptyBay>(unit_, bay, model_.motor != MotorKind::Stepper, *log_));
    }
    restore_from_eeprom();
    clock_.add(this);
}

std::unique_ptr<MotorModule> AptDevice::make_module(std::size_t bay)
{
    auto save = [this, bay](std::uint16_t id, std::string_view peer) { save_to_eeprom(bay, id, peer); };
    switch (model_.motor) {
    case MotorKind::DcServo:
        return std::make_unique<DcServoModule>(unit_, bay, address_of(bay), *channels_[bay], *log_, save);
    case MotorKind::Stepper:
        return std::make_unique<StepperModule>(unit_, bay, address_of(bay), *channels_[bay], *log_, save);
    case MotorKind::Brushless:
        return std::make_unique<BrushlessModule>(unit_, bay, address_of(bay), *channels_[bay], *log_, save);
    }
    return nullptr;
}

namespace {

/// The parameter SETs MOT_SET_EEPROMPARAMS saves (p. 60: "the message containing the
/// parameters to be saved"): the alternatives of AptDevice::SavedSet.
template <class V> struct SavedIds;
template <class... T> struct SavedIds<std::variant<T...>> {
    static constexpr std::uint16_t ids[] = {T::id...};
};

bool saved_by_eeprom(std::uint16_t id)
{
    const auto& ids = SavedIds<AptDevice::SavedSet>::ids;
    return std::find(std::begin(ids), std::end(ids), id) != std::end(ids);
}

template <class T, class V> struct IsAlternative;
template <class T, class... A> struct IsAlternative<T, std::variant<A...>> : std::disjunction<std::is_same<T, A>...> {};

std::string message_name(std::uint16_t id)
{
    if (const auto* info = find_message(id))
        return std::string(info->name);
    char buf[8];
    std::snprintf(buf, sizeof buf, "0x%04x", id);
    return buf;
}

/// State file key of a saved SET message: "bay0/0x0413".
std::string eeprom_key(std::size_t bay, std::uint16_t id)
{
    static constexpr char kHex[] = "0123456789abcdef";
    std::string k = "bay" + std::to_string(bay) + "/0x";
    for (int shift = 12; shift >= 0; shift -= 4)
        k += kHex[(id >> shift) & 0xf];
    return k;
}

/// The bay and message of a key exactly as eeprom_key writes it, or nullopt.
std::optional<std::pair<std::size_t, std::uint16_t>> parse_eeprom_key(const std::string& key)
{
    constexpr std::size_t kMaxBayDigits = 3;
    if (key.compare(0, 3, "bay") != 0)
        return std::nullopt;
    std::size_t i = 3;
    std::size_t bay = 0;
    while (i < key.size() && i - 3 < kMaxBayDigits && key[i] >= '0' && key[i] <= '9')
        bay = bay * 10 + static_cast<std::size_t>(key[i++] - '0');
    if (i == 3 || key.compare(i, 3, "/0x") != 0 || key.size() != i + 7)
        return std::nullopt;
    unsigned id = 0;
    for (i += 3; i < key.size(); ++i) {
        const char c = key[i];
        if (c >= '0' && c <= '9')
            id = id * 16 + static_cast<unsigned>(c - '0');
        else if (c >= 'a' && c <= 'f')
            id = id * 16 + static_cast<unsigned>(c - 'a' + 10);
        else
            return std::nullopt;
    }
    const auto parsed = std::make_pair(bay, static_cast<std::uint16_t>(id));
    if (eeprom_key(parsed.first, parsed.second) != key)   // "bay00/...": one spelling per entry
        return std::nullopt;
    return parsed;
}

std::string to_hex(std::string_view data)
{
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    for (unsigned char c : data) {
        out += kHex[c >> 4];
        out += kHex[c & 0xf];
    }
    return out;
}

/// `hex` (an even number of [0-9a-fA-F]) as bytes in `out`, or false and why not in `why`.
bool from_hex(const std::string& hex, std::string& out, std::string& why)
{
    auto digit = [](char c) {
        if (c >= '0' && c <= '9')
            return c - '0';
        if (c >= 'a' && c <= 'f')
            return c - 'a' + 10;
        if (c >= 'A' && c <= 'F')
            return c - 'A' + 10;
        return -1;
    };
    for (std::size_t i = 0; i < hex.size(); ++i) {
        if (digit(hex[i]) < 0) {
            why = "data is not hex (character " + std::to_string(i + 1) + " is '" + printable(hex.substr(i, 1)) + "')";
            return false;
        }
    }
    if (hex.size() % 2 != 0) {
        why = "data has an odd number of hex digits (" + std::to_string(hex.size()) + ")";
        return false;
    }
    out.clear();
    for (std::size_t i = 0; i < hex.size(); i += 2)
        out.push_back(static_cast<char>(digit(hex[i]) * 16 + digit(hex[i + 1])));
    return true;
}

} // namespace

void AptDevice::save_to_eeprom(std::size_t bay, std::uint16_t id, std::string_view peer)
{
    if (!saved_by_eeprom(id)) {
        log_->warn("{}: MOT_SET_EEPROMPARAMS for 0x{:04x} ({}): not a parameter SET it saves, nothing saved", peer, id,
                   message_name(id));
        return;
    }
    const auto it = last_set_.find({bay, id});
    if (it == last_set_.end()) {
        log_->warn("{}: MOT_SET_EEPROMPARAMS for 0x{:04x}: no such parameters were set, nothing saved", peer, id);
        return;
    }
    if (!store_) {
        log_->info("{}: MOT_SET_EEPROMPARAMS for 0x{:04x}: kept until the daemon exits (no --state-file)", peer, id);
        return;
    }
    // Saved as the parameters of the bay's channel, whatever channel word the SET carried.
    store_->set(config_.name, eeprom_key(bay, id), to_hex(saved_data(it->second)));
    log_->info("{}: MOT_SET_EEPROMPARAMS for 0x{:04x}: saved", peer, id);
}

std::string AptDevice::saved_data(SavedSet set)
{
    return std::visit(
        [](auto& s) {
            s.params.chan_ident = kChan1;
            return msg::encode_data(s);
        },
        set);
}

void AptDevice::remember(std::size_t bay, const msg::Message& m)
{
    msg::visit(
        [&](const auto& typed) {
            using T = std::decay_t<decltype(typed)>;
            if constexpr (IsAlternative<T, SavedSet>::value)
                last_set_.insert_or_assign({bay, T::id}, typed);
        },
        m);
}

void AptDevice::restore_from_eeprom()
{
    if (!store_)
        return;
    // What this device's non-volatile memory can hold: a parameter SET that MOT_SET_EEPROMPARAMS
    // saves, of one of its bays, as long as the table says, for the bay's channel, and accepted
    // by the bay as if a client had sent it. Returns why an entry is none of that.
    auto restore = [&](const std::string& key, const nlohmann::json& value) -> std::optional<std::string> {
        const auto parsed = parse_eeprom_key(key);
        if (!parsed)
            return "the key is not bay<N>/0x<4 lower-case hex digits>";
        const auto [bay, id] = *parsed;
        if (bay >= channels_.size())
            return "no bay " + std::to_string(bay) + " (the " + config_.model
                   + (channels_.size() == 1 ? " has bay 0 only)" : " has bays 0 to " + std::to_string(channels_.size() - 1) + ")");
        if (!saved_by_eeprom(id))
            return message_name(id) + " is not a parameter SET that MOT_SET_EEPROMPARAMS saves";
        if (!value.is_string())
            return std::string("expected a string of hex digits, got ") + value.type_name();
        std::string data;
        std::string why;
        if (!from_hex(value.get<std::string>(), data, why))
            return why;
        const auto* info = find_message(id);
        if (data.size() != static_cast<std::size_t>(info->data_length))
            return std::to_string(data.size()) + " data bytes, " + std::string(info->name) + " has "
                   + std::to_string(info->data_length);
        if (get_u16(data, 0) != kChan1)
            return "channel " + std::to_string(get_u16(data, 0)) + " in the data; bay " + std::to_string(bay)
                   + " is channel 1";
        Frame f;
        f.id = id;
        f.dest = address_of(bay);
        f.source = kHost;
        f.has_data = true;
        f.data = data;
        f.info = info;
        last_set_.erase({bay, id});
        std::string ignored;
        Request r{f, "state file", ignored, host_};
        handle_bay(bay, msg::decode(f), r);
        const auto accepted = last_set_.find({bay, id});
        if (accepted == last_set_.end() || saved_data(accepted->second) != data)
            return "the bay ignores this " + std::string(info->name) + " (its warning says why)";
        log_->info("restored {} of bay {} from the state file", info->name, bay);
        return std::nullopt;
    };
    // A copy: reject() drops the entry from the store.
    const nlohmann::json entries = store_->device_state(config_.name);
    for (const auto& [key, value] : entries.items())
        if (const auto why = restore(key, value))
            store_->reject(config_.name, key, *why);
}

std::uint8_t AptDevice::address_of(std::size_t bay) const
{
    return model_.rack ? static_cast<std::uint8_t>(kBay0 + bay) : kGenericUsb;
}

AptDevice::~AptDevice()
{
    clock_.remove(this);
}

std::unique_ptr<Session> AptDevice::open_session(SendFn send, std::string peer)
{
    return std::make_unique<AptSession>(*this, std::move(send), std::move(peer), *log_);
}

void AptDevice::detach(AptSession* s)
{
    sessions_.erase(std::remove(sessions_.begin(), sessions_.end(), s), sessions_.end());
}

void AptDevice::start_updates()
{
    updates_ = true;
    updates_since_ack_ = 0;
    next_update_ = clock_.now() + clock_.ticks_from_ms(kUpdatePeriod_ms);
}

void AptDevice::handle(const Frame& f, std::string_view peer, std::string& reply)
{
    notes_.clear();
    const std::size_t before = reply.size();
    route(f, peer, reply);
    // The wire log: the frame as it came (re-encoded: the framer keeps no copy), then the answers.
    record(true, peer,
           f.has_data ? encode_with_data(f.id, f.dest, f.source, f.data)
                      : encode_header_only(f.id, f.param1, f.param2, f.dest, f.source),
           std::move(notes_));
    notes_.clear();
    std::string_view out(reply);
    out.remove_prefix(before);
    while (out.size() >= 6) {
        const bool data = (static_cast<unsigned char>(out[4]) & 0x80) != 0;
        const std::size_t n = std::min(out.size(), 6 + (data ? std::size_t{get_u16(out, 2)} : 0));
        record(false, peer, out.substr(0, n));
        out.remove_prefix(n);
    }
}

void AptDevice::route(const Frame& f, std::string_view peer, std::string& reply)
{
    host_ = f.source;
    const auto m = msg::decode(f);
    Request r{f, peer, reply, host_};
    if (!model_.rack) {
        // A single unit answers as 0x50 and, as the real cubes do, also acts on messages
        // that clients address to the motherboard (0x11) or bay 0 (0x21).
        if (f.dest != kGenericUsb && f.dest != kRack && f.dest != kBay0) {
            log_->warn("{}: {} to 0x{:02x}: no such module, ignored", peer, f.info->name, f.dest);
            note(fmt::format("ignored by the unit: no module at destination 0x{:02x} (a single unit answers as 0x50)", f.dest));
            return;
        }
        return handle_bay(0, m, r);
    }
    if (f.dest >= kBay0 && f.dest < kBay0 + channels_.size())
        return handle_bay(f.dest - kBay0, m, r);
    if (f.dest == kRack || (f.dest >= kBay0 && f.dest < kBay0 + unit_.built_in_bays)) {
        if (handle_system(m, peer))
            return;
        if (f.dest == kRack)
            motherboard_->handle(m, r);
        else
            empty_bays_[f.dest - kBay0 - channels_.size()]->handle(m, r);
        if (r.ignored)
            note("ignored by the unit: " + r.why);
        return;
    }
    log_->warn("{}: {} to 0x{:02x}: no module in that bay, ignored", peer, f.info->name, f.dest);
    note(fmt::format("ignored by the unit: no module at destination 0x{:02x}", f.dest));
}

void AptDevice::handle_bay(std::size_t bay, const msg::Message& m, Request& r)
{
    if (handle_system(m, r.peer))
        return;
    if (msg::holds<msg::MoveAbsolute>(m) && !channels_[bay]->homed())
        note("MOVE_ABSOLUTE while not homed: the position counter is not referenced to the stage "
             "(p. 28: home the stage after power-up)");
    modules_[bay]->handle(m, r);
    // What MOT_SET_EEPROMPARAMS can save: the last SET the bay accepted.
    if (!r.ignored)
        remember(bay, m);
    else
        note("ignored by the unit: " + r.why);
}

bool AptDevice::handle_system(const msg::Message& m, std::string_view peer)
{
    return msg::visit(
        [&](const auto& typed) {
            if constexpr (std::decay_t<decltype(typed)>::family == msg::Family::System) {
                on(typed, peer);
                return true;
            } else {
                return false;
            }
        },
        m);
}

void AptDevice::on(const msg::ModIdentify&, std::string_view peer)
{
    ++identify_count_;   // the front panel LED flashes: counted (identify_count()) and logged
    log_->info("{}: MOD_IDENTIFY: front panel flashes", peer);
}

void AptDevice::on(const msg::HwDisconnect&, std::string_view peer)
{
    log_->info("{}: HW_DISCONNECT", peer);
}

void AptDevice::on(const msg::HwStartUpdateMsgs&, std::string_view)
{
    start_updates();
}

void AptDevice::on(const msg::HwStopUpdateMsgs&, std::string_view)
{
    updates_ = false;
    next_update_ = kNever;
}

void AptDevice::on(const msg::HwYesFlashProgramming&, std::string_view) {}   // later issues: accepted silently

void AptDevice::on(const msg::HwNoFlashProgramming&, std::string_view) {}

void AptDevice::on(const msg::SuspendEndOfMoveMsgs&, std::string_view)
{
    end_of_move_messages_ = false;   // p. 82-83: header only, params 0: the whole unit
}

void AptDevice::on(const msg::ResumeEndOfMoveMsgs&, std::string_view)
{
    end_of_move_messages_ = true;
}

void AptDevice::on(const msg::AckDcStatusUpdate&, std::string_view)
{
    updates_since_ack_ = 0;   // "server alive" (p. 80): no channel, params 0
    if (updates_ && next_update_ <= clock_.now())   // resume the 100 ms rhythm from now
        next_update_ = clock_.now() + clock_.ticks_from_ms(kUpdatePeriod_ms);
}

void AptDevice::broadcast(const std::string& frame, std::vector<std::string> notes)
{
    // One entry for every connection, as the MCS log has it: the pty's session is always open,
    // so an entry per session doubled each message in the log of a unit one client talks to.
    for (auto* s : sessions_)
        s->send(frame);
    record(false, "all", frame, std::move(notes), true);
}

std::string AptDevice::fault_report(std::size_t bay) const
{
    // The only fault rigsim models: the motor stalled against an end stop (a move past an
    // ignored limit switch), which trips its current limit (DC servo: status bit 0x01000000)
    // or the position error limit (brushless: motion error, bit 0x00004000).
    if (model_.rich_fault_reports) {
        // Later protocol issues: MsgIdent word (what caused it), Code word, Notes char[64].
        msg::HwRichResponse r{modules_[bay]->last_move(), kFaultCodeStalled, {}};
        // The control API's faults stop the motor mid-travel (docs/control-api/apt.md "Faults").
        const MotorChannel& ch = *channels_[bay];
        const std::string_view notes = ch.encoder_failed() ? "Motion error: encoder signal lost, position loop open"
                                       : ch.stalled()      ? "Motor stalled: current limit reached"
                                                           : "Motor stalled at the end of travel: current limit reached";
        notes.copy(r.notes.data(), r.notes.size());
        return msg::encode(r, host_, address_of(bay));
    }
    // p. 19: header only; in a card-slot system the motherboard sends it ("TX 80, 00, 00, 00, 01, 11").
    return msg::encode(msg::HwResponse{}, host_, model_.rack ? kRack : address_of(bay));
}

void AptDevice::flush()
{
    for (std::size_t bay = 0; bay < channels_.size(); ++bay) {
        const std::uint8_t me = address_of(bay);
        const auto events = channels_[bay]->take_events();
        for (const auto event : events) {
            if (!end_of_move_messages_)
                continue;
            // USB "server alive" (p. 80): end-of-move messages count as status update type
            // messages too, while update messages are on.
            if (updates_ && updates_since_ack_ >= kUpdatesWithoutAck)
                continue;
            if (updates_)
                ++updates_since_ack_;
            switch (event) {
            case MotorEvent::MoveCompleted:
                broadcast(msg::encode(msg::MoveCompleted{modules_[bay]->motor_status()}, host_, me), update_notes());
                break;
            case MotorEvent::Stopped:
                broadcast(msg::encode(msg::MoveStopped{modules_[bay]->motor_status()}, host_, me), update_notes());
                break;
            case MotorEvent::Homed:
                broadcast(msg::encode(msg::MoveHomed{kChan1}, host_, me), update_notes());
                break;
            case MotorEvent::Fault:
                broadcast(fault_report(bay), update_notes());
                break;
            }
        }
        publish_events(bay, events);
    }
}

Ticks AptDevice::next_change(Ticks now) const
{
    Ticks next = updates_ && updates_since_ack_ < kUpdatesWithoutAck ? std::max(next_update_, now + 1) : kNever;
    for (const auto& ch : channels_)
        next = std::min(next, ch->next_change(now));
    return next;
}

void AptDevice::tick(Ticks now)
{
    flush();   // end-of-move events the axes raised (the World moves them, not this tick)
    if (updates_ && now >= next_update_) {
        next_update_ += clock_.ticks_from_ms(kUpdatePeriod_ms);
        // USB units stop after 50 updates that the host did not acknowledge (MOT_ACK_DCSTATUSUPDATE).
        if (updates_since_ack_ < kUpdatesWithoutAck) {
            ++updates_since_ack_;
            for (const auto& module : modules_)
                broadcast(module->status_update(host_), update_notes());
        }
    }
}

} // namespace rigsim::apt
