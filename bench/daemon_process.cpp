#include "daemon_process.hpp"

#include "proc_cpu.hpp"

#include "unique_fd.hpp"

#include <nlohmann/json.hpp>

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

std::vector<DeviceEndpoints> parse_endpoints(const std::string& json)
{
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(json);
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(std::string{"not JSON: "} + e.what());
    }
    const auto devices = doc.find("devices");
    if (devices == doc.end() || !devices->is_array())
        throw std::runtime_error("no \"devices\" array");
    std::vector<DeviceEndpoints> result;
    for (std::size_t i = 0; i < devices->size(); ++i) {
        const auto& device = (*devices)[i];
        const auto pointer = "/devices/" + std::to_string(i);
        const auto text = [&](const char* key) {
            const auto it = device.find(key);
            if (it == device.end() || !it->is_string())
                throw std::runtime_error(pointer + "/" + key + ": expected a string");
            return it->get<std::string>();
        };
        DeviceEndpoints e;
        e.name = text("name");
        e.protocol = text("protocol");
        e.model = text("model");
        e.pty_path = text("pty");
        const std::string tcp = text("tcp");
        const auto colon = tcp.rfind(':');
        const std::string port_text = colon == std::string::npos ? "" : tcp.substr(colon + 1);
        char* end = nullptr;
        errno = 0;
        const long port = std::strtol(port_text.c_str(), &end, 10);
        if (colon == std::string::npos || colon == 0 || port_text.empty() || *end != '\0' ||
            errno != 0 || port <= 0 || port > 65535)
            throw std::runtime_error(pointer + "/tcp: expected \"HOST:PORT\", not \"" + tcp +
                                     "\"");
        e.tcp_host = tcp.substr(0, colon);
        e.tcp_port = static_cast<std::uint16_t>(port);
        result.push_back(std::move(e));
    }
    return result;
}

DaemonProcess::DaemonProcess(const std::string& path, std::optional<int> cpu,
                             std::chrono::milliseconds timeout, std::vector<std::string> extra_args)
{
    // A constructor that throws gets no destructor call: clean up here.
    try {
        start(path, cpu, timeout, extra_args);
    } catch (...) {
        clean_up();
        throw;
    }
}

void DaemonProcess::start(const std::string& path, std::optional<int> cpu,
                          std::chrono::milliseconds timeout, const std::vector<std::string>& extra_args)
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
    args.insert(args.end(), extra_args.begin(), extra_args.end());
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
        // The daemon lists its endpoints on stdout: keep the benchmark's stdout for figures.
        ::dup2(STDERR_FILENO, STDOUT_FILENO);
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
            try {
                devices_ = parse_endpoints(*text);
            } catch (const std::runtime_error& e) {
                throw std::runtime_error(endpoints_file + ": " + e.what() + "\n" + *text);
            }
            return;
        }
        if (SteadyClock::now() > deadline)
            throw std::runtime_error("daemon " + path + " wrote no " + endpoints_file +
                                     " within " + std::to_string(timeout.count()) + " ms");
        std::this_thread::sleep_for(kPollInterval);
    }
}

const DeviceEndpoints& DaemonProcess::device(const std::string& name,
                                             const std::string& protocol) const
{
    for (const auto& d : devices_) {
        if (d.name != name)
            continue;
        if (d.protocol != protocol)
            throw std::runtime_error("device \"" + name + "\" speaks " + d.protocol + ", not " +
                                     protocol);
        return d;
    }
    throw std::runtime_error("the rig has no device \"" + name + "\"");
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
