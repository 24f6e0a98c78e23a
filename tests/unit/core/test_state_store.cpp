// StateStore: loading (refusing what it cannot read), the writer thread (saves off the
// caller's thread, coalesced, flushed), and damaged files kept as <file>.damaged.
#include "emulator/core/state_store.hpp"

#include "emulator/core/atomic_file.hpp"

#include "tests/support/temp_dir.hpp"

#include <catch2/catch.hpp>
#include <spdlog/sinks/ostream_sink.h>

#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <future>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace test_state_store {

using namespace rigsim;
using rigsim::test::TempDir;
using rigsim::test::read;
using rigsim::test::write;

namespace {

struct CapturedLog {
    std::ostringstream text;
    std::shared_ptr<spdlog::logger> logger =
        std::make_shared<spdlog::logger>("state", std::make_shared<spdlog::sinks::ostream_sink_mt>(text));
};

} // namespace

TEST_CASE("state store: a state file that exists but cannot be read refuses start-up, naming it and why",
          "[unit][state_store]")
{
    TempDir dir;
    REQUIRE(::mkdir(dir.file("state.json").c_str(), 0755) == 0);
    CHECK_THROWS_WITH(StateStore(dir.file("state.json")),
                      "state file " + dir.file("state.json") + ": is a directory, not a file");
    // /proc/self/mem is a regular file whose first page cannot be read: an I/O error.
    CHECK_THROWS_WITH(StateStore("/proc/self/mem"), "state file /proc/self/mem: cannot read it: Input/output error");
    CHECK_THROWS_WITH(StateStore("/dev/null"), "state file /dev/null: is not a regular file");
    write(dir.file("bad.json"), "[1, 2]");
    CHECK_THROWS_WITH(StateStore(dir.file("bad.json")),
                      "state file " + dir.file("bad.json") + ": not a rigsim state file: expected an object");
    if (::geteuid() != 0) {   // root reads anything
        write(dir.file("secret.json"), "{}");
        REQUIRE(::chmod(dir.file("secret.json").c_str(), 0) == 0);
        CHECK_THROWS_WITH(StateStore(dir.file("secret.json")),
                          "state file " + dir.file("secret.json") + ": cannot read it: Permission denied");
    }
    // A file that does not exist yet is an empty state, created at the first save.
    StateStore fresh(dir.file("new.json"));
    CHECK(fresh.device_state("apt0").empty());
}

TEST_CASE("state store: set() hands the save to the writer thread and returns before the write",
          "[unit][state_store]")
{
    TempDir dir;
    const auto path = dir.file("state.json");
    const auto caller = std::this_thread::get_id();
    std::atomic<bool> wrote_on_caller{false};
    std::promise<void> writing;
    std::promise<void> release;
    auto released = release.get_future().share();
    bool first = true;
    StateStore store(path, nullptr, [&](const std::string& p, const std::string& text) {
        if (std::this_thread::get_id() == caller) {
            wrote_on_caller = true;   // the old, blocking behaviour: do not wait for ourselves
            write_file_atomically(p, text);
            return;
        }
        if (first) {
            first = false;
            writing.set_value();
            released.wait();   // a slow disk
        }
        write_file_atomically(p, text);
    });
    store.set("apt0", "bay0/0x0413", "01");
    REQUIRE_FALSE(wrote_on_caller);
    writing.get_future().wait();         // the writer is inside its (slow) write ...
    CHECK_FALSE(::access(path.c_str(), F_OK) == 0);   // ... and nothing is on disk yet
    store.set("apt0", "bay0/0x0413", "02");            // the caller is not blocked by it
    release.set_value();
    store.flush();
    CHECK(read(path) == "{\n  \"apt0\": {\n    \"bay0/0x0413\": \"02\"\n  }\n}\n");
}

TEST_CASE("state store: a burst of saves coalesces and the last one is on disk after flush()", "[unit][state_store]")
{
    TempDir dir;
    const auto path = dir.file("state.json");
    std::atomic<int> writes{0};
    std::promise<void> writing;
    std::promise<void> release;
    auto released = release.get_future().share();
    StateStore store(path, nullptr, [&](const std::string& p, const std::string& text) {
        if (writes++ == 0) {
            writing.set_value();
            released.wait();
        }
        write_file_atomically(p, text);
    });
    store.set("apt0", "n", 0);
    writing.get_future().wait();
    constexpr int kSaves = 1000;
    for (int i = 1; i <= kSaves; ++i)
        store.set("apt0", "n", i);
    release.set_value();
    store.flush();
    CHECK(writes == 2);   // the first, then the latest of the burst
    CHECK(read(path) == "{\n  \"apt0\": {\n    \"n\": 1000\n  }\n}\n");
    CHECK(dir.entries() == std::vector<std::string>{"state.json"});
}

