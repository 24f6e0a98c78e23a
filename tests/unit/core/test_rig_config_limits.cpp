// Config loader limits and messages: what a file may be, how big, which names, and how much
// of a bad value an error echoes.
#include "emulator/daemon/rig_families.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace test_rig_config_limits {

using rigsim::ConfigError;

namespace {

std::string error_of_text(std::string_view text)
{
    try {
        rigsim::parse_rig_config(text, "rig.json");
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "(no error)";
}

std::string error_of_file(const std::string& path)
{
    try {
        rigsim::load_rig_config(path);
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "(no error)";
}

std::string rig_with_device_named(const std::string& name)
{
    return R"({"devices": [{"name": ")" + name + R"(", "protocol": "mcs", "mcs": {"channels": [{}]}}]})";
}

} // namespace

TEST_CASE("rig config: a number that overflows a double names its JSON pointer", "[unit][config]")
{
    CHECK(error_of_text(R"({"tick_hz": 1e400, "devices": []})")
          == "rig.json: /tick_hz: number overflow parsing '1e400' (not a finite number)");
    CHECK(error_of_text(R"({"devices": [{"name": "a", "protocol": "mcs", "mcs": {"channels": [{}, {"step_width_nm": -1e999}]}}]})")
          == "rig.json: /devices/0/mcs/channels/1/step_width_nm: number overflow parsing '-1e999' (not a finite number)");
}

TEST_CASE("rig config: device names \".\" and \"..\" are refused", "[unit][config]")
{
    CHECK(error_of_text(rig_with_device_named("."))
          == "rig.json: /devices/0/name: expected a device name, got \".\" (\".\" and \"..\" name directories)");
    CHECK(error_of_text(rig_with_device_named(".."))
          == "rig.json: /devices/0/name: expected a device name, got \"..\" (\".\" and \"..\" name directories)");
    CHECK(error_of_text(rig_with_device_named("...")) == "(no error)");
    CHECK(error_of_text(rig_with_device_named(".hidden")) == "(no error)");
}

TEST_CASE("rig config: values and keys echoed in errors are cut to a sane length", "[unit][config]")
{
    const std::string long_key(5000, 'k');
    const auto e = error_of_text(R"({")" + long_key + R"(": 1, "devices": []})");
    CHECK(e.size() < 200);
    CHECK(e.rfind("rig.json: /: unknown key \"kkkk", 0) == 0);
    CHECK(e.find("... (5002 characters)") != std::string::npos);

    const std::string long_value(100000, 'x');
    const auto v = error_of_text(R"({"devices": [{"name": "a", "protocol": ")" + long_value + R"(", "mcs": {"channels": [{}]}}]})");
    CHECK(v.size() < 200);
    CHECK(v.rfind("rig.json: /devices/0/protocol: unknown protocol \"xxx", 0) == 0);

    // A cut never splits a UTF-8 character.
    std::string accents;
    for (int i = 0; i < 100; ++i)
        accents += "\xC3\xA9";   // é
    const auto u = error_of_text(R"({")" + accents + R"(": 1, "devices": []})");
    const auto cut_at = u.find("...");
    REQUIRE(cut_at != std::string::npos);
    CHECK((static_cast<unsigned char>(u[cut_at - 1]) & 0xC0) != 0xC0);   // not a lead byte left alone
}

TEST_CASE("rig config: only regular files of at most 4 MiB are read", "[unit][config]")
{
    CHECK(error_of_file("/dev/zero") == "/dev/zero: not a regular file (a character device): a rig is read from a JSON file");
    CHECK(error_of_file("/") == "/: not a regular file (a directory): a rig is read from a JSON file");

    char dir_template[] = "/tmp/rigsim-config-XXXXXX";
    REQUIRE(::mkdtemp(dir_template) != nullptr);
    const std::string dir = dir_template;
    const auto big = dir + "/big.json";
    {
        std::ofstream out(big);
        out << std::string((4 << 20) + 1, ' ');
    }
    CHECK(error_of_file(big) == big + ": 4194305 bytes: a rig file may hold at most 4194304 bytes");
    const auto fifo = dir + "/fifo";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    // With no writer: opening it for reading would wait for one for ever; it is refused at once.
    CHECK(error_of_file(fifo) == fifo + ": not a regular file (a pipe): a rig is read from a JSON file");
    // With a writer holding it open, the same.
    const int keep = ::open(fifo.c_str(), O_RDWR | O_NONBLOCK);
    REQUIRE(keep >= 0);
    CHECK(error_of_file(fifo) == fifo + ": not a regular file (a pipe): a rig is read from a JSON file");
    ::close(keep);
    ::unlink(fifo.c_str());
    ::unlink(big.c_str());
    ::rmdir(dir.c_str());
}

} // namespace test_rig_config_limits
