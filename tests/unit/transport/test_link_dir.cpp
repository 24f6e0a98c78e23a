// The directory of the pty links must be the daemon user's (or root's) and writable by no one
// else unless sticky: otherwise another user could replace a link and take a client's bytes.
#include "emulator/transport/link_lock.hpp"

#include "tests/support/temp_dir.hpp"

#include <catch2/catch.hpp>

#include <string>

#include <sys/stat.h>
#include <unistd.h>

namespace test_link_dir {

using rigsim::unsafe_link_dir;

TEST_CASE("link dir: the user's own directory is safe unless others may write in it", "[unit][transport]")
{
    rigsim::test::TempDir dir;
    const auto d = dir.file("ptys");
    REQUIRE(::mkdir(d.c_str(), 0755) == 0);
    const auto me = ::geteuid();
    CHECK_FALSE(unsafe_link_dir(d, me));
    REQUIRE(::chmod(d.c_str(), 0777) == 0);
    CHECK(unsafe_link_dir(d, me).value_or("") == "the pty directory " + d + " is writable by everyone and not sticky: "
          "another user could replace its links with their own: give --pty-dir a directory of your own (or pty paths in one)");
    REQUIRE(::chmod(d.c_str(), 0775) == 0);
    CHECK(unsafe_link_dir(d, me).value_or("").find("is writable by its group and not sticky") != std::string::npos);
    REQUIRE(::chmod(d.c_str(), 01777) == 0);   // as /tmp: no one removes another's links
    CHECK_FALSE(unsafe_link_dir(d, me));
    CHECK_FALSE(unsafe_link_dir("/tmp", me));
    CHECK_FALSE(unsafe_link_dir(dir.file("absent"), me));   // not judged: creating it says why
}

TEST_CASE("link dir: another user's directory is unsafe, root's is not", "[unit][transport]")
{
    rigsim::test::TempDir dir;
    const auto d = dir.file("ptys");
    REQUIRE(::mkdir(d.c_str(), 0755) == 0);
    struct stat st {};
    REQUIRE(::stat(d.c_str(), &st) == 0);
    // Judged as a daemon of another uid: the directory is st_uid's, not that user's.
    const uid_t other = st.st_uid + 4242;
    if (st.st_uid == 0) {
        CHECK_FALSE(unsafe_link_dir(d, other));   // root's directories are trusted
        REQUIRE(::chown(d.c_str(), 4243, static_cast<gid_t>(-1)) == 0);
    }
    REQUIRE(::stat(d.c_str(), &st) == 0);
    CHECK(unsafe_link_dir(d, st.st_uid + 1).value_or("")
          == "the pty directory " + d + " belongs to uid " + std::to_string(st.st_uid) + ", not to this user (uid "
                 + std::to_string(st.st_uid + 1) + ") or root: another user could replace its links with their own: "
                 "give --pty-dir a directory of your own (or pty paths in one)");
}

} // namespace test_link_dir
