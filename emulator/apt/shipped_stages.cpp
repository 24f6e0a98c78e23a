#include "emulator/apt/shipped_stages.hpp"

#include "emulator/apt/stage_file.hpp"
#include "emulator/core/config_reader.hpp"

#include <nlohmann/json.hpp>

#include <set>
#include <string>

namespace rigsim::apt {
namespace {

using nlohmann::json;

/// nlohmann keeps the last of two equal keys: a file's top-level object may not repeat one, as
/// a rig may not (a stage object holds no other object, whose keys the schema refuses anyway).
class DuplicateKeys {
public:
    explicit DuplicateKeys(const ConfigReader& r) : r_(r) {}

    bool on_event(json::parse_event_t event, const json& parsed)
    {
        switch (event) {
        case json::parse_event_t::object_start:
        case json::parse_event_t::array_start:
            ++depth_;
            break;
        case json::parse_event_t::object_end:
        case json::parse_event_t::array_end:
            --depth_;
            break;
        case json::parse_event_t::key:
            if (depth_ == 1 && !keys_.insert(parsed.get<std::string>()).second)
                r_.fail("", "duplicate key " + quote(parsed.get<std::string>()));
            break;
        case json::parse_event_t::value:
            break;
        }
        return true;
    }

private:
    const ConfigReader& r_;
    int depth_ = 0;
    std::set<std::string> keys_;
};

/// "MTS50-Z8" of "config/stages/MTS50-Z8.json".
std::string stem_of(std::string_view path)
{
    const auto slash = path.rfind('/');
    auto file = slash == std::string_view::npos ? path : path.substr(slash + 1);
    if (file.size() > 5 && file.substr(file.size() - 5) == ".json")
        file.remove_suffix(5);
    return std::string(file);
}

} // namespace

StageModel read_stage_file(const StageFile& file)
{
    const ConfigReader r(file.path);
    DuplicateKeys duplicates(r);
    json root;
    try {
        root = json::parse(file.text.begin(), file.text.end(),
                           [&duplicates](int, json::parse_event_t event, json& parsed) {
                               return duplicates.on_event(event, parsed);
                           });
    } catch (const json::parse_error& e) {
        throw ConfigError(std::string(file.path) + ": " + e.what());
    }
    const auto stem = stem_of(file.path);
    if (root.is_object() && !ConfigReader::find(root, "name"))
        r.fail("/name", "required key missing (a shipped stage is named as its file: " + quote(stem) + ")");
    auto stage = read_stage(r, root, "");
    if (stage.name != stem)
        r.fail("/name", "expected " + quote(stem) + " (the file's name), got " + quote(stage.name));
    return stage;
}

const std::vector<StageModel>& shipped_stages()
{
    static const std::vector<StageModel> stages = [] {
        std::vector<StageModel> out;
        for (const auto& file : shipped_stage_files())
            out.push_back(read_stage_file(file));
        return out;
    }();
    return stages;
}

const StageModel* find_stage(std::string_view name)
{
    for (const auto& s : shipped_stages())
        if (s.name == name)
            return &s;
    return nullptr;
}

const std::string& stage_names()
{
    static const std::string names = [] {
        std::string out;
        for (const auto& s : shipped_stages())
            out += (out.empty() ? "" : ", ") + s.name;
        return out;
    }();
    return names;
}

} // namespace rigsim::apt
