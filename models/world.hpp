#pragma once
// The physical world of a rig: every moving part (a motor axis, a stick-slip positioner, a
// piezo) under a stable key ("<device>/<channel>"), advanced on the one clock.
//
// A body's state is a function of clock time: a move is planned as an exact profile and a
// read samples it at "now". The world therefore wakes a body only when an event of its is
// due (a move ends, an end stop or switch is met, a hold expires), never once per tick, so
// a moving body costs nothing between its events. Protocol devices hold a reference to
// their body and translate (units, counters, status bits, error codes); they never
// integrate motion themselves.

#include "models/body.hpp"
#include "models/clock.hpp"

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <queue>
#include <string>
#include <string_view>
#include <vector>

namespace rigsim::models {

/// Every body of a rig, on one clock. The world is one Tickable of the clock: the clock
/// asks it for its earliest due event and it wakes only the bodies that are due.
class World : public Tickable {
public:
    explicit World(Clock& clock);
    ~World() override;
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    Clock& clock() { return clock_; }
    const Clock& clock() const { return clock_; }
    Ticks now() const { return clock_.now(); }

    /// Adds a body under `key` (std::invalid_argument if the key is taken or empty).
    template <class T, class... Args>
    T& emplace(const std::string& key, Args&&... args)
    {
        auto body = std::make_unique<T>(std::forward<Args>(args)...);
        T& ref = *body;
        insert(key, std::move(body));
        return ref;
    }
    /// The body under `key`, or nullptr.
    Body* find(std::string_view key) const;
    /// The body under `key` if it is a T, or nullptr.
    template <class T>
    T* find_as(std::string_view key) const { return dynamic_cast<T*>(find(key)); }
    /// Every key, sorted.
    std::vector<std::string> keys() const;
    std::size_t size() const { return bodies_.size(); }
    /// Body::link() of every body, in key order (the rig calls it once all devices exist).
    void link_all();

    /// Re-read `body`'s next_event() (Body::reschedule() calls this), then tell its watchers.
    void reschedule(Body& body);
    /// From now on `watcher`'s on_watched() hears of every reschedule of `watched` (a body of
    /// this world other than the watcher; std::invalid_argument otherwise).
    void watch(Body& watched, Body& watcher);

    /// Some body is settling (Body::settling(): a motion under way, a piezo creeping toward its
    /// extension, a gripper ramping): the world still changes by itself.
    bool settling() const;

    /// Starts physical fault `id` on the body under `key` (the control API's stall, slip,
    /// limit_switch, sensor_failure, the same for every family): the body's faults() become the
    /// combination of every fault on it, and it applies them at once. std::invalid_argument with
    /// the reason for a missing body, a body that refuses the fault (Body::refuses) or a taken id.
    void add_fault(std::uint64_t id, std::string_view key, BodyFault fault);
    /// Ends fault `id` (its body's faults() are combined again); false if no such fault.
    bool remove_fault(std::uint64_t id);
    /// The body fault `id` acts on, or nullptr.
    Body* fault_body(std::uint64_t id) const;

    Ticks next_change(Ticks now) const override;
    void tick(Ticks now) override;

private:
    struct Due {
        Ticks at;
        int phase;
        Body* body;
        std::uint64_t generation;
        bool operator>(const Due& o) const { return at != o.at ? at > o.at : phase > o.phase; }
    };
    void insert(const std::string& key, std::unique_ptr<Body> body);
    /// Recombines the faults on `body` and has it apply them.
    void combine_faults(Body& body);
    /// Drops void wake-ups from the top of the queue.
    void prune() const;

    Clock& clock_;
    std::map<std::string, std::unique_ptr<Body>, std::less<>> bodies_;
    mutable std::priority_queue<Due, std::vector<Due>, std::greater<>> due_;
    std::map<std::uint64_t, std::pair<Body*, BodyFault>> faults_;   ///< by id: oldest first
};

} // namespace rigsim::models
