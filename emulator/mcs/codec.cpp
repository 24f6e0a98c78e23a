#include "emulator/mcs/codec.hpp"

#include <array>
#include <charconv>
#include <limits>

namespace rigsim::mcs {
namespace {

constexpr std::size_t kMaxParams = 8;
using Params = std::array<std::int32_t, kMaxParams>;

struct CommandEntry {
    std::string_view name;
    std::size_t min_params;
    std::size_t max_params;
    Command (*build)(const Params& p, std::size_t n);
};

// The commands rigsim implements: name, parameter count range, builder.
const CommandEntry kCommands[] = {
    {"GNC", 0, 0, [](const Params&, std::size_t) -> Command { return GetNumberOfChannels{}; }},
    {"GSI", 0, 0, [](const Params&, std::size_t) -> Command { return GetSystemId{}; }},
    {"GIV", 0, 0, [](const Params&, std::size_t) -> Command { return GetInterfaceVersion{}; }},
    {"GCT", 1, 1, [](const Params& p, std::size_t) -> Command { return GetChannelType{p[0]}; }},
    {"GST", 1, 1, [](const Params& p, std::size_t) -> Command { return GetSensorType{p[0]}; }},
    {"SST", 2, 2, [](const Params& p, std::size_t) -> Command { return SetSensorType{p[0], p[1]}; }},
    {"GP", 1, 1, [](const Params& p, std::size_t) -> Command { return GetPosition{p[0]}; }},
    {"GS", 1, 1, [](const Params& p, std::size_t) -> Command { return GetStatus{p[0]}; }},
    {"MPA", 3, 3, [](const Params& p, std::size_t) -> Command { return MovePositionAbsolute{p[0], p[1], p[2]}; }},
    {"MPR", 3, 3, [](const Params& p, std::size_t) -> Command { return MovePositionRelative{p[0], p[1], p[2]}; }},
    {"S", 0, 1, [](const Params& p, std::size_t n) -> Command {
         return n == 0 ? Stop{std::nullopt} : Stop{p[0]};
     }},
    {"SCLS", 2, 2, [](const Params& p, std::size_t) -> Command { return SetClosedLoopSpeed{p[0], p[1]}; }},
    {"GCLS", 1, 1, [](const Params& p, std::size_t) -> Command { return GetClosedLoopSpeed{p[0]}; }},
    {"SCLA", 2, 2, [](const Params& p, std::size_t) -> Command { return SetClosedLoopAcceleration{p[0], p[1]}; }},
    {"GCLA", 1, 1, [](const Params& p, std::size_t) -> Command { return GetClosedLoopAcceleration{p[0]}; }},
};

// Chapter 3 commands that rigsim does not implement yet: answered like an unknown
// command (E-1,2), but logged as unimplemented rather than as a client mistake.
constexpr std::string_view kUnimplemented[] = {
    "GCM", "SCM", "R", "SHE", "GAL", "GCP", "GEET", "GESM", "GPL", "GSC", "GSD", "GSE",
    "SARP", "SAL", "SCLF", "SCP", "SEET", "SESM", "SP", "SPL", "SRC", "SRT", "SSC", "SSD",
    "SSE", "SSWS", "SZF", "SZP", "ATC", "CS", "CTCQ", "FRM", "MAA", "MAR", "MGFA", "MGOA",
    "MGOR", "MSCA", "MSCR", "MST", "TC", "GA", "GB", "GF", "GGO", "GPPK", "GVL", "CB",
    "GSN", "GFV", "GFP", "K",
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
    bool overflow = false;
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
            if (ec == std::errc::result_out_of_range) {
                overflow = true;
            } else if (ec != std::errc() || end != field.data() + field.size()) {
                return fail(d, ErrorCode::Parse);   // e.g. "1-2", "--3"
            } else if (value < std::numeric_limits<std::int32_t>::min()
                       || value > std::numeric_limits<std::int32_t>::max()) {
                overflow = true;
            }
            if (count < kMaxParams)
                params[count] = static_cast<std::int32_t>(value);
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
        if (overflow)
            return fail(d, ErrorCode::Overflow);
        d.command = entry.build(params, count);
        return d;
    }
    for (auto name : kUnimplemented)
        if (name == d.name)
            d.known_unimplemented = true;
    return fail(d, ErrorCode::InvalidCommand);
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
    } else {
        out += std::get<Answer>(reply).text;
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