TEST_CASE("state store: the destructor writes the last save, and write errors are logged, not thrown",
          "[unit][state_store]")
{
    TempDir dir;
    const auto path = dir.file("state.json");
    {
        StateStore store(path);
        store.set("apt0", "k", "v");
    }
    CHECK(read(path) == "{\n  \"apt0\": {\n    \"k\": \"v\"\n  }\n}\n");

    CapturedLog log;
    StateStore failing(path, log.logger, [](const std::string&, const std::string&) {
        throw std::runtime_error("disk full");
    });
    CHECK_NOTHROW(failing.set("apt0", "k", "w"));
    failing.flush();
    CHECK(log.text.str().find("state file " + path + ": cannot save: disk full") != std::string::npos);
    CHECK(failing.get("apt0", "k")->get<std::string>() == "w");   // kept in memory
}

TEST_CASE("state store: a state file with damaged entries is kept as <file>.damaged before it is rewritten",
          "[unit][state_store]")
{
    TempDir dir;
    const auto path = dir.file("state.json");
    const std::string original = R"({"apt0": {"bad": "zz", "good": "01"}, "apt1": 7, "apt2": {"x": "y"}})";
    write(path, original);
    {
        CapturedLog log;
        StateStore store(path, log.logger);
        CHECK(log.text.str().find("state file " + path
                                  + ": device \"apt1\": skipped: expected an object of saved entries, got number")
              != std::string::npos);
        store.reject("apt0", "bad", "data is not hex");
        CHECK(log.text.str().find("state file " + path + ": device \"apt0\", key \"bad\": skipped: data is not hex")
              != std::string::npos);
        CHECK(store.get("apt0", "bad") == nullptr);
        store.flush();
        CHECK(read(path) == original);   // nothing saved yet: untouched
        store.set("apt0", "new", "02");
        store.flush();
        CHECK(read(path + ".damaged") == original);
        CHECK(log.text.str().find("state file " + path + ": had damaged entries (logged at start-up): kept the file "
                                  "as loaded as " + path + ".damaged before saving")
              != std::string::npos);
        CHECK(nlohmann::json::parse(read(path))
              == nlohmann::json::parse(R"({"apt0": {"good": "01", "new": "02"}, "apt2": {"x": "y"}})"));
        store.set("apt0", "new", "03");   // kept once: later saves just save
        store.flush();
        CHECK(dir.entries() == std::vector<std::string>{"state.json", "state.json.damaged"});
    }
    // Damaged again: the earlier copy stays, this one is .damaged.1.
    write(path, original);
    {
        StateStore store(path);
        store.reject("apt0", "bad", "data is not hex");
        store.set("apt0", "new", "04");
    }
    CHECK(read(path + ".damaged.1") == original);
    CHECK(dir.entries() == std::vector<std::string>{"state.json", "state.json.damaged", "state.json.damaged.1"});
}

TEST_CASE("state store: a symlinked state file stays a link, and stale temporaries go at start-up", "[unit][state_store]")
{
    TempDir dir;
    write(dir.file("real.json"), R"({"apt0": {"k": "v"}})");
    REQUIRE(::symlink("real.json", dir.file("state.json").c_str()) == 0);
    write(dir.file("real.json.tmp999999999"), "half a st");   // a rigsimd killed while saving
    write(dir.file("real.json.tmp999999998.Xy12ab34"), "");
    CapturedLog log;
    {
        StateStore store(dir.file("state.json"), log.logger);
        CHECK(store.file() == dir.file("real.json"));
        CHECK(store.get("apt0", "k")->get<std::string>() == "v");
        CHECK(dir.entries() == std::vector<std::string>{"real.json", "state.json"});
        store.set("apt0", "k", "w");
    }
    struct stat st {};
    REQUIRE(::lstat(dir.file("state.json").c_str(), &st) == 0);
    CHECK(S_ISLNK(st.st_mode));
    CHECK(nlohmann::json::parse(read(dir.file("real.json"))) == nlohmann::json::parse(R"({"apt0": {"k": "w"}})"));
    CHECK(log.text.str().find("removed " + dir.file("real.json.tmp999999999") + ", left by a rigsimd that was killed")
          != std::string::npos);
}

} // namespace test_state_store
