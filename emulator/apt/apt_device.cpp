#include "emulator/apt/apt_device.hpp"
#include "emulator/core/log_format.hpp"
#include "emulator/apt/config.hpp"
#include "emulator/core/state_store.hpp"

#include "emulator/apt/brushless_module.hpp"
#include "emulator/apt/flipper_module.hpp"
#include "emulator/apt/piezo_card.hpp"
#include "emulator/apt/piezo_module.hpp"
#include "emulator/apt/polariser_module.hpp"
#include "emulator/apt/pzmot_module.hpp"
#include "emulator/apt/eeprom_entries.hpp"
#include "emulator/apt/messages.hpp"
#include "emulator/apt/solenoid_module.hpp"
#include "emulator/apt/strain_gauge_module.hpp"
#include "emulator/apt/wire.hpp"
#include "emulator/apt/wire_decode.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace rigsim::apt {

/// One connection: its own framer; frames go to the device, answers come back.
class AptSession : public Session {
public:
    AptSession(AptDevice& device, SendFn send, std::string peer, spdlog::logger& log)
        : device_(device), send_(std::move(send)), peer_(std::move(peer)), log_(log)
    {
        device_.attach(this);
        device_.announce_change();
    }
    ~AptSession() override
    {
        device_.detach(this);
        device_.announce_change();
    }

    void receive(std::string_view bytes) override
    {
        const Ticks now = device_.clock().now();
        if (framer_.buffered() > 0
            && now - last_byte_ > device_.clock().ticks_from_ms(AptDevice::kInterByteTimeout_ms)) {
            record_dropped();   // skipped before the unfinished message
            const auto n = framer_.discard_partial();
            log_.warn("{}: dropped {} byte(s) of an unfinished APT message after {} ms without its rest", peer_, n,
                      AptDevice::kInterByteTimeout_ms);
            record_dropped(true);
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
            record_dropped();   // the garbage before this frame, in wire order
            std::string reply;
            device_.handle(r.frame, peer_, reply);
            if (!reply.empty())
                send_(reply);   // one frame, one write
        }
        record_dropped();
        if (dropped > 0)
            log_.warn("{}: skipped {} byte(s) that start no valid APT message", peer_, dropped);
        device_.flush();
        device_.announce_change();   // a message may have started a timer (models/clock.hpp, "The schedule")
    }

    void send(std::string_view frame) { send_(frame); }
    const std::string& peer() const { return peer_; }

private:
    /// One wire-log entry with the bytes the framer dropped since the last one (the first
    /// FrameFramer::kKeptDropped of them): skipped as garbage, or an `unfinished` message cut off
    /// by the inter-byte timeout. None if it dropped nothing.
    void record_dropped(bool unfinished = false)
    {
        if (!framer_.has_dropped())   // the usual case, twice a read: nothing to take
            return;
        const auto d = framer_.take_dropped();
        std::string note = unfinished ? std::to_string(d.count)
                                            + " byte(s) of an unfinished message dropped: the rest did not come within "
                                            + std::to_string(AptDevice::kInterByteTimeout_ms) + " ms"
                                      : "ignored by the unit: " + std::to_string(d.count)
                                            + " byte(s) that start no valid message (an unknown message ID, address "
                                              "or data length)";
        if (d.bytes.size() < d.count)
            note += " (the first " + std::to_string(d.bytes.size()) + " shown)";
        device_.record(true, peer_, d.bytes, {std::move(note)});
    }

    AptDevice& device_;
    SendFn send_;
    std::string peer_;
    spdlog::logger& log_;
    FrameFramer framer_;
    Ticks last_byte_ = 0;   ///< clock tick of the last bytes received
};

