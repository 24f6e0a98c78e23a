// models::World: bodies under stable keys, woken only when an event of theirs is due.

#include "models/world.hpp"

#include <catch2/catch.hpp>

#include <stdexcept>
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

} // namespace test_world
