#pragma once
// What the fuzz targets share (docs/reliability.md): a rig as the daemon builds it, without
// endpoints, on a stepped clock; and the byte stream format of the session targets.
//
// A session target's input is a header line, then a stream:
//   <rig JSON on one line>\n   the rig (docs/config.md), read by the rig loader; an empty line
//                              is the target's default rig. A rig the loader refuses ends the
//                              input (the loader has a target of its own).
//   bytes                      client bytes to the current session, in one receive() per run
//   FF FF                      one 0xFF byte in the run
//   FF Fn (n = 0..E)           the current session becomes session n (modulo their number):
//                              session d is device d's (rig order); the last is a second
//                              connection to device 0
//   FF hi lo (hi < F0)         the clock advances (hi << 8 | lo) ms (at most a budget of
//                              kMaxTicks ticks in all, so that no input runs for long)
// tests/fuzz/make_corpus.py writes the golden transcripts in this format.
//
// Every input builds its rig afresh (clock, world, devices, store, links), so nothing but the
// process's read-only tables (the shipped stages, the message table) outlives an input.

#include "emulator/core/control_surface.hpp"
#include "emulator/core/device.hpp"
#include "emulator/core/event_bus.hpp"
#include "emulator/core/family_registry.hpp"
#include "emulator/core/rig_config.hpp"
#include "emulator/core/state_store.hpp"
#include "emulator/daemon/link.hpp"
#include "emulator/daemon/rig_families.hpp"
#include "emulator/daemon/rig_kinematics.hpp"
#include "models/clock.hpp"
#include "models/world.hpp"

#include <spdlog/logger.h>
#include <spdlog/sinks/null_sink.h>
#include <spdlog/spdlog.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rigsim::fuzz {

/// Clock ticks one input may advance in all (300 s at the usual 1 kHz).
inline constexpr Ticks kMaxTicks = 300'000;
/// Devices one input's rig may have: more only cost time.
inline constexpr std::size_t kMaxDevices = 4;

/// Once per process: the default logger writes nowhere (the loaders and the state store log
/// through it), so that a run's output is libFuzzer's alone.
inline void quiet_logging()
{
    static const bool done = [] {
        spdlog::set_default_logger(
            std::make_shared<spdlog::logger>("fuzz", std::make_shared<spdlog::sinks::null_sink_mt>()));
        return true;
    }();
    (void)done;
}

/// A logger that formats as the daemon's does (level info) and writes nowhere.
inline std::shared_ptr<spdlog::logger> null_logger(const std::string& name)
{
    return std::make_shared<spdlog::logger>(name, std::make_shared<spdlog::sinks::null_sink_st>());
}

/// A rig as emulator/daemon/rig.cpp builds one, without its endpoints: every device behind its
/// link, the world linked, the devices powered up in phases, the frames built, the clock keeping
/// its schedule. Throws ConfigError as the rig does (a channel a frame's joint cannot use).
class FuzzRig {
public:
    explicit FuzzRig(const RigConfig& config, StateStore* store = nullptr)
        : config_(config), clock_(config.tick_hz), world_(clock_), store_(store ? store : &own_store_)
    {
        for (const auto& dc : config.devices) {
            const auto* family = rig_families().find(dc.protocol);
            if (!family)
                throw ConfigError("device \"" + dc.name + "\": unknown protocol \"" + dc.protocol + "\"");
            auto entry = std::make_unique<Entry>();
            entry->device = family->make(dc, DeviceContext{world_, null_logger(dc.name), *store_, &events_});
            entry->link = std::make_unique<Link>(*entry->device, clock_);
            entries_.push_back(std::move(entry));
        }
        world_.link_all();
        power_up_in_phases(entries_, [](auto& e) -> Device& { return *e->device; });
        if (config.kinematics) {
            auto built = build_kinematics(*config.kinematics, [this](std::string_view name) -> ControlSurface* {
                for (std::size_t i = 0; i < config_.devices.size(); ++i)
                    if (config_.devices[i].name == name)
                        return entries_[i]->device->control();
                return nullptr;
            }, world_);
            watch_collisions(world_, built, *config.kinematics, events_);
            kinematics_ = std::move(built.kinematics);
            bindings_ = std::move(built.bindings);
        }
        clock_.changed_all();
        clock_.keep_schedule();
    }
    ~FuzzRig()
    {
        sessions_.clear();   // before the links and devices they talk to
    }
    FuzzRig(const FuzzRig&) = delete;
    FuzzRig& operator=(const FuzzRig&) = delete;

