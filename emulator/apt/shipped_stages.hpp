#pragma once
// The stages shipped with rigsim: config/stages/<NAME>.json, one file per stage, compiled into
// the daemon (CMake embeds every file of the folder: adding a stage is adding a file), read and
// checked once, at first use.

#include "emulator/apt/catalogue.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace rigsim::apt {

/// One compiled-in stage file: its path in the source tree and its text.
struct StageFile {
    std::string_view path;   ///< "config/stages/MTS50-Z8.json"
    std::string_view text;
};

/// Every file of config/stages, in file name order (generated from shipped_stage_files.cpp.in).
const std::vector<StageFile>& shipped_stage_files();

/// The stage of one file: the schema of an inline stage object (stage_file.hpp) with a required
/// "name", the file's own (MTS50-Z8 in MTS50-Z8.json). Throws ConfigError naming the file and
/// the pointer in it.
StageModel read_stage_file(const StageFile& file);

/// Every shipped stage, in file name order: the files are read at the first call (a bad file
/// throws its ConfigError there, and again at the next call).
const std::vector<StageModel>& shipped_stages();

/// The shipped stage with this name, or nullptr.
const StageModel* find_stage(std::string_view name);
/// The shipped stages' names, for error messages: "DDSM100, DRV001, ...".
const std::string& stage_names();

} // namespace rigsim::apt
