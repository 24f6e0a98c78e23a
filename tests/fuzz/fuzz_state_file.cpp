// Fuzz target: the state-file loader (emulator/core/state_store.*) and what the devices make of
// the entries it loads when they power up (emulator/apt/apt_eeprom.cpp: saved parameters replayed
// as their SET messages, a damaged entry rejected).
// Input: the text of a state file. The store reads only from a path, so each input is written to
// one file in a directory of this process under $TMPDIR (emptied before each input, removed at
// exit). A file the store accepts backs a rig whose devices are the names the seeds use (cube: a
// TDC001, rack: a BBD203, kcube: a KST101 of the later firmware, piezo: a TPZ001), which powers
// up, is asked for the saved parameters and saves them again.
// Checked beyond the sanitizers: the store throws nothing but std::runtime_error.
#include "tests/fuzz/fuzz_rig.hpp"

#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace {

constexpr std::string_view kRig = R"({"devices":[)"
    R"({"name":"cube","protocol":"apt","model":"TDC001","apt":{"stage":"MTS50-Z8"}},)"
    R"({"name":"rack","protocol":"apt","model":"BBD203","apt":{"bays":["MLS203-X","MLS203-Y"]}},)"
    R"({"name":"kcube","protocol":"apt","model":"KST101","firmware":"issue-44.1","apt":{"stage":"ZST225B"}},)"
    R"({"name":"piezo","protocol":"apt","model":"TPZ001","apt":{"actuator":{"travel_um":20,"max_voltage_v":75}}}]})";

/// To each device, for the unit and bays 0 and 1: its velocity, homing and limit switch
/// parameters asked for, and the velocity parameters saved (a restored value read back and saved).
std::string probe()
{
    std::string s;
    for (const unsigned char session : {0xF0, 0xF1, 0xF2, 0xF3}) {
        s += '\xFF';
        s += static_cast<char>(session);
        for (const unsigned char dest : {0x50, 0x21, 0x22}) {
            const unsigned char bytes[] = {0x14, 0x04, 0x01, 0x00, dest, 0x01,   // MOT_REQ_VELPARAMS
                                           0x41, 0x04, 0x01, 0x00, dest, 0x01,   // MOT_REQ_HOMEPARAMS
                                           0x24, 0x04, 0x01, 0x00, dest, 0x01,   // MOT_REQ_LIMSWITCHPARAMS
                                           0xB9, 0x04, 0x04, 0x00, static_cast<unsigned char>(dest | 0x80), 0x01,
                                           0x01, 0x00, 0x13, 0x04};   // MOT_SET_EEPROMPARAMS: VELPARAMS
            s.append(reinterpret_cast<const char*>(bytes), sizeof bytes);
        }
    }
    return s + std::string("\xFF\x00\x64", 3);   // 100 ms
}

/// This process's directory for the state file.
class StateDir {
public:
    StateDir()
    {
        const char* tmp = std::getenv("TMPDIR");
        path_ = std::string(tmp && *tmp ? tmp : "/tmp") + "/rigsim-fuzz-state-" + std::to_string(::getpid());
        if (::mkdir(path_.c_str(), 0700) != 0 && errno != EEXIST)
            throw std::runtime_error("cannot create " + path_);
    }
    ~StateDir()
    {
        empty();
        ::rmdir(path_.c_str());
    }
    /// Remove every file in it (the state file, its temporaries, .damaged copies).
    void empty()
    {
        if (DIR* dir = ::opendir(path_.c_str())) {
            while (const dirent* e = ::readdir(dir))
                if (std::string_view(e->d_name) != "." && std::string_view(e->d_name) != "..")
                    ::unlink((path_ + "/" + e->d_name).c_str());
            ::closedir(dir);
        }
    }
    std::string file() const { return path_ + "/state.json"; }

private:
    std::string path_;
};

StateDir& state_dir()
{
    static StateDir dir;   // removed at exit
    return dir;
}

const rigsim::RigConfig& rig_config()
{
    static const rigsim::RigConfig config = rigsim::parse_rig_config(kRig, "fuzz-state-rig.json");
    return config;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    rigsim::fuzz::quiet_logging();
    auto& dir = state_dir();
    dir.empty();
    const auto path = dir.file();
    {
        std::ofstream out(path, std::ios::binary);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
        if (!out)
            __builtin_trap();   // the machine, not the input: stop the run
    }
    std::unique_ptr<rigsim::StateStore> store;
    try {
        store = std::make_unique<rigsim::StateStore>(path, spdlog::default_logger());
    } catch (const std::runtime_error&) {
        return 0;
    }
    {
        rigsim::fuzz::FuzzRig rig(rig_config(), store.get());
        rig.open_sessions();
        rig.play(probe());
    }
    store->flush();
    return 0;
}
