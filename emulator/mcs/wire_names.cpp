#include "emulator/mcs/wire_names.hpp"

#include "emulator/mcs/codec.hpp"

#include <nlohmann/json.hpp>

#include <cctype>
#include <charconv>
#include <vector>

namespace rigsim::mcs {

namespace {

/// Chapter 3: answer strings, each named as a command is (E is decoded apart: acknowledge or error).
constexpr CommandInfo kAnswerNames[] = {
    {"A", "Angle", "channelIndex,angle,revolution"},
    {"AL", "Angle Limit", "channelIndex,minAngle,minRevolution,maxAngle,maxRevolution"},
    {"B", "Capture Buffer", "channelIndex,bufferIndex,data1,data2,data3"},
    {"BR", "Baudrate", "baudrate"},
    {"C", "Completed", "channelIndex"},
    {"CLA", "Closed Loop Acceleration", "channelIndex,acceleration"},
    {"CLS", "Closed Loop move Speed", "channelIndex,speed"},
    {"CM", "Communication Mode", "mode"},
    {"CP", "Channel Property", "channelIndex,key,value"},
    {"CT", "Channel Type", "channelIndex,type"},
    {"EET", "End Effector Type", "channelIndex,type,param1,param2"},
    {"ESM", "Emergency Stop Mode", "mode"},
    {"F", "Force", "channelIndex,force"},
    {"FP", "Feature Permissions", "channelIndex,value"},
    {"FV", "Firmware Version", "channelIndex"},
    {"GO", "Gripper Opening", "channelIndex,opening"},
    {"ID", "System Id", "id"},
    {"IV", "Interface Version", "versionHigh,versionLow,versionUpdate"},
    {"N", "Number of Channels", "channels"},
    {"P", "Position", "channelIndex,position"},
    {"PL", "Position Limit", "channelIndex,minPosition,maxPosition"},
    {"PPK", "Physical Position Known", "channelIndex,known"},
    {"S", "Status", "channelIndex,status"},
    {"SC", "Scale", "channelIndex,scale,inverted"},
    {"SD", "Safe Direction", "channelIndex,direction"},
    {"SE", "Sensor Enabled", "mode"},
    {"SN", "Serial Number", "channelIndex,serialNumber"},
    {"ST", "Sensor Type", "channelIndex,typeCode"},
    {"T", "Triggered", "channelIndex"},
    {"VL", "Voltage Level", "channelIndex,level"},
};

/// Appendix 4.2.
struct ErrorName {
    int code;
    std::string_view name;
};
constexpr ErrorName kErrorNames[] = {
    {0, "No Error"}, {1, "Syntax Error"}, {2, "Invalid Command Error"}, {3, "Overflow Error"},
    {4, "Parse Error"}, {5, "Too Few Parameters Error"}, {6, "Too Many Parameters Error"},
    {7, "Invalid Parameter Error"}, {8, "Wrong Mode Error"}, {129, "No Sensor Present Error"},
    {140, "Sensor Disabled Error"}, {141, "Command Overridden Error"}, {142, "End Stop Reached Error"},
    {143, "Wrong Sensor Type Error"}, {144, "Could Not Find Reference Mark Error"},
    {145, "Wrong End Effector Type Error"}, {146, "Movement Locked Error"}, {147, "Range Limit Reached Error"},
    {148, "Physical Position Unknown Error"}, {150, "Command Not Processable Error"},
    {151, "Waiting For Trigger Error"}, {152, "Command Not Triggerable Error"}, {153, "Command Queue Full Error"},
    {154, "Invalid Component Error"}, {155, "Invalid Sub Component Error"}, {156, "Invalid Property Error"},
    {157, "Permission Denied Error"},
};

template <std::size_t N>
const CommandInfo* find(const CommandInfo (&table)[N], std::string_view mnemonic)
{
    for (const auto& n : table)
        if (n.mnemonic == mnemonic)
            return &n;
    return nullptr;
}

std::vector<std::string_view> split(std::string_view s)
{
    std::vector<std::string_view> parts;
    while (!s.empty()) {
        const auto comma = s.find(',');
        parts.push_back(s.substr(0, comma));
        if (comma == std::string_view::npos)
            break;
        s.remove_prefix(comma + 1);
    }
    return parts;
}

nlohmann::json value_of(std::string_view text)
{
    long long v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec == std::errc{} && end == text.data() + text.size())
        return v;
    return std::string(text);
}

void decode_error(std::string_view params, nlohmann::json& out)
{
    const auto p = split(params);
    nlohmann::json fields = nlohmann::json::object();
    if (!p.empty())
        fields["sourceChannel"] = value_of(p[0]);
    int code = -1;
    if (p.size() > 1) {
        fields["errorCode"] = value_of(p[1]);
        std::from_chars(p[1].data(), p[1].data() + p[1].size(), code);
    }
    out["name"] = code == 0 ? "Acknowledge" : "Error";
    if (code > 0)
        fields["meaning"] = error_name(code);
    out["fields"] = std::move(fields);
}

} // namespace

