#pragma once
// Device-test harness for the MCS2: session + framer + controller on a stepped clock, no sockets:
// h.send(":MOVE0 1000000000") -> the answer line; h.advance_ms(500); h.errors() drains the queue.

#include "emulator/mcs2/config.hpp"
#include "emulator/mcs2/device.hpp"
#include "models/clock.hpp"
#include "models/world.hpp"

#include <spdlog/logger.h>
#include <spdlog/sinks/null_sink.h>

#include <memory>
#include <string>
#include <vector>

namespace rigsim::test {

/// Three linear positioners of type 300 (S sensor, single mark at 0), ±10.5 mm, 10 mm/s top speed,
/// steps of exactly 1 µm (no jitter).
inline DeviceConfig mcs2_device_config(std::size_t channels = 3)
{
    DeviceConfig c;
    c.name = "mcs2-test";
    c.protocol = "mcs2";
    c.model = "MCS2";
    c.firmware = "current";
    auto& section = mcs2::config_of(c);
    section.channels.resize(channels);
    for (auto& ch : section.channels)
        ch.step_jitter_percent = 0;
    return c;
}

class Mcs2Harness {
public:
    explicit Mcs2Harness(const DeviceConfig& config = mcs2_device_config())
        : clock_(1000), world_(clock_),
          device_(config, world_, std::make_shared<spdlog::logger>("mcs2-test", std::make_shared<spdlog::sinks::null_sink_st>())),
          session_(open(out_, "test"))
    {
    }

    /// One message (CR LF added); what the device sent back, as bytes.
    std::string send(const std::string& message) { return send_to(*session_, out_, message); }
    std::string send_to(Session& s, std::string& sink, const std::string& message)
    {
        s.receive(message + "\r\n");
        std::string result = std::move(sink);
        sink.clear();
        return result;
    }
    /// The answer of a query without its CR LF ("" if none came).
    std::string ask(const std::string& query)
    {
        auto a = send(query);
        if (a.size() >= 2 && a.compare(a.size() - 2, 2, "\r\n") == 0)
            a.resize(a.size() - 2);
        return a;
    }
    std::int64_t number(const std::string& query) { return std::stoll(ask(query)); }
    /// Every queued error of the harness's own connection, drained: "34,\"Invalid channel index\"".
    std::vector<std::string> errors()
    {
        std::vector<std::string> out;
        for (auto n = number(":SYST:ERR:COUN?"); n > 0; --n)
            out.push_back(ask(":SYST:ERR?"));
        return out;
    }
    std::unique_ptr<Session> open(std::string& sink, std::string peer = "test2")
    {
        Connection conn;
        conn.hangup = [this](Hangup) { ++hangups_; };
        return device_.open_connection([&sink](std::string_view b) { sink.append(b); }, std::move(conn), std::move(peer));
    }

    void advance_ms(std::int64_t ms) { clock_.advance_ms(ms); }
    Clock& clock() { return clock_; }
    models::World& world() { return world_; }
    mcs2::Mcs2Device& device() { return device_; }
    int hangups() const { return hangups_; }

private:
    Clock clock_;
    models::World world_;
    mcs2::Mcs2Device device_;
    std::string out_;
    int hangups_ = 0;
    std::unique_ptr<Session> session_;
};

} // namespace rigsim::test
