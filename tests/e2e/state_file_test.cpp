// --state-file through the real daemon: files it cannot read stop start-up, a symlink is
// written through, temporaries of a killed daemon are removed, damaged entries are skipped
// and the damaged file is kept as <file>.damaged (docs/cli.md, "State file").
#include <catch2/catch.hpp>

#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <string>

#include "e2e_support.hpp"

namespace state_file_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

namespace {

std::string header(std::uint16_t id, std::uint8_t p1, std::uint8_t p2)
{
    return {static_cast<char>(id & 0xff), static_cast<char>(id >> 8), static_cast<char>(p1),
            static_cast<char>(p2), '\x50', '\x01'};
}

std::string with_data(std::uint16_t id, const std::string& data)
{
    return std::string{static_cast<char>(id & 0xff), static_cast<char>(id >> 8), static_cast<char>(data.size() & 0xff),
                       static_cast<char>(data.size() >> 8), static_cast<char>(0x50 | 0x80), '\x01'}
           + data;
}

std::int32_t get32(const std::string& s, std::size_t at)
{
    return static_cast<std::int32_t>(static_cast<std::uint8_t>(s[at]) | static_cast<std::uint8_t>(s[at + 1]) << 8
                                     | static_cast<std::uint8_t>(s[at + 2]) << 16
                                     | static_cast<std::uint32_t>(static_cast<std::uint8_t>(s[at + 3])) << 24);
}

/// The data of the next frame with `id` (other frames skipped), or nullopt by the deadline.
std::optional<std::string> wait_for(int fd, std::uint16_t id, Millis timeout = 10'000ms)
{
    const auto deadline = SteadyClock::now() + timeout;
    std::string in;
    while (SteadyClock::now() < deadline) {
        while (in.size() >= 6) {
            const bool has_data = static_cast<std::uint8_t>(in[4]) & 0x80;
            const std::size_t len = has_data ? (static_cast<std::uint8_t>(in[2]) | static_cast<std::uint8_t>(in[3]) << 8) : 0;
            if (in.size() < 6 + len)
                break;
            const auto got = static_cast<std::uint16_t>(static_cast<std::uint8_t>(in[0]) | static_cast<std::uint8_t>(in[1]) << 8);
            if (got == id)
                return in.substr(6, len);
            in.erase(0, 6 + len);
        }
        pollfd p{fd, POLLIN, 0};
        const auto left = std::chrono::duration_cast<Millis>(deadline - SteadyClock::now()).count();
        if (::poll(&p, 1, static_cast<int>(std::max<long long>(left, 0))) <= 0)
            continue;
        char buf[512];
        const auto n = ::read(fd, buf, sizeof buf);
        if (n <= 0)
            return std::nullopt;
        in.append(buf, static_cast<std::size_t>(n));
    }
    return std::nullopt;
}

/// VELPARAMS of channel 1: minimum 0, acceleration 16, maximum 4096 (APT units).
const std::string kVelParams("\x01\x00\x00\x00\x00\x00\x10\x00\x00\x00\x00\x10\x00\x00", 14);
const std::string kSaveVelParams("\x01\x00\x13\x04", 4);

bool is_symlink(const std::string& path)
{
    struct stat st {};
    return ::lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode);
}

} // namespace

TEST_CASE("state file: a directory or an unreadable file stops start-up (exit 1), naming it", "[e2e][state]")
{
    TempDir dir;
    const auto pty_dir = dir.file("pty");
    {
        const auto r = run_rigsimd({"--state-file", dir.path(), "--ephemeral-ports", "--pty-dir", pty_dir});
        CHECK(r.exited);
        CHECK(r.exit_code == 1);
        CHECK_THAT(r.err, Catch::Contains("rigsimd: state file " + dir.path() + ": is a directory, not a file"));
    }
    {
        // The daemon's own /proc/self/mem: a regular file whose first page cannot be read (EIO).
        const auto r = run_rigsimd({"--state-file", "/proc/self/mem", "--ephemeral-ports", "--pty-dir", pty_dir});
        CHECK(r.exited);
        CHECK(r.exit_code == 1);
        CHECK_THAT(r.err, Catch::Contains("rigsimd: state file /proc/self/mem: cannot read it: Input/output error"));
    }
}