    /// One session per device (through its link), then a second one on device 0; what each
    /// sends is counted, not kept.
    void open_sessions()
    {
        for (auto& e : entries_)
            sessions_.push_back(e->link->open_session([this](std::string_view b) { sent_ += b.size(); }, "fuzz"));
        if (!entries_.empty())
            sessions_.push_back(
                entries_[0]->link->open_session([this](std::string_view b) { sent_ += b.size(); }, "fuzz2"));
    }

    /// Replay the stream after the header (see the top of this file).
    void play(std::string_view stream)
    {
        if (sessions_.empty())
            return;
        std::size_t current = 0;
        std::string run;
        auto flush = [&] {
            if (!run.empty() && sessions_[current])
                sessions_[current]->receive(run);
            run.clear();
        };
        for (std::size_t i = 0; i < stream.size(); ++i) {
            const auto byte = static_cast<unsigned char>(stream[i]);
            if (byte != 0xFF || i + 1 == stream.size()) {
                run.push_back(static_cast<char>(byte));
                continue;
            }
            const auto command = static_cast<unsigned char>(stream[++i]);
            if (command == 0xFF) {
                run.push_back('\xFF');
                continue;
            }
            flush();
            if (command >= 0xF0) {
                current = (command - 0xF0u) % sessions_.size();
                continue;
            }
            const unsigned lo = i + 1 < stream.size() ? static_cast<unsigned char>(stream[++i]) : 0;
            advance_ms((command << 8) | lo);
        }
        flush();
    }

    /// Advance the clock `ms` (within the input's budget of kMaxTicks).
    void advance_ms(std::int64_t ms)
    {
        const Ticks ticks = std::min<Ticks>(clock_.ticks_from_ms(ms), kMaxTicks - spent_);
        spent_ += ticks;
        clock_.advance(ticks);
    }

    Clock& clock() { return clock_; }
    models::World& world() { return world_; }
    EventBus& events() { return events_; }
    std::size_t size() const { return entries_.size(); }
    Device& device(std::size_t i) { return *entries_.at(i)->device; }
    Link& link(std::size_t i) { return *entries_.at(i)->link; }
    models::Kinematics* kinematics() { return kinematics_.get(); }
    const std::vector<JointBinding>& bindings() const { return bindings_; }
    std::uint64_t sent() const { return sent_; }

private:
    struct Entry {
        std::unique_ptr<Device> device;
        std::unique_ptr<Link> link;
    };

    const RigConfig& config_;
    Clock clock_;
    models::World world_;
    EventBus events_;
    StateStore own_store_;
    StateStore* store_;
    std::vector<std::unique_ptr<Entry>> entries_;
    std::unique_ptr<models::Kinematics> kinematics_;
    std::vector<JointBinding> bindings_;
    std::vector<std::unique_ptr<Session>> sessions_;
    Ticks spent_ = 0;
    std::uint64_t sent_ = 0;
};

/// The rig of a header line: `fallback` when the line is empty, else the line read by the rig
/// loader; nothing when the loader refuses it or the rig has over kMaxDevices devices.
inline std::optional<RigConfig> header_rig(std::string_view line, std::string_view fallback)
{
    try {
        auto rig = parse_rig_config(line.empty() ? fallback : line, "fuzz-rig.json");
        if (rig.devices.size() > kMaxDevices)
            return std::nullopt;
        return rig;
    } catch (const ConfigError&) {
        return std::nullopt;
    }
}

/// Splits an input at its first '\n': the header line and the stream after it (no '\n': all of
/// it is the stream, after an empty header).
inline std::pair<std::string_view, std::string_view> split_header(std::string_view input)
{
    const auto nl = input.find('\n');
    if (nl == std::string_view::npos)
        return {{}, input};
    return {input.substr(0, nl), input.substr(nl + 1)};
}

/// Play one session input on a fresh rig (the header's, or `fallback`). A rig that powers up
/// with an error its config should have caught (ConfigError from the frames) is no finding.
inline void run_session_input(std::string_view input, std::string_view fallback)
{
    quiet_logging();
    const auto [header, stream] = split_header(input);
    const auto config = header_rig(header, fallback);
    if (!config)
        return;
    std::unique_ptr<FuzzRig> rig;
    try {
        rig = std::make_unique<FuzzRig>(*config);
    } catch (const ConfigError&) {
        return;
    }
    rig->open_sessions();
    rig->play(stream);
}

} // namespace rigsim::fuzz
