// Grabs (wedge/grab.hpp, core/src/contact/grab.cpp) against what a damped spring must do, 2D-6D:
//   - held still against gravity the point sags by g / w^2 (the spring's static deflection; implicit
//     Euler keeps it exact at equilibrium) and rests there, for a 10 g and a 100 kg body alike;
//   - without gravity, a critically damped spring closes a gap with no overshoot;
//   - a target moving at 1 m/s (with its velocity) is followed within 2 cm once the start is over;
//   - the force limit caps the acceleration at max_acceleration;
//   - contacts win: a body pulled into the ground rests on it; a held body pushes a free one;
//   - ids are checked; a removed grab does nothing.
#include <catch2/catch.hpp>
#include <cmath>

#include "test_util.hpp"
#include "wedge/mass.hpp"
#include "wedge/world.hpp"

using namespace wedge;

namespace {

template <int N>
BodyDef<N> cube(double half, double density, const Vec<N>& at) {
  BodyDef<N> d;
  const Vec<N> he = Vec<N>::Constant(half);
  d.shape = std::make_shared<const Shape<N>>(Shape<N>::box(he));
  const MassProperties<N> mp = box_mass_properties<N>(he, density);
  d.mass = mp.mass;
  d.inertia = mp.inertia;
  d.position = at;
  return d;
}

template <int N>
Vec<N> up(double y) {
  Vec<N> v = Vec<N>::Zero();
  v[1] = y;
  return v;
}

}  // namespace

TEMPLATE_TEST_CASE("grab: held still, a body sags by g / w^2 whatever its mass", "[grab]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  const double g = 9.81, f = 8.0, w = 2 * M_PI * f, h = 1.0 / 120.0;
  std::vector<Vec<N>> rest;
  for (double density : {10.0, 1000.0, 1e5}) {  // 0.08 g .. 0.8 kg .. 80 kg for a 0.2 m cube (4D: 0.0016 m^4)
    WorldSettings<N> s;
    s.gravity = up<N>(-g);
    World<N> world(s);
    const BodyId id = world.add_body(cube<N>(0.1, density, up<N>(1.0)));
    GrabDef<N> def;
    def.body = id;
    def.target = up<N>(1.0);
    def.frequency = f;
    const GrabId grab = world.add_grab(def);
    for (int i = 0; i < 360; ++i) world.step(h);
    const Vec<N> p = world.grab_point(grab);
    // Static deflection of a spring of natural frequency w: x = g / w^2 = 3.88 mm. Implicit Euler has the
    // same equilibrium; after 3 s (150 time constants 1/w) the transient is below round-off.
    CHECK(p[1] - 1.0 == Approx(-g / (w * w)).epsilon(1e-6));
    CHECK((p - up<N>(1.0 - g / (w * w))).norm() < 1e-9);
    CHECK(world.body(id).velocity.norm() < 1e-9);
    rest.push_back(p);
  }
  // K = I/m at the centre: the motion is the same for every mass (to round-off).
  CHECK((rest[0] - rest[2]).norm() < 1e-12);
}

TEMPLATE_TEST_CASE("grab: critically damped, the gap closes without overshoot", "[grab]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  World<N> world;  // no gravity
  const BodyId id = world.add_body(cube<N>(0.1, 1000.0, Vec<N>::Zero()));
  GrabDef<N> def;
  def.body = id;
  def.target = Vec<N>::Zero();
  def.target[0] = 0.3;
  const GrabId grab = world.add_grab(def);
  double last_gap = 0.3;
  for (int i = 0; i < 120; ++i) {
    world.step(1.0 / 120.0);
    const double gap = def.target[0] - world.grab_point(grab)[0];
    CHECK(gap >= -1e-12);        // never past the target
    CHECK(gap <= last_gap + 1e-15);  // monotone
    last_gap = gap;
  }
  // Critically damped: x(t) = x0 (1 + w t) e^{-w t}; at t = 1 s that is 0.3 * 51 e^{-50} ~ 3e-21. Implicit
  // Euler decays slower (by 1/(1 + h w) per step, squared): still below 1 mm.
  CHECK(last_gap < 1e-3);
}

TEMPLATE_TEST_CASE("grab: a target moving at 1 m/s is followed within 2 cm", "[grab]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  WorldSettings<N> s;
  s.gravity = up<N>(-9.81);
  World<N> world(s);
  const BodyId id = world.add_body(cube<N>(0.1, 1000.0, up<N>(1.0)));
  GrabDef<N> def;
  def.body = id;
  def.local_point = Vec<N>::Constant(0.05);  // off the centre: the body also turns
  def.target = world.body(id).position() + def.local_point;
  const GrabId grab = world.add_grab(def);
  const double h = 1.0 / 120.0;
  Vec<N> v = Vec<N>::Zero();
  v[0] = 1.0;
  double worst = 0.0;
  for (int i = 0; i < 120; ++i) {
    const Vec<N> target = def.target + (i * h) * v;
    world.set_grab_target(grab, target, v);
    world.step(h);
    if (i >= 30) worst = std::max(worst, (world.grab_point(grab) - (target + h * v)).norm());
  }
  INFO("worst lag after 0.25 s: " << worst);
  CHECK(worst < 0.02);
}

