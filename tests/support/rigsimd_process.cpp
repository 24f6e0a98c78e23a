#include "tests/support/rigsimd_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace rigsim::launch {

namespace {

constexpr Millis kPollPeriod{2};

std::string errno_text(const std::string& what)
{
    return what + ": " + std::strerror(errno);
}

int remaining_ms(SteadyClock::time_point deadline)
{
    auto left = std::chrono::duration_cast<Millis>(deadline - SteadyClock::now()).count();
    return left < 0 ? 0 : static_cast<int>(std::min<long long>(left, 1000 * 1000));
}

std::optional<std::string> read_whole_file(const std::string& path)
{
    std::ifstream f(path, std::ios::binary);
    if (!f)
        return std::nullopt;
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

/// argv (or envp) for exec, built before fork so the child only calls async-signal-safe
/// functions.
class Argv {
public:
    explicit Argv(const std::vector<std::string>& args) : storage_(args)
    {
        for (auto& s : storage_)
            pointers_.push_back(s.data());
        pointers_.push_back(nullptr);
    }
    char* const* get() { return pointers_.data(); }

private:
    std::vector<std::string> storage_;
    std::vector<char*> pointers_;
};

/// What the child does between fork and exec, decided before the fork.
struct ChildSetup {
    int in_fd = -1;
    int out_fd = -1;
    int err_fd = -1;
    pid_t parent = -1;
    int parent_death_signal = SIGKILL;
    const rlimit* max_open_files = nullptr;
    const cpu_set_t* cpus = nullptr;
    char* const* envp = nullptr;   ///< nullptr: this process's environment
    const char* exec_failed = "";  ///< written to stderr if exec fails
};

/// Writes `text` to stderr from the child (async-signal-safe).
void child_says(const char* text)
{
    [[maybe_unused]] const auto ignored = ::write(STDERR_FILENO, text, std::strlen(text));
}

/// In the child after fork: die with the parent, default signal handling, stdio redirected,
/// then exec. Only async-signal-safe calls.
[[noreturn]] void exec_child(char* const* argv, const ChildSetup& setup)
{
    if (setup.max_open_files && ::setrlimit(RLIMIT_NOFILE, setup.max_open_files) != 0)
        ::_exit(127);
#ifdef __linux__
    ::prctl(PR_SET_PDEATHSIG, setup.parent_death_signal);
    if (::getppid() != setup.parent)
        ::_exit(127);
#endif
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    ::signal(SIGPIPE, SIG_DFL);
    ::signal(SIGINT, SIG_DFL);
    ::signal(SIGTERM, SIG_DFL);
    if (::dup2(setup.in_fd, STDIN_FILENO) < 0 || ::dup2(setup.out_fd, STDOUT_FILENO) < 0 ||
        ::dup2(setup.err_fd, STDERR_FILENO) < 0)
        ::_exit(127);
    if (setup.cpus && ::sched_setaffinity(0, sizeof *setup.cpus, setup.cpus) < 0) {
        child_says("rigsimd launcher: cannot pin rigsimd to its CPU\n");
        ::_exit(126);
    }
    if (setup.envp)
        ::execve(argv[0], argv, setup.envp);
    else
        ::execv(argv[0], argv);
    child_says(setup.exec_failed);
    ::_exit(127);
}

/// This process's environment with `entries` ("NAME=value") added or replacing NAME's.
std::vector<std::string> environment_with(const std::vector<std::string>& entries)
{
    std::vector<std::string> env = entries;
    for (char** e = environ; *e; ++e) {
        const std::string entry(*e);
        const auto name = entry.substr(0, entry.find('=') + 1);
        const bool replaced = std::any_of(entries.begin(), entries.end(),
                                          [&](const std::string& x) { return x.rfind(name, 0) == 0; });
        if (!replaced)
            env.push_back(entry);
    }
    return env;
}

} // namespace

bool wait_until(const std::function<bool()>& pred, Millis timeout)
{
    const auto deadline = SteadyClock::now() + timeout;
    for (;;) {
        if (pred())
            return true;
        if (SteadyClock::now() >= deadline)
            return false;
        // Not a fixed delay: a short poll period between checks of the predicate.
        std::this_thread::sleep_for(kPollPeriod);   // poll: re-check until the deadline
    }
}

std::string describe_wait_status(int status)
{
    if (WIFEXITED(status))
        return "exited " + std::to_string(WEXITSTATUS(status));
    if (WIFSIGNALED(status))
        return "killed by signal " + std::to_string(WTERMSIG(status));
    return "wait status " + std::to_string(status);
}

// --- TempDir -------------------------------------------------------------------------

TempDir::TempDir(const std::string& prefix, const char* keep_variable) : keep_variable_(keep_variable)
{
    const char* base = std::getenv("TMPDIR");
    std::string templ = std::string(base && *base ? base : "/tmp") + "/" + prefix + "-XXXXXX";
    if (!::mkdtemp(templ.data()))
        throw std::runtime_error(errno_text("mkdtemp " + templ));
    path_ = templ;
}

TempDir::~TempDir()
{
    if (keep_variable_ && std::getenv(keep_variable_))
        return;
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
}

// --- run to completion ---------------------------------------------------------------

ProcessResult run_to_completion(const std::vector<std::string>& args, Millis timeout)
{
    Argv argv(args);
    int out_pipe[2], err_pipe[2];
    if (::pipe2(out_pipe, O_CLOEXEC) < 0)
        throw std::runtime_error(errno_text("pipe2"));
    if (::pipe2(err_pipe, O_CLOEXEC) < 0) {
        ::close(out_pipe[0]);
        ::close(out_pipe[1]);
        throw std::runtime_error(errno_text("pipe2"));
    }
    int null_fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    ChildSetup setup;
    setup.in_fd = null_fd;
    setup.out_fd = out_pipe[1];
    setup.err_fd = err_pipe[1];
    setup.parent = ::getpid();
    pid_t pid = ::fork();
    if (pid == 0)
        exec_child(argv.get(), setup);
    ::close(null_fd);
    ::close(out_pipe[1]);
    ::close(err_pipe[1]);
    if (pid < 0) {
        ::close(out_pipe[0]);
        ::close(err_pipe[0]);
        throw std::runtime_error(errno_text("fork"));
    }

    ProcessResult result;
    const auto deadline = SteadyClock::now() + timeout;
    pollfd fds[2] = {{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}};
    std::string* sinks[2] = {&result.out, &result.err};
    int open_pipes = 2;
    while (open_pipes > 0) {
        int left = remaining_ms(deadline);
        if (left == 0) {
            result.timed_out = true;
            break;
        }
        int n = ::poll(fds, 2, left);
        if (n < 0 && errno != EINTR)
            break;
        for (int i = 0; i < 2; ++i) {
            if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR)))
                continue;
            char buf[4096];
            ssize_t got = ::read(fds[i].fd, buf, sizeof buf);
            if (got > 0) {
                sinks[i]->append(buf, static_cast<std::size_t>(got));
            } else if (got == 0 || errno != EINTR) {
                ::close(fds[i].fd);
                fds[i].fd = -1;
                --open_pipes;
            }
        }
    }
    for (auto& p : fds)
        if (p.fd >= 0)
            ::close(p.fd);

    int status = 0;
    bool reaped = wait_until(
        [&] { return ::waitpid(pid, &status, WNOHANG) == pid; },
        result.timed_out ? Millis{0} : Millis{std::max(remaining_ms(deadline), 1)});
    if (!reaped) {
        result.timed_out = true;
        ::kill(pid, SIGKILL);
        ::waitpid(pid, &status, 0);
        return result;
    }
    if (WIFEXITED(status)) {
        result.exited = true;
        result.exit_code = WEXITSTATUS(status);
    }
    return result;
}

