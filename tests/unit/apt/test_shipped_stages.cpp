// The shipped stage files (config/stages/*.json): each one compiled in loads, and the files are
// those of the source tree; a bad file is refused naming the file and the pointer in it.
#include "emulator/apt/catalogue.hpp"
#include "emulator/apt/shipped_stages.hpp"
#include "emulator/apt/stage_file.hpp"
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

// Found by the stage_file fuzz target (tests/fuzz/regressions/stage_file/number-overflow): a
// number the JSON parser cannot hold threw its out_of_range past the loader, which ended the
// process instead of naming the file.
TEST_CASE("shipped stages: a number beyond a double is refused naming the file", "[unit][apt][stages]")
{
    CHECK(error_of("config/stages/DRV001.json", R"({"name": 1e400})")
          == "config/stages/DRV001.json: [json.exception.out_of_range.406] number overflow parsing '1e400'");
    CHECK(error_of("config/stages/BAD.json", R"({"name": "BAD", "counts_per_mm": -1e999})")
          == "config/stages/BAD.json: [json.exception.out_of_range.406] number overflow parsing '-1e999'");
}

namespace {

/// The figures of each stage as audited against their sources (each file's `about`;
/// docs/protocol/errata.md, "Stage scales"): the C++ table's values the files replaced (commit
/// 0f814f9), but for the DRV001's and the ZST225B's microsteps per mm, which that table had at the
/// manual's generic 25,600.
struct Pinned {
    const char* name;
    StageKind kind;
    MotorKind motor;
    double travel_mm, counts_per_mm, max_velocity, acceleration, home_velocity, home_offset;
};

constexpr Pinned kPinned[]{
    {"DRV001", StageKind::Linear, MotorKind::Stepper, 13, 51'200, 2, 4, 1, 0.5},
    {"ZST225B", StageKind::Linear, MotorKind::Stepper, 25, 125'540.352, 2, 4, 1, 0.5},
    {"DRV014", StageKind::Linear, MotorKind::Stepper, 50, 25'600, 2, 4, 1, 0.5},
    {"MTS50-Z8", StageKind::Linear, MotorKind::DcServo, 50, 34'304, 2.4, 1.5, 1, 0.3},
    {"MTS25-Z8", StageKind::Linear, MotorKind::DcServo, 25, 34'304, 2.4, 1.5, 1, 0.3},
    {"Z825B", StageKind::Linear, MotorKind::DcServo, 25, 34'304, 2.6, 4, 1, 0.3},
    {"Z812B", StageKind::Linear, MotorKind::DcServo, 12, 34'304, 2.6, 4, 1, 0.3},
    {"PRM1-Z8", StageKind::Rotary, MotorKind::DcServo, 0, 1'919.6418, 10, 10, 10, 4},
    {"MLS203-X", StageKind::Linear, MotorKind::Brushless, 110, 20'000, 100, 500, 10, 1},
    {"MLS203-Y", StageKind::Linear, MotorKind::Brushless, 75, 20'000, 100, 500, 10, 1},
    {"DDSM100", StageKind::Linear, MotorKind::Brushless, 100, 2'000, 500, 5'000, 5, 0.5},
    // The units of today (issue 28): each file's `about` gives its sources.
    {"K10CR1", StageKind::Rotary, MotorKind::Stepper, 0, 136'533.333333, 10, 10, 10, 4},
    {"LTS150", StageKind::Linear, MotorKind::Stepper, 150, 409'600, 20, 20, 2, 0.5},
    {"LTS300", StageKind::Linear, MotorKind::Stepper, 300, 409'600, 20, 20, 2, 0.5},
    {"DDS100", StageKind::Linear, MotorKind::Brushless, 100, 2'000, 500, 5'000, 5, 0.5},
    {"DDS220", StageKind::Linear, MotorKind::Brushless, 220, 20'000, 100, 500, 10, 1},
    {"DDS300", StageKind::Linear, MotorKind::Brushless, 300, 20'000, 100, 500, 10, 1},
    {"DDS600", StageKind::Linear, MotorKind::Brushless, 600, 20'000, 100, 500, 10, 1},
    {"DDR25", StageKind::Rotary, MotorKind::Brushless, 0, 4'000, 100, 1'000, 10, 0},
};

} // namespace

TEST_CASE("shipped stages: the nineteen stages keep their audited figures", "[unit][apt][stages]")
{
    REQUIRE(shipped_stages().size() == std::size(kPinned));
    for (const auto& p : kPinned) {
        INFO(p.name);
        const auto* s = find_stage(p.name);
        REQUIRE(s);
        CHECK(s->kind == p.kind);
        CHECK(s->motor == p.motor);
        CHECK(s->travel_mm == p.travel_mm);
        CHECK(s->counts_per_mm == p.counts_per_mm);
        CHECK(s->max_velocity_mm_s == p.max_velocity);
        CHECK(s->acceleration_mm_s2 == p.acceleration);
        CHECK(s->home_velocity_mm_s == p.home_velocity);
        CHECK(s->home_offset_mm == p.home_offset);
        CHECK(s->limit_switches == LimitSwitches::Both);
        CHECK_FALSE(s->home_forward);
        const bool mls = s->name.rfind("MLS203", 0) == 0;
        CHECK(s->velocity_per_mm_s == (mls ? 134'218.0 : 0.0));
        CHECK(s->acceleration_per_mm_s2 == (mls ? 13.7439 : 0.0));
        CHECK(s->pmd_max_velocity == (mls ? 26'843'546 : 0));
        CHECK(s->pmd_max_acceleration == (mls ? 27'488 : 0));
    }
    CHECK(find_stage("MLS203-X")->pmd_stage_id == 0x10);
    CHECK(find_stage("MLS203-X")->pmd_part_number == "MLS203 X Axis");
    CHECK(find_stage("DDSM100")->pmd_part_number.empty());
    CHECK(stage_names() == "DDR25, DDS100, DDS220, DDS300, DDS600, DDSM100, DRV001, DRV014, K10CR1, LTS150, LTS300, "
                           "MLS203-X, MLS203-Y, MTS25-Z8, MTS50-Z8, PRM1-Z8, Z812B, Z825B, ZST225B");
}

TEST_CASE("shipped stages: docs/config.md lists every one", "[unit][apt][stages]")
{
    const auto doc = read_text(RIGSIM_SOURCE_DIR "/docs/config.md");
    for (const auto& s : shipped_stages()) {
        INFO(s.name);
        CHECK(doc.find("| `" + s.name + "` | " + kind_name(s.kind) + " |") != std::string::npos);
    }
}

} // namespace test_shipped_stages
