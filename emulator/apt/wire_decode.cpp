#include "emulator/apt/wire_decode.hpp"

#include "emulator/apt/codec.hpp"
#include "emulator/apt/frame_framer.hpp"
#include "emulator/apt/messages.hpp"
#include "emulator/core/device.hpp"
#include "emulator/core/wire_log.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <variant>
#include <vector>

namespace rigsim::apt {

namespace {

// The field names the wire log shows, by message ID: each codec struct's own list
// (RIGSIM_APT_FIELDS in codec.hpp: "s.chan_ident, s.position"), split once into its members'
// names, for every message of every chapter of msg::Message.
using NamesTable = std::unordered_map<std::uint16_t, std::vector<std::string_view>>;

std::vector<std::string_view> split_field_names(std::string_view list)
{
    std::vector<std::string_view> names;
    for (std::size_t at = 0; at < list.size();) {
        const auto comma = std::min(list.find(',', at), list.size());
        auto name = list.substr(at, comma - at);
        while (!name.empty() && name.front() == ' ')
            name.remove_prefix(1);
        names.push_back(name.substr(name.rfind('.') + 1));   // "s.params.unused" -> "unused"
        at = comma + 1;
    }
    return names;
}

/// True for the end-of-move messages, whose one field is a status structure that put_status
/// flattens into the fields of its own kind (DC or stepper).
template <class T>
constexpr bool kStatusOnly = std::is_same_v<decltype(T::fields(std::declval<const T&>())), std::tuple<const msg::MotorStatus&>>;

template <class... Messages> void add_chapter(NamesTable& t, const std::variant<Messages...>*)
{
    (
        [&] {
            if (!Messages::field_names.empty() && !kStatusOnly<Messages>)
                t.emplace(Messages::id, split_field_names(Messages::field_names));
        }(),
        ...);
}

template <class... Chapter> void add_chapters(NamesTable& t, const std::tuple<Chapter...>*)
{
    (add_chapter(t, static_cast<const typename Chapter::variant*>(nullptr)), ...);
}

const NamesTable& names_table()
{
    static const NamesTable table = [] {
        NamesTable t;
        add_chapters(t, static_cast<const msg::Chapters*>(nullptr));
        return t;
    }();
    return table;
}

std::string hex_id(unsigned v, int digits)
{
    char buf[12];
    std::snprintf(buf, sizeof buf, "0x%0*x", digits, v);
    return buf;
}

nlohmann::json value(std::uint8_t v) { return v; }
nlohmann::json value(std::uint16_t v) { return v; }
nlohmann::json value(std::int16_t v) { return v; }
nlohmann::json value(std::uint32_t v) { return v; }
nlohmann::json value(std::int32_t v) { return v; }
nlohmann::json value(const std::optional<std::int32_t>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }
/// A PZMOT sub-message block (codec_pzmot.hpp): its ID, its name and its fields by name.
nlohmann::json value(const msg::PzmotBlock& b)
{
    return std::visit(
        [](const auto& block) {
            using B = std::decay_t<decltype(block)>;
            nlohmann::json out{{"sub_msg_id", B::sub_id}, {"sub_msg", B::sub_name}};
            static const auto names = split_field_names(B::field_names);
            std::size_t i = 0;
            std::apply([&](const auto&... f) { ((out[std::string(names[i++])] = f), ...); }, B::fields(block));
            return out;
        },
        b);
}
template <std::size_t N> nlohmann::json value(const std::array<char, N>& a)
{
    std::size_t n = 0;
    while (n < N && a[n] != '\0')
        ++n;
    return printable(std::string_view(a.data(), n), N);
}

/// The table naming the bits of message `id`'s status word on `unit`'s wire.
StatusTable table_of(std::uint16_t id, const LogContext& unit)
{
    if (id == MGMSG_RACK_GET_STATUSBITS)
        return StatusTable::Rack;
    if (id == MGMSG_PZ_GET_PZSTATUSUPDATE || id == MGMSG_PZ_GET_PZSTATUSBITS)
        return unit.unit == StatusTable::StrainGauge ? StatusTable::StrainGauge : StatusTable::Piezo;
    return unit.unit == StatusTable::Solenoid ? StatusTable::Solenoid : StatusTable::Motor;
}

/// The status structure of the end-of-move messages (p. 44, p. 50), flattened. The codec reads
/// it as the DC structure (the bytes cannot tell); a stepper's is MOT_GET_STATUSUPDATE's, whose
/// encoder count (a long) fills the DC structure's velocity and reserved words.
void put_status(const msg::MotorStatus& s, const LogContext& unit, StatusTable table, nlohmann::json& fields)
{
    msg::MotStatus st;
    if (const auto* dc = std::get_if<msg::DcStatus>(&s)) {
        if (!unit.stepper_status) {
            fields["chan_ident"] = dc->chan_ident;
            fields["position"] = dc->position;
            fields["velocity"] = dc->velocity;
            fields["status_bits"] = dc->status_bits;
            fields["status_set"] = status_bit_names(dc->status_bits, table);
            return;
        }
        const auto enc = static_cast<std::uint32_t>(static_cast<std::uint16_t>(dc->velocity))
                         | static_cast<std::uint32_t>(dc->reserved) << 16;
        st = {dc->chan_ident, dc->position, static_cast<std::int32_t>(enc), dc->status_bits};
    } else {
        st = std::get<msg::MotStatus>(s);
    }
    fields["chan_ident"] = st.chan_ident;
    fields["position"] = st.position;
    fields["enc_count"] = st.enc_count;
    fields["status_bits"] = st.status_bits;
    fields["status_set"] = status_bit_names(st.status_bits, table);
}

template <class T> void put_fields(const T& m, std::uint16_t id, const LogContext& unit, nlohmann::json& fields)
{
    auto values = nlohmann::json::array();
    bool status = false;
    std::apply(
        [&](const auto&... f) {
            [[maybe_unused]] auto one = [&](const auto& v) {
                if constexpr (std::is_same_v<std::decay_t<decltype(v)>, msg::MotorStatus>) {
                    put_status(v, unit, table_of(id, unit), fields);
                    status = true;
                } else {
                    values.push_back(value(v));
                }
            };
            (one(f), ...);
        },
        T::fields(m));
    if (status)
        return;
    // Every typed message names its fields (RIGSIM_APT_FIELDS): the list and the values are one.
    const auto* names = field_names(id);
    for (std::size_t i = 0; i < values.size(); ++i)
        fields[names ? std::string((*names)[i]) : "field" + std::to_string(i + 1)] = values[i];
    if (const auto bits = fields.find("status_bits"); bits != fields.end() && bits->is_number_unsigned())
        fields["status_set"] = status_bit_names(bits->get<std::uint32_t>(), table_of(id, unit));
}

} // namespace

const std::vector<std::string_view>* field_names(std::uint16_t id)
{
    const auto& t = names_table();
    const auto it = t.find(id);
    return it == t.end() ? nullptr : &it->second;
}

namespace {

using BitNames = std::vector<std::pair<std::uint32_t, std::string_view>>;

const BitNames& bit_names(StatusTable table)
{
    // MOT_GET_STATUSUPDATE / MOT_GET_DCSTATUSUPDATE (p. 78-79; ERRATA for 0x00000008).
    static const BitNames motor{
        {0x00000001, "forward_hard_limit"}, {0x00000002, "reverse_hard_limit"},
        {0x00000004, "forward_soft_limit"}, {0x00000008, "reverse_soft_limit"},
        {0x00000010, "moving_forward"},     {0x00000020, "moving_reverse"},
        {0x00000040, "jogging_forward"},    {0x00000080, "jogging_reverse"},
        {0x00000100, "motor_connected"},    {0x00000200, "homing"},
        {0x00000400, "homed"},              {0x00001000, "interlock"},
        {0x00002000, "settled"},            {0x00004000, "motion_error"},
        {0x01000000, "current_limit"},      {0x80000000, "enabled"},
    };
    // A solenoid unit's (D-4): the output (the bit Kinesis reads from a KSC101), the interlock
    // mode (p. 77), the key switch (msl-equipment ksc.py is_key_unlocked, bit 13).
    static const BitNames solenoid{{0x00000001, "output_on"}, {0x00001000, "interlock"}, {0x00002000, "key_unlocked"}};
    // PZ_GET_PZSTATUSBITS / PZSTATUSUPDATE (p. 101-104): the TPZ001's table and the BPC's, which
    // adds the hardware voltage range, the digital inputs, active and enabled.
    static const BitNames piezo{
        {0x00000001, "actuator_connected"}, {0x00000010, "zeroed"},          {0x00000020, "zeroing"},
        {0x00000100, "gauge_connected"},    {0x00000400, "closed_loop"},     {0x00001000, "hw_max_75v"},
        {0x00002000, "hw_max_100v"},        {0x00004000, "hw_max_150v"},     {0x00100000, "digital_input_1"},
        {0x00200000, "digital_input_2"},    {0x00400000, "digital_input_3"}, {0x00800000, "digital_input_4"},
        {0x01000000, "digital_input_5"},    {0x02000000, "digital_input_6"}, {0x04000000, "digital_input_7"},
        {0x08000000, "digital_input_8"},    {0x20000000, "active"},          {0x80000000, "enabled"},
    };
    // A strain gauge reader's reading of the piezo table (strain_gauge_module.hpp): bit 0 is its gauge.
    static const BitNames gauge{{0x00000001, "gauge_connected"}, {0x00000010, "zeroed"}, {0x00000020, "zeroing"}};
    // RACK_GET_STATUSBITS (p. 25): the USER IO lines ("inputs" in its text, "Digital output N
    // state" in its table).
    static const BitNames rack{{0x1, "user_io_1"}, {0x2, "user_io_2"}, {0x4, "user_io_3"}, {0x8, "user_io_4"}};
    switch (table) {
    case StatusTable::Motor:
        return motor;
    case StatusTable::Solenoid:
        return solenoid;
    case StatusTable::Piezo:
        return piezo;
    case StatusTable::StrainGauge:
        return gauge;
    case StatusTable::Rack:
        return rack;
    }
    return motor;
}

} // namespace

/// What the wire log must know of `model` to name the fields of its frames.
LogContext log_context(const ControllerModel& model)
{
    LogContext c;
    c.stepper_status = model.kind == UnitKind::Motor && model.motor == MotorKind::Stepper;
    switch (model.kind) {
    case UnitKind::Motor:
        c.unit = StatusTable::Motor;
        break;
    case UnitKind::Solenoid:
        c.unit = StatusTable::Solenoid;
        break;
    case UnitKind::Piezo:
        c.unit = StatusTable::Piezo;
        break;
    case UnitKind::StrainGauge:
        c.unit = StatusTable::StrainGauge;
        break;
    case UnitKind::Flipper:   // its positions in the limit bits (flipper_module.hpp): logged as a motor's
    case UnitKind::Polariser:
    case UnitKind::PiezoMotor:   // PZMOT_GET_STATUSUPDATE's bits are the motor table's (issue 37 p. 405)
        c.unit = StatusTable::Motor;
        break;
    }
    return c;
}

std::vector<std::string_view> status_bit_names(std::uint32_t bits, StatusTable table)
{
    std::vector<std::string_view> out;
    for (const auto& [bit, name] : bit_names(table))
        if (bits & bit)
            out.push_back(name);
    return out;
}

void decode_for_log(std::string_view bytes, nlohmann::json& out, const LogContext& unit)
{
    FrameFramer framer;
    const auto r = framer.parse(bytes);
    if (r.status != FrameFramer::Status::Frame || r.dropped != 0) {
        out["name"] = "not a frame";
        return;
    }
    const Frame& f = r.frame;
    out["id"] = hex_id(f.id, 4);
    out["name"] = f.info ? std::string(f.info->name) : hex_id(f.id, 4);
    out["source"] = hex_id(f.source, 2);
    out["destination"] = hex_id(f.dest, 2);
    auto fields = nlohmann::json::object();
    msg::visit(
        [&](const auto& m) {
            using T = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<T, msg::Untyped>) {
                if (m.has_data)
                    fields["data"] = hex_bytes(m.data);
                else {
                    fields["param1"] = m.param1;
                    fields["param2"] = m.param2;
                }
            } else {
                put_fields(m, f.id, unit, fields);
            }
        },
        msg::decode(f));
    out["fields"] = std::move(fields);
}

} // namespace rigsim::apt
