#include "e2e_support.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#if !defined(RIGSIMD_PATH) || !defined(RIGSIM_E2E_DIR)
#error "RIGSIMD_PATH and RIGSIM_E2E_DIR are set by tests/e2e/CMakeLists.txt"
#endif

namespace rigsim::e2e {

namespace {

std::string errno_text(const std::string& what)
{
    return what + ": " + std::strerror(errno);
}

int remaining_ms(SteadyClock::time_point deadline)
{
    auto left = std::chrono::duration_cast<Millis>(deadline - SteadyClock::now()).count();
    return left < 0 ? 0 : static_cast<int>(std::min<long long>(left, 1000 * 1000));
}

void set_nonblocking(int fd)
{
    int flags = ::fcntl(fd, F_GETFL);
    if (flags < 0 || ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0)
        throw std::runtime_error(errno_text("fcntl(O_NONBLOCK)"));
}

std::vector<std::string> with_binary(const std::vector<std::string>& args)
{
    std::vector<std::string> all{RIGSIMD_PATH};
    all.insert(all.end(), args.begin(), args.end());
    return all;
}

} // namespace

double elapsed_ms(SteadyClock::time_point start)
{
    return std::chrono::duration<double, std::milli>(SteadyClock::now() - start).count();
}

// --- files ---------------------------------------------------------------------------

void write_file(const std::string& path, const std::string& text)
{
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f << text;
    if (!f)
        throw std::runtime_error("cannot write " + path);
}

std::optional<std::string> read_file(const std::string& path)
{
    std::ifstream f(path, std::ios::binary);
    if (!f)
        return std::nullopt;
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

bool path_exists(const std::string& path)
{
    struct stat st {};
    return ::lstat(path.c_str(), &st) == 0;
}

// --- endpoints file ------------------------------------------------------------------

std::optional<std::string> json_string_value(const std::string& text, const std::string& key)
{
    const std::string quoted = "\"" + key + "\"";
    auto skip_ws = [&](std::size_t i) {
        while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i])))
            ++i;
        return i;
    };
    for (std::size_t at = text.find(quoted); at != std::string::npos;
         at = text.find(quoted, at + 1)) {
        std::size_t i = skip_ws(at + quoted.size());
        if (i >= text.size() || text[i] != ':')
            continue; // the key text appeared as a value
        i = skip_ws(i + 1);
        if (i >= text.size() || text[i] != '"')
            return std::nullopt; // not a string value
        std::string value;
        for (++i; i < text.size(); ++i) {
            char c = text[i];
            if (c == '"')
                return value;
            if (c == '\\' && i + 1 < text.size()) {
                char e = text[++i];
                switch (e) {
                case 'n': value += '\n'; break;
                case 't': value += '\t'; break;
                default: value += e; break; // \" \\ \/
                }
                continue;
            }
            value += c;
        }
        return std::nullopt; // unterminated
    }
    return std::nullopt;
}

std::optional<Endpoint> find_endpoint(const std::string& json, const std::string& name)
{
    // Device entries are the innermost objects: a '{' whose matching '}' comes before any
    // other '{'.
    for (std::size_t open = json.find('{'); open != std::string::npos;
         open = json.find('{', open + 1)) {
        std::size_t close = json.find('}', open);
        if (close == std::string::npos)
            break;
        std::size_t nested = json.find('{', open + 1);
        if (nested != std::string::npos && nested < close)
            continue;
        std::string object = json.substr(open, close - open + 1);
        if (json_string_value(object, "name") != name)
            continue;
        Endpoint ep;
        ep.name = name;
        ep.tcp = json_string_value(object, "tcp").value_or("");
        ep.pty = json_string_value(object, "pty").value_or("");
        auto colon = ep.tcp.rfind(':');
        if (colon != std::string::npos) {
            ep.host = ep.tcp.substr(0, colon);
            if (ep.host.size() >= 2 && ep.host.front() == '[' && ep.host.back() == ']')
                ep.host = ep.host.substr(1, ep.host.size() - 2);
            try {
                long port = std::stol(ep.tcp.substr(colon + 1));
                if (port > 0 && port < 65536)
                    ep.port = static_cast<std::uint16_t>(port);
            } catch (const std::exception&) {
            }
        }
        return ep;
    }
    return std::nullopt;
}

// --- processes -----------------------------------------------------------------------

