#pragma once
// Collisions between the declared bounding boxes of a rig's frames (models/kinematics.hpp).
//
// The watch is a body of the World. While a joint on the path between the two frames of a
// watched pair moves, it wakes on every tick, after the bodies that move (phase 1): it updates
// the poses and tests the boxes of every pair with a joint between its frames that went
// somewhere since the last test (the others cannot have come together or apart). Otherwise it
// sleeps, and the World wakes it when a body that drives one of those joints is rescheduled (a
// motion starts, changes or ends).
//
// On a new contact every joint on the two frames' paths up to their common ancestor that moves
// is stopped where it stands: an obstacle at its position on the side it moves toward (moving
// up: the maximum; down: the minimum), which its axis meets as its own end stop (a servo
// stalls, a stepper loses microsteps, a stick-slip positioner is blocked). Motion away is free.
// A joint whose axis cannot be stopped (a piezo: it pushes on) is only reported. A contact
// lasts while the boxes touch; when they part its obstacles go (a joint held by another live
// contact keeps that contact's).
//
// Detection is at tick resolution: the boxes are tested at every tick while a joint moves, and
// the motion is stopped at the position of the first tick at which they touch, so a box goes
// into the other at most one tick's travel of the joints between them. While a contact lasts,
// a joint between the two frames that takes the boxes deeper (the least overlap of their
// projections on the 15 axes of the separating-axis test grows) is stopped the same way: a
// joint that began to move during the contact, or one moving away from its obstacle that turns
// round. Sliding along the contact or parting is free.

#include "models/clock.hpp"
#include "models/kinematics.hpp"
#include "models/world.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rigsim::models {

/// How the watch reads and stops the joint of one frame (built from a device channel).
struct JointDrive {
    std::string body_key;                 ///< the world body that moves the joint (its motions wake the watch)
    std::function<double()> velocity;    ///< now: mm/s or degrees/s, signed; 0 at rest
    /// Obstacles in joint units (std::nullopt clears that side). Empty: the joint's axis cannot
    /// be stopped; a contact only reports it.
    std::function<void(std::optional<double> min, std::optional<double> max)> set_obstacles;
};

/// A moving joint a contact met.
struct ContactJoint {
    std::size_t frame = 0;   ///< the frame the joint moves
    double position = 0;     ///< mm or degrees, where the joint stood at the contact
    int direction = 0;       ///< +1 / -1: the way it was moving
};

inline bool operator==(const ContactJoint& a, const ContactJoint& b)
{
    return a.frame == b.frame && a.position == b.position && a.direction == b.direction;
}

/// Two boxes touching, and the joints the watch stopped (or could not stop) while they touch.
struct Contact {
    std::size_t frame_a = 0;
    std::size_t frame_b = 0;
    std::vector<ContactJoint> stopped;       ///< held by an obstacle at their position
    std::vector<ContactJoint> not_stopped;   ///< moving on: their axes cannot be stopped
};

using FramePair = std::pair<std::size_t, std::size_t>;

/// The frames whose moving joints lie between `a` and `b` (each up to their common ancestor),
/// from `a` up, then from `b` up.
std::vector<std::size_t> joints_between(const Kinematics& kinematics, std::size_t a, std::size_t b);

/// Every pair of frames (tools included) that both have a box, with a moving joint between
/// them, and that are not parent and child: the pairs of "collisions": "auto".
std::vector<FramePair> auto_collision_pairs(const Kinematics& kinematics);

class CollisionWatch : public Body {
public:
    using Listener = std::function<void(const Contact&)>;

    /// Watches `pairs` of `kinematics`' frames; `drives` has one entry per frame (a fixed
    /// frame's is empty). std::invalid_argument for a pair of one frame, an unknown frame, a
    /// frame without a box, or `drives` of another size.
    CollisionWatch(Kinematics& kinematics, std::vector<FramePair> pairs, std::vector<JointDrive> drives);

    /// Told of every new contact at the tick it is found (after its joints were stopped), and
    /// of a lasting contact taken deeper: then `stopped` and `not_stopped` hold the joints
    /// stopped or found pushing on that tick.
    void set_listener(Listener listener) { listener_ = std::move(listener); }
    const std::vector<FramePair>& pairs() const { return pairs_; }
    /// The contacts that last now (as of the last check), in the order of pairs(), with every
    /// joint each has stopped or found pushing on so far.
    std::vector<Contact> contacts() const;
    /// Checks made so far (ticks at which the boxes were tested).
    std::uint64_t checks() const { return checks_; }
    /// Whether the watch wakes on the next tick (a joint it watches moves).
    bool awake() const { return awake_; }

    /// Watches the bodies of the drives on the pairs' paths (std::invalid_argument for a key
    /// the world does not have).
    void link(World& world) override;
    int phase() const override { return 1; }
    void on_watched(Body& body) override;
    Ticks next_event(Ticks now) const override;
    void on_event(Ticks now) override;
    BodyKind kind() const override { return BodyKind::Watch; }

private:
    /// An obstacle a contact put on a joint.
    struct Hold {
        std::size_t pair;
        std::size_t frame;
        int direction;
        double position;
    };
    void begin_contact(std::size_t pair);
    void deepen_contact(std::size_t pair);
    /// Stops the joints between the pair's frames that move and are not yet held in that
    /// direction by this contact; returns the contact with just those (and the unstoppable ones
    /// not reported yet).
    Contact stop_joints(std::size_t pair);
    void end_contact(std::size_t pair);
    /// Sets the frame's obstacles from the holds on it.
    void apply_holds(std::size_t frame);

    Kinematics& kinematics_;
    std::vector<FramePair> pairs_;
    std::vector<JointDrive> drives_;
    std::vector<std::vector<std::size_t>> paths_;   ///< per pair: joints_between()
    std::vector<double> radius_mm_;                 ///< per pair: the sum of the boxes' half diagonals
    std::vector<std::size_t> watched_;              ///< frames on any path, once each
    std::vector<int> direction_;                    ///< per frame: the way its joint moves now
    std::vector<double> last_q_;                    ///< per frame: its position at the last check
    std::vector<std::vector<std::size_t>> pairs_of_;   ///< per frame: the pairs it lies between
    std::vector<bool> pair_due_;                    ///< per pair: a joint between moved since the last check
    std::vector<std::optional<Contact>> live_;      ///< per pair
    std::vector<double> depth_mm_;                  ///< per pair: penetration at the last check
    std::vector<Hold> holds_;
    Listener listener_;
    bool awake_ = true;   ///< the first tick checks the rig as it powered up
    Ticks last_check_ = -2;
    std::uint64_t checks_ = 0;
};

} // namespace rigsim::models
