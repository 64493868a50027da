// The Wedge side of the peer benchmarks (wedge_bench_contact, wedge_bench_peers): the settings the
// engines share and the Wedge worlds, built by the wedge::scenes builders, from which each peer scene
// copies every initial position and orientation, so that the engines start from the same state.
//
// Shared settings: time step 1/60 s, gravity 9.81 m/s^2 along -x_1, box half extent 0.5 m, density
// 1000 kg/m^n, friction 0.6 per pair, restitution 0.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "wedge/scenes/builders.hpp"
#include "wedge/ga/products.hpp"
#include "wedge/mass.hpp"
#include "wedge/world.hpp"

namespace wedge::bench {


inline constexpr double kDt = 1.0 / 60.0;  // s
inline constexpr double kGravity = 9.81;   // m/s^2
inline constexpr double kHalf = 0.5;       // m, the builders' default box half extent
inline constexpr double kDensity = 1000.0;  // kg/m^n, as in scenes/builders
inline constexpr double kFriction = 0.6;    // per pair (both engines' mixing rules give 0.6 for 0.6 & 0.6)

// Wedge settings: gravity along -x_1 and the contact defaults, with the given iteration counts.
template <int N>
WorldSettings<N> make_settings(bool sleep, int contact_iterations = 10, int position_iterations = 4) {
  WorldSettings<N> s;
  s.gravity = -kGravity * Vec<N>::Unit(1);
  s.contact.allow_sleep = sleep;
  s.contact.contact_iterations = contact_iterations;
  s.contact.position_iterations = position_iterations;
  return s;
}

// Wedge worlds of the benchmarks: a ground plus the builder's boxes.
inline World<2> wedge_pyramid(int rows, bool sleep) {
  World<2> w(make_settings<2>(sleep, 8, 3));
  scenes::add_ground<2>(w, kFriction);
  scenes::add_box_pyramid<2>(w, rows, kHalf, kFriction);
  return w;
}
// The peers' 2D pyramid (wedge_bench_peers, wedge_peers_stand): Wedge's defaults, sleeping off.
inline World<2> peers_pyramid(int rows) {
  World<2> w(make_settings<2>(false));
  scenes::add_ground<2>(w, kFriction);
  scenes::add_box_pyramid<2>(w, rows, kHalf, kFriction);
  return w;
}
template <int N>
World<N> wedge_pile(int count, bool sleep, std::uint64_t seed = 1) {
  World<N> w(make_settings<N>(sleep));
  scenes::add_ground<N>(w, kFriction);
  scenes::add_box_pile<N>(w, count, seed, kHalf, kFriction);
  return w;
}

// Jolt's PerformanceTest "Pyramid" (PerformanceTest/PyramidScene.h): 15 staggered layers of boxes of
// half extent 1 m, each layer 0.5 m above the one below when placed, 1,240 boxes on the ground y = 0.
// Default contact settings, sleeping off.
inline World<3> wedge_jolt_pyramid() {
  World<3> w(make_settings<3>(false));
  scenes::add_ground<3>(w, kFriction);
  const int height = 15;
  const double size = 2.0, gap = 0.5, half = 1.0;
  BodyDef<3> def = body_def<3>(std::make_shared<const Shape<3>>(Shape<3>::box(Vec<3>::Constant(half))), kDensity);
  def.material.friction = def.material.kinetic_friction = kFriction;
  for (int i = 0; i < height; ++i)
    for (int j = i / 2; j < height - (i + 1) / 2; ++j)
      for (int k = i / 2; k < height - (i + 1) / 2; ++k) {
        const double shift = (i & 1) ? half : 0.0;
        def.position = Vec<3>(-height + size * j + shift, 1.0 + (size + gap) * i, -height + size * k + shift);
        w.add_body(def);
      }
  return w;
}

// Box2D v3's joint_grid benchmark (its shared/benchmarks.c, CreateJointGrid): an n x n grid of disks of
// radius 0.4 m and density 1 kg/m^2, 1 m apart, each joined to the one above it and the one to its left
// by a revolute joint at their midpoint; the seven middle disks of the top row static; sleeping off.
// Box2D keeps the disks from colliding with a filter; here they have no shape, only a disk's mass and
// moment. At Box2D v3's stiffness and sub-steps (joints at 60 Hz, damping ratio 2, 4 sub-steps), or
// with more sub-steps.
inline constexpr double kGridRadius = 0.4;  // m
inline World<2> joint_grid(int n, int substeps = 4) {
  WorldSettings<2> s = make_settings<2>(false);
  s.contact.substeps = substeps;
  s.contact.joint_hertz = 60.0;
  s.contact.joint_damping_ratio = 2.0;
  World<2> w(s);
  std::vector<BodyId> ids;
  BodyDef<2> def;
  def.mass = M_PI * kGridRadius * kGridRadius;
  def.inertia = BivMat<2>::Constant(0.5 * def.mass * kGridRadius * kGridRadius);
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i) {
      def.type = k >= n / 2 - 3 && k <= n / 2 + 3 && i == 0 ? BodyType::Static : BodyType::Dynamic;
      def.position = Vec<2>(k, -i);
      ids.push_back(w.add_body(def));
      RevoluteJointDef<2> joint;
      joint.body_b = ids.back();
      // (Box2D also joins the static disks of the top row to each other, joints that never act; Wedge
      // refuses a joint between two static bodies.)
      const bool top_static = i == 0 && k > n / 2 - 3 && k <= n / 2 + 3;
      if (i > 0) {
        joint.body_a = ids[ids.size() - 2];
        joint.anchor_a = Vec<2>(0.0, -0.5);
        joint.anchor_b = Vec<2>(0.0, 0.5);
        w.add_joint(joint);
      }
      if (k > 0 && !top_static) {
        joint.body_a = ids[ids.size() - 1 - std::size_t(n)];
        joint.anchor_a = Vec<2>(0.5, 0.0);
        joint.anchor_b = Vec<2>(-0.5, 0.0);
        w.add_joint(joint);
      }
    }
  return w;
}

// Dynamic bodies whose centre moves faster than `speed` (m/s).
template <int N>
int moving_count(const World<N>& w, double speed) {
  int n = 0;
  for (const Body<N>& b : w.bodies()) n += b.is_dynamic() && b.velocity.norm() > speed ? 1 : 0;
  return n;
}

// Largest speed of a body's centre (m/s): how settled a scene is. NaN if a speed is not finite (a
// scene that blew up is not settled).
template <int N>
double max_speed(const World<N>& w) {
  double v = 0.0;
  for (const Body<N>& b : w.bodies()) {
    const double s = b.velocity.norm();
    if (!std::isfinite(s)) return std::nan("");
    v = std::max(v, s);
  }
  return v;
}

}  // namespace wedge::bench
