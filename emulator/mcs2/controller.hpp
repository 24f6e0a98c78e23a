#pragma once
// An MCS2 as the ASCII interface sees it (MCS2 Programmer's Guide 1.0.6, chapter 6): its channels
// and modules, the device properties, and the execution of one message: each command found in the
// command tree, checked (access, parameters, index, range) and executed; queries answered in one
// line, `;`-separated (6.2.4); every failure a code in the connection's error queue (6.3.8).
// Command groups (6.4) are the device's: one open at a time, held by the connection that opened
// it. No I/O: a session hands in a message and writes back the answer.

#include "emulator/mcs2/channel.hpp"
#include "emulator/mcs2/command_tree.hpp"
#include "emulator/mcs2/config.hpp"
#include "emulator/mcs2/errors.hpp"
#include "emulator/mcs2/message.hpp"
#include "emulator/mcs2/properties.hpp"
#include "models/clock.hpp"
#include "models/world.hpp"

#include <cstdint>
#include <array>
#include <deque>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace rigsim::mcs2 {

/// One connection's error queue (6.3.8): first in, first out. The guide gives no depth; rigsim's
/// holds kDepth, and an error that finds it full replaces the newest with -350 "Queue overflow"
/// (SCPI's rule).
class ErrorQueue {
public:
    static constexpr std::size_t kDepth = 32;
    struct Entry {
        std::int32_t code;
        std::string text;
    };
    void push(std::int32_t code, std::string_view text);
    std::size_t count() const { return entries_.size(); }
    /// The next entry, removed; `0,"No Error"` when empty.
    Entry next();
    void clear() { entries_.clear(); }

private:
    std::deque<Entry> entries_;
};

/// What one connection keeps between messages.
struct SessionState {
    ErrorQueue errors;
    std::int64_t ese = 0;
    std::int64_t sre = 0;
};

class Controller {
public:
    /// Bodies join `world` as "<name>/<channel index>".
    Controller(const Config& config, models::World& world, const std::string& name);
    ~Controller();
    Controller(const Controller&) = delete;
    Controller& operator=(const Controller&) = delete;

    /// What executing a message did.
    struct Result {
        bool answered = false;   ///< a query answered: `answer` is the line (without CR LF)
        std::string answer;
        std::size_t errors = 0;  ///< errors it queued
        bool reset = false;      ///< *RST: the device reset; the connection is to be closed
    };
    /// Execute one message (a line without its CR LF) for `session`.
    Result execute(std::string_view message, SessionState& session);
    /// A connection went: its command group, if open, is aborted, and the movements it started
    /// stop ("all movements that were sent over the disconnected interface are stopped as a safety
    /// measure", User Manual 2).
    void forget(const SessionState& session);

    std::size_t channel_count() const { return channels_.size(); }
    std::size_t module_count() const { return (channels_.size() + 2) / 3; }
    Channel& channel(std::size_t i) { return *channels_[i]; }
    const Channel& channel(std::size_t i) const { return *channels_[i]; }
    const Config& config() const { return config_; }
    std::uint32_t device_state() const;
    std::uint32_t module_state(std::size_t module) const;
    std::uint32_t channel_state(std::size_t i) const;
    const std::string& device_name() const { return device_name_; }

    /// Power-up: every channel's volatile state, the device's volatile properties.
    void power_up();
    /// Non-volatile settings back to the rig's, then power_up().
    void restore_defaults();

    /// The device's trigger input line (DIN-1, 2.17), driven from outside (the control API): an
    /// edge of its Input Trigger Condition acts by its Input Trigger Mode. Only with an I/O module.
    void set_trigger_input(bool high);
    bool trigger_input() const { return input_high_; }
    /// Locked by an emergency stop (device state bit 1, 2.17.2).
    bool locked() const { return locked_; }