// --- RigsimdProcess ------------------------------------------------------------------

RigsimdProcess::RigsimdProcess(LaunchOptions options) : options_(std::move(options))
{
    // A constructor that throws gets no destructor call: the child is killed here.
    try {
        start();
        wait_for_endpoints();
    } catch (...) {
        kill();
        throw;
    }
}

RigsimdProcess::~RigsimdProcess()
{
    if (options_.stop_timeout > Millis{0} && stop(SIGTERM, options_.stop_timeout))
        return;
    kill();
}

void RigsimdProcess::start()
{
    std::vector<std::string> args{
        options_.binary,
        "--ephemeral-ports",
        "--pty-dir", options_.dir,
        "--endpoints-json", endpoints_path(),
    };
    args.insert(args.end(), options_.args.begin(), options_.args.end());
    Argv argv(args);
    std::optional<Argv> envp;
    if (!options_.environment.empty())
        envp.emplace(environment_with(options_.environment));
    const std::string exec_failed = "rigsimd launcher: exec of " + options_.binary + " failed\n";

    int in_fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    int out_fd = -1;
    int err_fd = -1;
    if (options_.output == LaunchOptions::Output::Files) {
        out_fd = ::open((options_.dir + "/stdout.log").c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
        err_fd = ::open((options_.dir + "/rigsimd.log").c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    } else {
        out_fd = ::fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 3);
        err_fd = ::fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 3);
    }
    const auto close_stdio = [&] {
        for (int fd : {in_fd, out_fd, err_fd})
            if (fd >= 0)
                ::close(fd);
    };
    if (in_fd < 0 || out_fd < 0 || err_fd < 0) {
        const auto error = errno_text("open rigsimd's stdio in " + options_.dir);
        close_stdio();
        throw std::runtime_error(error);
    }
    rlimit limit{};
    if (options_.max_open_files)
        limit.rlim_cur = limit.rlim_max = *options_.max_open_files;
    cpu_set_t cpus;
    CPU_ZERO(&cpus);
    if (options_.cpu)
        CPU_SET(*options_.cpu, &cpus);
    ChildSetup setup;
    setup.in_fd = in_fd;
    setup.out_fd = out_fd;
    setup.err_fd = err_fd;
    setup.parent = ::getpid();
    setup.parent_death_signal = options_.parent_death_signal;
    setup.max_open_files = options_.max_open_files ? &limit : nullptr;
    setup.cpus = options_.cpu ? &cpus : nullptr;
    setup.envp = envp ? envp->get() : nullptr;
    setup.exec_failed = exec_failed.c_str();

    const pid_t pid = ::fork();
    if (pid == 0)
        exec_child(argv.get(), setup);
    close_stdio();
    if (pid < 0)
        throw std::runtime_error(errno_text("fork"));
    pid_ = pid;
}

