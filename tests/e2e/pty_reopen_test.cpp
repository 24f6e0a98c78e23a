// A pty reopened at once, over and over: each process opens the port, asks, reads its
// answer, closes, and the next opens it straight away. On a real serial port one process's
// close never takes bytes from the next, so every answer must reach the process that asked.
//
// The count of cycles per device is RIGSIM_PTY_REOPEN_CYCLES (default kDefaultCycles, a few
// seconds under the sanitizers); the figures go to standard output.

#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "apt_support.hpp"
#include "e2e_support.hpp"

namespace pty_reopen_test {

using namespace rigsim::e2e;
using namespace std::chrono_literals;

constexpr int kDefaultCycles = 2000;
/// A lost answer never comes: any bound tells it from a slow one.
constexpr Millis kLostAfter{2000};

/// RIGSIM_PTY_REOPEN_CYCLES, or kDefaultCycles if it is unset or not a positive integer.
int cycles()
{
    const char* v = std::getenv("RIGSIM_PTY_REOPEN_CYCLES");
    if (!v)
        return kDefaultCycles;
    char* end = nullptr;
    const long n = std::strtol(v, &end, 10);
    return (*end == '\0' && n > 0 && n <= 10'000'000) ? static_cast<int>(n) : kDefaultCycles;
}

/// One cycle's request on a freshly opened client: "" if its answer came, else what came.
using Ask = std::function<std::string(PtyClient& client, int cycle)>;

struct Figures {
    int cycles = 0;
    int losses = 0;
    double wall_ms = 0;
    std::vector<std::string> first_failures;
};

Figures reopen_and_ask(const std::string& pty, int count, const Ask& ask)
{
    Figures f;
    const auto start = SteadyClock::now();
    for (int i = 0; i < count; ++i) {
        PtyClient client(pty);
        const auto failure = ask(client, i);
        ++f.cycles;
        if (failure.empty())
            continue;
        ++f.losses;
        if (f.first_failures.size() < 5)
            f.first_failures.push_back("cycle " + std::to_string(i) + ": " + failure);
    }
    f.wall_ms = elapsed_ms(start);
    return f;
}

void report(const std::string& device, const Figures& f)
{
    std::printf("pty reopen %s: %d cycles, %d lost, %.0f ms\n", device.c_str(), f.cycles, f.losses, f.wall_ms);
    std::fflush(stdout);
    for (const auto& failure : f.first_failures)
        UNSCOPED_INFO(failure);
    CHECK(f.losses == 0);
}

/// MCS: four requests in turn whose answers differ, so a stale answer is told from a fresh one.
std::string ask_mcs(PtyClient& client, int cycle)
{
    static const std::pair<const char*, const char*> kTurns[] = {
        {":GNC\n", ":N3\n"}, {":GSI\n", ":ID3118100\n"}, {":GS0\n", ":S0,0\n"}, {":GS1\n", ":S1,0\n"}};
    const auto& [request, answer] = kTurns[cycle % 4];
    const auto got = client.request(request, kLostAfter);
    return got == answer ? std::string() : got;
}

/// APT: HW_REQ_INFO, MOD_REQ_CHANENABLESTATE and MOT_REQ_POSCOUNTER in turn, each answer
/// checked by its message id.
std::string ask_apt(PtyClient& client, int cycle)
{
    static const std::pair<std::uint16_t, std::uint16_t> kTurns[] = {
        {0x0005, 0x0006}, {0x0211, 0x0212}, {0x0411, 0x0412}};
    const auto& [request, answer] = kTurns[cycle % 3];
    client.send(header(request, 0x01, 0x00));
    const auto frame = read_frame(client.fd(), kLostAfter);
    if (!frame)
        return "no answer";
    if (frame->id == answer)
        return {};
    char text[64];
    std::snprintf(text, sizeof text, "message 0x%04x instead of 0x%04x", frame->id, answer);
    return text;
}

TEST_CASE("pty: a process that reopens the port at once gets every answer", "[e2e][pty]")
{
    Daemon daemon;
    const int count = cycles();

    SECTION("MCS")
    {
        report("mcs0", reopen_and_ask(daemon.endpoint("mcs0").pty, count, ask_mcs));
    }
    SECTION("APT")
    {
        report("tdc001", reopen_and_ask(daemon.endpoint("tdc001").pty, count, ask_apt));
    }
}

} // namespace pty_reopen_test