AptDevice::AptDevice(const DeviceConfig& config, models::World& world, std::shared_ptr<spdlog::logger> log,
                     StateStore* store, EventBus* events)
    : config_(config), clock_(world.clock()), world_(world), log_(std::move(log)),
      model_(*find_controller(config.model, config_of(config).firmware)),
      serial_(config_of(config).serial_number != 0 ? config_of(config).serial_number : model_.serial_prefix * 1'000'000 + 1),
      // A rack's slots are built in (a BPC303's three channels), but a modular rack's (an MMR601's)
      // hold the cards the rig puts in them.
      unit_{config.model, model_, serial_,
            model_.bay_model_name.empty() ? std::max(rack_bays(), static_cast<std::size_t>(model_.max_bays)) : rack_bays(),
            model_.later_only ? model_.firmware : config_of(config).firmware,
            model_.reports_stage_type ? dc_stage_type(config_of(config).stage.name) : std::uint16_t{0}},
      store_(store), events_(events), wire_log_(config.name, clock_.tick_hz(), events, log_)
{
    wire_log_.set_decoder([unit = log_context(model_)](const WireEntry& e, nlohmann::json& out) {
        decode_for_log(e.bytes, out, unit);
    });
    // World keys number bays as the APT software does: channel 1 of a single unit, bays 1..n
    // of a rack (addresses 0x21..).
    const auto key = [&](std::size_t bay) { return config.name + "/" + std::to_string(bay + 1); };
    const std::size_t bays = rack_bays();
    if (model_.kind == UnitKind::Motor)
        for (std::size_t bay = 0; bay < bays; ++bay)
            channels_.push_back(std::make_unique<MotorChannel>(
                model_, model_.rack ? config_of(config).bays[bay] : config_of(config).stage, world, key(bay)));
    for (std::size_t bay = 0; bay < bays; ++bay) {
        modules_.push_back(make_module(bay));
        connect_events(bay);
    }
    published_status_.assign(channels_.size(), 0);
    was_moving_.assign(channels_.size(), false);
    stalled_.assign(channels_.size(), false);
    if (model_.rack) {
        motherboard_ = std::make_unique<RackMotherboard>(unit_, modules_.size(), *log_);
        for (std::size_t bay = modules_.size(); bay < unit_.built_in_bays; ++bay)
            empty_bays_.push_back(std::make_unique<EmptyBay>(unit_, bay, model_.motor != MotorKind::Stepper, *log_));
    }
    // Its timers move in its tick(), in a session (announced there), through a body's event (a
    // tick of the clock) or a control request (Ticker::reschedule()). A TPZ001's or KPZ101's
    // closed loop also wakes when its feedback input starts or stops reading a gauge, which the
    // gauge reader's commands route (TSG_IOSETTINGS, another device): the gauge announces that
    // (connect_feedback()).
    clock_.add(this, Clock::Schedule::Announced);
}

void AptDevice::power_up()
{
    linked_ = true;
    for (std::size_t bay = 0; bay < modules_.size(); ++bay)
        connect_feedback(bay);
    restore_from_eeprom(true);
}

int AptDevice::power_up_phase() const
{
    return model_.kind == UnitKind::StrainGauge ? 0 : 1;
}

std::unique_ptr<Module> AptDevice::make_module(std::size_t bay)
{
    auto save = [this, bay](std::uint16_t id, std::string_view peer) { save_to_eeprom(bay, id, peer); };
    // The one place a unit kind picks its module class.
    switch (model_.kind) {
    case UnitKind::Motor:
        return make_motor_module(bay, std::move(save));
    case UnitKind::Solenoid:
        return make_solenoid_module(bay, std::move(save));
    case UnitKind::Piezo:
        return make_piezo_module(bay, std::move(save));
    case UnitKind::StrainGauge:
        return make_strain_gauge_module(unit_, address_of(bay), config_, world_, *log_, std::move(save));
    case UnitKind::Flipper: {
        // The arm is a body of the world ("<device>/1"); a power cycle keeps it where it is.
        const auto key = config_.name + "/" + std::to_string(bay + 1);
        const int position = config_of(config_).flipper.position;
        auto* arm = world_.find_as<models::Flipper>(key);
        if (!arm)
            arm = &world_.emplace<models::Flipper>(key, position);
        return std::make_unique<FlipperModule>(unit_, bay, address_of(bay), *arm, position, clock_, *log_, save);
    }
    case UnitKind::Polariser: {
        // The paddles are bodies of the world ("<device>/1" ... "/3"); a power cycle keeps them.
        std::vector<models::Paddle*> paddles;
        for (int p = 1; p <= model_.paddles; ++p) {
            const auto key = config_.name + "/" + std::to_string(p);
            auto* paddle = world_.find_as<models::Paddle>(key);
            if (!paddle)
                paddle = &world_.emplace<models::Paddle>(key, PolariserModule::kMaxDeg);
            paddles.push_back(paddle);
        }
        return std::make_unique<PolariserModule>(unit_, bay, address_of(bay), std::move(paddles), clock_, *log_, save);
    }
    case UnitKind::PiezoMotor: {
        // Each channel's actuator is a body of the world ("<device>/1" ... "/4"); a power cycle keeps them.
        const auto& actuators = config_of(config_).inertial_actuators;
        std::vector<models::InertialDrive*> drives;
        for (int c = 0; c < model_.pzmot_channels; ++c) {
            const auto key = config_.name + "/" + std::to_string(c + 1);
            auto* drive = world_.find_as<models::InertialDrive>(key);
            if (!drive) {
                const auto a = static_cast<std::size_t>(c) < actuators.size() ? actuators[c] : InertialActuatorConfig{};
                models::InertialDriveConfig d;
                d.travel_max_nm = a.travel_mm * 1e6;
                d.start_nm = a.position_mm * 1e6;
                d.step_forward_nm = a.step_forward_nm;
                d.step_reverse_nm = a.step_reverse_nm;
                drive = &world_.emplace<models::InertialDrive>(key, clock_, d);
            }
            drives.push_back(drive);
        }
        return std::make_unique<PzMotorModule>(unit_, bay, address_of(bay), std::move(drives), *log_, save);
    }
    }
    throw std::invalid_argument(config_.name + ": the " + config_.model + " is of a unit kind rigsim has no module for");
}

