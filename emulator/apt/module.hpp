#pragma once
// The module of one channel of an APT unit: a T-/K-Cube's only channel or a rack bay's card,
// of any kind (motor, solenoid, piezo, strain gauge: ControllerModel::kind). What every kind
// shares is here: its address and identity, the addressing and range checks of a message, the
// Bay family's handlers, and the typed dispatch. A kind derives from Module, gives one on()
// per message of the families it acts on (`static constexpr bool handles(msg::Family)`) and
// visits each message through dispatch(): a message of a family it acts on without its on()
// does not compile. A message of another family, or one outside the model's MessageSet
// (`takes`, the manual's cross-reference column), is ignored and logged as a real unit without
// such a module does.
//
// The unit shell (AptDevice) handles the System family before a module sees a message, sends
// each module's status update every 100 ms, runs its tick(), and keeps what the EEPROMPARAMS
// messages save: every SET a module does not mark ignored and says it saves (saved_data()).

#include "emulator/apt/catalogue.hpp"
#include "emulator/apt/codec.hpp"
#include "emulator/apt/firmware.hpp"
#include "emulator/core/control_surface.hpp"
#include "models/clock.hpp"

#include <nlohmann/json_fwd.hpp>

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace spdlog {
class logger;
}

namespace rigsim::apt {

/// One message being handled: where it came from and where the answer goes.
struct Request {
    const Frame& frame;
    std::string_view peer;
    std::string& reply;
    std::uint8_t host;       ///< where answers go (the requester's source)
    bool ignored = false;    ///< the module ignored it (a SET: EEPROMPARAMS must not save it)
    std::string why{};       ///< why it was ignored (the warning without the peer)
};

/// What every module knows of the unit it sits in.
struct UnitIdentity {
    std::string model_name;        ///< as configured ("TDC001"), for HW_GET_INFO and logs
    const ControllerModel& model;
    std::uint32_t serial;
    std::size_t built_in_bays;     ///< a rack's bays with a card (its motherboard's channel count)
    /// The firmware generation the unit follows (the rig's "firmware"): later messages and later
    /// behaviour only under a later generation (docs/protocol/apt.md, "Firmware generations").
    Firmware firmware = Firmware::Issue3;
    std::uint16_t stage_type = 0;  ///< HW_GET_INFO's later stage type word (catalogue.hpp dc_stage_type)
};

/// HW_GET_INFO (p. 21) of a unit or motherboard (no bay) or of a rack bay's card.
msg::HwGetInfo hw_get_info(const UnitIdentity& unit, std::optional<std::size_t> bay);

/// The SET messages a module kind's EEPROMPARAMS message saves, as the shell stores them: the
/// data packet for the module's channel 1 (a header-only SET: its param1 and param2 bytes).
template <class... Sets> struct SavedSets {
    /// Whether `id` is one of Sets.
    static bool saves(std::uint16_t id) { return ((id == Sets::id) || ...); }
    /// The stored form of `m` if it is one of Sets, else nullopt.
    static std::optional<std::string> data(const msg::Message& m);
};

/// What every module kind shares: addressing checks, the Bay family's handlers, the typed
/// dispatch, and the hooks the unit shell calls.
class Module {
public:
    /// EEPROMPARAMS (MOT_ p. 60, PZ_ p. 113): ask the unit shell to save the last SET of message `id`.
    using SaveToEeprom = std::function<void(std::uint16_t id, std::string_view peer)>;

    Module(const UnitIdentity& unit, std::size_t bay, std::uint8_t address, spdlog::logger& log, SaveToEeprom save);
    virtual ~Module() = default;
    Module(const Module&) = delete;
    Module& operator=(const Module&) = delete;

