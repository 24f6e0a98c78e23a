// models::Paddle: a polarisation controller's fibre paddle (MPC320/MPC220) on the stepped clock: a
// move at a set rate ends on its tick, a stop holds it where it is, its angle stays in 0..170.

#include "models/paddle.hpp"
#include "models/world.hpp"

#include <catch2/catch.hpp>

#include <vector>

namespace test_paddle {

using namespace rigsim;
using namespace rigsim::models;

TEST_CASE("paddle: a move at 0.2 degree per tick ends on its tick, a stop holds the angle, targets are clamped",
          "[unit][models][paddle]")
{
    Clock clock;
    World world{clock};
    auto& paddle = world.emplace<Paddle>("mpc320/1", 170.0);
    world.link_all();
    std::vector<Ticks> ends;
    int owner = 0;
    paddle.set_listener(&owner, [&](Ticks at) { ends.push_back(at); });
    CHECK(paddle.kind() == BodyKind::Paddle);
    paddle.move_to(0, 85.0, 0.2);   // 425 ticks
    CHECK(paddle.direction_at(0) == 1);
    clock.advance(200);
    CHECK(paddle.angle_at(200) == Approx(40.0));
    clock.advance(224);
    CHECK(ends.empty());
    clock.advance(1);
    CHECK(ends == std::vector<Ticks>{425});
    CHECK(paddle.angle_at(425) == Approx(85.0));
    CHECK_FALSE(paddle.moving_at(425));
    paddle.move_to(425, 500.0, 1.0);   // clamped to 170: 85 ticks
    CHECK(paddle.target() == 170.0);
    clock.advance(40);
    paddle.stop(465);
    CHECK(paddle.angle_at(465) == Approx(125.0));
    clock.advance(100);
    CHECK(ends.size() == 1);
    CHECK(paddle.angle_at(565) == Approx(125.0));
    paddle.move_to(565, 100.0, 1.0);
    CHECK(paddle.direction_at(565) == -1);
    paddle.clear_listener(&owner);
    clock.advance(100);
    CHECK(ends.size() == 1);
    CHECK(paddle.angle_at(665) == Approx(100.0));
}

} // namespace test_paddle
