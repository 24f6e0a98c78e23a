#include "models/world.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace rigsim::models {

World::World(Clock& clock) : clock_(clock)
{
    clock_.add(this);
}

World::~World()
{
    clock_.remove(this);
}

void World::insert(const std::string& key, std::unique_ptr<Body> body)
{
    if (key.empty())
        throw std::invalid_argument("a body of the world needs a key");
    if (bodies_.count(key))
        throw std::invalid_argument("the world already has a body \"" + key + "\"");
    body->world_ = this;
    body->key_ = key;
    Body& ref = *body;
    bodies_.emplace(key, std::move(body));
    reschedule(ref);
}

Body* World::find(std::string_view key) const
{
    const auto it = bodies_.find(key);
    return it == bodies_.end() ? nullptr : it->second.get();
}

std::vector<std::string> World::keys() const
{
    std::vector<std::string> k;
    k.reserve(bodies_.size());
    for (const auto& [key, body] : bodies_)
        k.push_back(key);
    return k;
}

void World::link_all()
{
    for (auto& [key, body] : bodies_)
        body->link(*this);
}

void World::reschedule(Body& body)
{
    ++body.generation_;
    const Ticks at = body.next_event(clock_.now());
    if (at != kNever)
        due_.push(Due{std::max(at, clock_.now() + 1), body.phase(), &body, body.generation_});
    for (Body* watcher : body.watchers_)
        watcher->on_watched(body);
}

void World::watch(Body& watched, Body& watcher)
{
    if (&watched == &watcher || watched.world_ != this || watcher.world_ != this)
        throw std::invalid_argument("a body watches another body of its world");
    if (std::find(watched.watchers_.begin(), watched.watchers_.end(), &watcher) == watched.watchers_.end())
        watched.watchers_.push_back(&watcher);
}

bool World::settling() const
{
    return std::any_of(bodies_.begin(), bodies_.end(), [](const auto& b) { return b.second->settling(); });
}

void World::add_fault(std::uint64_t id, std::string_view key, BodyFault fault)
{
    Body* body = find(key);
    if (!body)
        throw std::invalid_argument("the world has no body \"" + std::string(key) + "\"");
    if (faults_.count(id))
        throw std::invalid_argument("fault " + std::to_string(id) + " is active already");
    if (const auto why = body->refuses(fault))
        throw std::invalid_argument(*why);
    faults_.emplace(id, std::make_pair(body, fault));
    combine_faults(*body);
}

bool World::remove_fault(std::uint64_t id)
{
    const auto it = faults_.find(id);
    if (it == faults_.end())
        return false;
    Body& body = *it->second.first;
    faults_.erase(it);
    combine_faults(body);
    return true;
}

Body* World::fault_body(std::uint64_t id) const
{
    const auto it = faults_.find(id);
    return it == faults_.end() ? nullptr : it->second.first;
}

void World::combine_faults(Body& body)
{
    PhysicalFaults all;
    for (const auto& [id, entry] : faults_) {   // oldest first: the newest switch wins
        if (entry.first != &body)
            continue;
        const BodyFault& f = entry.second;
        switch (f.kind) {
        case PhysicalFault::Stall:
            all.stalled = true;
            break;
        case PhysicalFault::Slip:
            all.slip_steps += f.slip_steps.value_or(0);
            // Each takes its part of what the others left (one slip: exactly its fraction).
            all.slip_fraction += f.slip_fraction.value_or(0) * (1 - all.slip_fraction);
            break;
        case PhysicalFault::LimitSwitch:
            all.switch_pressed = f.switch_side;
            break;
        case PhysicalFault::SensorFailure:
            all.sensor_failed = true;
            break;
        }
    }
    body.faults_ = all;
    body.apply_faults();
}

void World::prune() const
{
    while (!due_.empty() && due_.top().generation != due_.top().body->generation_)
        due_.pop();
}

Ticks World::next_change(Ticks now) const
{
    if (due_.empty())
        return kNever;   // the usual case between moves: no call into prune()
    prune();
    return due_.empty() ? kNever : std::max(due_.top().at, now + 1);
}

void World::tick(Ticks now)
{
    for (prune(); !due_.empty() && due_.top().at <= now; prune()) {
        Body& body = *due_.top().body;
        due_.pop();
        ++body.generation_;   // this wake-up is spent; on_event() may schedule the next
        body.on_event(now);
        reschedule(body);
    }
}

} // namespace rigsim::models
