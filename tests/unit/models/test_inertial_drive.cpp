// models::InertialDrive: a piezo inertia actuator (PIA) driven open loop by a KIM101/TIM101, on the
// stepped clock: a run of pulses ends on its tick, forward and reverse pulses are of different
// lengths, the length scales with the drive voltage, the end stops hold the screw while the pulses
// go on, the rate ramps up at the step acceleration, and the faults stall or shorten it.

#include "models/inertial_drive.hpp"
#include "models/world.hpp"

#include <catch2/catch.hpp>

#include <vector>

namespace test_inertial_drive {

using namespace rigsim;
using namespace rigsim::models;

struct Rig {
    Clock clock;
    World world{clock};
    InertialDrive& drive;
    std::vector<Ticks> ends;
    int owner = 0;

    explicit Rig(InertialDriveConfig config = {})
        : drive(world.emplace<InertialDrive>("kim101/1", clock, config))
    {
        world.link_all();
        drive.set_listener(&owner, [this](Ticks at) { ends.push_back(at); });
    }
};

TEST_CASE("inertial drive: 500 pulses at 500 a second end after 1 s, reverse pulses are shorter",
          "[unit][models][inertial_drive]")
{
    Rig rig;   // 6.5 mm, 20 nm forward, 18 nm reverse at 110 V
    auto& d = rig.drive;
    CHECK(d.kind() == BodyKind::Linear);
    CHECK(d.position_m() == Approx(6.5e-3));
    d.run(+1, 500, 500, 0, 110);
    CHECK(d.direction() == 1);
    rig.clock.advance(400);
    CHECK(d.pulses() == 200);
    CHECK(d.position_nm() == Approx(6.5e6 + 200 * 20.0));
    CHECK(d.velocity_m_per_s() == Approx(500 * 20e-9));
    rig.clock.advance(599);
    CHECK(rig.ends.empty());
    rig.clock.advance(1);
    CHECK(rig.ends == std::vector<Ticks>{1000});
    CHECK(d.pulses() == 500);
    CHECK_FALSE(d.running());
    CHECK(d.position_nm() == Approx(6.5e6 + 10'000.0));
    d.run(-1, 500, 500, 0, 110);
    rig.clock.advance(1000);
    CHECK(d.pulses() == 0);   // the counter is back at zero ...
    CHECK(d.position_nm() == Approx(6.5e6 + 1'000.0));   // ... the screw is not: 500 × (20 - 18) nm
}

TEST_CASE("inertial drive: the step length scales with the drive voltage", "[unit][models][inertial_drive]")
{
    Rig rig;
    rig.drive.run(+1, 100, 1000, 0, 55);
    rig.clock.advance(100);
    CHECK(rig.drive.position_nm() == Approx(6.5e6 + 100 * 10.0));
}

TEST_CASE("inertial drive: at an end stop the pulses go on and the screw stays", "[unit][models][inertial_drive]")
{
    InertialDriveConfig config;
    config.start_nm = 13e6 - 100;
    Rig rig(config);
    auto& d = rig.drive;
    d.run(+1, 100, 1000, 0, 110);
    rig.clock.advance(50);
    CHECK(d.position_nm() == Approx(13e6));
    CHECK(d.velocity_m_per_s() == 0);
    rig.clock.advance(50);
    CHECK(d.pulses() == 100);
    CHECK(rig.ends.size() == 1);
    d.run(-1, 10, 1000, 0, 110);   // away from the stop at once
    rig.clock.advance(10);
    CHECK(d.position_nm() == Approx(13e6 - 180));
}

TEST_CASE("inertial drive: the rate ramps up at the step acceleration", "[unit][models][inertial_drive]")
{
    Rig rig;
    // 100 pulses at up to 1000/s, 10,000/s²: a triangle of 0.1 s up and 0.1 s down.
    rig.drive.run(+1, 100, 1000, 10'000, 110);
    rig.clock.advance(100);
    CHECK(rig.drive.pulses() == 50);
    CHECK(rig.drive.rate_per_s() == Approx(1000).margin(1));
    rig.clock.advance(100);
    CHECK(rig.ends == std::vector<Ticks>{200});
    CHECK(rig.drive.pulses() == 100);
}

TEST_CASE("inertial drive: an endless run goes on until stopped, without an event", "[unit][models][inertial_drive]")
{
    Rig rig;
    auto& d = rig.drive;
    d.run(-1, std::nullopt, 2000, 0, 110);
    CHECK(d.endless());
    CHECK(d.next_event(0) == kNever);
    rig.clock.advance(1500);
    CHECK(d.pulses() == -3000);
    d.stop();
    rig.clock.advance(1000);
    CHECK(d.pulses() == -3000);
    CHECK(d.position_nm() == Approx(6.5e6 - 3000 * 18.0));
    CHECK(rig.ends.empty());
    // A new run replaces the one under way: its pulses so far are kept.
    d.run(+1, 1000, 1000, 0, 110);
    rig.clock.advance(300);
    d.run(+1, 10, 1000, 0, 110);
    rig.clock.advance(10);
    CHECK(d.pulses() == -3000 + 310);
    CHECK(rig.ends == std::vector<Ticks>{2810});
}

TEST_CASE("inertial drive: a stall holds the screw, a slip shortens the pulses, no limit switch or sensor",
          "[unit][models][inertial_drive]")
{
    Rig rig;
    auto& d = rig.drive;
    const auto fault = [](PhysicalFault kind) {
        BodyFault f;
        f.kind = kind;
        return f;
    };
    BodyFault stall = fault(PhysicalFault::Stall);
    CHECK_FALSE(d.refuses(stall));
    BodyFault slip = fault(PhysicalFault::Slip);
    CHECK_FALSE(d.refuses(slip));
    CHECK(slip.slip_fraction == 0.5);
    BodyFault counts = fault(PhysicalFault::Slip);
    counts.slip_steps = 12.0;
    CHECK(d.refuses(counts));
    BodyFault limit = fault(PhysicalFault::LimitSwitch);
    CHECK(d.refuses(limit));
    BodyFault sensor = fault(PhysicalFault::SensorFailure);
    CHECK(d.refuses(sensor));

    d.run(+1, 1000, 1000, 0, 110);
    rig.clock.advance(100);
    rig.world.add_fault(1, "kim101/1", stall);
    rig.clock.advance(100);
    CHECK(d.position_nm() == Approx(6.5e6 + 2000));
    CHECK(d.pulses() == 200);
    CHECK(rig.world.remove_fault(1));
    rig.world.add_fault(2, "kim101/1", slip);
    rig.clock.advance(100);
    CHECK(d.position_nm() == Approx(6.5e6 + 2000 + 100 * 10.0));
}

TEST_CASE("inertial drive: an obstacle stops the screw like an end stop", "[unit][models][inertial_drive]")
{
    Rig rig;
    auto& d = rig.drive;
    d.set_obstacles_m(std::nullopt, 6.5e-3 + 1e-6);
    d.run(+1, 100, 1000, 0, 110);
    rig.clock.advance(100);
    CHECK(d.position_nm() == Approx(6.5e6 + 1000));
    d.set_obstacles_m(std::nullopt, std::nullopt);
    d.run(+1, 10, 1000, 0, 110);
    rig.clock.advance(10);
    CHECK(d.position_nm() == Approx(6.5e6 + 1200));
}

} // namespace test_inertial_drive
