// write_file_atomically and its helpers: whole files or nothing, never through a planted link.
#include "emulator/core/atomic_file.hpp"

#include "tests/support/temp_dir.hpp"

#include <catch2/catch.hpp>

#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace test_atomic_file {

using namespace rigsim;
using rigsim::test::TempDir;
using rigsim::test::read;
using rigsim::test::write;

namespace {

bool is_symlink(const std::string& path)
{
    struct stat st {};
    return ::lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode);
}

} // namespace

TEST_CASE("write_file_atomically: a symlink planted at the temporary path is not followed", "[unit][atomic_file]")
{
    TempDir dir;
    write(dir.file("victim"), "precious");
    const auto out = dir.file("out.json");
    // The name the temporary file used to have: "<path>.tmp<pid>".
    const auto planted = out + ".tmp" + std::to_string(::getpid());
    REQUIRE(::symlink(dir.file("victim").c_str(), planted.c_str()) == 0);
    write_file_atomically(out, "new\n");
    CHECK(read(dir.file("victim")) == "precious");
    CHECK(read(out) == "new\n");
    CHECK(is_symlink(planted));
    CHECK(dir.entries() == std::vector<std::string>{"out.json", "out.json.tmp" + std::to_string(::getpid()), "victim"});
}

TEST_CASE("write_file_atomically: a symlinked destination is written through, the link stays", "[unit][atomic_file]")
{
    TempDir dir;
    write(dir.file("real.json"), "old\n");
    REQUIRE(::chmod(dir.file("real.json").c_str(), 0640) == 0);
    REQUIRE(::symlink("real.json", dir.file("link1").c_str()) == 0);            // relative
    REQUIRE(::symlink(dir.file("link1").c_str(), dir.file("link2").c_str()) == 0);   // absolute, to a link
    write_file_atomically(dir.file("link2"), "new\n");
    CHECK(is_symlink(dir.file("link1")));
    CHECK(is_symlink(dir.file("link2")));
    CHECK(read(dir.file("real.json")) == "new\n");
    struct stat st {};
    REQUIRE(::stat(dir.file("real.json").c_str(), &st) == 0);
    CHECK((st.st_mode & 07777) == 0640);   // the replaced file keeps its permissions
    CHECK(dir.entries() == std::vector<std::string>{"link1", "link2", "real.json"});   // no temporary left
    CHECK(resolve_symlinks(dir.file("link2")) == dir.file("real.json"));
}

TEST_CASE("write_file_atomically: a dangling link creates its target, and failures name the file and leave nothing",
          "[unit][atomic_file]")
{
    TempDir dir;
    REQUIRE(::symlink("target.json", dir.file("link").c_str()) == 0);
    write_file_atomically(dir.file("link"), "x");
    CHECK(read(dir.file("target.json")) == "x");
    CHECK(is_symlink(dir.file("link")));

    REQUIRE(::symlink("loop2", dir.file("loop1").c_str()) == 0);
    REQUIRE(::symlink("loop1", dir.file("loop2").c_str()) == 0);
    CHECK_THROWS_WITH(write_file_atomically(dir.file("loop1"), "x"),
                      Catch::Contains("cannot follow the symlink " + dir.file("loop1")));
    CHECK_THROWS_WITH(write_file_atomically(dir.file("no-such-dir/out.json"), "x"),
                      Catch::Contains("cannot create " + dir.file("no-such-dir/out.json.tmp")));
    CHECK(dir.entries() == std::vector<std::string>{"link", "loop1", "loop2", "target.json"});
}

TEST_CASE("remove_stale_temporaries removes only temporaries of dead processes for that file", "[unit][atomic_file]")
{
    TempDir dir;
    const auto out = dir.file("state.json");
    const std::string dead = "999999999";   // above any pid_max
    const std::string alive = std::to_string(::getpid());
    for (const auto& name : {"state.json", "state.json.tmp999999999", "state.json.tmp999999999.aB3xY9zQ",
                             "state.json.tmpfoo", "state.json.tmp999999999.x-y", "other.json.tmp999999999"})
        write(dir.file(name), "x");
    write(dir.file("state.json.tmp" + alive + ".k2"), "x");
    REQUIRE(::symlink("/etc/passwd", dir.file("state.json.tmp999999999.lnk").c_str()) == 0);
    auto removed = remove_stale_temporaries(out);
    std::sort(removed.begin(), removed.end());
    CHECK(removed == std::vector<std::string>{out + ".tmp" + dead, out + ".tmp" + dead + ".aB3xY9zQ",
                                              out + ".tmp" + dead + ".lnk"});
    CHECK(dir.entries()
          == std::vector<std::string>{"other.json.tmp999999999", "state.json", "state.json.tmp" + alive + ".k2",
                                      "state.json.tmp999999999.x-y", "state.json.tmpfoo"});
}

TEST_CASE("write_new_file never replaces: base, then base.1, base.2", "[unit][atomic_file]")
{
    TempDir dir;
    const auto base = dir.file("state.json.damaged");
    CHECK(write_new_file(base, "a") == base);
    CHECK(write_new_file(base, "b") == base + ".1");
    REQUIRE(::symlink("/nonexistent", (base + ".2").c_str()) == 0);   // a link is an existing name too
    CHECK(write_new_file(base, "c") == base + ".3");
    CHECK(read(base) == "a");
    CHECK(read(base + ".1") == "b");
    CHECK(read(base + ".3") == "c");
}

} // namespace test_atomic_file