std::string_view error_name(int code)
{
    for (const auto& e : kErrorNames)
        if (e.code == code)
            return e.name;
    return "Unknown Error";
}

std::string_view command_name(std::string_view mnemonic)
{
    const auto* n = find_command(mnemonic);
    return n ? n->name : std::string_view{};
}

void decode_line(std::string_view line, bool inbound, nlohmann::json& out)
{
    if (!line.empty() && line.front() == ':')
        line.remove_prefix(1);
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r'))
        line.remove_suffix(1);
    std::size_t k = 0;
    while (k < line.size() && std::isupper(static_cast<unsigned char>(line[k])))
        ++k;
    const auto mnemonic = line.substr(0, k);
    const auto params = line.substr(k);
    out["text"] = std::string(line);
    out["command"] = std::string(mnemonic);
    if (!inbound && mnemonic == "E") {
        decode_error(params, out);
        return;
    }
    const auto* n = inbound ? find_command(mnemonic) : find(kAnswerNames, mnemonic);
    out["name"] = n ? n->name : std::string_view("unknown");
    nlohmann::json fields = nlohmann::json::object();
    const auto names = n ? split(n->params) : std::vector<std::string_view>{};
    const auto values = split(params);
    for (std::size_t i = 0; i < values.size(); ++i)
        fields[i < names.size() ? std::string(names[i]) : "param" + std::to_string(i + 1)] = value_of(values[i]);
    out["fields"] = std::move(fields);
}

std::string command_text(const Command& command)
{
    auto join = [](std::string_view name, std::initializer_list<std::int64_t> values) {
        std::string s(name);
        bool first = true;
        for (const auto v : values) {
            if (!first)
                s += ',';
            s += std::to_string(v);
            first = false;
        }
        return s;
    };
    if (const auto* c = std::get_if<MovePositionAbsolute>(&command))
        return join("MPA", {c->channel, c->position_nm, c->hold_ms});
    if (const auto* c = std::get_if<MovePositionRelative>(&command))
        return join("MPR", {c->channel, c->distance_nm, c->hold_ms});
    if (const auto* c = std::get_if<MoveAngleAbsolute>(&command))
        return join("MAA", {c->channel, c->angle_udeg, c->revolution, c->hold_ms});
    if (const auto* c = std::get_if<MoveAngleRelative>(&command))
        return join("MAR", {c->channel, c->angle_udeg, c->revolution, c->hold_ms});
    if (const auto* c = std::get_if<MoveStep>(&command))
        return join("MST", {c->channel, c->steps, c->amplitude, c->frequency_hz});
    if (const auto* c = std::get_if<MoveScanAbsolute>(&command))
        return join("MSCA", {c->channel, c->target, c->speed});
    if (const auto* c = std::get_if<MoveScanRelative>(&command))
        return join("MSCR", {c->channel, c->diff, c->speed});
    if (const auto* c = std::get_if<FindReferenceMark>(&command))
        return join("FRM", {c->channel, c->direction, c->hold_ms, c->auto_zero});
    return "?";   // the queue takes movement commands only (2.4.5)
}

} // namespace rigsim::mcs
