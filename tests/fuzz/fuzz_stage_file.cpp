// Fuzz target: the APT stage-file loader (read_stage_file, emulator/apt/shipped_stages.cpp and
// stage_file.*), then the stage it accepts on a controller of its motor.
// Input: the file's name on the first line (as under config/stages/, "MTS50-Z8.json"), then its
// text. A stage the loader accepts is set, inline and renamed (a rig may not describe a shipped
// stage's name again), on a controller of its motor kind in a rig (KDC101 for a DC servo, KST101
// for a stepper, a BBD203 bay for a brushless motor) through the rig loader, which may still
// refuse it there; an accepted rig is built, homed, moved, jogged and asked for its status on the
// clock: a stage the loaders let through must be one the unit lives with.
// Checked beyond the sanitizers: the loaders throw nothing but ConfigError.
#include "tests/fuzz/fuzz_rig.hpp"

#include "emulator/apt/shipped_stages.hpp"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace {

/// MOVE_HOME, MOVE_ABSOLUTE to 34,304 counts, a jog forward, REQ_DCSTATUSUPDATE, REQ_STATUSUPDATE
/// to `dest` (0x50 a unit, 0x21 bay 0), with clock advances between
/// (FF hi lo: fuzz_rig.hpp).
std::string probe(unsigned char dest)
{
    const unsigned char d = dest, dd = dest | 0x80;
    const unsigned char bytes[] = {
        0x43, 0x04, 0x01, 0x00, d,  0x01, 0xFF, 0x13, 0x88,                                // home, 5 s
        0x53, 0x04, 0x06, 0x00, dd, 0x01, 0x01, 0x00, 0x00, 0x86, 0x00, 0x00, 0xFF, 0x03, 0xE8,   // 1 s
        0x6A, 0x04, 0x01, 0x01, d,  0x01, 0xFF, 0x03, 0xE8,                                // jog, 1 s
        0x90, 0x04, 0x01, 0x00, d,  0x01, 0x80, 0x04, 0x01, 0x00, d, 0x01, 0xFF, 0x27, 0x10,   // 10 s
    };
    return std::string(reinterpret_cast<const char*>(bytes), sizeof bytes);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    rigsim::fuzz::quiet_logging();
    const auto [name, text] = rigsim::fuzz::split_header(std::string_view(reinterpret_cast<const char*>(data), size));
    const std::string path = "config/stages/" + std::string(name);
    rigsim::apt::StageModel stage;
    try {
        stage = rigsim::apt::read_stage_file(rigsim::apt::StageFile{path, text});
    } catch (const rigsim::ConfigError&) {
        return 0;
    }
    // The same object inline, renamed (a rig may not describe a shipped stage's name again): the
    // rig loader checks it against its controller.
    auto object = nlohmann::json::parse(text.begin(), text.end());
    object["name"] = "fuzz-" + stage.name;
    const auto inline_stage = object.dump();
    std::string rig;
    unsigned char dest = 0x50;
    switch (stage.motor) {
    case rigsim::apt::MotorKind::DcServo:
        rig = R"({"devices":[{"name":"s","protocol":"apt","model":"KDC101","apt":{"stage":)" + inline_stage + "}}]}";
        break;
    case rigsim::apt::MotorKind::Stepper:
        rig = R"({"devices":[{"name":"s","protocol":"apt","model":"KST101","apt":{"stage":)" + inline_stage + "}}]}";
        break;
    case rigsim::apt::MotorKind::Brushless:
        rig = R"({"devices":[{"name":"s","protocol":"apt","model":"BBD203","apt":{"bays":[)" + inline_stage + "]}}]}";
        dest = 0x21;
        break;
    }
    const auto config = rigsim::fuzz::header_rig(rig, {});
    if (!config)
        return 0;
    rigsim::fuzz::FuzzRig built(*config);
    built.open_sessions();
    built.play(probe(dest));
    return 0;
}
