// Stress where VR users will push (4D, the default settings and step of 1/120 s): a held tesseract
// rammed into a pile at the grab's force limit, a tall stack hit by a thrown tesseract, and 1:100 mass
// ratios under a hand. What must hold in each: every state finite, nothing through the ground, no body
// flung faster than the motion put in could make it, and overlaps bounded. Each test prints its figures
// (docs/contact.md, "Known limits", quotes them).
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "wedge/mass.hpp"
#include "wedge/world.hpp"

using namespace wedge;

namespace {

constexpr int N = 4;
constexpr double kStep = 1.0 / 120.0;
constexpr double kHalf = 0.1;  // m: every tesseract is 20 cm across

Vec<N> at(double x, double y, double z = 0.0, double w = 0.0) { return Vec<N>(x, y, z, w); }

BodyDef<N> tesseract(const Vec<N>& position, double mass) {
  BodyDef<N> d;
  const Vec<N> he = Vec<N>::Constant(kHalf);
  d.shape = std::make_shared<const Shape<N>>(Shape<N>::box(he));
  const MassProperties<N> mp = box_mass_properties<N>(he, 1.0);
  d.mass = mass;
  d.inertia = mp.inertia * (mass / mp.mass);
  d.position = position;
  return d;
}

World<N> table() {
  WorldSettings<N> s;
  s.gravity[1] = -9.81;
  World<N> w(s);
  BodyDef<N> ground;
  ground.type = BodyType::Static;
  ground.shape = std::make_shared<const Shape<N>>(Shape<N>::halfspace(at(0, 1), 0.0));
  w.add_body(ground);
  return w;
}

struct Watch {
  bool finite = true;
  double lowest = 1e300;   // m, the lowest centre of any dynamic body
  double fastest = 0.0;    // m/s
  double deepest = 0.0;    // m, the deepest contact point of any pair
  void look(const World<N>& w) {
    for (const Body<N>& b : w.bodies()) {
      if (!b.is_dynamic()) continue;
      finite &= all_finite(b.center) && all_finite(b.velocity) && all_finite(b.angular_velocity.c);
      lowest = std::min(lowest, b.center[1]);
      fastest = std::max(fastest, b.velocity.norm());
    }
    for (const ContactInfo<N>& c : w.contacts())
      for (int k = 0; k < c.manifold.count; ++k) deepest = std::max(deepest, c.manifold.points[k].depth);
  }
};

}  // namespace

TEST_CASE("stress: a held tesseract rammed into a pile at the grab's force limit", "[stress][contact][4d]") {
  World<N> w = table();
  // A pile of 3 x 3 columns of 3, in x-z, resting on the ground.
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j) w.add_body(tesseract(at(1.0 + 0.21 * i, kHalf + 0.2 * j, 0.21 * (k - 1)), 1.0));
  const BodyId held = w.add_body(tesseract(at(0.0, 0.3), 1.0));
  for (int i = 0; i < 120; ++i) w.step(kStep);  // settle
  GrabDef<N> g;
  g.body = held;
  g.target = at(0.0, 0.3);
  const GrabId grab = w.add_grab(g);
  // The hand sweeps at 3 m/s through the pile and on, 2 m past it: the spring saturates at its force
  // limit (mass x 300 m/s^2) while the pile holds the body back.
  Watch watch;
  for (int i = 0; i < 240; ++i) {
    const double x = std::min(3.0 * (i + 1) * kStep, 3.5);
    w.set_grab_target(grab, at(x, 0.3), at(x < 3.5 ? 3.0 : 0.0, 0.0));
    w.step(kStep);
    watch.look(w);
  }
  std::printf("stress, ram: fastest %.2f m/s, lowest centre %.3f m, deepest contact %.1f mm\n", watch.fastest,
              watch.lowest, 1e3 * watch.deepest);
  CHECK(watch.finite);
  CHECK(watch.lowest > kHalf - 0.02);  // on the ground, never into it beyond the soft contacts' give
  // A 1 kg body pushed at up to 300 m/s^2 by a hand moving at 3 m/s: what it hits leaves at no more than
  // about twice the hand's speed plus what the spring stores (1/2 k x^2 at the force limit).
  CHECK(watch.fastest < 15.0);
  CHECK(watch.deepest < 0.05);
}

