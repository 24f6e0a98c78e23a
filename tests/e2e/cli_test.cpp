// rigsimd's command line: --help, --check-config, unknown flags.

#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include <sys/stat.h>

#include "e2e_support.hpp"

namespace cli_test {

using namespace rigsim::e2e;

namespace {

long count_lines(const std::string& text)
{
    return static_cast<long>(std::count(text.begin(), text.end(), '\n'));
}

} // namespace

TEST_CASE("cli: --check-config accepts valid rigs", "[e2e][cli]")
{
    const std::string file = GENERATE(std::string(RIGSIM_SOURCE_DIR "/config/default.json"),
                                      fixture("two_channel_rig.json"),
                                      fixture("long_travel_rig.json"),
                                      std::string(RIGSIM_SOURCE_DIR "/config/examples/three_axis_stack.json"),
                                      std::string(RIGSIM_SOURCE_DIR "/config/examples/rotary_stage.json"),
                                      std::string(RIGSIM_SOURCE_DIR "/config/examples/gripper.json"),
                                      std::string(RIGSIM_SOURCE_DIR "/config/examples/open_loop_bench.json"),
                                      std::string(RIGSIM_SOURCE_DIR "/config/examples/apt_stages.json"),
                                      std::string(RIGSIM_SOURCE_DIR "/config/examples/xyz_on_rotation.json"),
                                      std::string(RIGSIM_SOURCE_DIR "/config/examples/fibre_alignment.json"),
                                      std::string(RIGSIM_SOURCE_DIR "/config/examples/goniometer_pair.json"),
                                      std::string(RIGSIM_SOURCE_DIR "/config/examples/current_units.json"));
    const auto r = run_rigsimd({"--check-config", file});
    INFO(file << "\nstdout: " << r.out << "\nstderr: " << r.err);
    REQUIRE(r.exited);
    CHECK(r.exit_code == 0);
}

TEST_CASE("cli: --check-config rejects a bad rig naming the JSON pointer", "[e2e][cli]")
{
    SECTION("unknown sensor type")
    {
        const std::string file = fixture("bad_sensor_type.json");
        const auto r = run_rigsimd({"--check-config", file});
        INFO("stderr: " << r.err);
        REQUIRE(r.exited);
        CHECK(r.exit_code == 2);
        CHECK(count_lines(r.err) == 1);
        CHECK(r.err.find("bad_sensor_type.json") != std::string::npos);
        CHECK(r.err.find("/devices/0/mcs/channels/0/sensor_type") != std::string::npos);
        CHECK(r.err.find("S9") != std::string::npos);
    }

    SECTION("unknown key")
    {
        const auto r = run_rigsimd({"--check-config", fixture("unknown_key.json")});
        INFO("stderr: " << r.err);
        REQUIRE(r.exited);
        CHECK(r.exit_code == 2);
        CHECK(count_lines(r.err) == 1);
        CHECK(r.err.find("/devices/0/mcs/channels/1") != std::string::npos);
        CHECK(r.err.find("colour") != std::string::npos);
    }

    SECTION("malformed JSON")
    {
        TempDir dir;
        const std::string file = dir.file("broken.json");
        write_file(file, "{\"tick_hz\": 1000, \"devices\": [\n");
        const auto r = run_rigsimd({"--check-config", file});
        INFO("stderr: " << r.err);
        REQUIRE(r.exited);
        CHECK(r.exit_code == 2);
        CHECK(count_lines(r.err) == 1);
        CHECK(r.err.find("broken.json") != std::string::npos);
    }

    SECTION("a frame's joint its channel cannot drive: found on the devices, before anything is served")
    {
        TempDir dir;
        const std::string file = dir.file("frames.json");
        write_file(file, R"({"devices": [{"name": "stack", "protocol": "mcs", "mcs": {"channels": [{}]}}],
            "kinematics": {"frames": [{"name": "table"},
                {"name": "x", "parent": "table", "axis": {"device": "stack", "channel": 0},
                 "joint": {"type": "revolute", "axis": [0, 0, 1]}}]}})");
        const std::string message =
            file + ": /kinematics/frames/1/joint/type: a revolute joint on a linear stage (stack channel 0)\n";
        const auto r = run_rigsimd({"--check-config", file});
        INFO("stderr: " << r.err);
        REQUIRE(r.exited);
        CHECK(r.exit_code == 2);
        CHECK(r.err == message);
        CHECK(r.out.empty());
        const auto run = run_rigsimd({"--config", file, "--pty-dir", dir.path(), "--ephemeral-ports"});
        INFO("stderr: " << run.err);
        REQUIRE(run.exited);
        CHECK(run.exit_code == 2);
        CHECK(run.err.size() >= message.size());
        CHECK(run.err.substr(run.err.size() - message.size()) == message);
        CHECK_FALSE(path_exists(dir.file("stack")));   // no pty was opened
    }