std::unique_ptr<Module> AptDevice::make_solenoid_module(std::size_t bay, Module::SaveToEeprom save)
{
    // The output is a body of the world ("<device>/1"); a power cycle keeps it, and the plug.
    const auto key = config_.name + "/" + std::to_string(bay + 1);
    auto* output = world_.find_as<models::Solenoid>(key);
    if (!output)
        output = &world_.emplace<models::Solenoid>(key);
    bool fitted = config_of(config_).solenoid.interlock_fitted;
    if (bay < modules_.size())
        if (const auto* old = dynamic_cast<const SolenoidModule*>(modules_[bay].get()))
            fitted = old->interlock_fitted();
    return std::make_unique<SolenoidModule>(unit_, bay, address_of(bay), *output, clock_, fitted, *log_, save);
}

std::size_t AptDevice::rack_bays() const
{
    if (!model_.rack)
        return 1;
    const auto& apt = config_of(config_);
    return model_.kind == UnitKind::Piezo ? apt.piezo_bays.size() / static_cast<std::size_t>(model_.bay_channels)
                                          : apt.bays.size();
}

std::string AptDevice::piezo_key(std::size_t bay, std::size_t card_channel) const
{
    // A channel of a two-channel card (an MMR601's MPZ601) is "<device>/<bay + 1>.<channel>".
    const auto key = config_.name + "/" + std::to_string(bay + 1);
    return model_.bay_channels > 1 ? key + "." + std::to_string(card_channel + 1) : key;
}

std::unique_ptr<Module> AptDevice::make_piezo_module(std::size_t bay, Module::SaveToEeprom save)
{
    if (model_.bay_channels == 1)
        return make_piezo_channel(bay, 0, std::move(save));
    std::array<std::unique_ptr<Module>, PiezoCard::kChannels> channels;
    for (std::size_t c = 0; c < PiezoCard::kChannels; ++c)
        channels[c] = make_piezo_channel(bay, c, save);
    return std::make_unique<PiezoCard>(unit_, bay, address_of(bay), std::move(channels), *log_);
}

std::unique_ptr<Module> AptDevice::make_piezo_channel(std::size_t bay, std::size_t card_channel, Module::SaveToEeprom save)
{
    const auto& apt = config_of(config_);
    const PiezoBayConfig cube_bay{apt.actuator, false, 2000};
    const auto index = bay * static_cast<std::size_t>(model_.bay_channels) + card_channel;
    const PiezoBayConfig& b = model_.rack ? apt.piezo_bays[index] : cube_bay;
    // The actuator is the world's: a power cycle makes a new module over the same body.
    const auto key = piezo_key(bay, card_channel);
    auto* actuator = world_.find_as<models::PiezoActuator>(key);
    if (!actuator) {
        models::PiezoActuatorConfig a;
        a.travel_um = b.actuator.travel_um;
        a.max_voltage_v = b.actuator.max_voltage_v;
        a.response_ms = b.actuator.response_ms;
        a.hysteresis = b.actuator.hysteresis;
        a.creep = b.actuator.creep;
        actuator = &world_.emplace<models::PiezoActuator>(key, world_.clock(), a);
    }
    const PiezoSetup setup{*actuator, clock_, model_.rack && b.strain_gauge,
                           model_.rack ? apt.hardware_max_voltage_v : b.actuator.max_voltage_v, b.zero_time_ms};
    auto module = std::make_unique<PiezoModule>(unit_, bay, address_of(bay), setup, *log_, std::move(save));
    if (!model_.rack && linked_)   // a power cycle's new module; at start-up power_up() connects it
        module->set_feedback(gauge_feedback(world_, *actuator));
    return module;
}

