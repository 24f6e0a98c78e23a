// The shipped stage files (config/stages/*.json): each one compiled in loads, and the files are
// those of the source tree; a bad file is refused naming the file and the pointer in it.
#include "emulator/apt/catalogue.hpp"
#include "emulator/apt/shipped_stages.hpp"
#include "emulator/core/rig_config.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

namespace test_shipped_stages {

using namespace rigsim::apt;

namespace {

/// The ConfigError of reading `text` as the stage file `path`.
std::string error_of(std::string_view path, std::string_view text)
{
    try {
        read_stage_file(StageFile{path, text});
    } catch (const rigsim::ConfigError& e) {
        return e.what();
    }
    return "(no error)";
}

std::string read_text(const std::filesystem::path& p)
{
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

} // namespace

TEST_CASE("shipped stages: every file of config/stages loads, named as its file", "[unit][apt][stages]")
{
    REQUIRE_FALSE(shipped_stage_files().empty());
    for (const auto& file : shipped_stage_files()) {
        INFO(file.path);
        // A bad file fails here with its ConfigError: "config/stages/X.json: /pointer: ...".
        const auto stage = read_stage_file(file);
        CHECK("config/stages/" + stage.name + ".json" == file.path);
    }
    CHECK(shipped_stages().size() == shipped_stage_files().size());
}

TEST_CASE("shipped stages: the compiled-in files are those of the source tree, byte for byte", "[unit][apt][stages]")
{
    std::set<std::string> on_disk;
    for (const auto& entry : std::filesystem::directory_iterator(RIGSIM_SOURCE_DIR "/config/stages"))
        if (entry.path().extension() == ".json")
            on_disk.insert("config/stages/" + entry.path().filename().string());
    std::set<std::string> compiled;
    for (const auto& file : shipped_stage_files()) {
        compiled.insert(std::string(file.path));
        CHECK(read_text(std::filesystem::path(RIGSIM_SOURCE_DIR) / std::string(file.path)) == file.text);
    }
    CHECK(compiled == on_disk);
    CHECK(std::is_sorted(shipped_stage_files().begin(), shipped_stage_files().end(),
                         [](const StageFile& a, const StageFile& b) { return a.path < b.path; }));
}

TEST_CASE("shipped stages: a bad file is refused naming the file and the pointer", "[unit][apt][stages]")
{
    const std::string good_tail =
        R"("kind": "linear", "motor": "stepper", "travel_mm": 10, "max_velocity_mm_s": 2, )"
        R"("acceleration_mm_s2": 4, "home_velocity_mm_s": 1)";
    CHECK(error_of("config/stages/BAD.json", R"({"name": "BAD", "counts_per_mm": -3, )" + good_tail + "}")
          == "config/stages/BAD.json: /counts_per_mm: expected a number > 0, got -3");
    CHECK(error_of("config/stages/BAD.json", R"({"counts_per_mm": 3, )" + good_tail + "}")
          == "config/stages/BAD.json: /name: required key missing (a shipped stage is named as its file: \"BAD\")");
    CHECK(error_of("config/stages/BAD.json", R"({"name": "GOOD", "counts_per_mm": 3, )" + good_tail + "}")
          == "config/stages/BAD.json: /name: expected \"BAD\" (the file's name), got \"GOOD\"");
    CHECK(error_of("config/stages/BAD.json", R"({"name": "BAD", "counts_per_mm": 3, "counts_per_mm": 4, )"
                                                 + good_tail + "}")
          == "config/stages/BAD.json: /: duplicate key \"counts_per_mm\"");
    CHECK(error_of("config/stages/BAD.json", R"({"name": "BAD",)").rfind("config/stages/BAD.json: ", 0) == 0);
    CHECK(error_of("config/stages/BAD.json", R"({"name": "BAD", "counts_per_mm": 3, )" + good_tail + "}")
          == "(no error)");
}

TEST_CASE("shipped stages: each file holds exactly the values of the C++ stage table", "[unit][apt][stages]")
{
    std::set<std::string> table_names;
    for (const char* name : {"DRV001", "ZST225B", "DRV014", "MTS50-Z8", "MTS25-Z8", "Z825B", "Z812B", "PRM1-Z8",
                             "MLS203-X", "MLS203-Y", "DDSM100"})
        table_names.insert(name);
    std::set<std::string> file_names;
    for (const auto& s : shipped_stages()) {
        INFO(s.name);
        file_names.insert(s.name);
        const auto* old = find_stage(s.name);
        REQUIRE(old);
        CHECK(s.kind == old->kind);
        CHECK(s.motor == old->motor);
        // A rotation stage's table entry held a turn as its travel; its file has none.
        CHECK(s.travel_mm == (old->kind == StageKind::Rotary ? 0.0 : old->travel_mm));
        CHECK(s.angle_min_deg == old->angle_min_deg);
        CHECK(s.angle_max_deg == old->angle_max_deg);
        CHECK(s.counts_per_mm == old->counts_per_mm);
        CHECK(s.max_velocity_mm_s == old->max_velocity_mm_s);
        CHECK(s.acceleration_mm_s2 == old->acceleration_mm_s2);
        CHECK(s.home_velocity_mm_s == old->home_velocity_mm_s);
        CHECK(s.home_offset_mm == old->home_offset_mm);
        CHECK(s.velocity_per_mm_s == old->velocity_per_mm_s);
        CHECK(s.acceleration_per_mm_s2 == old->acceleration_per_mm_s2);
        CHECK(s.limit_switches == old->limit_switches);
        CHECK(s.home_forward == old->home_forward);
        CHECK(s.pmd_stage_id == old->pmd_stage_id);
        CHECK(s.pmd_part_number == old->pmd_part_number);
        CHECK(s.pmd_max_velocity == old->pmd_max_velocity);
        CHECK(s.pmd_max_acceleration == old->pmd_max_acceleration);
    }
    CHECK(file_names == table_names);
}

} // namespace test_shipped_stages
