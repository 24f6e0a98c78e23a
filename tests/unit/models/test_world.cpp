// models::World: bodies under stable keys, woken only when an event of theirs is due.

#include "models/world.hpp"

#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace test_world {

using namespace rigsim;
using namespace rigsim::models;

namespace {

/// A body that wants waking at the ticks it is told, and records when it was woken.
class Alarm : public Body {
public:
    explicit Alarm(std::vector<Ticks> at) : at_(std::move(at)) {}
    Ticks next_event(Ticks now) const override
    {
        for (Ticks t : at_)
            if (t > now)
                return t;
        return kNever;
    }
    void on_event(Ticks now) override { woken.push_back(now); }
    models::BodyKind kind() const override { return models::BodyKind::Watch; }
    void set(std::vector<Ticks> at)
    {
        at_ = std::move(at);
        reschedule();
    }
    std::vector<Ticks> woken;

private:
    std::vector<Ticks> at_;
};

} // namespace

TEST_CASE("world: a body is woken at its events only, not once per tick", "[unit][models][world]")
{
    Clock clock;
    World world(clock);
    auto& a = world.emplace<Alarm>("dev/0", std::vector<Ticks>{5, 1000, 250'000});
    auto& idle = world.emplace<Alarm>("dev/1", std::vector<Ticks>{});
    CHECK(world.next_change(0) == 5);
    clock.advance(300'000);
    CHECK(a.woken == std::vector<Ticks>{5, 1000, 250'000});
    CHECK(idle.woken.empty());
    CHECK(world.next_change(clock.now()) == kNever);
}

TEST_CASE("world: a rescheduled body drops its old wake-up", "[unit][models][world]")
{
    Clock clock;
    World world(clock);
    auto& a = world.emplace<Alarm>("apt/0", std::vector<Ticks>{100});
    clock.advance(10);
    a.set({40});   // a new command: the move now ends at 40
    clock.advance(200);
    CHECK(a.woken == std::vector<Ticks>{40});
    a.set({});     // stopped
    CHECK(world.next_change(clock.now()) == kNever);
}

TEST_CASE("world: bodies due at the same tick are all woken in that tick",
          "[unit][models][world]")
{
    Clock clock;
    World world(clock);
    auto& b = world.emplace<Alarm>("b/0", std::vector<Ticks>{7});
    auto& a = world.emplace<Alarm>("a/0", std::vector<Ticks>{7, 9});
    clock.advance(8);
    CHECK(a.woken == std::vector<Ticks>{7});
    CHECK(b.woken == std::vector<Ticks>{7});
    CHECK(world.next_change(clock.now()) == 9);
}

TEST_CASE("world: keys are unique, non-empty and found again", "[unit][models][world]")
{
    Clock clock;
    World world(clock);
    auto& a = world.emplace<Alarm>("mcs/0", std::vector<Ticks>{});
    CHECK_THROWS_AS(world.emplace<Alarm>("mcs/0", std::vector<Ticks>{}), std::invalid_argument);
    CHECK_THROWS_AS(world.emplace<Alarm>("", std::vector<Ticks>{}), std::invalid_argument);
    CHECK(world.find("mcs/0") == &a);
    CHECK(world.find_as<Alarm>("mcs/0") == &a);
    CHECK(world.find("mcs/1") == nullptr);
    CHECK(a.key() == "mcs/0");
    CHECK(world.keys() == std::vector<std::string>{"mcs/0"});
}

namespace {

/// A body that reads another body of the world, found by key in link().
class Reader : public Alarm {
public:
    explicit Reader(std::string source) : Alarm({}), source_(std::move(source)) {}
    void link(World& world) override
    {
        ++links;
        found = world.find_as<Alarm>(source_);
        if (!found)
            throw std::invalid_argument("no alarm \"" + source_ + "\"");
    }
    Alarm* found = nullptr;
    int links = 0;

private:
    std::string source_;
};

} // namespace

TEST_CASE("world: link_all lets every body find the bodies it reads, whatever their order",
          "[unit][models][world]")
{
    Clock clock;
    World world(clock);
    auto& reader = world.emplace<Reader>("a/reader", "z/source");   // before its source
    auto& plain = world.emplace<Alarm>("m/plain", std::vector<Ticks>{});
    auto& source = world.emplace<Alarm>("z/source", std::vector<Ticks>{});
    CHECK(reader.found == nullptr);
    world.link_all();
    CHECK(reader.found == &source);
    CHECK(reader.links == 1);
    CHECK(plain.woken.empty());   // Body::link() does nothing by default

    world.emplace<Reader>("b/reader", "nowhere");
    CHECK_THROWS_WITH(world.link_all(), "no alarm \"nowhere\"");
}

namespace {

/// An alarm of a later phase that records, when woken, what it heard from the bodies it watches.
class Watcher : public Alarm {
public:
    Watcher() : Alarm({}) {}
    int phase() const override { return 1; }
    void on_watched(Body& body) override { heard.push_back(body.key()); }
    void on_event(Ticks now) override
    {
        Alarm::on_event(now);
        order.push_back("watcher");
    }
    std::vector<std::string> heard;
    std::vector<std::string> order;
};

/// An alarm that appends its key to a shared list when woken.
class Logged : public Alarm {
public:
    Logged(std::vector<Ticks> at, std::vector<std::string>& order) : Alarm(std::move(at)), order_(order) {}
    void on_event(Ticks now) override
    {
        Alarm::on_event(now);
        order_.push_back(key());
    }

private:
    std::vector<std::string>& order_;
};

} // namespace

TEST_CASE("world: a body of a later phase runs after the others due at the same tick", "[unit][models][world]")
{
    Clock clock;
    World world(clock);
    // Keys and insertion order put the watcher first; its phase puts it last.
    auto& w = world.emplace<Watcher>("a/watch");
    world.emplace<Logged>("z/0", std::vector<Ticks>{5}, w.order);
    world.emplace<Logged>("m/0", std::vector<Ticks>{5}, w.order);
    w.set({5});
    clock.advance(6);
    REQUIRE(w.order.size() == 3);
    CHECK(w.order.back() == "watcher");
    CHECK(w.woken == std::vector<Ticks>{5});
}

TEST_CASE("world: a watcher hears every reschedule of the bodies it watches, and no other", "[unit][models][world]")
{
    Clock clock;
    World world(clock);
    auto& w = world.emplace<Watcher>("w/0");
    auto& a = world.emplace<Alarm>("a/0", std::vector<Ticks>{});
    auto& b = world.emplace<Alarm>("b/0", std::vector<Ticks>{});
    world.watch(a, w);
    world.watch(a, w);   // once is enough
    a.set({10});
    b.set({10});
    CHECK(w.heard == std::vector<std::string>{"a/0"});
    clock.advance(10);   // a's event: the world reschedules it after on_event()
    CHECK(w.heard == std::vector<std::string>{"a/0", "a/0"});
    CHECK_THROWS_AS(world.watch(w, w), std::invalid_argument);
    Clock other_clock;
    World other(other_clock);
    auto& stranger = other.emplace<Alarm>("s/0", std::vector<Ticks>{});
    CHECK_THROWS_AS(world.watch(stranger, w), std::invalid_argument);
}

} // namespace test_world
