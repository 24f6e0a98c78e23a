#include "emulator/mcs/codec.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <iterator>
#include <limits>
#include <type_traits>

namespace rigsim::mcs {
namespace {

constexpr std::size_t kMaxParams = 8;
using Params = std::array<std::int64_t, kMaxParams>;

std::int32_t i32(std::int64_t v) { return static_cast<std::int32_t>(v); }

struct CommandEntry {
    CommandInfo info;
    std::size_t min_params;   ///< fewer than its parameters: the last ones are optional (S, K)
    Command (*build)(const Params& p, std::size_t n);
    unsigned wide_params = 0;   ///< bit i: parameter i may be 0..4,294,967,295

    /// As many as the manual names.
    std::size_t max_params() const
    {
        return info.params.empty() ? 0 : 1 + static_cast<std::size_t>(std::count(info.params.begin(), info.params.end(), ','));
    }
};

// Every command of chapter 3, once: its mnemonic, the manual's name and parameter names (the
// wire log shows them, wire_names.cpp), the fewest parameters it takes, and its builder.
const CommandEntry kCommands[] = {
    {{"GCM", "Get Communication Mode", ""}, 0,
     [](const Params&, std::size_t) -> Command { return GetCommunicationMode{}; }},
    {{"SCM", "Set Communication Mode", "mode"}, 1,
     [](const Params& p, std::size_t) -> Command { return SetCommunicationMode{i32(p[0])}; }},
    {{"GNC", "Get Number of Channels", ""}, 0,
     [](const Params&, std::size_t) -> Command { return GetNumberOfChannels{}; }},
    {{"GSI", "Get System Id", ""}, 0,
     [](const Params&, std::size_t) -> Command { return GetSystemId{}; }},
    {{"GIV", "Get Interface Version", ""}, 0,
     [](const Params&, std::size_t) -> Command { return GetInterfaceVersion{}; }},
    {{"R", "Reset", ""}, 0,
     [](const Params&, std::size_t) -> Command { return Reset{}; }},
    {{"SHE", "Set HCM Enabled", "enabled"}, 1,
     [](const Params& p, std::size_t) -> Command { return SetHcmEnabled{i32(p[0])}; }},
    {{"GCT", "Get Channel Type", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetChannelType{i32(p[0])}; }},
    {{"GSE", "Get Sensor Enabled", ""}, 0,
     [](const Params&, std::size_t) -> Command { return GetSensorEnabled{}; }},
    {{"SSE", "Set Sensor Enabled", "mode"}, 1,
     [](const Params& p, std::size_t) -> Command { return SetSensorEnabled{i32(p[0])}; }},
    {{"GST", "Get Sensor Type", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetSensorType{i32(p[0])}; }},
    {{"SST", "Set Sensor Type", "channelIndex,type"}, 2,
     [](const Params& p, std::size_t) -> Command { return SetSensorType{i32(p[0]), i32(p[1])}; }},
    {{"GP", "Get Position", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetPosition{i32(p[0])}; }},
    {{"GS", "Get Status", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetStatus{i32(p[0])}; }},
    {{"GPPK", "Get Physical Position Known", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetPhysicalPositionKnown{i32(p[0])}; }},
    {{"MPA", "Move to Position Absolute", "channelIndex,position,holdTime"}, 3,
     [](const Params& p, std::size_t) -> Command { return MovePositionAbsolute{i32(p[0]), i32(p[1]), i32(p[2])}; }},
    {{"MPR", "Move to Position Relative", "channelIndex,diff,holdTime"}, 3,
     [](const Params& p, std::size_t) -> Command { return MovePositionRelative{i32(p[0]), i32(p[1]), i32(p[2])}; }},
    {{"S", "Stop", "channelIndex"}, 0,
     [](const Params& p, std::size_t n) -> Command {
         return n == 0 ? Stop{std::nullopt} : Stop{i32(p[0])};
     }},
    {{"SCLS", "Set Closed Loop move Speed", "channelIndex,speed"}, 2,
     [](const Params& p, std::size_t) -> Command { return SetClosedLoopSpeed{i32(p[0]), i32(p[1])}; }},
    {{"GCLS", "Get Closed Loop move Speed", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetClosedLoopSpeed{i32(p[0])}; }},
    {{"SCLA", "Set Closed Loop Acceleration", "channelIndex,acceleration"}, 2,
     [](const Params& p, std::size_t) -> Command { return SetClosedLoopAcceleration{i32(p[0]), i32(p[1])}; }},
    {{"GCLA", "Get Closed Loop Acceleration", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetClosedLoopAcceleration{i32(p[0])}; }},
    {{"SCLF", "Set Closed Loop max Frequency", "channelIndex,frequency"}, 2,
     [](const Params& p, std::size_t) -> Command { return SetClosedLoopMaxFrequency{i32(p[0]), i32(p[1])}; }},
    {{"SARP", "Set Accumulate Relative Positions", "channelIndex,accumulate"}, 2,
     [](const Params& p, std::size_t) -> Command { return SetAccumulateRelativePositions{i32(p[0]), i32(p[1])}; }},
    {{"SP", "Set Position", "channelIndex,position"}, 2,
     [](const Params& p, std::size_t) -> Command { return SetPosition{i32(p[0]), i32(p[1])}; }},
    {{"SZP", "Set Zero Position", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return SetZeroPosition{i32(p[0])}; }},
    {{"SSC", "Set Scale", "channelIndex,scale,inverted"}, 3,
     [](const Params& p, std::size_t) -> Command { return SetScale{i32(p[0]), i32(p[1]), i32(p[2])}; }},
    {{"GSC", "Get Scale", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetScale{i32(p[0])}; }},
    {{"SSD", "Set Safe Direction", "channelIndex,direction"}, 2,
     [](const Params& p, std::size_t) -> Command { return SetSafeDirection{i32(p[0]), i32(p[1])}; }},
    {{"GSD", "Get Safe Direction", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetSafeDirection{i32(p[0])}; }},
    {{"SSWS", "Set Step While Scan", "channelIndex,step"}, 2,
     [](const Params& p, std::size_t) -> Command { return SetStepWhileScan{i32(p[0]), i32(p[1])}; }},
    {{"SRC", "Set Report on Complete", "channelIndex,report"}, 2,
     [](const Params& p, std::size_t) -> Command { return SetReportOnComplete{i32(p[0]), i32(p[1])}; }},
    {{"K", "Keep alive", "delay"}, 0,
     [](const Params& p, std::size_t n) -> Command {
         return n == 0 ? KeepAlive{std::nullopt} : KeepAlive{i32(p[0])};
     }},
    {{"CB", "Configure Baudrate", "baudrate"}, 1,
     [](const Params& p, std::size_t) -> Command { return ConfigureBaudrate{i32(p[0])}; }},
    {{"GSN", "Get Serial Number", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetSerialNumber{i32(p[0])}; }},
    {{"GFV", "Get Firmware Version", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetFirmwareVersion{i32(p[0])}; }},
    {{"GFP", "Get Feature Permissions", "channelIndex,byteIndex"}, 2,
     [](const Params& p, std::size_t) -> Command { return GetFeaturePermissions{i32(p[0]), i32(p[1])}; }},
    {{"FRM", "Find Reference Mark", "channelIndex,direction,holdTime,autoZero"}, 4,
     [](const Params& p, std::size_t) -> Command { return FindReferenceMark{i32(p[0]), i32(p[1]), i32(p[2]), i32(p[3])}; }},
    {{"CS", "Calibrate Sensor", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return CalibrateSensor{i32(p[0])}; }},
    {{"MAA", "Move to Angle Absolute", "channelIndex,angle,revolution,holdTime"}, 4,
     [](const Params& p, std::size_t) -> Command { return MoveAngleAbsolute{i32(p[0]), i32(p[1]), i32(p[2]), i32(p[3])}; }},
    {{"MAR", "Move to Angle Relative", "channelIndex,angle,revolution,holdTime"}, 4,
     [](const Params& p, std::size_t) -> Command { return MoveAngleRelative{i32(p[0]), i32(p[1]), i32(p[2]), i32(p[3])}; }},
    {{"GA", "Get Angle", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetAngle{i32(p[0])}; }},
    {{"SPL", "Set Position Limit", "channelIndex,minPosition,maxPosition"}, 3,
     [](const Params& p, std::size_t) -> Command { return SetPositionLimit{i32(p[0]), i32(p[1]), i32(p[2])}; }},
    {{"GPL", "Get Position Limit", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetPositionLimit{i32(p[0])}; }},
    {{"SAL", "Set Angle Limit", "channelIndex,minAngle,minRevolution,maxAngle,maxRevolution"}, 5,
     [](const Params& p, std::size_t) -> Command { return SetAngleLimit{i32(p[0]), i32(p[1]), i32(p[2]), i32(p[3]), i32(p[4])}; }},
    {{"GAL", "Get Angle Limit", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetAngleLimit{i32(p[0])}; }},
    {{"MST", "Move STep", "channelIndex,steps,amplitude,frequency"}, 4,
     [](const Params& p, std::size_t) -> Command { return MoveStep{i32(p[0]), i32(p[1]), i32(p[2]), i32(p[3])}; }},
    // MSCA/MSCR scan speed: 1 .. 4,095,000,000, wider than a signed 32-bit value.
    {{"MSCA", "Move SCan Absolute", "channelIndex,target,scanSpeed"}, 3,
     [](const Params& p, std::size_t) -> Command { return MoveScanAbsolute{i32(p[0]), i32(p[1]), p[2]}; }, 1u << 2},
    {{"MSCR", "Move SCan Relative", "channelIndex,diff,scanSpeed"}, 3,
     [](const Params& p, std::size_t) -> Command { return MoveScanRelative{i32(p[0]), i32(p[1]), p[2]}; }, 1u << 2},
    {{"GVL", "Get Voltage Level", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetVoltageLevel{i32(p[0])}; }},
    {{"GCP", "Get Channel Property", "channelIndex,key"}, 2,
     [](const Params& p, std::size_t) -> Command { return GetChannelProperty{i32(p[0]), i32(p[1])}; }},
    {{"SCP", "Set Channel Property", "channelIndex,key,value"}, 3,
     [](const Params& p, std::size_t) -> Command { return SetChannelProperty{i32(p[0]), i32(p[1]), i32(p[2])}; }},
    {{"GESM", "Get Emergency Stop Mode", ""}, 0,
     [](const Params&, std::size_t) -> Command { return GetEmergencyStopMode{}; }},
    {{"SESM", "Set Emergency Stop Mode", "mode"}, 1,
     [](const Params& p, std::size_t) -> Command { return SetEmergencyStopMode{i32(p[0])}; }},
    {{"ATC", "Append Triggered Command", "channelIndex,triggerSource"}, 2,
     [](const Params& p, std::size_t) -> Command { return AppendTriggeredCommand{i32(p[0]), i32(p[1])}; }},
    {{"CTCQ", "Clear Triggered Command Queue", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return ClearTriggeredCommandQueue{i32(p[0])}; }},
    {{"TC", "Trigger Command", "triggerIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return TriggerCommand{i32(p[0])}; }},
    {{"SRT", "Set Report on Triggered", "channelIndex,report"}, 2,
     [](const Params& p, std::size_t) -> Command { return SetReportOnTriggered{i32(p[0]), i32(p[1])}; }},
    {{"GB", "Get capture Buffer", "channelIndex,bufferIndex"}, 2,
     [](const Params& p, std::size_t) -> Command { return GetCaptureBuffer{i32(p[0]), i32(p[1])}; }},
    {{"SEET", "Set End Effector Type", "channelIndex,type,param1,param2"}, 4,
     [](const Params& p, std::size_t) -> Command { return SetEndEffectorType{i32(p[0]), i32(p[1]), i32(p[2]), i32(p[3])}; }},
    {{"GEET", "Get End Effector Type", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetEndEffectorType{i32(p[0])}; }},
    {{"MGOA", "Move to Gripper Opening Absolute", "channelIndex,opening,speed"}, 3,
     [](const Params& p, std::size_t) -> Command { return MoveGripperOpeningAbsolute{i32(p[0]), i32(p[1]), i32(p[2])}; }},
    {{"MGOR", "Move to Gripper Opening Relative", "channelIndex,diff,speed"}, 3,
     [](const Params& p, std::size_t) -> Command { return MoveGripperOpeningRelative{i32(p[0]), i32(p[1]), i32(p[2])}; }},
    {{"MGFA", "Move to Gripper Force Absolute", "channelIndex,force,speed,holdTime"}, 4,
     [](const Params& p, std::size_t) -> Command { return MoveGripperForceAbsolute{i32(p[0]), i32(p[1]), i32(p[2]), i32(p[3])}; }},
    {{"GGO", "Get Gripper Opening", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetGripperOpening{i32(p[0])}; }},
    {{"GF", "Get Force", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return GetForce{i32(p[0])}; }},
    {{"SZF", "Set Zero Force", "channelIndex"}, 1,
     [](const Params& p, std::size_t) -> Command { return SetZeroForce{i32(p[0])}; }},
};

/// kCommands by mnemonic: an open-addressing table of the mnemonics packed into integers (length
/// and characters), built once. A lookup is a multiplication and a compare or two; comparing the
/// mnemonics in table order took one string compare per entry before the one sent.
class CommandIndex {
public:
    CommandIndex()
    {
        slots_.fill(kEmpty);
        for (std::size_t i = 0; i < std::size(kCommands); ++i) {
            const auto key = pack(kCommands[i].info.mnemonic);
            auto slot = slot_of(key);
            while (slots_[slot] != kEmpty)   // an earlier entry keeps the earlier slot
                slot = (slot + 1) & kMask;
            slots_[slot] = static_cast<std::uint8_t>(i);
            keys_[slot] = key;
        }
    }

    /// The entry of `mnemonic`, or nullptr.
    const CommandEntry* find(std::string_view mnemonic) const
    {
        if (mnemonic.empty() || mnemonic.size() > kMaxMnemonic)
            return nullptr;
        const auto key = pack(mnemonic);
        for (auto slot = slot_of(key); slots_[slot] != kEmpty; slot = (slot + 1) & kMask)
            if (keys_[slot] == key)
                return &kCommands[slots_[slot]];
        return nullptr;
    }

private:
    static constexpr std::size_t kMaxMnemonic = 7;   // the length and 7 characters fill 64 bits
    static constexpr std::size_t kSlots = 256;       // kCommands fills under a third of it
    static constexpr std::size_t kMask = kSlots - 1;
    static constexpr std::uint8_t kEmpty = 0xff;
    static_assert(std::size(kCommands) < kEmpty && std::size(kCommands) * 3 < kSlots);

    static std::uint64_t pack(std::string_view mnemonic)
    {
        std::uint64_t key = mnemonic.size();
        for (const char c : mnemonic)
            key = key << 8 | static_cast<unsigned char>(c);
        return key;
    }
    static std::size_t slot_of(std::uint64_t key) { return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 56); }

    std::array<std::uint8_t, kSlots> slots_{};
    std::array<std::uint64_t, kSlots> keys_{};
};

const CommandIndex& command_index()
{
    static const CommandIndex index;
    return index;
}

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

    const auto* entry = command_index().find(d.name);
    if (!entry)
        return fail(d, ErrorCode::InvalidCommand);
    if (count < entry->min_params)
        return fail(d, ErrorCode::TooFewParameters);
    if (count > entry->min_params && count > entry->max_params())   // max_params() counts the names
        return fail(d, ErrorCode::TooManyParameters);
    if ((overflow_mask & ~entry->wide_params) != 0 || (huge_mask & entry->wide_params) != 0)
        return fail(d, ErrorCode::Overflow);
    d.command = entry->build(params, count);
    return d;
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
    // One visit (a jump on the alternative), not eight holds_alternative: each of those finds its
    // type's index by a loop over the ~70 alternatives when inlined, which the fuzz build's
    // comparison tracing made 85 % of fuzz_mcs_framer's time.
    return std::visit(
        [](const auto& c) {
            using T = std::decay_t<decltype(c)>;
            return std::is_same_v<T, MovePositionAbsolute> || std::is_same_v<T, MovePositionRelative>
                || std::is_same_v<T, MoveAngleAbsolute> || std::is_same_v<T, MoveAngleRelative>
                || std::is_same_v<T, MoveStep> || std::is_same_v<T, MoveScanAbsolute>
                || std::is_same_v<T, MoveScanRelative> || std::is_same_v<T, FindReferenceMark>;
        },
        command);
}

void encode(const Reply& reply, std::string& out)
{
    if (const auto* answer = std::get_if<Answer>(&reply)) {
        out += ':';
        out += answer->text;
        out += '\n';
        return;
    }
    // E<channel>,<code>: composed in place, appended once.
    int channel = 0;
    int code = 0;
    if (const auto* ack = std::get_if<Ack>(&reply)) {
        channel = ack->channel;
    } else if (const auto* err = std::get_if<Error>(&reply)) {
        channel = err->channel;
        code = static_cast<int>(err->code);
    } else {
        return;   // Silent: nothing at all
    }
    char text[32] = {':', 'E'};
    char* end = std::to_chars(text + 2, text + 14, channel).ptr;   // 11 characters at most
    *end++ = ',';
    end = std::to_chars(end, text + 28, code).ptr;
    *end++ = '\n';
    out.append(text, end);
}

std::string encode(const Reply& reply)
{
    std::string out;
    encode(reply, out);
    return out;
}

const CommandInfo* find_command(std::string_view mnemonic)
{
    const auto* entry = command_index().find(mnemonic);
    return entry ? &entry->info : nullptr;
}

} // namespace rigsim::mcs
