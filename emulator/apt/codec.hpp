#pragma once
// APT codec: one struct per message a motor unit acts on or sends, with the manual's field
// names (Thorlabs APT protocol, issue 3, corrected by the ERRATA), decode(frame) into a
// std::variant and encode(struct, dest, source) back to bytes. It knows no device.
//
// Every struct lists its fields in wire order once, in `fields()`; encode and decode walk
// that list (little-endian, section 6 corrected by the ERRATA). Header-only messages carry
// their fields in the header's param1 and param2 (one byte each). A parameter block shared
// by a SET/REQ/GET trio is one struct (VelParams, ...) wrapped by Set<>, Req<> and Get<>:
// a SET knows its GET through the block's IDs, so no ID arithmetic is needed.
//
// decode() never throws: an ID outside the table, or a packet short of the fields any unit reads
// (messages.hpp fields_length), is an Untyped (ID, params, data); a longer packet's tail is ignored,
// a shorter one's reserved tail read as zeros (codec.cpp as<T>). Same length: encode gives it back.
//
// The structs stand in one file per chapter of the manual, each a part of this header:
// codec_system.hpp, codec_motor.hpp, codec_solenoid.hpp, codec_piezo.hpp (with the strain gauge
// reader), and the later issues' codec_kcube_units.hpp, codec_pzmot.hpp and codec_kcube.hpp.

#include "emulator/apt/frame_framer.hpp"
#include "emulator/apt/messages.hpp"
#include "emulator/apt/wire.hpp"

#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>