TEST_CASE("stress: a tall stack of tesseracts knocked over by a thrown one", "[stress][contact][4d]") {
  World<N> w = table();
  for (int j = 0; j < 10; ++j) w.add_body(tesseract(at(0.0, kHalf + 0.2 * j), 1.0));
  for (int i = 0; i < 240; ++i) w.step(kStep);  // settle
  BodyDef<N> thrown = tesseract(at(-2.0, 1.5, 0.0, 0.05), 1.0);
  thrown.velocity = at(12.0, 0.5, 0.0, 0.0);
  thrown.angular_velocity.c[0] = 20.0;  // tumbling, as a throw from a hand
  const BodyId ball = w.add_body(thrown);
  Watch watch;
  double top_moved = 0.0;
  const Vec<N> top0 = w.body(BodyId{10}).center;
  for (int i = 0; i < 600; ++i) {
    w.step(kStep);
    watch.look(w);
    top_moved = std::max(top_moved, (w.body(BodyId{10}).center - top0).norm());
  }
  std::printf("stress, knock: fastest %.2f m/s, lowest centre %.3f m, deepest contact %.1f mm, top moved %.2f m\n",
              watch.fastest, watch.lowest, 1e3 * watch.deepest, top_moved);
  CHECK(watch.finite);
  CHECK(watch.lowest > kHalf - 0.02);
  CHECK(top_moved > 0.5);  // the stack went over
  // Nothing leaves faster than the throw (12.0 m/s and a 20 rad/s tumble: its corners at 12 + 20 x 0.2)
  // plus free fall from the stack's top, 2 m: sqrt(2 g 2) = 6.3 m/s.
  CHECK(watch.fastest < 12.0 + 4.0 + 6.3);
  CHECK(watch.deepest < 0.05);
  (void)ball;
}

TEST_CASE("stress: a 1:100 mass ratio under a hand", "[stress][contact][4d]") {
  SECTION("a hand presses a 100 kg tesseract onto a 1 kg one lying on the ground") {
    World<N> w = table();
    const BodyId light = w.add_body(tesseract(at(0.0, kHalf), 1.0));
    const BodyId heavy = w.add_body(tesseract(at(0.0, 3 * kHalf + 0.001), 100.0));
    for (int i = 0; i < 120; ++i) w.step(kStep);
    GrabDef<N> g;
    g.body = heavy;
    g.target = at(0.0, 0.25);  // 5 cm below where it rests: the spring presses with up to 30 kN
    w.add_grab(g);
    Watch watch;
    for (int i = 0; i < 360; ++i) {
      w.step(kStep);
      watch.look(w);
    }
    const double gap = w.body(heavy).center[1] - w.body(light).center[1];
    std::printf("stress, press: light body's centre %.4f m (rest %.1f), heavy - light %.4f m, deepest %.1f mm, "
                "fastest %.3f m/s\n",
                w.body(light).center[1], kHalf, gap, 1e3 * watch.deepest, watch.fastest);
    CHECK(watch.finite);
    CHECK(w.body(light).center[1] > 0.0);  // squeezed, but not through the ground
    CHECK(gap > kHalf);                   // nor the heavy one through the light one
  }
  SECTION("a hand holds a 1 kg tesseract with a 100 kg one resting on it") {
    World<N> w = table();
    const BodyId light = w.add_body(tesseract(at(0.0, 0.5), 1.0));
    GrabDef<N> g;
    g.body = light;
    g.target = at(0.0, 0.5);
    w.add_grab(g);
    for (int i = 0; i < 60; ++i) w.step(kStep);
    const BodyId heavy = w.add_body(tesseract(at(0.0, 0.5 + 2 * kHalf + 0.001), 100.0));
    Watch watch;
    for (int i = 0; i < 480; ++i) {
      w.step(kStep);
      watch.look(w);
    }
    // The grab's force limit (1 kg x 300 m/s^2 = 300 N) is below the load (981 N): the pair sinks to
    // the ground and rests there, the light one under the heavy one.
    std::printf("stress, hold: light %.4f m, heavy %.4f m, deepest %.1f mm, fastest %.3f m/s at the end %.4f m/s\n",
                w.body(light).center[1], w.body(heavy).center[1], 1e3 * watch.deepest, watch.fastest,
                w.body(heavy).velocity.norm());
    CHECK(watch.finite);
    CHECK(w.body(light).center[1] > 0.0);
    CHECK(w.body(heavy).center[1] - w.body(light).center[1] > kHalf);
    CHECK(w.body(heavy).velocity.norm() < 0.05);  // come to rest
  }
}