TEMPLATE_TEST_CASE("grab: the force limit caps the acceleration", "[grab]", D2, D3, D4) {
  constexpr int N = TestType::value;
  World<N> world;
  const BodyId id = world.add_body(cube<N>(0.1, 1000.0, Vec<N>::Zero()));
  GrabDef<N> def;
  def.body = id;
  def.target = Vec<N>::Constant(100.0);  // far away: the spring wants far more than the limit
  def.max_acceleration = 50.0;
  world.add_grab(def);
  const double h = 1.0 / 120.0;
  Vec<N> last = Vec<N>::Zero();
  for (int i = 0; i < 60; ++i) {
    world.step(h);
    const Vec<N> v = world.body(id).velocity;
    CHECK((v - last).norm() <= 50.0 * h * (1 + 1e-12));
    last = v;
  }
  CHECK(last.norm() == Approx(50.0 * 0.5).epsilon(1e-9));  // at the limit all the way
}

TEMPLATE_TEST_CASE("grab: contacts win over the hand", "[grab]", D2, D3, D4) {
  constexpr int N = TestType::value;
  WorldSettings<N> s;
  s.gravity = up<N>(-9.81);
  World<N> world(s);
  BodyDef<N> ground;
  ground.type = BodyType::Static;
  ground.shape = std::make_shared<const Shape<N>>(Shape<N>::halfspace(up<N>(1.0), 0.0));
  world.add_body(ground);
  const BodyId held = world.add_body(cube<N>(0.1, 1000.0, up<N>(0.5)));
  Vec<N> beside = up<N>(0.1);
  beside[0] = 0.5;
  const BodyId free = world.add_body(cube<N>(0.1, 1000.0, beside));
  GrabDef<N> def;
  def.body = held;
  def.target = up<N>(-0.5);  // half a metre into the ground
  const GrabId grab = world.add_grab(def);
  const double h = 1.0 / 120.0;
  for (int i = 0; i < 240; ++i) world.step(h);
  // Resting on the ground: its lowest face within the contact slop and the correction's residual.
  CHECK(world.body(held).center[1] == Approx(0.1).margin(0.005));
  // Slide it along the ground into the free box: the free box is pushed away in +x.
  Vec<N> v = Vec<N>::Zero();
  v[0] = 1.0;
  for (int i = 0; i < 120; ++i) {
    Vec<N> target = up<N>(0.1);
    target[0] = (i + 1) * h;
    world.set_grab_target(grab, target, v);
    world.step(h);
  }
  CHECK(world.body(free).center[0] > 0.7);
  CHECK(world.body(held).center[0] < world.body(free).center[0] - 0.19);  // never through it
}

TEST_CASE("grab: ids are checked and a removed grab lets go", "[grab]") {
  World<3> world;
  BodyDef<3> wall;
  wall.type = BodyType::Static;
  wall.shape = std::make_shared<const Shape<3>>(Shape<3>::box(Vec<3>::Constant(1.0)));
  const BodyId wall_id = world.add_body(wall);
  const BodyId id = world.add_body(cube<3>(0.1, 1000.0, Vec<3>(5, 0, 0)));
  GrabDef<3> def;
  def.body = wall_id;
  CHECK_THROWS_WITH(world.add_grab(def), Catch::Contains("not dynamic"));
  def.body = BodyId{7};
  CHECK_THROWS_WITH(world.add_grab(def), Catch::Contains("body id 7"));
  def.body = id;
  def.frequency = 0.0;
  CHECK_THROWS_WITH(world.add_grab(def), Catch::Contains("frequency"));
  def.frequency = 8.0;
  def.target = Vec<3>(5, 1, 0);
  const GrabId g = world.add_grab(def);
  CHECK_THROWS(world.set_grab_target(g, Vec<3>(NAN, 0, 0), Vec<3>::Zero()));
  world.step(0.01);
  CHECK(world.body(id).velocity[1] > 0.0);
  world.remove_grab(g);
  CHECK_FALSE(world.has_grab(g));
  CHECK_THROWS_WITH(world.remove_grab(g), Catch::Contains("not a live grab"));
  const Vec<3> v = world.body(id).velocity;
  world.step(0.01);
  CHECK(world.body(id).velocity == v);  // no gravity, no grab: coasts
  const GrabId again = world.add_grab(def);  // reuses the slot with a new generation
  CHECK(again.index == g.index);
  CHECK_FALSE(world.has_grab(g));
  CHECK(world.has_grab(again));
}
