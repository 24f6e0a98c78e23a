#include "daemon_process.hpp"

#include <nlohmann/json.hpp>

#include <sys/wait.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace rigsim::bench {

namespace {

launch::LaunchOptions launch_options(const launch::TempDir& dir, const std::string& path, std::optional<int> cpu,
                                     std::chrono::milliseconds timeout, std::vector<std::string> extra_args)
{
    launch::LaunchOptions launch;
    launch.binary = path;
    launch.dir = dir.path();
    launch.args = {"--log-level", "warn"};
    launch.args.insert(launch.args.end(), extra_args.begin(), extra_args.end());
    // The daemon lists its endpoints on stdout: keep the benchmark's stdout for figures.
    launch.output = launch::LaunchOptions::Output::Stderr;
    launch.start_timeout = timeout;
    // Stopped by terminate(), which checks its exit; a benchmark that fails kills it at once.
    launch.stop_timeout = std::chrono::milliseconds{0};
    // The daemon dies with the benchmark, however the benchmark ends.
    launch.parent_death_signal = SIGTERM;
    launch.cpu = cpu;
    return launch;
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
    : dir_("rigsim_bench"), process_(launch_options(dir_, path, cpu, timeout, std::move(extra_args)))
{
    try {
        devices_ = parse_endpoints(process_.endpoints_json());
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(process_.endpoints_path() + ": " + e.what() + "\n" + process_.endpoints_json());
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

void DaemonProcess::terminate(std::chrono::milliseconds timeout)
{
    if (process_.wait_status())
        return;
    const pid_t pid = process_.pid();
    const auto status = process_.stop(SIGTERM, timeout);
    if (!status) {
        process_.kill();
        throw std::runtime_error("daemon (pid " + std::to_string(pid) + ") still running " +
                                 std::to_string(timeout.count()) + " ms after SIGTERM; killed");
    }
    if (!WIFEXITED(*status) || WEXITSTATUS(*status) != 0)
        throw std::runtime_error("daemon ended (" + launch::describe_wait_status(*status) + ") after SIGTERM");
}

}  // namespace rigsim::bench