    SECTION("missing file")
    {
        TempDir dir;
        const auto r = run_rigsimd({"--check-config", dir.file("absent.json")});
        INFO("stderr: " << r.err);
        REQUIRE(r.exited);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find("absent.json") != std::string::npos);
    }
}

TEST_CASE("cli: --control on a device's port exits 2 before anything listens", "[e2e][cli]")
{
    TempDir dir;
    // The default rig's second device listens on 40101.
    const auto r = run_rigsimd({"--control", "127.0.0.1:40101", "--pty-dir", dir.file("ptys")});
    INFO("stderr: " << r.err);
    REQUIRE(r.exited);
    CHECK(r.exit_code == 2);
    CHECK(r.err == "rigsimd: --control: port 40101 is device \"tdc001\"'s tcp_port (/devices/1/tcp_port); choose "
                   "another, or add --ephemeral-ports\n");
    CHECK_FALSE(path_exists(dir.file("ptys")));   // nothing was opened
}

TEST_CASE("cli: a pty directory others may write in exits 2 before any link is made", "[e2e][cli]")
{
    TempDir dir;
    const auto ptys = dir.file("ptys");
    REQUIRE(::mkdir(ptys.c_str(), 0700) == 0);
    REQUIRE(::chmod(ptys.c_str(), 0777) == 0);
    const auto r = run_rigsimd({"--pty-dir", ptys, "--ephemeral-ports"});
    INFO("stderr: " << r.err);
    REQUIRE(r.exited);
    CHECK(r.exit_code == 2);
    CHECK(r.err == "rigsimd: the pty directory " + ptys + " is writable by everyone and not sticky: another user could "
                   "replace its links with their own: give --pty-dir a directory of your own (or pty paths in one)\n");
    CHECK_FALSE(path_exists(ptys + "/mcs0"));
    CHECK_FALSE(path_exists(ptys + "/.mcs0.lock"));
}

TEST_CASE("cli: --pty-group naming no group exits 2 naming the flag", "[e2e][cli]")
{
    TempDir dir;
    const auto r = run_rigsimd({"--pty-group", "no-such-group-rigsim", "--pty-dir", dir.file("ptys")});
    INFO("stderr: " << r.err);
    REQUIRE(r.exited);
    CHECK(r.exit_code == 2);
    CHECK(r.err == "rigsimd: --pty-group: no group \"no-such-group-rigsim\" on this system\n");
    CHECK_FALSE(path_exists(dir.file("ptys")));
}

TEST_CASE("cli: an unknown flag exits 2 naming the flag", "[e2e][cli]")
{
    const auto r = run_rigsimd({"--no-such-flag"});
    INFO("stderr: " << r.err);
    REQUIRE(r.exited);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--no-such-flag") != std::string::npos);
}

TEST_CASE("cli: --help lists every flag and exits 0", "[e2e][cli]")
{
    const auto r = run_rigsimd({"--help"});
    INFO("stdout: " << r.out << "\nstderr: " << r.err);
    REQUIRE(r.exited);
    CHECK(r.exit_code == 0);
    for (const char* flag : {"--config", "--check-config", "--endpoints-json", "--pty-dir", "--replace-links",
                             "--ephemeral-ports", "--rfc2217", "--pty-group", "--bind", "--max-connections", "--max-connections-per-device",
                             "--time-scale", "--tick-hz", "--state-file",
                             "--log-level", "--help"}) {
        INFO("flag " << flag);
        CHECK(r.out.find(flag) != std::string::npos);
    }
}

} // namespace cli_test