TEST_CASE("state file: a symlinked state file stays a link after a save, and stale temporaries are removed",
          "[e2e][state]")
{
    TempDir state_dir;
    REQUIRE(::mkdir(state_dir.file("real").c_str(), 0755) == 0);
    const auto target = state_dir.file("real/state.json");
    const auto link = state_dir.file("state.json");
    write_file(target, R"({"other-rig-device": {"bay0/0x0413": "0100"}})" "\n");
    REQUIRE(::symlink("real/state.json", link.c_str()) == 0);
    const auto stale = target + ".tmp999999999.Ab12Cd34";   // left by a daemon killed mid-save
    write_file(stale, "{\"half");

    Daemon::Options options;
    options.extra_args = {"--state-file", link};
    Daemon daemon(options);
    CHECK_FALSE(path_exists(stale));
    CHECK_THAT(daemon.log(), Catch::Contains("removed " + stale + ", left by a rigsimd that was killed while saving"));

    TcpClient c(daemon.endpoint("kdc101"));
    c.send(with_data(0x0413, kVelParams));
    c.send(with_data(0x04B9, kSaveVelParams));
    REQUIRE(wait_until([&] { return read_file(target).value_or("").find("bay0/0x0413") != std::string::npos
                                    && read_file(target)->find("kdc101") != std::string::npos; },
                       5000ms));
    CHECK(is_symlink(link));
    CHECK_THAT(*read_file(target), Catch::Contains("other-rig-device"));   // other devices' entries kept
    REQUIRE(daemon.stop(SIGTERM) == std::optional<int>(0));
    CHECK(is_symlink(link));
}

TEST_CASE("state file: a damaged entry is skipped and logged, and the damaged file is kept at the next save",
          "[e2e][state]")
{
    TempDir state_dir;
    const auto state = state_dir.file("state.json");
    // A MOVE_ABSOLUTE to 100,000 counts (never saved by MOT_SET_EEPROMPARAMS) and a good VELPARAMS.
    const std::string original = R"({"kdc101": {"bay0/0x0453": "0100a0860100", "bay0/0x0413": "0100000000001000000000100000"}})" "\n";
    write_file(state, original);
    Daemon::Options options;
    options.extra_args = {"--state-file", state};
    Daemon daemon(options);
    CHECK_THAT(daemon.log(), Catch::Contains("state file " + state + ": device \"kdc101\", key \"bay0/0x0453\": skipped: "
                                             "MGMSG_MOT_MOVE_ABSOLUTE is not a parameter SET that MOT_SET_EEPROMPARAMS saves"));
    TcpClient c(daemon.endpoint("kdc101"));
    c.send(header(0x0411, 1, 0));
    const auto pos = wait_for(c.fd(), 0x0412);
    REQUIRE(pos);
    CHECK(get32(*pos, 2) == 0);   // the stage did not move ...
    c.send(header(0x0429, 1, 0));   // MOT_REQ_STATUSBITS
    const auto bits = wait_for(c.fd(), 0x042A);
    REQUIRE(bits);
    CHECK((get32(*bits, 2) & 0x30) == 0);   // ... and is not moving (0x10 forward, 0x20 reverse)
    c.send(header(0x0414, 1, 0));
    const auto vel = wait_for(c.fd(), 0x0415);
    REQUIRE(vel);
    CHECK(get32(*vel, 10) == 4096);   // the good entry was restored
    CHECK(read_file(state) == original);   // nothing saved yet: untouched

    c.send(with_data(0x0413, kVelParams));
    c.send(with_data(0x04B9, kSaveVelParams));
    REQUIRE(wait_until([&] { return read_file(state) != original && path_exists(state + ".damaged"); }, 5000ms));
    CHECK(read_file(state + ".damaged") == original);
    CHECK(read_file(state)->find("0x0453") == std::string::npos);
    REQUIRE(wait_until([&] { return daemon.log().find("kept the file as loaded as " + state + ".damaged") != std::string::npos; },
                       5000ms));
}

} // namespace state_file_test

namespace state_file_test {

TEST_CASE("state file: with --state-sync, kill -9 after the unit answered loses no save", "[e2e][state]")
{
    TempDir state_dir;
    const auto file = state_dir.file("state.json");
    Daemon::Options options;
    options.extra_args = {"--state-file", file, "--state-sync"};
    Daemon daemon(options);
    TcpClient c(daemon.endpoint("kdc101"));
    // 50 saves of VELPARAMS, the maximum velocity 1..50, then a REQ: its answer comes after every
    // save before it was acted on. Written behind, the file lags them (bench/state_durability.py).
    std::string burst;
    for (int i = 1; i <= 50; ++i) {
        auto vel = kVelParams;
        vel[10] = static_cast<char>(i);
        vel[11] = 0;
        burst += with_data(0x0413, vel) + with_data(0x04B9, kSaveVelParams);
    }
    c.send(burst + header(0x0414, 1, 0));
    const auto vel = wait_for(c.fd(), 0x0415);
    REQUIRE(vel);
    CHECK(get32(*vel, 10) == 50);
    REQUIRE(daemon.stop(SIGKILL).has_value());
    const auto text = read_file(file);
    REQUIRE(text);
    CHECK_THAT(*text, Catch::Contains("\"bay0/0x0413\": \"0100000000001000000032000000\""));
}

TEST_CASE("state file: --state-sync without --state-file exits 2", "[e2e][state]")
{
    const auto r = run_rigsimd({"--state-sync"});
    REQUIRE(r.exited);
    CHECK(r.exit_code == 2);
    CHECK(r.err == "rigsimd: --state-sync: needs --state-file (without a file, saves last until the daemon exits)\n");
}

} // namespace state_file_test
