#pragma once
// Device-test harness for APT controllers: framer + handler + modules on a stepped clock,
// bytes as hex. No sockets, no sleeps:
//   AptHarness h;  h.send("43 04 01 00 50 01");  h.advance_ms(2000);  h.take();
// Several devices share the world and clock: h.add_device(config) == 1; h.send("...", 1).
// As the rig does, the harness links the world and powers the devices up (saved settings
// restored) once they all exist: at start(), which the first send, take, advance, device() or
// world() call makes; a harness built on a state store starts at once (tests read its verdicts
// before they send), so a multi-device one on a store takes all its devices in its constructor.

#include "emulator/apt/apt_device.hpp"
#include "emulator/apt/messages.hpp"
#include "emulator/apt/wire.hpp"
#include "models/clock.hpp"
#include "models/world.hpp"
#include "emulator/apt/config.hpp"
#include "emulator/apt/shipped_stages.hpp"
#include "emulator/core/config_reader.hpp"
#include "emulator/core/state_store.hpp"
#include "tests/support/hex.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <spdlog/logger.h>
#include <spdlog/sinks/null_sink.h>

#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace rigsim::test {

using namespace rigsim::apt;


/// The shipped stage `name`; FAILs the test naming it when there is none.
inline const StageModel& shipped_stage(const std::string& name)
{
    const auto* stage = find_stage(name);
    if (!stage)
        FAIL("no shipped stage named \"" << name << "\"");
    return *stage;
}

/// A single-unit controller (T-Cube/K-Cube) driving the shipped stage `stage`.
inline DeviceConfig apt_cube(const std::string& model, const std::string& stage)
{
    DeviceConfig c;
    c.name = "cube";
    c.protocol = "apt";
    c.model = model;
    config_of(c).stage = shipped_stage(stage);
    return c;
}

/// The device of rig device object `device` (its "name", "model", "firmware" and "apt") as the
/// rig loader reads it; the loader's ConfigError names "/devices/0" pointers.
inline DeviceConfig loaded_apt_device(const nlohmann::json& device)
{
    DeviceConfig c;
    c.name = device.at("name").get<std::string>();
    c.protocol = "apt";
    c.model = device.at("model").get<std::string>();
    if (device.contains("firmware"))
        c.firmware = device.at("firmware").get<std::string>();
    load_device_section(ConfigReader("rig.json"), device, "/devices/0", c);
    return c;
}