void AptDevice::connect_feedback(std::size_t bay)
{
    if (model_.kind != UnitKind::Piezo || model_.rack)
        return;
    const auto* actuator = world_.find_as<models::PiezoActuator>(config_.name + "/" + std::to_string(bay + 1));
    if (!actuator)
        return;
    static_cast<PiezoModule&>(*modules_[bay]).set_feedback(gauge_feedback(world_, *actuator));
    // Whether that input reads the gauge follows the reader's hub output, another device's
    // command: the gauge tells this device's clock (models/clock.hpp, "The schedule").
    if (auto* gauge = find_mounted_gauge(world_, *actuator)) {
        gauge->on_route_change([this] { announce_change(); });
        routed_gauge_ = gauge;
    }
}

std::unique_ptr<MotorModule> AptDevice::make_motor_module(std::size_t bay, Module::SaveToEeprom save)
{
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

std::uint8_t AptDevice::address_of(std::size_t bay) const
{
    return model_.rack ? static_cast<std::uint8_t>(kBay0 + bay) : kGenericUsb;
}

AptDevice::~AptDevice()
{
    if (routed_gauge_)   // the world outlives its devices
        routed_gauge_->on_route_change({});
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
    if (f.has_data && !f.info->header_only() && f.data.size() > static_cast<std::size_t>(f.info->data_length))
        note(fmt::format("{} with {} data byte(s), longer than the {} of its layout: the unit ignores the last {}",
                         f.info->name, f.data.size(), f.info->data_length, f.data.size() - f.info->data_length));
    const std::size_t before = reply.size();
    route(f, peer, reply);
    // The wire log: the frame as it came (a frame not from the framer re-encoded), then the answers.
    std::string encoded;
    std::string_view in = f.bytes;
    if (in.empty()) {
        encoded = f.has_data ? encode_with_data(f.id, f.dest, f.source, f.data)
                             : encode_header_only(f.id, f.param1, f.param2, f.dest, f.source);
        in = encoded;
    }
    record(true, peer, in, std::move(notes_));
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
    if (frozen_) {
        // pyLabLib issue 81: "some devices will completely freeze if you try to communicate with them
        // using the wrong is_rack_system"; only a power cycle brings them back.
        log_->warn("{}: {} to 0x{:02x}: the {} is frozen (it was addressed as a single unit), ignored until a power "
                   "cycle",
                   peer, f.info->name, f.dest, config_.model);
        note("ignored by the unit: it is frozen since a client addressed it as a single unit (0x50); power cycle it");
        return;
    }
    host_ = f.source;
    const auto m = msg::decode(f);
    Request r{f, peer, reply, host_};
    if (model_.rack && model_.wrong_address_freezes && f.dest == kGenericUsb) {
        frozen_ = true;
        log_->error("{}: {} to 0x50 (a single unit's address; the rack is 0x11, its bays 0x21..): the {} freezes "
                    "until it is power cycled",
                    peer, f.info->name, config_.model);
        note("the unit freezes: a rack addressed as a single unit (0x50, the wrong rack flag) answers nothing until "
             "power cycled");
        return;
    }
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
    if (f.dest >= kBay0 && f.dest < kBay0 + modules_.size())
        return handle_bay(f.dest - kBay0, m, r);
    if (f.dest == kRack || (f.dest >= kBay0 && f.dest < kBay0 + unit_.built_in_bays)) {
        if (handle_system(m, peer))
            return;
        if (f.dest == kRack)
            motherboard_->handle(m, r);
        else
            empty_bays_[f.dest - kBay0 - modules_.size()]->handle(m, r);
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
    if (bay < channels_.size() && msg::holds<msg::MoveAbsolute>(m) && !channels_[bay]->homed())
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
            using T = std::decay_t<decltype(typed)>;
            if constexpr (T::family == msg::Family::Untyped) {
                return false;
            } else {
                if (T::id == model_.ack_id) {
                    server_alive();
                    return true;
                }
                if constexpr (T::family == msg::Family::System)
                    on(typed, peer);
                return T::family == msg::Family::System;
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

void AptDevice::on(const msg::AckDcStatusUpdate&, std::string_view peer)
{
    // Only reached on a unit whose updates another message acknowledges (handle_system).
    log_->warn("{}: MGMSG_MOT_ACK_DCSTATUSUPDATE: the {} acknowledges its status updates with 0x{:04x}, ignored",
               peer, config_.model, model_.ack_id);
    note(fmt::format("ignored by the unit: the {} acknowledges its status updates with 0x{:04x}", config_.model,
                     model_.ack_id));
}

void AptDevice::server_alive()
{
    updates_since_ack_ = 0;   // "server alive" (p. 80, p. 105): no channel, params 0
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
        msg::HwRichResponse r{motor_module(bay).last_move(), kFaultCodeStalled, {}};
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
    if (frozen_) {
        // A frozen rack sends nothing: what its modules and channels raise meanwhile is dropped.
        for (auto& ch : channels_)
            ch->take_events();
        for (const auto& module : modules_)
            module->take_unprompted(host_);
        return;
    }
    for (std::size_t bay = 0; bay < channels_.size(); ++bay) {
        const std::uint8_t me = address_of(bay);
        const auto events = channels_[bay]->take_events();
        for (const auto event : events) {
            if (!end_of_move_messages_)
                continue;
            // USB "server alive" (p. 80): end-of-move messages count as status update type
            // messages too, while update messages are on.
            if (updates_ && updates_since_ack_ >= updates_without_ack())
                continue;
            if (updates_)
                ++updates_since_ack_;
            switch (event) {
            case MotorEvent::MoveCompleted:
                broadcast(msg::encode(msg::MoveCompleted{motor_module(bay).motor_status()}, host_, me), update_notes());
                break;
            case MotorEvent::Stopped:
                broadcast(msg::encode(msg::MoveStopped{motor_module(bay).motor_status()}, host_, me), update_notes());
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
    for (const auto& module : modules_)
        for (const auto& frame : module->take_unprompted(host_))
            broadcast(frame);
}

Ticks AptDevice::next_change(Ticks now) const
{
    Ticks next = updates_ && updates_since_ack_ < updates_without_ack() ? std::max(next_update_, now + 1) : kNever;
    for (const auto& ch : channels_)
        next = std::min(next, ch->next_change(now));
    for (const auto& module : modules_)
        next = std::min(next, module->next_change(now));
    return next;
}

bool AptDevice::busy() const
{
    const Ticks now = clock_.now();
    return std::any_of(channels_.begin(), channels_.end(), [now](const auto& ch) { return ch->next_change(now) != kNever; })
        || std::any_of(modules_.begin(), modules_.end(), [now](const auto& m) { return m->busy(now); });
}

void AptDevice::tick(Ticks now)
{
    for (const auto& module : modules_)
        module->tick(now);
    flush();   // end-of-move events the axes raised (the World moves them, not this tick), and the modules' own
    if (updates_ && now >= next_update_ && !frozen_) {
        next_update_ += clock_.ticks_from_ms(kUpdatePeriod_ms);
        // USB units stop after 50 updates that the host did not acknowledge (MOT_ACK_DCSTATUSUPDATE).
        if (updates_since_ack_ < updates_without_ack()) {
            ++updates_since_ack_;
            for (const auto& module : modules_) {
                // One frame, or one per channel of a two-channel card (PiezoCard): each its own send.
                const auto update = module->status_update(host_);
                for (std::string_view rest = update; rest.size() >= kHeaderSize;) {
                    const bool data = (static_cast<unsigned char>(rest[4]) & kDataFlag) != 0;
                    const std::size_t n = std::min(rest.size(), kHeaderSize + (data ? std::size_t{get_u16(rest, 2)} : 0));
                    broadcast(std::string(rest.substr(0, n)), update_notes());
                    rest.remove_prefix(n);
                }
            }
        }
    }
}

} // namespace rigsim::apt