    Ticks next_change(Ticks now) const;
    void tick(Ticks now);

private:
    struct Grouped {
        const Property* property;
        std::vector<std::int64_t> indices;
        Command command;
    };
    /// Execute one resolved command; a query's answer is appended to `answers`.
    void run(const Property& p, const std::vector<std::int64_t>& indices, const Command& c, SessionState& s,
             std::vector<std::string>& answers, Result& r);
    /// The value of a readable property, or an error.
    std::optional<Error> read(const Property& p, const std::vector<std::int64_t>& indices, std::string& out);
    std::optional<Error> write(const Property& p, const std::vector<std::int64_t>& indices, const Command& c,
                               SessionState& s, Result& r);
    std::optional<Error> write_channel(const Property& p, Channel& ch, std::int64_t v);
    std::optional<Error> read_channel(const Property& p, std::size_t index, std::string& out);
    /// The channel's settings field a stored property lives in, or nullptr.
    static std::int64_t* setting(Channel& ch, Id id);
    std::int64_t& stored_channel(std::size_t channel, Id id);
    void broadcast_stop(std::size_t from);
    void close_group(SessionState& s);
    /// Run the group's commands now; their errors and values go to `s`.
    void run_group(SessionState& s);
    /// Input trigger mode EMERGENCY_STOP (2.17.2): every channel stopped hard, stream and group
    /// aborted, and with Emergency Stop Mode 1 or 2 movements locked until released.
    void emergency_stop();
    void set_locked(bool locked);
    // Trajectory streaming (2.15, 6.5).
    std::optional<Error> stream_open(std::int64_t mode, const SessionState& s);
    std::optional<Error> stream_frame(const Command& c);
    std::optional<Error> stream_close();
    void stream_abort(Error e);
    void stream_start(Ticks now);
    /// The tick frame `k` of the running stream is due at.
    Ticks frame_tick(std::int64_t k) const;
    void stream_tick(Ticks now);

    Config config_;
    const Clock& clock_;
    std::vector<std::unique_ptr<Channel>> channels_;
    std::vector<std::vector<std::int64_t>> channel_store_;   ///< per channel, per table row (stored rows)
    std::vector<bool> module_power_;
    std::vector<const SessionState*> started_by_;   ///< per channel: who started its movement
    std::string device_name_;
    std::int64_t estop_mode_ = 0;
    std::vector<std::int64_t> device_store_;                 ///< per table row (stored device rows)
    // The command group (6.4): open by `group_owner_`, its commands, the values its queries read.
    const SessionState* group_owner_ = nullptr;
    std::vector<Grouped> group_;
    bool group_finished_ = false;
    std::vector<std::string> group_values_;
    bool group_external_ = false;            ///< opened with trigger mode 1: CLOSe arms it
    SessionState* group_armed_ = nullptr;    ///< closed, waiting for the input trigger, for this session
    // The I/O module (config io_module): the trigger input and each module's I/O values.
    std::int64_t trigger_mode_ = 0;
    std::int64_t trigger_condition_ = 0;
    bool input_high_ = false;
    bool locked_ = false;
    struct IoModule {
        std::int64_t options = 0, voltage = 0, ain_range = 0, dout = 0;
        std::array<std::int64_t, 2> aout{};
    };
    std::vector<IoModule> io_;
    /// The trajectory stream: open, its channels (from the first frame), the frames not yet run.
    struct Stream {
        bool open = false;
        bool closed = false;
        bool running = false;
        const SessionState* owner = nullptr;
        std::vector<std::size_t> channels;
        std::deque<std::vector<std::int64_t>> frames;   ///< positions, in channel order
        std::int64_t rate = 1000;     ///< frames per second (Stream Base Rate at open)
        bool interpolate = true;      ///< Stream Options bit 0 clear
        std::int64_t mode = 0;        ///< 0 direct, 1 external once, 2 external sync
        bool ready = false;           ///< an external stream waiting for its trigger
        Ticks start = 0;
        std::int64_t next = 0;        ///< the index of the next frame to run
        std::size_t total = 0;        ///< frames received
    };
    Stream stream_;
};

/// The stream buffer, in (channel, position) tuples (2.15.1).
inline constexpr std::size_t kStreamBuffer = 1024;

/// The most commands a command group holds (the guide: "limited in size", no figure).
inline constexpr std::size_t kMaxGroupCommands = 256;
/// The longest answer line one message may have; a query past it queues 13 BUFFER_OVERFLOW.
inline constexpr std::size_t kMaxAnswer = 65536;

} // namespace rigsim::mcs2
