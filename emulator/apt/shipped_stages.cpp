#include "emulator/apt/shipped_stages.hpp"

#include "emulator/apt/stage_file.hpp"
#include "emulator/core/config_reader.hpp"
#include "emulator/core/json_text.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace rigsim::apt {
namespace {

using nlohmann::json;

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
    json root;
    try {
        // A key twice in one object is refused, as in a rig (nlohmann would keep the last).
        root = parse_json_text(file.text);
    } catch (const JsonTextError& e) {
        if (e.kind == JsonTextError::Kind::DuplicateKey || e.kind == JsonTextError::Kind::TooDeep)
            r.fail(e.pointer, e.what());
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