    // ---- What a kind gives the unit shell ----
    /// Act on a message addressed to this module (not a System one: the shell took those).
    virtual void handle(const msg::Message& m, Request& r) = 0;
    /// The status update sent every 100 ms after HW_START_UPDATEMSGS; empty: this kind sends none.
    virtual std::string status_update(std::uint8_t /*host*/) const { return {}; }
    /// The earliest tick (> now) at which tick() has work, or kNever (a motor's channel is the
    /// shell's own Tickable: a motor module has none).
    virtual Ticks next_change(Ticks /*now*/) const { return kNever; }
    /// Something the module does changes by itself after `now` that a test waits for
    /// (AptDevice::busy()); by default, whenever it has a tick to come.
    virtual bool busy(Ticks now) const { return next_change(now) != kNever; }
    /// Bring the module's own timed state (a solenoid's cycles, a piezo's slew and LUT) up to `now`.
    virtual void tick(Ticks /*now*/) {}
    /// Frames the module sent by itself since the last call, to every connection (from `host`'s view:
    /// addressed to it).
    virtual std::vector<std::string> take_unprompted(std::uint8_t /*host*/) { return {}; }
    /// Power cycle: the hardware behind the module (a motor channel, an amplifier's output) back
    /// to its power-up state, and with `restore_positions` the mechanics to where they started.
    /// The shell then replaces the module by a new one (protocol state at power-up).
    virtual void power_down(bool /*restore_positions*/) {}
    /// Whether this kind's EEPROMPARAMS saves SET message `id`.
    virtual bool saves(std::uint16_t id) const = 0;
    /// The data bytes of message `id` this unit reads (a shorter packet is ignored and logged):
    /// the table's fields_length, or more where the model reads more (KCubeParams::fields_read).
    virtual std::size_t fields_read(std::uint16_t id) const;
    /// The stored form of `m` (SavedSets) if it is a SET this kind saves, else nullopt.
    virtual std::optional<std::string> saved_data(const msg::Message& m) const = 0;
    /// The kind's fields of its channel object in the control API (docs/control-api/apt.md
    /// "Channels"). A motor channel's object is the shell's (its faults and switch PATCHes act
    /// on the MotorChannel): a motor module adds nothing.
    virtual void describe(nlohmann::json& /*out*/) const {}
    /// PATCH of the channel: the kind's keys. Motor channels are patched by the shell.
    virtual Refused patch(const nlohmann::json& body);
    /// GET .../channels/{index}/trace (ControlSurface::trace): the kind's output trace; a kind
    /// without an output to trace answers 404.
    virtual Refused trace(Ticks from, std::size_t max, nlohmann::json& out) const;

    /// Where a module publishes its events (lut_started, lut_ended, solenoid) for the control
    /// API's stream: the unit shell's, which adds the channel and drops them while nobody listens.
    using EventSink = std::function<void(std::string_view type, const nlohmann::json& data)>;
    virtual void set_event_sink(EventSink sink) { event_sink_ = std::move(sink); }

    std::uint8_t address() const { return address_; }
    std::size_t bay() const { return bay_; }
    /// Whether a message for channel `sent` (a cube's 0 read as 1) is this module's: channel 1;
    /// a polarisation controller's paddles are bits 1, 2, 4 of the channel byte.
    virtual bool takes_channel(std::uint16_t sent) const { return sent == 0x01; }
    /// MOD_SET/REQ_CHANENABLESTATE's state: a motor's channel, else the module's own flag.
    virtual bool enabled() const { return enabled_; }
    virtual void set_enabled(bool on) { enabled_ = on; }

    // ---- Bay family (every kind) ----
    /// MGMSG_MOD_SET_CHANENABLESTATE (p. 17).
    void on(const msg::ModSetChanEnableState& m);
    /// MGMSG_MOD_REQ_CHANENABLESTATE (p. 17): answers MGMSG_MOD_GET_CHANENABLESTATE.
    void on(const msg::ModReqChanEnableState& m);
    /// MGMSG_HW_REQ_INFO (p. 21): answers MGMSG_HW_GET_INFO.
    void on(const msg::HwReqInfo& m);
    /// MGMSG_HUB_REQ_BAYUSED (p. 24): a cube answers it stands alone; a rack bay ignores it.
    void on(const msg::HubReqBayUsed& m);

protected:
    /// handle() of a kind `Self`: `m` through dispatch() as Self.
    template <class Self> void visit_as(Self& self, const msg::Message& m, Request& r);
    /// The visit of a module kind `Self`: System messages were the shell's; Bay messages go to
    /// their handler; the others must be in the model's MessageSet (if it has one) and address
    /// channel 1, then go to Self's handler if Self acts on their family and their SET fields are
    /// in range, else are ignored and logged.
    template <class Self, class T> void dispatch(Self& self, const T& m);

    /// Log warning `text` and mark the message ignored (a SET is then not saved by EEPROMPARAMS).
    void ignore(const std::string& text);
    /// "<name> is not a message a <model> acts on: ignored".
    void not_mine();
    /// The message is in the model's MessageSet (with the later generation: or in its
    /// later_takes), or the model has none; else logged and ignored.
    bool taken();
    /// The data packet holds the fields the unit reads (fields_read); else logged and ignored.
    bool long_enough();
    /// The unit follows a later firmware generation than the manual's (its "firmware").
    bool later_generation() const { return unit_.firmware != Firmware::Issue3; }
    /// The unit takes message `id` only as the later generation does (ControllerModel::later_takes).
    bool takes_later(std::uint16_t id) const { return later_generation() && unit_.model.later_takes.contains(id); }
    /// The channel the message addresses (a cube's channel 0 read as 1).
    std::uint16_t channel() const;
    /// Log and ignore a message for another channel than 1.
    void wrong_channel();
    /// The channel the message addresses is this module's; else logged and ignored.
    bool channel_ok();
    /// Every field of the SET being handled is within the manual's range; else logged and ignored.
    bool in_range();
    /// Reply with message `m` from this module.
    template <class T> void answer(const T& m);
    /// next_change() of a module whose bodies (`bodies`, pointers to models::Body) end their moves
    /// by themselves and whose end messages wait for the tick after (`pending`: some do now).
    template <class Bodies> static Ticks next_body_event(const Bodies& bodies, Ticks now, bool pending)
    {
        if (pending)
            return now + 1;   // an end the world has woken a body for is sent at that tick
        Ticks next = kNever;
        for (const auto* body : bodies) {
            const Ticks at = body->next_event(now);
            if (at != kNever)
                next = std::min(next, std::max(at, now + 1));
        }
        return next;
    }
    /// Publish event `type` with `data` (an object) through the shell's sink, if any.
    void publish(std::string_view type, const nlohmann::json& data) const
    {
        if (event_sink_)
            event_sink_(type, data);
    }