void RigsimdProcess::wait_for_endpoints()
{
    const std::string path = endpoints_path();
    // The daemon writes the file atomically (temporary file + rename): once it exists it is
    // complete.
    struct stat st {};
    const auto written = [&] { return ::lstat(path.c_str(), &st) == 0; };
    const bool appeared = wait_until([&] { return written() || !running(); }, options_.start_timeout);
    const auto its_log = [&] {
        return options_.output == LaunchOptions::Output::Files ? "; its log:\n" + log() : std::string();
    };
    if (!running())
        throw std::runtime_error("rigsimd (" + options_.binary + ") " + describe_wait_status(*wait_status_) +
                                 " before writing " + path + its_log());
    if (!appeared)
        throw std::runtime_error("rigsimd (" + options_.binary + ") did not write " + path + " within " +
                                 std::to_string(options_.start_timeout.count()) + " ms" + its_log());
    endpoints_json_ = read_whole_file(path).value_or("");
}

std::string RigsimdProcess::log() const
{
    if (options_.output != LaunchOptions::Output::Files)
        return "<no log>";
    return read_whole_file(options_.dir + "/rigsimd.log").value_or("<no log>");
}

bool RigsimdProcess::reap_nohang()
{
    if (wait_status_)
        return true;
    int status = 0;
    pid_t r = ::waitpid(pid_, &status, WNOHANG);
    if (r == pid_) {
        wait_status_ = status;
        return true;
    }
    if (r < 0 && errno == ECHILD) {
        wait_status_ = -1;
        return true;
    }
    return false;
}

bool RigsimdProcess::running()
{
    return pid_ > 0 && !reap_nohang();
}

std::optional<int> RigsimdProcess::stop(int signal, Millis timeout)
{
    if (running())
        ::kill(pid_, signal);
    if (!wait_until([this] { return pid_ <= 0 || reap_nohang(); }, timeout))
        return std::nullopt;
    return wait_status_;
}

void RigsimdProcess::kill()
{
    if (!running())
        return;
    ::kill(pid_, SIGKILL);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    wait_status_ = status;
}

} // namespace rigsim::launch