ProcessResult run_rigsimd(const std::vector<std::string>& args, Millis timeout)
{
    return launch::run_to_completion(with_binary(args), timeout);
}

// --- Daemon --------------------------------------------------------------------------

Daemon::Daemon() : Daemon(Options{}) {}

Daemon::Daemon(Options options) : Daemon(std::move(options), Limits{}) {}

Daemon::Daemon(Options options, Limits limits) : process_(launch_options(dir_, options, limits)) {}

launch::LaunchOptions Daemon::launch_options(const TempDir& dir, const Options& options, const Limits& limits)
{
    launch::LaunchOptions launch;
    launch.binary = RIGSIMD_PATH;
    launch.dir = dir.path();
    if (!options.config_json.empty()) {
        write_file(dir.file("rig.json"), options.config_json);
        launch.args = {"--config", dir.file("rig.json")};
    } else if (!options.config_path.empty()) {
        launch.args = {"--config", options.config_path};
    }
    launch.args.insert(launch.args.end(), options.extra_args.begin(), options.extra_args.end());
    launch.start_timeout = kStartTimeout;
    launch.stop_timeout = kShutdownTimeout;
    launch.max_open_files = limits.max_open_files;
    // A sanitized daemon's run-time checks need descriptors of their own: UBSan's vptr check
    // tells whether a vtable is readable by writing it to a pipe, which fails with EMFILE once
    // a test has used up the daemon's descriptors, and is then reported as "invalid vptr ...
    // memory cannot be printed" (a false report). Asio's timer queue is checked at every timer
    // armed (the accept back-off's among them), so a daemon with a descriptor limit runs with
    // that check ("vptr") suppressed in Asio's headers, matched by the file name the check
    // carries (no symbolizer, which would need descriptors too). A plain daemon ignores it.
    if (limits.max_open_files) {
        const std::string suppressions = dir.file("ubsan.supp");
        write_file(suppressions, "vptr:boost/asio/\n");
        const char* ubsan = std::getenv("UBSAN_OPTIONS");
        launch.environment = {std::string("UBSAN_OPTIONS=") + (ubsan && *ubsan ? std::string(ubsan) + ":" : "")
                              + "suppressions=" + suppressions};
    }
    return launch;
}

Endpoint Daemon::endpoint(const std::string& name) const
{
    auto ep = find_endpoint(endpoints_json(), name);
    if (!ep)
        throw std::runtime_error("no device \"" + name + "\" in endpoints file: " +
                                 endpoints_json());
    return *ep;
}

// --- clients -------------------------------------------------------------------------

LineClient::~LineClient()
{
    close();
}

void LineClient::close()
{
    if (fd_ >= 0)
        ::close(fd_);
    fd_ = -1;
    buffer_.clear();
}

void LineClient::send(const std::string& bytes, Millis timeout)
{
    if (fd_ < 0)
        throw std::runtime_error("send on a closed client");
    const auto deadline = SteadyClock::now() + timeout;
    std::size_t sent = 0;
    while (sent < bytes.size()) {
        ssize_t n = is_socket_
            ? ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL)
            : ::write(fd_, bytes.data() + sent, bytes.size() - sent);
        if (n > 0) {
            sent += static_cast<std::size_t>(n);
            continue;
        }
        if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)
            throw std::runtime_error(errno_text("send after " + std::to_string(sent) + " of " +
                                                std::to_string(bytes.size()) + " bytes"));
        int left = remaining_ms(deadline);
        pollfd p{fd_, POLLOUT, 0};
        if (left == 0 || (::poll(&p, 1, left) == 0 && remaining_ms(deadline) == 0))
            throw std::runtime_error("send timed out after " + std::to_string(sent) + " of " +
                                     std::to_string(bytes.size()) + " bytes");
    }
}

int LineClient::fill(Millis timeout)
{
    if (fd_ < 0)
        return -1;
    pollfd p{fd_, POLLIN, 0};
    int ready = ::poll(&p, 1, static_cast<int>(timeout.count()));
    if (ready <= 0)
        return 0;
    char buf[65536];
    ssize_t n = ::read(fd_, buf, sizeof buf);
    if (n > 0) {
        buffer_.append(buf, static_cast<std::size_t>(n));
        return static_cast<int>(n);
    }
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR))
        return 0;
    return -1; // end of stream, reset, or EIO on a pty whose master is gone
}

