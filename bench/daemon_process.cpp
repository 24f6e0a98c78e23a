#include "daemon_process.hpp"

#include "unique_fd.hpp"

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

namespace rigsim::bench {

namespace {

using SteadyClock = std::chrono::steady_clock;

/// Interval between two looks at the endpoints file or the child's status.
constexpr std::chrono::milliseconds kPollInterval{5};

std::optional<std::string> read_file(const std::string& path)
{
    std::ifstream in{path, std::ios::binary};
    if (!in)
        return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/// The string value following `"key"` and a ':', from the first occurrence of the key.
std::optional<std::string> string_value(const std::string& json, const std::string& key)
{
    const std::string quoted = "\"" + key + "\"";
    auto pos = json.find(quoted);
    if (pos == std::string::npos)
        return std::nullopt;
    pos = json.find_first_not_of(" \t\r\n", pos + quoted.size());
    if (pos == std::string::npos || json[pos] != ':')
        return std::nullopt;
    pos = json.find_first_not_of(" \t\r\n", pos + 1);
    if (pos == std::string::npos || json[pos] != '"')
        return std::nullopt;
    const auto end = json.find('"', pos + 1);
    if (end == std::string::npos)
        return std::nullopt;
    // Paths and host:port strings need no JSON escapes; one would mean a bad parse.
    std::string value = json.substr(pos + 1, end - pos - 1);
    if (value.find('\\') != std::string::npos)
        return std::nullopt;
    return value;
}

std::string describe_status(int status)
{
    if (WIFEXITED(status))
        return "exit status " + std::to_string(WEXITSTATUS(status));
    if (WIFSIGNALED(status))
        return std::string{"signal "} + std::to_string(WTERMSIG(status)) + " (" +
               ::strsignal(WTERMSIG(status)) + ")";
    return "status " + std::to_string(status);
}

}  // namespace

std::optional<Endpoints> parse_endpoints(const std::string& json)
{
    const auto tcp = string_value(json, "tcp");
    const auto pty = string_value(json, "pty");
    if (!tcp || !pty)
        return std::nullopt;
    const auto colon = tcp->rfind(':');
    if (colon == std::string::npos || colon == 0)
        return std::nullopt;
    const std::string port_text = tcp->substr(colon + 1);
    char* end = nullptr;
    errno = 0;
    const long port = std::strtol(port_text.c_str(), &end, 10);
    if (port_text.empty() || *end != '\0' || errno != 0 || port <= 0 || port > 65535)
        return std::nullopt;
    return Endpoints{tcp->substr(0, colon), static_cast<std::uint16_t>(port), *pty};
}

DaemonProcess::DaemonProcess(const std::string& path, std::optional<int> cpu,
                             std::chrono::milliseconds timeout)
{
    // A constructor that throws gets no destructor call: clean up here.
    try {
        start(path, cpu, timeout);
    } catch (...) {
        clean_up();
        throw;
    }
}

void DaemonProcess::start(const std::string& path, std::optional<int> cpu,
                          std::chrono::milliseconds timeout)
{
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string{tmp && *tmp ? tmp : "/tmp"} + "/rigsim_bench.XXXXXX";
    if (!::mkdtemp(pattern.data()))
        throw std::runtime_error(errno_message("mkdtemp " + pattern));
    temp_dir_ = pattern;
    const std::string pty_dir = temp_dir_ + "/pty";
    const std::string endpoints_file = temp_dir_ + "/endpoints.json";
    if (::mkdir(pty_dir.c_str(), 0700) < 0)
        throw std::runtime_error(errno_message("mkdir " + pty_dir));

    // Everything the child needs is built before fork(): after it only exec.
    std::vector<std::string> args = {path,           "--ephemeral-ports", "--pty-dir",
                                     pty_dir,        "--endpoints-json",  endpoints_file,
                                     "--log-level",  "warn"};
    std::vector<char*> argv;
    for (auto& arg : args)
        argv.push_back(arg.data());
    argv.push_back(nullptr);
    const pid_t parent = ::getpid();
    // Set in the child before exec, so that every thread of the daemon inherits it.
    cpu_set_t cpus;
    CPU_ZERO(&cpus);
    if (cpu)
        CPU_SET(*cpu, &cpus);

    pid_ = ::fork();
    if (pid_ < 0)
        throw std::runtime_error(errno_message("fork"));
    if (pid_ == 0) {
        // The daemon dies with the benchmark, however the benchmark ends.
        ::prctl(PR_SET_PDEATHSIG, SIGTERM);
        if (::getppid() != parent)
            ::_exit(127);
        if (cpu && ::sched_setaffinity(0, sizeof cpus, &cpus) < 0) {
            const char message[] = "rigsim_bench: cannot pin the daemon to its CPU\n";
            [[maybe_unused]] auto ignored = ::write(STDERR_FILENO, message, sizeof message - 1);
            ::_exit(126);
        }
        struct sigaction dfl {};
        dfl.sa_handler = SIG_DFL;
        ::sigaction(SIGPIPE, &dfl, nullptr);
        const int null = ::open("/dev/null", O_RDONLY);
        if (null >= 0)
            ::dup2(null, STDIN_FILENO);
        ::execv(argv[0], argv.data());
        const char message[] = "rigsim_bench: exec of the daemon failed\n";
        [[maybe_unused]] auto ignored = ::write(STDERR_FILENO, message, sizeof message - 1);
        ::_exit(127);
    }

    const auto deadline = SteadyClock::now() + timeout;
    for (;;) {
        int status = 0;
        if (reaped(status))
            throw std::runtime_error("daemon " + path + " ended (" + describe_status(status) +
                                     ") before writing " + endpoints_file);
        // The daemon writes the file atomically: once it exists it is complete.
        if (const auto text = read_file(endpoints_file)) {
            if (auto endpoints = parse_endpoints(*text)) {
                endpoints_ = *endpoints;
                return;
            }
            throw std::runtime_error("no \"tcp\" and \"pty\" endpoint in " + endpoints_file +
                                     ": " + *text);
        }
        if (SteadyClock::now() > deadline)
            throw std::runtime_error("daemon " + path + " wrote no " + endpoints_file +
                                     " within " + std::to_string(timeout.count()) + " ms");
        std::this_thread::sleep_for(kPollInterval);
    }
}

DaemonProcess::~DaemonProcess()
{
    clean_up();
}

void DaemonProcess::clean_up()
{
    if (pid_ > 0) {
        ::kill(pid_, SIGKILL);
        int status = 0;
        while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
        }
        pid_ = -1;
    }
    if (!temp_dir_.empty()) {
        std::error_code ec;
        std::filesystem::remove_all(temp_dir_, ec);
    }
}

bool DaemonProcess::reaped(int& status)
{
    const pid_t r = ::waitpid(pid_, &status, WNOHANG);
    if (r == pid_) {
        pid_ = -1;
        return true;
    }
    if (r < 0 && errno != EINTR)
        throw std::runtime_error(errno_message("waitpid"));
    return false;
}

void DaemonProcess::terminate(std::chrono::milliseconds timeout)
{
    if (pid_ <= 0)
        return;
    const pid_t pid = pid_;
    if (::kill(pid, SIGTERM) < 0)
        throw std::runtime_error(errno_message("kill SIGTERM"));
    const auto start = SteadyClock::now();
    for (;;) {
        int status = 0;
        if (reaped(status)) {
            if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
                throw std::runtime_error("daemon ended with " + describe_status(status) +
                                         " after SIGTERM");
            return;
        }
        if (SteadyClock::now() - start > timeout)
            throw std::runtime_error("daemon (pid " + std::to_string(pid) +
                                     ") still running " + std::to_string(timeout.count()) +
                                     " ms after SIGTERM; killed");
        std::this_thread::sleep_for(kPollInterval);
    }
}

}  // namespace rigsim::bench