/// The rig loader's message for rig device object `device`, or "" when it takes it.
inline std::string apt_load_error(const nlohmann::json& device)
{
    try {
        loaded_apt_device(device);
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

/// A card-slot controller (BBD203, BSC203) with these shipped stages in bays 0, 1, ...
inline DeviceConfig apt_rack(const std::string& model, std::vector<std::string> bays)
{
    DeviceConfig c;
    c.name = "rack";
    c.protocol = "apt";
    c.model = model;
    for (const auto& stage : bays)
        config_of(c).bays.push_back(shipped_stage(stage));
    return c;
}

inline DeviceConfig tdc001()
{
    return apt_cube("TDC001", "MTS50-Z8");
}

/// Devices on one world and one stepped clock, each with one session; bytes as hex
/// ("05 00 00 00 50 01"). Device 0 is the one the harness is built with; add_device() adds
/// more (a strain gauge reader beside its piezo driver).
class AptHarness {
public:
    explicit AptHarness(const DeviceConfig& config = tdc001(), StateStore* store = nullptr, EventBus* events = nullptr)
    {
        add_device(config, store, events);
        if (store)
            start();
    }
    /// Devices 0, 1, ... on one state store, started (linked, powered up) once all exist.
    AptHarness(const std::vector<DeviceConfig>& configs, StateStore* store)
    {
        for (const auto& config : configs)
            add_device(config, store);
        start();
    }
    /// Another device on the same world and clock; returns its index (1, 2, ...).
    std::size_t add_device(const DeviceConfig& config, StateStore* store = nullptr, EventBus* events = nullptr)
    {
        auto unit = std::make_unique<Unit>();
        unit->device = std::make_unique<AptDevice>(
            config, world_, std::make_shared<spdlog::logger>("apt", std::make_shared<spdlog::sinks::null_sink_st>()),
            store, events);
        auto* out = &unit->out;
        unit->session = unit->device->open_session([out](std::string_view b) { out->append(b); }, "test");
        units_.push_back(std::move(unit));
        if (started_)
            start_last();
        return units_.size() - 1;
    }
    /// Link the world and power every device up in the rig's order (power_up_in_phases), as the
    /// rig does once its devices exist (a gauge finds its actuator wherever it was added); the
    /// other calls do it first.
    void start()
    {
        if (started_)
            return;
        started_ = true;
        world_.link_all();
        power_up_in_phases(units_, [](auto& unit) -> Device& { return *unit->device; });
        clock_.changed_all();   // powered up: as the rig does
        if (keep_schedule_)
            clock_.keep_schedule();
    }
    /// Run the clock as the daemon's rig does (models/clock.hpp, "The schedule"): from start() on
    /// it keeps the devices' next changes between their announcements. Only for tests that reach
    /// the devices through their sessions and the clock alone (the control API announces its
    /// requests; a test calling a device's ControlSurface directly does not).
    void keep_schedule()
    {
        keep_schedule_ = true;
        if (started_)
            clock_.keep_schedule();
    }
    /// Hex in to device `d`; hex of everything device `d` sent since the last call out.
    std::string send(const std::string& hex_in, std::size_t d = 0)
    {
        start();
        units_.at(d)->session->receive(bytes(hex_in));
        return take(d);
    }
    /// Hex of everything device `d` sent since the last call.
    std::string take(std::size_t d = 0)
    {
        start();
        auto r = hex(units_.at(d)->out);
        units_[d]->out.clear();
        return r;
    }
    void advance_ms(std::int64_t ms)
    {
        start();
        clock_.advance_ms(ms);
    }
    AptDevice& device(std::size_t d = 0)
    {
        start();
        return *units_.at(d)->device;
    }
    std::size_t device_count() const { return units_.size(); }
    models::World& world()
    {
        start();
        return world_;
    }

private:
    /// A device, what it sent, and its session (destroyed before the device).
    struct Unit {
        std::unique_ptr<AptDevice> device;
        std::string out;
        std::unique_ptr<Session> session;
    };
    Clock clock_;
    models::World world_{clock_};
    std::vector<std::unique_ptr<Unit>> units_;
    bool started_ = false;
    bool keep_schedule_ = false;

    /// A device added after start(): linked and powered up at once.
    void start_last()
    {
        world_.link_all();
        units_.back()->device->power_up();
        clock_.changed_all();
    }
};

/// `v` as the hex of its 4 little-endian bytes.
inline std::string le32(std::int32_t v)
{
    std::string d;
    put_i32(d, v);
    return hex(d);
}

/// MOVE_STOPPED / MOVE_COMPLETED / status update: the status dword (data offset 10).
inline std::uint32_t status_of(const std::string& frame_hex)
{
    return get_u32(bytes(frame_hex), 16);
}

inline std::int32_t position_of(const std::string& reply_hex)
{
    const auto b = bytes(reply_hex);
    REQUIRE(b.size() >= 12);
    return get_i32(b, 8);
}

/// The clock ms from now until the unit sends something (a MOVE_COMPLETED), at most `limit`
/// (-1: nothing came).
inline int ms_until_reply(AptHarness& h, std::string& reply, int limit)
{
    for (int ms = 1; ms <= limit; ++ms) {
        h.advance_ms(1);
        reply = h.take();
        if (!reply.empty())
            return ms;
    }
    return -1;
}

/// The frames of a reply stream (hex in, hex per frame out), split by their headers.
inline std::vector<std::string> frames(const std::string& reply_hex)
{
    const auto b = bytes(reply_hex);
    std::vector<std::string> out;
    std::size_t i = 0;
    while (i + 6 <= b.size()) {
        const bool data = (static_cast<unsigned char>(b[i + 4]) & 0x80) != 0;
        const std::size_t n = 6 + (data ? get_u16(b, i + 2) : 0);
        out.push_back(hex(b.substr(i, n)));
        i += n;
    }
    REQUIRE(i == b.size());
    return out;
}

} // namespace rigsim::test
