// The torque-free Dzhanibekov study (paper section 9, figure 5): box inertia, the initial conditions of
// every case and the simulation loop, shared by the wedge-dzhanibekov program and tests/apps/dzhanibekov/test_dzhanibekov.cpp
// so that the tests check exactly the runs that the plots show.
//
// Every run is one free box with World<N> (gravity 0, gyroscopic term on, defaults otherwise), starting
// at the identity orientation, so the initial world and body angular velocities coincide. What is
// recorded is the BODY-frame angular velocity ~R w R (the frame in which the Euler equations of section 9
// are written), the kinetic energy and the norm of the world angular momentum bivector |L| = |I' w|.
// See docs/dzhanibekov.md for the reasons behind each number below.
#pragma once

#include <array>
#include <cmath>
#include <initializer_list>
#include <string>
#include <tuple>
#include <vector>

#include "wedge/world.hpp"

namespace wedge::dzhanibekov {

// Body-frame inertia of a solid box of the given side lengths and mass about its centre:
// I_ij = m (a_i^2 + a_j^2) / 12 on the diagonal (component order e01, e02, .., e12, ..).
template <int N>
BivMat<N> box_inertia(const std::array<double, N>& sides, double mass) {
  BivMat<N> inertia = BivMat<N>::Zero();
  for (int i = 0; i < N; ++i)
    for (int j = i + 1; j < N; ++j) {
      const int k = Bivector<N>::index(i, j);
      inertia(k, k) = mass * (sides[i] * sides[i] + sides[j] * sides[j]) / 12.0;
    }
  return inertia;
}

// A body-frame bivector from (i, j, value) triples.
template <int N>
Bivector<N> bivector(std::initializer_list<std::tuple<int, int, double>> parts) {
  Bivector<N> b;
  for (const auto& [i, j, v] : parts) b[Bivector<N>::index(i, j)] += v;
  return b;
}

template <int N>
struct Case {
  std::string id;     // file stem, e.g. "4d_a"
  std::string title;  // plot title
  std::array<double, N> sides{};
  double mass = 1.0;
  Bivector<N> w0;  // initial angular velocity, body frame = world frame at t = 0 (identity rotor)
};

template <int N>
struct Sample {
  double time = 0.0;
  Bivector<N> w_body;
  double energy = 0.0;
  double momentum = 0.0;  // |L|, the norm of the world angular momentum bivector
};

// Runs the case for `duration` seconds with step `dt`, recording a sample every `stride` steps
// (and at t = 0).
// `settings` defaults to gravity 0, gyroscopic term on, rotor repair every step.
template <int N>
std::vector<Sample<N>> simulate(const Case<N>& c, double dt, double duration, int stride = 1,
                                const WorldSettings<N>& settings = {}) {
  World<N> world(settings);
  BodyDef<N> def;
  def.name = c.id;
  def.mass = c.mass;
  def.inertia = box_inertia<N>(c.sides, c.mass);
  def.angular_velocity = c.w0;  // identity rotor: world = body frame at t = 0
  const BodyId id = world.add_body(def);
  const auto steps = static_cast<long long>(std::llround(duration / dt));
  std::vector<Sample<N>> out;
  out.reserve(std::size_t(steps / stride + 2));
  auto record = [&] {
    const Body<N>& b = world.body(id);
    out.push_back(Sample<N>{world.time(), rotate_inverse(b.rotor, b.angular_velocity), world.kinetic_energy(),
                            world.angular_momentum().norm()});
  };
  record();
  for (long long s = 1; s <= steps; ++s) {
    world.step(dt);
    if (s % stride == 0) record();
  }
  return out;
}

// ------------------------------------------------------------------ the cases
// 4D: the cuboid of figure 5, sides (1.1, 0.3, 2.5, 0.7) along x, y, z, w, mass 1. Its plane moments
// (x 1/12): xy 1.30, xz 7.46, xw 1.70, yz 6.34, yw 0.58, zw 6.74.
inline constexpr std::array<double, 4> kCuboid4{1.1, 0.3, 2.5, 0.7};
inline constexpr double kSpin = 5.0;     // rad/s, the main rotation of every case
inline constexpr double kPerturb = 0.05; // rad/s, 1% of the main rotation

// (a) mainly xy, small perturbations in the four planes coupled to xy (xz, xw, yz, yw); zw starts at 0.
inline Case<4> case_4d_a() {
  return {"4d_a", "(a) 4D cuboid: xy rotation, small perturbations in xz, xw, yz, yw", kCuboid4, 1.0,
          bivector<4>({{0, 1, kSpin}, {0, 2, kPerturb}, {0, 3, -kPerturb}, {1, 2, kPerturb}, {1, 3, kPerturb}})};
}
// (b) (a) without the perturbations: the pure xy rotation, read literally. In exact arithmetic this is a
// relative equilibrium (nothing happens), but xy is the intermediate plane of the xyw subspace, so any
// round-off that reaches xw or yw grows like exp(2.7 t). In World none reaches them: every other component
// stays exactly 0, with or without rotor repair (tested). Before 4818c4f the repair leaked round-off into
// xw and yw and the motion of (a) developed after ~12 s. See docs/dzhanibekov.md.
inline Case<4> case_4d_b() {
  return {"4d_b", "(b) 4D cuboid: pure xy rotation (perturbations removed)", kCuboid4, 1.0,
          bivector<4>({{0, 1, kSpin}})};
}
// (c) the 3D subspace yzw (every plane containing x at 0, i.e. c = x in the paper's notation): its plane
// moments are yw 0.58 < yz 6.34 < zw 6.74 (x 1/12), so yz is intermediate. Spin in yz, perturb yw and zw
// (inside the subspace). The xy, xz, xw components then stay exactly 0 in World (tested).
inline Case<4> case_4d_c() {
  return {"4d_c", "(c) 4D cuboid: yz rotation (intermediate in the yzw subspace), perturbation inside yzw",
          kCuboid4, 1.0, bivector<4>({{1, 2, kSpin}, {1, 3, kPerturb}, {2, 3, kPerturb}})};
}
// (d) (c) plus a perturbation out of the subspace, in the three planes containing x. yz is also the
// intermediate plane of xyz (xy 1.30 < yz 6.34 < xz 7.46), so this perturbation grows as well.
inline Case<4> case_4d_d() {
  return {"4d_d", "(d) 4D cuboid: case (c) plus a perturbation in xy, xz, xw", kCuboid4, 1.0,
          bivector<4>({{1, 2, kSpin}, {1, 3, kPerturb}, {2, 3, kPerturb}, {0, 1, kPerturb}, {0, 2, kPerturb},
                       {0, 3, kPerturb}})};
}
// Supplement to (c): the same yz spin in the xyz subspace (c = w), perturbed inside xyz. Also exactly 3D:
// xw, yw, zw stay exactly 0 in World, with or without rotor repair (tested), and yz flips as in 3D. Before
// 4818c4f the repair leaked round-off (1e-16) into xw, yw, zw, and since yz is intermediate in yzw too, the
// leak grew to O(1) within ~9 s.
inline Case<4> case_4d_c_xyz() {
  return {"4d_c_xyz", "(c') 4D cuboid: yz rotation in the xyz subspace, perturbation inside xyz", kCuboid4, 1.0,
          bivector<4>({{1, 2, kSpin}, {0, 1, kPerturb}, {0, 2, kPerturb}})};
}

// 3D: a box of sides (1, 2, 3), mass 1: plane moments xy 5/12 < xz 10/12 < yz 13/12, so the xz plane
// (rotation about the y axis) is intermediate. Spun in xz with a 1e-3 relative perturbation.
inline constexpr std::array<double, 3> kBox3{1.0, 2.0, 3.0};
inline Case<3> case_3d_flip() {
  return {"3d_flip", "3D box (1, 2, 3): spin in the intermediate plane xz, 1e-3 perturbation", kBox3, 1.0,
          bivector<3>({{0, 2, kSpin}, {0, 1, 1e-3 * kSpin}, {1, 2, 1e-3 * kSpin}})};
}
// The stable 3D rotations (used by the tests): smallest (xy) and largest (yz) moment planes.
inline Case<3> case_3d_stable_small() {
  return {"3d_small", "3D box (1, 2, 3): spin in xy (smallest moment)", kBox3, 1.0,
          bivector<3>({{0, 1, kSpin}, {0, 2, 1e-2 * kSpin}, {1, 2, 1e-2 * kSpin}})};
}
inline Case<3> case_3d_stable_large() {
  return {"3d_large", "3D box (1, 2, 3): spin in yz (largest moment)", kBox3, 1.0,
          bivector<3>({{1, 2, kSpin}, {0, 1, 1e-2 * kSpin}, {0, 2, 1e-2 * kSpin}})};
}

}  // namespace wedge::dzhanibekov