std::optional<std::string> LineClient::read_line(Millis timeout)
{
    const auto deadline = SteadyClock::now() + timeout;
    for (;;) {
        auto nl = buffer_.find('\n');
        if (nl != std::string::npos) {
            std::string line = buffer_.substr(0, nl + 1);
            buffer_.erase(0, nl + 1);
            return line;
        }
        int left = remaining_ms(deadline);
        if (left == 0)
            return std::nullopt;
        if (fill(Millis{left}) < 0)
            return std::nullopt;
    }
}

std::string LineClient::request(const std::string& cmd, Millis timeout)
{
    send(cmd);
    auto answer = read_line(timeout);
    if (!answer)
        return "<no answer to " + cmd.substr(0, 40) + " within " +
               std::to_string(timeout.count()) + " ms; pending: " + buffer_.substr(0, 80) + ">";
    return *answer;
}

bool LineClient::wait_for_eof(Millis timeout)
{
    const auto deadline = SteadyClock::now() + timeout;
    for (;;) {
        int left = remaining_ms(deadline);
        if (left == 0)
            return false;
        if (fill(Millis{left}) < 0)
            return true;
        buffer_.clear();
    }
}

TcpClient::TcpClient(const Endpoint& endpoint)
{
    is_socket_ = true;
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_flags = AI_NUMERICSERV;
    addrinfo* found = nullptr;
    const std::string port = std::to_string(endpoint.port);
    if (int rc = ::getaddrinfo(endpoint.host.c_str(), port.c_str(), &hints, &found); rc != 0)
        throw std::runtime_error("getaddrinfo " + endpoint.tcp + ": " + ::gai_strerror(rc));
    std::string last_error = "no address";
    for (addrinfo* a = found; a; a = a->ai_next) {
        int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
        if (fd < 0)
            continue;
        if (::connect(fd, a->ai_addr, a->ai_addrlen) == 0) {
            fd_ = fd;
            break;
        }
        last_error = std::strerror(errno);
        ::close(fd);
    }
    ::freeaddrinfo(found);
    if (fd_ < 0)
        throw std::runtime_error("connect " + endpoint.tcp + ": " + last_error);
    int one = 1;
    ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    set_nonblocking(fd_);
}

void TcpClient::abort()
{
    if (fd_ < 0)
        return;
    linger l{1, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_LINGER, &l, sizeof l);
    close();
}

PtyClient::PtyClient(const std::string& path, speed_t baud)
{
    fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0)
        throw std::runtime_error(errno_text("open " + path));
    set_baud(baud);
}

void PtyClient::set_baud(speed_t baud)
{
    termios t{};
    if (::tcgetattr(fd_, &t) < 0)
        throw std::runtime_error(errno_text("tcgetattr"));
    ::cfmakeraw(&t);
    if (::cfsetispeed(&t, baud) < 0 || ::cfsetospeed(&t, baud) < 0)
        throw std::runtime_error(errno_text("cfsetspeed"));
    if (::tcsetattr(fd_, TCSANOW, &t) < 0)
        throw std::runtime_error(errno_text("tcsetattr"));
}

speed_t PtyClient::baud() const
{
    termios t{};
    if (::tcgetattr(fd_, &t) < 0)
        return 0;
    return ::cfgetospeed(&t);
}

bool poll_status_until(LineClient& client, int channel, int state, Millis timeout,
                       std::vector<std::string>* seen)
{
    const std::string command = ":GS" + std::to_string(channel) + "\n";
    const std::string wanted = ":S" + std::to_string(channel) + "," + std::to_string(state) + "\n";
    return wait_until(
        [&] {
            std::string answer = client.request(command);
            if (seen)
                seen->push_back(answer);
            return answer == wanted;
        },
        timeout);
}

std::vector<std::string> open_fds(pid_t pid)
{
    std::vector<std::string> targets;
    std::error_code ec;
    const std::string dir = "/proc/" + std::to_string(pid) + "/fd";
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
        std::error_code link_ec;
        const auto target = std::filesystem::read_symlink(entry.path(), link_ec);
        if (!link_ec)
            targets.push_back(target.string());
    }
    return targets;
}

std::string fixture(const std::string& name)
{
    return std::string(RIGSIM_E2E_DIR) + "/" + name;
}

std::size_t count_of(const std::string& text, const std::string& needle)
{
    std::size_t n = 0;
    for (auto at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1))
        ++n;
    return n;
}

} // namespace rigsim::e2e