    const UnitIdentity& unit_;
    std::size_t bay_;
    std::uint8_t address_;
    spdlog::logger& log_;
    SaveToEeprom save_to_eeprom_;
    Request* request_ = nullptr;           ///< the message being handled
    const msg::Message* message_ = nullptr;

private:
    bool enabled_ = true;
    EventSink event_sink_;
};

// ---- templates ----

namespace module_detail {
/// Whether SET T's parameter block starts with a channel word (TPZ_DISPSETTINGS has none, p. 114).
template <class T, class = void> struct HasChannelWord : std::false_type {};
template <class T>
struct HasChannelWord<T, std::void_t<decltype(std::declval<T&>().params.chan_ident)>> : std::true_type {};
/// Whether T is a parameter SET/GET (it has a parameter block).
template <class T, class = void> struct HasParams : std::false_type {};
template <class T> struct HasParams<T, std::void_t<decltype(std::declval<T&>().params)>> : std::true_type {};
/// Whether T declares it addresses no channel (PZ_SET_LUTVALUETYPE: param1 is the type, p. 126).
template <class T, class = void> struct DeclaresNoChannel : std::false_type {};
template <class T> struct DeclaresNoChannel<T, std::void_t<decltype(T::no_channel)>> : std::bool_constant<T::no_channel> {};
/// A parameter SET whose block carries no channel word (PZ_SET_TPZ_DISPSETTINGS, p. 114): the
/// unit's one display, whatever its first word says; or a message that addresses no channel.
template <class T>
constexpr bool kNoChannelWord = (HasParams<T>::value && !HasChannelWord<T>::value) || DeclaresNoChannel<T>::value;
} // namespace module_detail

namespace module_detail {
/// The stored form of SET `typed` (SavedSets::data).
template <class T> std::string saved_data(const T& typed)
{
    if constexpr (T::header_only) {
        // The channel in param1, the setting in param2 (the SOL_ and PZ_ mode SETs, p. 85-94).
        const auto frame = msg::encode(typed, 0, 0);
        return std::string{static_cast<char>(1), frame[3]};
    } else {
        // Saved as the parameters of the module's channel, whatever channel word the SET carried.
        T saved = typed;
        if constexpr (HasChannelWord<T>::value)
            saved.params.chan_ident = 1;
        return msg::encode_data(saved);
    }
}
} // namespace module_detail

template <class... Sets> std::optional<std::string> SavedSets<Sets...>::data(const msg::Message& m)
{
    // One get_if per SET this kind saves, not a visit of every message: a visit instantiated a
    // body for each of the 166 messages per module kind (docs/architecture.md#build-options).
    std::optional<std::string> stored;
    (void)((msg::get_if<Sets>(m) != nullptr && (stored = module_detail::saved_data(*msg::get_if<Sets>(m)), true)) ||
           ...);
    return stored;
}

template <class T> void Module::answer(const T& m)
{
    assert(request_ != nullptr && "a module answers or ignores only while it handles a message");
    request_->reply += msg::encode(m, request_->host, address_);
}

template <class Self> void Module::visit_as(Self& self, const msg::Message& m, Request& r)
{
    // The request lives for this call only: ticks, PATCHes and power-downs run without one.
    struct Clear {
        Module& module;
        ~Clear() { module.request_ = nullptr; module.message_ = nullptr; }
    } clear{*this};
    request_ = &r;
    message_ = &m;
    msg::visit([this, &self](const auto& typed) { this->dispatch(self, typed); }, m);
}

template <class Self, class T> void Module::dispatch(Self& self, const T& m)
{
    constexpr msg::Family family = T::family;
    if constexpr (family == msg::Family::System) {
        return;   // the unit shell acted on it before
    } else if constexpr (family == msg::Family::Bay) {
        self.on(m);
    } else {
        if (!taken() || !long_enough() || (!module_detail::kNoChannelWord<T> && !channel_ok()))
            return;
        // Ranges are the acting module's: a unit without the family's module just ignores it.
        if constexpr (Self::handles(family)) {
            if (in_range())
                self.on(m);
        } else {
            not_mine();
        }
    }
}

} // namespace rigsim::apt
