#include "emulator/mcs/controller.hpp"

#include "models/gripper.hpp"

#include <algorithm>
#include <cmath>

namespace rigsim::mcs {

namespace {

/// The controller's baud rate generator divides a 4 MHz clock: CB57600 -> BR57142 (3.5).
constexpr std::int64_t kBaudClock_hz = 4'000'000;

/// The answer a channel's own event becomes (asynchronous mode).
Reply reply_of(int channel, const ChannelEvent& event)
{
    switch (event.kind) {
    case ChannelEvent::Kind::Error:
        // emplace with an explicit alternative: GCC 12 -O2 misreads Reply{Error{...}}
        // as copying an uninitialised std::string of the Answer alternative.
        return Reply(std::in_place_type<Error>, Error{channel, event.code});
    case ChannelEvent::Kind::Completed:
        // SRC: the manual gives no format for "completed"; rigsim sends C<ch> (docs/protocol/mcs.md).
        return Answer{"C" + std::to_string(channel)};
    case ChannelEvent::Kind::Triggered:
        return Answer{"T" + std::to_string(channel)};   // SRT
    }
    return Silent{};
}

} // namespace

Controller::Controller(const McsConfig& config, models::World& world, const std::string& device)
    : clock_(world.clock()), system_id_(config.system_id),
      interface_version_{config.interface_version.high, config.interface_version.low, config.interface_version.update}
{
    channels_.reserve(config.channels.size());
    for (std::size_t i = 0; i < config.channels.size(); ++i) {
        const auto& c = config.channels[i];
        if (c.kind == "end_effector") {
            channels_.push_back(nullptr);   // no positioner: its body in the world is the gripper
            auto& gripper = world.emplace<models::Gripper>(
                device + "/" + std::to_string(i), world.clock(),
                models::GripperConfig{static_cast<std::int32_t>(c.gripper_contact_cv),
                                      static_cast<std::int32_t>(c.gripper_stiffness_dun_per_cv)});
            effectors_.push_back(std::make_unique<EndEffector>(gripper));
        } else {
            channels_.push_back(std::make_unique<Channel>(static_cast<int>(i), c, config.firmware, world,
                                                             device + "/" + std::to_string(i)));
            positioners_.push_back(channels_.back().get());
            effectors_.push_back(nullptr);
        }
    }
    effector_report_.assign(channels_.size(), false);
    any_effector_ = std::any_of(effectors_.begin(), effectors_.end(), [](const auto& e) { return e != nullptr; });
}

EndEffector* Controller::effector(std::int32_t index)
{
    if (!valid_index(index))
        return nullptr;
    return effectors_[static_cast<std::size_t>(index)].get();
}

const EndEffector* Controller::effector(std::int32_t index) const
{
    return const_cast<Controller*>(this)->effector(index);
}

void Controller::set_effector_report(std::int32_t index, bool report)
{
    if (valid_index(index))
        effector_report_[static_cast<std::size_t>(index)] = report;
}

void Controller::set_sensor_mode(SensorMode mode)
{
    sensor_mode_ = mode;
    for (auto* c : positioners_)
        c->set_sensor_mode(mode);
}

void Controller::set_keep_alive(std::int32_t timeout_ms)
{
    keep_alive_ms_ = timeout_ms;
    note_command();
}

void Controller::note_command()
{
    keep_alive_deadline_ = keep_alive_ms_ > 0 ? clock_.now() + clock_.ticks_from_ms(keep_alive_ms_) : kNever;
}

std::int32_t Controller::configure_baudrate(std::int32_t baudrate)
{
    configured_baudrate_ = baudrate;
    const auto divider = (kBaudClock_hz + baudrate - 1) / baudrate;   // never faster than asked
    return static_cast<std::int32_t>(kBaudClock_hz / divider);
}

void Controller::reset()
{
    mode_ = CommunicationMode::Sync;
    hcm_mode_ = 1;
    keep_alive_ms_ = 0;
    keep_alive_deadline_ = kNever;
    baudrate_ = configured_baudrate_;   // CB takes effect at the next reset
    outbox_.clear();
    for (auto* c : positioners_)
        c->reset();
    for (auto& e : effectors_)
        if (e)
            e->reset();   // the end effector type (SEET) is kept, like the sensor types
    effector_report_.assign(channels_.size(), false);
    keep_alive_expired_ = false;
    esm_mode_ = 0;        // SESM: 0 is "the default mode"; channels restart in their default
}

void Controller::restore_defaults()
{
    sensor_mode_ = SensorMode::Enabled;
    configured_baudrate_ = kDefaultBaudrate;
    for (auto* c : positioners_)
        c->restore_defaults();
    for (auto& e : effectors_)
        if (e)
            e->restore_defaults();
}

void Controller::place_at_start()
{
    for (auto* c : positioners_)
        c->place_at_start();
}

void Controller::stop_all()
{
    for (auto* c : positioners_)
        c->stop();
    for (auto& e : effectors_)
        if (e)
            e->stop();
}

void Controller::set_emergency_stop_mode(std::int32_t mode)
{
    esm_mode_ = mode;
    for (auto* c : positioners_)
        c->set_emergency_stop_mode(mode);
}

void Controller::emergency_stop_pulse()
{
    for (auto* c : positioners_)
        c->emergency_stop_edge(false);
    for (auto* c : positioners_)
        c->emergency_stop_edge(true);
}

void Controller::trigger(std::int32_t source)
{
    for (auto* c : positioners_)
        c->on_event(source);
}

void Controller::collect_events()
{
    bool broadcast = false;
    for (auto* c : positioners_)
        broadcast = c->take_broadcast_request() || broadcast;
    if (broadcast)   // 2.2.3: an end stop on a channel with broadcast stop halts them all
        emergency_stop_pulse();
    if (any_effector_)
        for (std::size_t i = 0; i < effectors_.size(); ++i)
            if (effectors_[i] && effectors_[i]->take_completed() && effector_report_[i]
                && mode_ == CommunicationMode::Async)
                outbox_.push_back(Answer{"C" + std::to_string(i)});
    for (std::size_t i = 0; i < channels_.size(); ++i) {
        if (!channels_[i])
            continue;
        auto& events = channels_[i]->events();
        if (events.empty())   // the usual case, after every batch of commands
            continue;
        if (mode_ == CommunicationMode::Async)
            for (const auto& e : events)
                outbox_.push_back(reply_of(static_cast<int>(i), e));
        events.clear();
    }
}

Ticks Controller::next_change(Ticks now) const
{
    Ticks next = keep_alive_deadline_ > now ? keep_alive_deadline_ : (keep_alive_deadline_ == kNever ? kNever : now + 1);
    for (const auto* c : positioners_)
        next = std::min(next, c->next_change(now));
    if (any_effector_)
        for (const auto& e : effectors_)
            if (e)
                next = std::min(next, e->next_change(now));
    return next;
}

bool Controller::busy(Ticks now) const
{
    return std::any_of(positioners_.begin(), positioners_.end(), [now](const auto* c) { return c->next_change(now) != kNever; })
        || std::any_of(effectors_.begin(), effectors_.end(), [](const auto& e) { return e && e->busy(); });
}

void Controller::tick(Ticks now)
{
    if (now >= keep_alive_deadline_) {
        // K: "If a timeout occurs, all positioners are immediately stopped."
        for (auto* c : positioners_)
            c->stop();
        keep_alive_deadline_ = kNever;
        keep_alive_expired_ = true;
    }
    for (auto* c : positioners_)
        if (c->next_change(now - 1) <= now)
            c->tick(now);
    for (auto& e : effectors_)
        if (e && e->next_change(now - 1) <= now)
            e->tick(now);
    collect_events();
}

} // namespace rigsim::mcs