namespace rigsim::apt {
/// The typed messages (a namespace of their own: motor_channel.hpp has a JogParams too).
namespace msg {

/// Which module acts on a message; the others ignore it (and log it).
enum class Family {
    System,      ///< the unit shell: identify, disconnect, update messages, end-of-move messages
    Bay,         ///< every module of every kind: channel enable state, info, hub bay
    Rack,        ///< a rack's motherboard
    Motor,       ///< every motor module: counters, moves, trios, status; the solenoid module its
                 ///< AVMODES, BUTTONPARAMS, EEPROMPARAMS (catalogue takes list)
    DcServo,     ///< DC servo and brushless modules (not steppers): PID, DC status
    Pmd,         ///< brushless (PMD) modules: the PMD parameter trios
    Solenoid,    ///< SolenoidModule (TSC001, KSC101)
    Piezo,       ///< PiezoModule (TPZ001, KPZ101, BPC30x bays); StrainGaugeModule its share of the TSG001 list
    StrainGauge, ///< StrainGaugeModule (TSG001, KSG101)
    KCubeMotor,  ///< motor messages of later protocol issues (codec_kcube.hpp): the motor modules' KCubeParams
    Flipper,     ///< FlipperModule (MFF101, MFF102): MFF_OPERPARAMS (codec_kcube_units.hpp)
    Polariser,   ///< PolariserModule (MPC320, MPC220): POL_PARAMS (codec_kcube_units.hpp)
    PzMotor,     ///< PzMotorModule (KIM101, TIM101): the PZMOT family (codec_pzmot.hpp)
    UnitToHost,  ///< sent by units (GETs, end-of-move messages): a unit ignores them
    Untyped,     ///< not typed by the codec (unknown ID, or a form its struct does not have)
};

/// Lists a struct's fields in wire order, once: `fields(s)` ties them for encode and decode, and
/// `field_names` is the same list as text ("s.chan_ident, s.position"), from which the wire log
/// takes the names it shows (wire_decode.cpp). The members are named as `s.<member>`.
#define RIGSIM_APT_FIELDS(...)                                                                                        \
    template <class S> static auto fields(S& s) { return std::tie(__VA_ARGS__); }                                     \
    static constexpr std::string_view field_names = #__VA_ARGS__

/// Which units read a field whose range a SET must keep.
enum class ReadBy : std::uint8_t {
    AnyUnit,     ///< every unit that takes the message
    WheelUnit,   ///< a unit with a top-panel wheel only (ControllerModel::mmi_wheel): the others take any value
};

/// One field's range as a SET of its block must keep it (out_of_range(), set_ranges.hpp).
struct FieldRange {
    std::string_view name;   ///< as the log names it: "<name> <value> (<min>..<max>)"
    std::int64_t value;
    std::int64_t min;
    std::int64_t max;
    ReadBy read_by = ReadBy::AnyUnit;
};

/// A signed long's largest value: the upper end of a count or velocity that has no other.
inline constexpr std::int64_t kMaxLong = 2'147'483'647;

namespace codec_detail {
template <std::size_t N> std::array<FieldRange, N> field_ranges(const FieldRange (&ranges)[N])
{
    std::array<FieldRange, N> out{};
    for (std::size_t i = 0; i < N; ++i)
        out[i] = ranges[i];
    return out;
}
} // namespace codec_detail

/// Lists, next to RIGSIM_APT_FIELDS, the ranges (the manual's, or a later issue's public source's: a
/// comment above cites it) that a SET of the block must keep: `{"name", s.member, min, max}` each (a fifth
/// ReadBy::WheelUnit for a field only some units read), in the order out_of_range() checks them. A field
/// without an entry takes any value; a block without the macro has no ranges.
#define RIGSIM_APT_RANGES(...)                                                                                        \
    template <class S> static auto ranges(const S& s) { return codec_detail::field_ranges({__VA_ARGS__}); }         \
    static constexpr bool has_ranges = true

/// True when message `id` is a bare header in its table layout (messages.def); an ID the table
/// does not know does not compile.
constexpr bool header_only_in_table(std::uint16_t id)
{
    const auto length = data_length_of(id);
    return length == kNotInTable ? throw "an APT message struct whose ID is not in messages.def" : length < 0;
}

/// SET of a parameter trio: the host sets the block.
template <class P> struct Set {
    static constexpr std::uint16_t id = P::set_id;
    static constexpr bool header_only = header_only_in_table(id);
    static constexpr Family family = P::family;
    using Params = P;
    P params;
    template <class S> static auto fields(S& s) { return P::fields(s.params); }
    static constexpr std::string_view field_names = P::field_names;
};

/// REQ of a parameter trio: header only, the channel in param1.
template <class P> struct Req {
    static constexpr std::uint16_t id = P::req_id;
    static constexpr bool header_only = header_only_in_table(id);
    static constexpr Family family = P::family;
    using Params = P;
    std::uint8_t chan_ident = 1;
    RIGSIM_APT_FIELDS(s.chan_ident);
};

/// GET of a parameter trio: the unit's answer to the REQ.
template <class P> struct Get {
    static constexpr std::uint16_t id = P::get_id;
    static constexpr bool header_only = header_only_in_table(id);
    static constexpr Family family = Family::UnitToHost;
    using Params = P;
    P params;
    template <class S> static auto fields(S& s) { return P::fields(s.params); }
    static constexpr std::string_view field_names = P::field_names;
};

// ---- The macros of the messages of one struct each (the chapter files below use them) ----

/// Declares the ID and family of a message struct; its form (header-only or not) is the table's
/// (messages.def).
#define RIGSIM_APT_MESSAGE(ID, FAMILY)                                                                                \
    static constexpr std::uint16_t id = ID;                                                                           \
    static constexpr bool header_only = header_only_in_table(ID);                                                     \
    static constexpr Family family = Family::FAMILY

/// A header-only message without parameters.
#define RIGSIM_APT_BARE_MESSAGE(NAME, ID, FAMILY)                                                                     \
    struct NAME {                                                                                                     \
        RIGSIM_APT_MESSAGE(ID, FAMILY);                                                                               \
        template <class S> static auto fields(S&) { return std::tuple<>(); }                                          \
        static constexpr std::string_view field_names = "";                                                          \
    }

} // namespace msg
} // namespace rigsim::apt

// The messages by the manual's chapters; each file is a part of this header.
#include "emulator/apt/codec_system.hpp"
#include "emulator/apt/codec_motor.hpp"
#include "emulator/apt/codec_solenoid.hpp"
#include "emulator/apt/codec_piezo.hpp"
// The K-Cube piezo driver's and strain gauge reader's own messages (later protocol issues).
#include "emulator/apt/codec_kcube_units.hpp"
// The KIM101/TIM101 piezo motor controllers' PZMOT family (later protocol issues).
#include "emulator/apt/codec_pzmot.hpp"

namespace rigsim::apt {
namespace msg {

#undef RIGSIM_APT_BARE_MESSAGE
#undef RIGSIM_APT_MESSAGE

/// A message the codec does not type (an ID outside the table), or whose data packet has another length than
/// its struct's: kept whole.
struct Untyped {
    static constexpr Family family = Family::Untyped;
    std::uint16_t id = 0;
    std::uint8_t param1 = 0;
    std::uint8_t param2 = 0;
    bool has_data = false;
    std::string data;   ///< the data packet
    RIGSIM_APT_FIELDS(s.id, s.param1, s.param2, s.has_data, s.data);
};

} // namespace msg
} // namespace rigsim::apt

