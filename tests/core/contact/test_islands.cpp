// Islands, sleeping and kinematic bodies (core/src/contact/islands.cpp): a resting island falls asleep
// and stops moving, wakes when touched or pushed, and kinematic bodies push without being pushed.
#include <catch2/catch.hpp>
#include <memory>

#include "wedge/scenes/builders.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/mass.hpp"
#include "wedge/world.hpp"

using namespace wedge;

namespace {
WorldSettings<3> with_gravity() {
  WorldSettings<3> s;
  s.gravity = -9.81 * Vec<3>::Unit(1);
  return s;
}
}  // namespace

TEST_CASE("a resting stack falls asleep, then wakes as an island when a ball hits it", "[contact][sleep]") {
  World<3> w(with_gravity());
  scenes::add_ground(w);
  scenes::add_box_tower(w, 3);
  for (int i = 0; i < 120; ++i) w.step(1.0 / 120.0);
  for (int i = 1; i <= 3; ++i) CHECK_FALSE(w.is_awake(BodyId{std::uint32_t(i)}));
  const std::uint64_t asleep = w.state_hash();
  for (int i = 0; i < 60; ++i) w.step(1.0 / 120.0);
  CHECK(w.state_hash() == asleep);  // nothing moves while asleep
  // A ball dropped on the top box wakes the whole island.
  BodyDef<3> ball = body_def<3>(std::make_shared<const Shape<3>>(Shape<3>::ball(0.2)), 1000.0);
  ball.position = Vec<3>(0.1, 3.0 + 0.2 + 0.5, 0.0);
  const BodyId id = w.add_body(ball);
  bool woke_bottom = false;
  for (int i = 0; i < 120 && !woke_bottom; ++i) {
    w.step(1.0 / 120.0);
    woke_bottom = w.is_awake(BodyId{1});
  }
  CHECK(woke_bottom);
  CHECK(w.is_awake(id));
}

TEST_CASE("sleeping off keeps every body awake, and once on, a resting stack sleeps time_to_sleep later",
          "[contact][sleep]") {
  World<3> w(with_gravity());
  w.update_settings([&](auto& s) { s.contact.allow_sleep = false; });
  scenes::add_ground(w);
  scenes::add_box_tower(w, 3);
  const double h = 1.0 / 120.0;
  for (int i = 0; i < 240; ++i) w.step(h);  // 2 s at rest, four times time_to_sleep
  for (int i = 1; i <= 3; ++i) CHECK(w.is_awake(BodyId{std::uint32_t(i)}));
  // The rest while sleeping was off does not count: the island sleeps once it has rested
  // time_to_sleep (0.5 s, 60 steps) with sleeping on, not at the first step, and not much later.
  w.update_settings([&](auto& s) { s.contact.allow_sleep = true; });
  int steps = 0;
  while (w.is_awake(BodyId{3}) && steps < 240) {
    w.step(h);
    ++steps;
  }
  CHECK(steps >= 60);
  CHECK(steps <= 61);
  for (int i = 1; i <= 3; ++i) CHECK_FALSE(w.is_awake(BodyId{std::uint32_t(i)}));
}

TEST_CASE("input wakes a sleeping body and its island", "[contact][sleep]") {
  World<3> w(with_gravity());
  scenes::add_ground(w);
  scenes::add_box_tower(w, 2);
  for (int i = 0; i < 120; ++i) w.step(1.0 / 120.0);
  REQUIRE_FALSE(w.is_awake(BodyId{2}));
  w.apply_impulse_at(BodyId{2}, Vec<3>(200.0, 0.0, 0.0), w.body(BodyId{2}).center);
  CHECK(w.is_awake(BodyId{1}));
  CHECK(w.is_awake(BodyId{2}));
  const double x = w.body(BodyId{2}).center[0];
  w.step(1.0 / 120.0);
  CHECK(w.body(BodyId{2}).center[0] > x);
}

TEST_CASE("a kinematic paddle follows its path exactly and pushes a box", "[contact][kinematic]") {
  World<3> w(with_gravity());
  scenes::add_ground(w);
  BodyDef<3> paddle;
  paddle.type = BodyType::Kinematic;
  paddle.shape = std::make_shared<const Shape<3>>(Shape<3>::box(Vec<3>(0.1, 0.5, 0.5)));
  paddle.position = Vec<3>(-1.0, 0.5, 0.0);
  const BodyId pid = w.add_body(paddle);
  const BodyId box = scenes::add_box_tower(w, 1);
  const double h = 1.0 / 120.0;
  for (int i = 1; i <= 120; ++i) {
    // Along x at 1 m/s, turning slowly about y.
    const Vec<3> target(-1.0 + i * h, 0.5, 0.0);
    const Rotor<3> turn = exp<3>(Bivector<3>::basis(0, 2) * (0.1 * i * h));
    w.move_kinematic(pid, target, turn, h);
    w.step(h);
    CHECK((w.body(pid).position() - target).norm() < 1e-12);
    CHECK((w.body(pid).rotor - turn).norm() < 1e-9);
  }
  // The paddle's face started 0.4 m from the box and moved 1 m: the box was pushed about 0.6 m.
  CHECK(w.body(box).center[0] > 0.4);
  CHECK(w.body(box).center[0] < 0.8);
  CHECK(w.is_awake(box));
}
