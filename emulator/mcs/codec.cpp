#include "emulator/mcs/codec.hpp"

#include <array>
#include <charconv>
#include <limits>
#include <type_traits>

namespace rigsim::mcs {
namespace {

constexpr std::size_t kMaxParams = 8;
using Params = std::array<std::int64_t, kMaxParams>;

std::int32_t i32(std::int64_t v) { return static_cast<std::int32_t>(v); }

struct CommandEntry {
    std::string_view name;
    std::size_t min_params;
    std::size_t max_params;
    Command (*build)(const Params& p, std::size_t n);
    unsigned wide_params = 0;   ///< bit i: parameter i may be 0..4,294,967,295
};

// The commands rigsim implements: name, parameter count range, builder.
const CommandEntry kCommands[] = {
    {"GCM", 0, 0, [](const Params&, std::size_t) -> Command { return GetCommunicationMode{}; }},
    {"SCM", 1, 1, [](const Params& p, std::size_t) -> Command { return SetCommunicationMode{i32(p[0])}; }},
    {"GNC", 0, 0, [](const Params&, std::size_t) -> Command { return GetNumberOfChannels{}; }},
    {"GSI", 0, 0, [](const Params&, std::size_t) -> Command { return GetSystemId{}; }},
    {"GIV", 0, 0, [](const Params&, std::size_t) -> Command { return GetInterfaceVersion{}; }},
    {"R", 0, 0, [](const Params&, std::size_t) -> Command { return Reset{}; }},
    {"SHE", 1, 1, [](const Params& p, std::size_t) -> Command { return SetHcmEnabled{i32(p[0])}; }},
    {"GCT", 1, 1, [](const Params& p, std::size_t) -> Command { return GetChannelType{i32(p[0])}; }},
    {"GSE", 0, 0, [](const Params&, std::size_t) -> Command { return GetSensorEnabled{}; }},
    {"SSE", 1, 1, [](const Params& p, std::size_t) -> Command { return SetSensorEnabled{i32(p[0])}; }},
    {"GST", 1, 1, [](const Params& p, std::size_t) -> Command { return GetSensorType{i32(p[0])}; }},
    {"SST", 2, 2, [](const Params& p, std::size_t) -> Command { return SetSensorType{i32(p[0]), i32(p[1])}; }},
    {"GP", 1, 1, [](const Params& p, std::size_t) -> Command { return GetPosition{i32(p[0])}; }},
    {"GS", 1, 1, [](const Params& p, std::size_t) -> Command { return GetStatus{i32(p[0])}; }},
    {"GPPK", 1, 1, [](const Params& p, std::size_t) -> Command { return GetPhysicalPositionKnown{i32(p[0])}; }},
    {"MPA", 3, 3, [](const Params& p, std::size_t) -> Command { return MovePositionAbsolute{i32(p[0]), i32(p[1]), i32(p[2])}; }},
    {"MPR", 3, 3, [](const Params& p, std::size_t) -> Command { return MovePositionRelative{i32(p[0]), i32(p[1]), i32(p[2])}; }},
    {"S", 0, 1, [](const Params& p, std::size_t n) -> Command {
         return n == 0 ? Stop{std::nullopt} : Stop{i32(p[0])};
     }},
    {"SCLS", 2, 2, [](const Params& p, std::size_t) -> Command { return SetClosedLoopSpeed{i32(p[0]), i32(p[1])}; }},
    {"GCLS", 1, 1, [](const Params& p, std::size_t) -> Command { return GetClosedLoopSpeed{i32(p[0])}; }},
    {"SCLA", 2, 2, [](const Params& p, std::size_t) -> Command { return SetClosedLoopAcceleration{i32(p[0]), i32(p[1])}; }},
    {"GCLA", 1, 1, [](const Params& p, std::size_t) -> Command { return GetClosedLoopAcceleration{i32(p[0])}; }},
    {"SCLF", 2, 2, [](const Params& p, std::size_t) -> Command { return SetClosedLoopMaxFrequency{i32(p[0]), i32(p[1])}; }},
    {"SARP", 2, 2, [](const Params& p, std::size_t) -> Command { return SetAccumulateRelativePositions{i32(p[0]), i32(p[1])}; }},
    {"SP", 2, 2, [](const Params& p, std::size_t) -> Command { return SetPosition{i32(p[0]), i32(p[1])}; }},
    {"SZP", 1, 1, [](const Params& p, std::size_t) -> Command { return SetZeroPosition{i32(p[0])}; }},
    {"SSC", 3, 3, [](const Params& p, std::size_t) -> Command { return SetScale{i32(p[0]), i32(p[1]), i32(p[2])}; }},
    {"GSC", 1, 1, [](const Params& p, std::size_t) -> Command { return GetScale{i32(p[0])}; }},
    {"SSD", 2, 2, [](const Params& p, std::size_t) -> Command { return SetSafeDirection{i32(p[0]), i32(p[1])}; }},
    {"GSD", 1, 1, [](const Params& p, std::size_t) -> Command { return GetSafeDirection{i32(p[0])}; }},
    {"SSWS", 2, 2, [](const Params& p, std::size_t) -> Command { return SetStepWhileScan{i32(p[0]), i32(p[1])}; }},
    {"SRC", 2, 2, [](const Params& p, std::size_t) -> Command { return SetReportOnComplete{i32(p[0]), i32(p[1])}; }},
    {"K", 0, 1, [](const Params& p, std::size_t n) -> Command {
         return n == 0 ? KeepAlive{std::nullopt} : KeepAlive{i32(p[0])};
     }},
    {"CB", 1, 1, [](const Params& p, std::size_t) -> Command { return ConfigureBaudrate{i32(p[0])}; }},
    {"GSN", 1, 1, [](const Params& p, std::size_t) -> Command { return GetSerialNumber{i32(p[0])}; }},
    {"GFV", 1, 1, [](const Params& p, std::size_t) -> Command { return GetFirmwareVersion{i32(p[0])}; }},
    {"GFP", 2, 2, [](const Params& p, std::size_t) -> Command { return GetFeaturePermissions{i32(p[0]), i32(p[1])}; }},
    {"FRM", 4, 4, [](const Params& p, std::size_t) -> Command { return FindReferenceMark{i32(p[0]), i32(p[1]), i32(p[2]), i32(p[3])}; }},
    {"CS", 1, 1, [](const Params& p, std::size_t) -> Command { return CalibrateSensor{i32(p[0])}; }},
    {"MAA", 4, 4, [](const Params& p, std::size_t) -> Command { return MoveAngleAbsolute{i32(p[0]), i32(p[1]), i32(p[2]), i32(p[3])}; }},
    {"MAR", 4, 4, [](const Params& p, std::size_t) -> Command { return MoveAngleRelative{i32(p[0]), i32(p[1]), i32(p[2]), i32(p[3])}; }},
    {"GA", 1, 1, [](const Params& p, std::size_t) -> Command { return GetAngle{i32(p[0])}; }},
    {"SPL", 3, 3, [](const Params& p, std::size_t) -> Command { return SetPositionLimit{i32(p[0]), i32(p[1]), i32(p[2])}; }},
    {"GPL", 1, 1, [](const Params& p, std::size_t) -> Command { return GetPositionLimit{i32(p[0])}; }},
    {"SAL", 5, 5, [](const Params& p, std::size_t) -> Command { return SetAngleLimit{i32(p[0]), i32(p[1]), i32(p[2]), i32(p[3]), i32(p[4])}; }},
    {"GAL", 1, 1, [](const Params& p, std::size_t) -> Command { return GetAngleLimit{i32(p[0])}; }},
    {"MST", 4, 4, [](const Params& p, std::size_t) -> Command { return MoveStep{i32(p[0]), i32(p[1]), i32(p[2]), i32(p[3])}; }},
    // MSCA/MSCR scan speed: 1 .. 4,095,000,000, wider than a signed 32-bit value.
    {"MSCA", 3, 3, [](const Params& p, std::size_t) -> Command { return MoveScanAbsolute{i32(p[0]), i32(p[1]), p[2]}; }, 1u << 2},
    {"MSCR", 3, 3, [](const Params& p, std::size_t) -> Command { return MoveScanRelative{i32(p[0]), i32(p[1]), p[2]}; }, 1u << 2},
    {"GVL", 1, 1, [](const Params& p, std::size_t) -> Command { return GetVoltageLevel{i32(p[0])}; }},
    {"GCP", 2, 2, [](const Params& p, std::size_t) -> Command { return GetChannelProperty{i32(p[0]), i32(p[1])}; }},
    {"SCP", 3, 3, [](const Params& p, std::size_t) -> Command { return SetChannelProperty{i32(p[0]), i32(p[1]), i32(p[2])}; }},
    {"GESM", 0, 0, [](const Params&, std::size_t) -> Command { return GetEmergencyStopMode{}; }},
    {"SESM", 1, 1, [](const Params& p, std::size_t) -> Command { return SetEmergencyStopMode{i32(p[0])}; }},
    {"ATC", 2, 2, [](const Params& p, std::size_t) -> Command { return AppendTriggeredCommand{i32(p[0]), i32(p[1])}; }},
    {"CTCQ", 1, 1, [](const Params& p, std::size_t) -> Command { return ClearTriggeredCommandQueue{i32(p[0])}; }},
    {"TC", 1, 1, [](const Params& p, std::size_t) -> Command { return TriggerCommand{i32(p[0])}; }},
    {"SRT", 2, 2, [](const Params& p, std::size_t) -> Command { return SetReportOnTriggered{i32(p[0]), i32(p[1])}; }},
    {"GB", 2, 2, [](const Params& p, std::size_t) -> Command { return GetCaptureBuffer{i32(p[0]), i32(p[1])}; }},
    {"SEET", 4, 4, [](const Params& p, std::size_t) -> Command { return SetEndEffectorType{i32(p[0]), i32(p[1]), i32(p[2]), i32(p[3])}; }},
    {"GEET", 1, 1, [](const Params& p, std::size_t) -> Command { return GetEndEffectorType{i32(p[0])}; }},
    {"MGOA", 3, 3, [](const Params& p, std::size_t) -> Command { return MoveGripperOpeningAbsolute{i32(p[0]), i32(p[1]), i32(p[2])}; }},
    {"MGOR", 3, 3, [](const Params& p, std::size_t) -> Command { return MoveGripperOpeningRelative{i32(p[0]), i32(p[1]), i32(p[2])}; }},
    {"MGFA", 4, 4, [](const Params& p, std::size_t) -> Command { return MoveGripperForceAbsolute{i32(p[0]), i32(p[1]), i32(p[2]), i32(p[3])}; }},
    {"GGO", 1, 1, [](const Params& p, std::size_t) -> Command { return GetGripperOpening{i32(p[0])}; }},
    {"GF", 1, 1, [](const Params& p, std::size_t) -> Command { return GetForce{i32(p[0])}; }},
    {"SZF", 1, 1, [](const Params& p, std::size_t) -> Command { return SetZeroForce{i32(p[0])}; }},
};

bool is_upper(char c) { return c >= 'A' && c <= 'Z'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

Decoded fail(Decoded d, ErrorCode code)
{
    d.error = Error{kSystem, code};
    return d;
}

} // namespace

Decoded decode(std::string_view line)
{
    Decoded d;
    std::size_t i = 0;
    while (i < line.size() && is_upper(line[i]))
        ++i;
    d.name = line.substr(0, i);
    if (d.name.empty())
        return fail(d, ErrorCode::Syntax);

    // Parameters: decimal integers, optionally signed, separated by commas (manual 1.1).
    // Any other character (white space, lower case, '.', '\r') is a syntax error.
    const auto rest = line.substr(i);
    for (char c : rest)
        if (!is_digit(c) && c != ',' && c != '-' && c != '+')
            return fail(d, ErrorCode::Syntax);

    Params params{};
    std::size_t count = 0;
    unsigned overflow_mask = 0;   // bit i: parameter i does not fit a signed 32-bit value
    unsigned huge_mask = 0;       // bit i: parameter i does not fit 0..4,294,967,295 either
    if (!rest.empty()) {
        std::size_t pos = 0;
        while (true) {
            const auto comma = rest.find(',', pos);
            auto field = rest.substr(pos, comma == std::string_view::npos ? std::string_view::npos : comma - pos);
            if (!field.empty() && field.front() == '+')
                field.remove_prefix(1);
            if (field.empty() || field == "-")
                return fail(d, ErrorCode::Parse);
            long long value = 0;
            const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
            const unsigned bit = count < 32 ? 1u << count : 0u;
            if (ec == std::errc::result_out_of_range) {
                overflow_mask |= bit;
                huge_mask |= bit;
            } else if (ec != std::errc() || end != field.data() + field.size()) {
                return fail(d, ErrorCode::Parse);   // e.g. "1-2", "--3"
            } else {
                if (value < std::numeric_limits<std::int32_t>::min()
                    || value > std::numeric_limits<std::int32_t>::max())
                    overflow_mask |= bit;
                if (value < std::numeric_limits<std::int32_t>::min()
                    || value > std::numeric_limits<std::uint32_t>::max())
                    huge_mask |= bit;
            }
            if (count < kMaxParams)
                params[count] = value;
            ++count;
            if (comma == std::string_view::npos)
                break;
            pos = comma + 1;
        }
    }

    for (const auto& entry : kCommands) {
        if (entry.name != d.name)
            continue;
        if (count < entry.min_params)
            return fail(d, ErrorCode::TooFewParameters);
        if (count > entry.max_params)
            return fail(d, ErrorCode::TooManyParameters);
        if ((overflow_mask & ~entry.wide_params) != 0 || (huge_mask & entry.wide_params) != 0)
            return fail(d, ErrorCode::Overflow);
        d.command = entry.build(params, count);
        return d;
    }
    return fail(d, ErrorCode::InvalidCommand);
}

namespace {

template <typename T, typename = void>
struct HasChannel : std::false_type {};
template <typename T>
struct HasChannel<T, std::void_t<decltype(T::channel)>>
    : std::is_same<std::decay_t<decltype(T::channel)>, std::int32_t> {};

} // namespace

std::optional<std::int32_t> channel_of(const Command& command)
{
    return std::visit(
        [](const auto& c) -> std::optional<std::int32_t> {
            if constexpr (HasChannel<std::decay_t<decltype(c)>>::value)
                return c.channel;
            else
                return std::nullopt;
        },
        command);
}

bool is_movement(const Command& command)
{
    return std::holds_alternative<MovePositionAbsolute>(command)
        || std::holds_alternative<MovePositionRelative>(command)
        || std::holds_alternative<MoveAngleAbsolute>(command)
        || std::holds_alternative<MoveAngleRelative>(command)
        || std::holds_alternative<MoveStep>(command) || std::holds_alternative<MoveScanAbsolute>(command)
        || std::holds_alternative<MoveScanRelative>(command)
        || std::holds_alternative<FindReferenceMark>(command);
}

void encode(const Reply& reply, std::string& out)
{
    out += ':';
    if (const auto* ack = std::get_if<Ack>(&reply)) {
        out += 'E';
        out += std::to_string(ack->channel);
        out += ",0";
    } else if (const auto* err = std::get_if<Error>(&reply)) {
        out += 'E';
        out += std::to_string(err->channel);
        out += ',';
        out += std::to_string(static_cast<int>(err->code));
    } else if (const auto* answer = std::get_if<Answer>(&reply)) {
        out += answer->text;
    } else {
        out.pop_back();   // Silent: nothing at all
        return;
    }
    out += '\n';
}

std::string encode(const Reply& reply)
{
    std::string out;
    encode(reply, out);
    return out;
}

} // namespace rigsim::mcs