#include "emulator/apt/codec_kcube.hpp"
#undef RIGSIM_APT_FIELDS
#undef RIGSIM_APT_RANGES

namespace rigsim::apt {
namespace msg {

// ---- The decoded message: a variant of the manual's chapters, each a variant of its messages ----
//
// One flat std::variant of all 166 messages would cost minutes of compile time and hundreds of
// megabytes of debug information per file that visits it (libstdc++ instantiates its storage and
// accessors per alternative, each named after all 166 types). Two levels, each a struct with a short
// name, cost a few percent of that. msg::visit() walks both levels; get_if<T>() and holds<T>() find
// one message.

/// Generic System Control Messages (p. 15-26).
struct GenericMessage : std::variant<ModIdentify, ModSetChanEnableState, ModReqChanEnableState, ModGetChanEnableState,
                                     HwDisconnect, HwResponse, HwRichResponse, HwStartUpdateMsgs, HwStopUpdateMsgs,
                                     HwReqInfo, HwGetInfo, RackReqBayUsed, RackGetBayUsed, HubReqBayUsed,
                                     HubGetBayUsed, RackReqStatusBits, RackGetStatusBits, RackSetDigOutputs,
                                     RackReqDigOutputs, RackGetDigOutputs, HwYesFlashProgramming,
                                     HwNoFlashProgramming> {
    using variant::variant;
};
/// The motor parameter trios (p. 27-60).
struct MotorTrioMessage
    : std::variant<SetPosCounter, ReqPosCounter, GetPosCounter, SetEncCounter, ReqEncCounter, GetEncCounter,
                   SetVelParams, ReqVelParams, GetVelParams, SetJogParams, ReqJogParams, GetJogParams,
                   SetGenMoveParams, ReqGenMoveParams, GetGenMoveParams, SetMoveRelParams, ReqMoveRelParams,
                   GetMoveRelParams, SetMoveAbsParams, ReqMoveAbsParams, GetMoveAbsParams, SetHomeParams,
                   ReqHomeParams, GetHomeParams, SetLimSwitchParams, ReqLimSwitchParams, GetLimSwitchParams,
                   SetDcPidParams, ReqDcPidParams, GetDcPidParams, SetAvModes, ReqAvModes, GetAvModes, SetPotParams,
                   ReqPotParams, GetPotParams, SetButtonParams, ReqButtonParams, GetButtonParams> {
    using variant::variant;
};
/// The brushless (PMD) parameter trios (p. 61-76).
struct PmdTrioMessage
    : std::variant<SetPmdPositionLoopParams, ReqPmdPositionLoopParams, GetPmdPositionLoopParams,
                   SetPmdMotorOutputParams, ReqPmdMotorOutputParams, GetPmdMotorOutputParams,
                   SetPmdTrackSettleParams, ReqPmdTrackSettleParams, GetPmdTrackSettleParams,
                   SetPmdProfileModeParams, ReqPmdProfileModeParams, GetPmdProfileModeParams,
                   SetPmdCurrentLoopParams, ReqPmdCurrentLoopParams, GetPmdCurrentLoopParams,
                   SetPmdSettledCurrentLoopParams, ReqPmdSettledCurrentLoopParams, GetPmdSettledCurrentLoopParams,
                   SetPmdStageAxisParams, ReqPmdStageAxisParams, GetPmdStageAxisParams> {
    using variant::variant;
};
/// Moves, end-of-move and status messages (p. 41-83).
struct MoveStatusMessage
    : std::variant<MoveHome, MoveHomed, MoveRelative, MoveAbsolute, MoveJog, MoveVelocity, MoveStop, MoveCompleted,
                   MoveStopped, SetEepromParams, ReqStatusUpdate, GetStatusUpdate, ReqDcStatusUpdate,
                   GetDcStatusUpdate, AckDcStatusUpdate, ReqStatusBits, GetStatusBits, SuspendEndOfMoveMsgs,
                   ResumeEndOfMoveMsgs> {
    using variant::variant;
};
/// Solenoid Control Messages (p. 84-92).
struct SolenoidMessage
    : std::variant<SolSetOperatingMode, SolReqOperatingMode, SolGetOperatingMode, SetSolCycleParams,
                   ReqSolCycleParams, GetSolCycleParams, SolSetInterlockMode, SolReqInterlockMode,
                   SolGetInterlockMode, SolSetState, SolReqState, SolGetState> {
    using variant::variant;
};
/// The piezo and strain gauge parameter trios (p. 93-129).
struct PiezoTrioMessage
    : std::variant<SetPzOutputVolts, ReqPzOutputVolts, GetPzOutputVolts, SetPzOutputPos, ReqPzOutputPos,
                   GetPzOutputPos, SetPzInputVoltsSrc, ReqPzInputVoltsSrc, GetPzInputVoltsSrc, SetPzPiConsts,
                   ReqPzPiConsts, GetPzPiConsts, SetPzOutputLut, ReqPzOutputLut, GetPzOutputLut, SetPzOutputLutParams,
                   ReqPzOutputLutParams, GetPzOutputLutParams, SetTpzDispSettings, ReqTpzDispSettings,
                   GetTpzDispSettings, SetTpzIoSettings, ReqTpzIoSettings, GetTpzIoSettings, SetPzIoSettings,
                   ReqPzIoSettings, GetPzIoSettings, SetPzOutputMaxVolts, ReqPzOutputMaxVolts, GetPzOutputMaxVolts,
                   SetTpzSlewRates, ReqTpzSlewRates, GetTpzSlewRates, SetTsgIoSettings, ReqTsgIoSettings,
                   GetTsgIoSettings> {
    using variant::variant;
};
/// The other piezo and strain gauge messages (p. 93-129).
struct PiezoMessage
    : std::variant<PzSetPosControlMode, PzReqPosControlMode, PzGetPosControlMode, PzReqPzStatusBits,
                   PzAckPzStatusUpdate, PzStartLutOutput, PzStopLutOutput, PzSetZero, PzReqMaxTravel,
                   MotSetPzStageParamDefaults, PzSetLutValueType, TsgReqReading, PzGetPzStatusBits,
                   PzGetPzStatusUpdate, PzSetEepromParams, PzGetMaxTravel, TsgGetReading> {
    using variant::variant;
};

namespace codec_detail {
template <class T, class V> struct IsIn : std::false_type {};
// A fold of is_same_v (a compiler built-in), not std::disjunction of 166 is_same classes per message.
template <class T, class... Ts> struct IsIn<T, std::variant<Ts...>> : std::bool_constant<(std::is_same_v<T, Ts> || ...)> {};
/// The chapter (Group) whose variant holds message T; no `type` if none does.
template <class T, class... Groups> struct GroupOf {};
template <class T, class G, class... Groups>
struct GroupOf<T, G, Groups...>
    : std::conditional_t<IsIn<T, typename G::variant>::value, std::common_type<G>, GroupOf<T, Groups...>> {};
} // namespace codec_detail

/// Every chapter, in the order of Message's alternatives.
using Chapters = std::tuple<GenericMessage, MotorTrioMessage, PmdTrioMessage, MoveStatusMessage, SolenoidMessage,
                            PiezoTrioMessage, PiezoMessage, KCubeMotorMessage, KCubeUnitMessage, PzmotMessage>;

namespace codec_detail {
template <class T, class C> struct GroupOfIn;
template <class T, class... G> struct GroupOfIn<T, std::tuple<G...>> : GroupOf<T, G...> {};
} // namespace codec_detail

/// The chapter of typed message T (GenericMessage, ...).
template <class T> using GroupOf = typename codec_detail::GroupOfIn<T, Chapters>::type;

/// Every message decode() can return: a chapter's message, or an Untyped.
struct Message : std::variant<GenericMessage, MotorTrioMessage, PmdTrioMessage, MoveStatusMessage, SolenoidMessage,
                              PiezoTrioMessage, PiezoMessage, KCubeMotorMessage, KCubeUnitMessage, PzmotMessage,
                              Untyped> {
    Message() = default;
    /// Typed message `m`, in its chapter.
    template <class T, class G = GroupOf<T>>
    Message(T m) : variant(std::in_place_type<G>, std::in_place_type<T>, std::move(m))
    {
    }
    Message(Untyped m) : variant(std::in_place_type<Untyped>, std::move(m)) {}
};

namespace codec_detail {
template <class R, class F, class V, std::size_t I> R call_alternative(F& f, const V& v)
{
    return f(*std::get_if<I>(&v));
}
/// f called with the alternative `v` holds, through a table of one function per alternative.
/// libstdc++'s std::visit (C++17) also checks every alternative's invoke_result against the
/// others' and builds its table through templates of its own: with 166 messages visited by every
/// module kind, that was most of what the APT library cost to compile
/// (docs/architecture.md#build-options). R is f's result for the first alternative; every
/// alternative's must convert to it.
template <class F, class V, std::size_t... I> decltype(auto) visit_alternatives(F& f, const V& v, std::index_sequence<I...>)
{
    using R = decltype(f(*std::get_if<0>(&v)));
    using Call = R (*)(F&, const V&);
    static constexpr Call table[] = {&call_alternative<R, F, V, I>...};
    if (v.valueless_by_exception())
        throw std::bad_variant_access{};
    return table[v.index()](f, v);
}
template <class F, class... Ts> decltype(auto) visit_variant(F& f, const std::variant<Ts...>& v)
{
    return visit_alternatives(f, v, std::index_sequence_for<Ts...>{});
}
} // namespace codec_detail

/// Calls f with the typed message (or Untyped) `m` holds; f returns one type for all.
template <class F> decltype(auto) visit(F&& f, const Message& m)
{
    auto in_group = [&f](const auto& group) -> decltype(auto) {
        if constexpr (std::is_same_v<std::decay_t<decltype(group)>, Untyped>)
            return f(group);
        else
            return codec_detail::visit_variant(f, static_cast<const typename std::decay_t<decltype(group)>::variant&>(group));
    };
    return codec_detail::visit_variant(in_group, static_cast<const Message::variant&>(m));
}

/// The message T that `m` holds, or nullptr.
template <class T> const T* get_if(const Message& m)
{
    if constexpr (std::is_same_v<T, Untyped>) {
        return std::get_if<Untyped>(&static_cast<const Message::variant&>(m));
    } else {
        using G = GroupOf<T>;
        const auto* group = std::get_if<G>(&static_cast<const Message::variant&>(m));
        return group ? std::get_if<T>(&static_cast<const typename G::variant&>(*group)) : nullptr;
    }
}

/// Whether `m` holds message T.
template <class T> bool holds(const Message& m) { return get_if<T>(m) != nullptr; }

/// The typed message of a frame (an Untyped if the codec has no struct for it).
Message decode(const Frame& frame);

// ---- Encoding ----

namespace codec_detail {

inline void put(std::string& out, std::uint8_t v) { put_u8(out, v); }
inline void put(std::string& out, std::uint16_t v) { put_u16(out, v); }
inline void put(std::string& out, std::int16_t v) { put_i16(out, v); }
inline void put(std::string& out, std::uint32_t v) { put_u32(out, v); }
inline void put(std::string& out, std::int32_t v) { put_i32(out, v); }
template <std::size_t N> void put(std::string& out, const std::array<char, N>& v) { out.append(v.data(), N); }
inline void put(std::string& out, const MotorStatus& v)
{
    std::visit([&](const auto& s) { std::apply([&](const auto&... f) { (put(out, f), ...); }, s.fields(s)); }, v);
}
inline void put(std::string& out, const std::optional<std::int32_t>& v)
{
    if (v)
        put_i32(out, *v);
}
/// A PZMOT sub-message block: its SubMsgID, then its fields.
inline void put(std::string& out, const PzmotBlock& b)
{
    std::visit(
        [&](const auto& s) {
            put_u16(out, std::decay_t<decltype(s)>::sub_id);
            std::apply([&](const auto&... f) { (put(out, f), ...); }, s.fields(s));
        },
        b);
}

template <class T> std::uint8_t param_byte(const T& v) { return static_cast<std::uint8_t>(v); }

} // namespace codec_detail

/// The data packet of message `m` (empty for a header-only message).
template <class T> std::string encode_data(const T& m)
{
    std::string out;
    std::apply([&](const auto&... f) { (codec_detail::put(out, f), ...); }, T::fields(m));
    return out;
}

namespace codec_detail {
/// A frame being written: a buffer of the largest frame, copied into a string once (status
/// updates and GETs are the hot path; byte-wise string appends cost more than the handler).
struct FrameBuffer {
    std::array<char, kMaxFrameSize> bytes;
    std::size_t size = 0;
    void append(const char* p, std::size_t n)
    {
        std::memcpy(bytes.data() + size, p, n);
        size += n;
    }
};
inline void put(FrameBuffer& out, std::uint8_t v)
{
    const char c = static_cast<char>(v);
    out.append(&c, 1);
}
inline void put(FrameBuffer& out, std::uint16_t v)
{
    const char b[2] = {static_cast<char>(v & 0xFF), static_cast<char>(v >> 8)};
    out.append(b, 2);
}
inline void put(FrameBuffer& out, std::int16_t v) { put(out, static_cast<std::uint16_t>(v)); }
inline void put(FrameBuffer& out, std::uint32_t v)
{
    const char b[4] = {static_cast<char>(v & 0xFF), static_cast<char>((v >> 8) & 0xFF),
                       static_cast<char>((v >> 16) & 0xFF), static_cast<char>(v >> 24)};
    out.append(b, 4);
}
inline void put(FrameBuffer& out, std::int32_t v) { put(out, static_cast<std::uint32_t>(v)); }
template <std::size_t N> void put(FrameBuffer& out, const std::array<char, N>& v) { out.append(v.data(), N); }
inline void put(FrameBuffer& out, const MotorStatus& v)
{
    std::visit([&](const auto& s) { std::apply([&](const auto&... f) { (put(out, f), ...); }, s.fields(s)); }, v);
}
inline void put(FrameBuffer& out, const std::optional<std::int32_t>& v)
{
    if (v)
        put(out, *v);
}
inline void put(FrameBuffer& out, const PzmotBlock& b)
{
    std::visit(
        [&](const auto& s) {
            put(out, std::decay_t<decltype(s)>::sub_id);
            std::apply([&](const auto&... f) { (put(out, f), ...); }, s.fields(s));
        },
        b);
}

/// The frame of `m` with its data packet: the header (length patched in at the end), then the fields.
template <class T> std::string encode_frame_with_data(const T& m, std::uint8_t dest, std::uint8_t source)
{
    FrameBuffer out;
    put(out, T::id);
    put(out, std::uint16_t{0});
    put(out, static_cast<std::uint8_t>(dest | kDataFlag));
    put(out, source);
    std::apply([&](const auto&... f) { (put(out, f), ...); }, T::fields(m));
    const auto length = static_cast<std::uint16_t>(out.size - kHeaderSize);
    out.bytes[2] = static_cast<char>(length & 0xFF);
    out.bytes[3] = static_cast<char>(length >> 8);
    return std::string(out.bytes.data(), out.size);
}
} // namespace codec_detail

/// Message `m` as a frame from `source` to `dest` (without the data flag).
template <class T> std::string encode(const T& m, std::uint8_t dest, std::uint8_t source)
{
    if constexpr (std::is_same_v<T, MoveRelative> || std::is_same_v<T, MoveAbsolute>) {
        const auto& distance = std::get<1>(T::fields(m));
        if (!distance)
            return encode_header_only(T::id, static_cast<std::uint8_t>(m.chan_ident), 0, dest, source);
        return codec_detail::encode_frame_with_data(m, dest, source);
    } else if constexpr (std::is_same_v<T, Untyped>) {
        return m.has_data ? encode_with_data(m.id, dest, source, m.data)
                          : encode_header_only(m.id, m.param1, m.param2, dest, source);
    } else if constexpr (T::header_only) {
        std::uint8_t params[2] = {0, 0};
        std::size_t i = 0;
        std::apply([&](const auto&... f) { ((params[i++] = codec_detail::param_byte(f)), ...); }, T::fields(m));
        return encode_header_only(T::id, params[0], params[1], dest, source);
    } else {
        return codec_detail::encode_frame_with_data(m, dest, source);
    }
}

/// Any decoded message back to its frame.
std::string encode(const Message& m, std::uint8_t dest, std::uint8_t source);

/// The message ID of a decoded message.
std::uint16_t message_id(const Message& m);

/// Field-by-field equality of two messages of one type (the round-trip tests use it).
template <class T, class = decltype(T::fields(std::declval<const T&>()))>
bool operator==(const T& a, const T& b)
{
    return T::fields(a) == T::fields(b);
}
template <class T, class = decltype(T::fields(std::declval<const T&>()))>
bool operator!=(const T& a, const T& b)
{
    return !(a == b);
}

} // namespace msg
} // namespace rigsim::apt
