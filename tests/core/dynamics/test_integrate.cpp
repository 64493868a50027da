// gyroscopic_step (core/src/dynamics/integrate.cpp) against the equation it solves and the invariants of
// torque-free motion: the implicit midpoint step must satisfy I (w' - w) = h m x I m, m = (w + w') / 2,
// to round-off (checked against the residual and against a Newton solve run to convergence here, with
// Eigen's LU), and so keep the energy w.I w and |I w| (the midpoint rule conserves quadratic invariants).
#include <catch2/catch.hpp>

#include <Eigen/LU>
#include <cmath>
#include <random>

#include "dynamics/integrate.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/world.hpp"

using namespace wedge;

namespace {

// The diagonal inertia of a box (I_pq = m (a_p^2 + a_q^2) / 12) with sides from 0.1 to 2 m: moments 60:1 apart.
template <int N>
BivMat<N> box_inertia(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> side(0.1, 2.0);
  Vec<N> a;
  for (int i = 0; i < N; ++i) a[i] = side(rng);
  BivMat<N> inertia = BivMat<N>::Zero();
  for (int p = 0; p < N; ++p)
    for (int q = p + 1; q < N; ++q) {
      const int k = Bivector<N>::index(p, q);
      inertia(k, k) = (a[p] * a[p] + a[q] * a[q]) / 12.0;
    }
  return inertia;
}

template <int N>
Bivector<N> midpoint_residual(const BivMat<N>& inertia, const Bivector<N>& w, const Bivector<N>& w2, double h) {
  const Bivector<N> m = (w + w2) * 0.5;
  return Bivector<N>::from(inertia * (w2 - w).c) - commutator(m, Bivector<N>::from(inertia * m.c)) * h;
}

// The midpoint equation solved by full Newton iterations with a fresh Jacobian each time, until the step is
// round-off: the oracle.
template <int N>
Bivector<N> midpoint_by_newton(const BivMat<N>& inertia, const Bivector<N>& w, double h) {
  Bivector<N> w2 = w;
  for (int i = 0; i < 50; ++i) {
    const Bivector<N> m = (w + w2) * 0.5;
    const Bivector<N> im = Bivector<N>::from(inertia * m.c);
    const BivMat<N> jac = inertia - 0.5 * h * (commutator_matrix(m) * inertia - commutator_matrix(im));
    const Bivector<N> step = Bivector<N>::from(jac.partialPivLu().solve(midpoint_residual<N>(inertia, w, w2, h).c));
    w2 -= step;
    if (step.c.norm() <= 1e-17 * w.c.norm()) break;
  }
  return w2;
}

template <int N>
void check_midpoint() {
  std::mt19937_64 rng(90 + N);
  std::normal_distribution<double> normal;
  int cases = 0;
  for (const double speed : {0.1, 3.0, 20.0, 60.0}) {     // |w|, rad/s
    for (const double h : {1.0 / 960, 1.0 / 480, 1.0 / 60}) {  // a sub-step .. a whole step
      for (int rep = 0; rep < 10; ++rep) {
        const BivMat<N> inertia = box_inertia<N>(rng);
        Bivector<N> w;
        for (int i = 0; i < kBiv<N>; ++i) w[i] = normal(rng);
        w *= speed / w.norm();
        const Bivector<N> w2 = gyroscopic_step<N>(inertia, w, h);
        INFO("N = " << N << ", |w| = " << speed << ", h = " << h << ", w = " << w.c.transpose());
        const double e0 = w.c.dot(inertia * w.c), e1 = w2.c.dot(inertia * w2.c);
        const double l0 = (inertia * w.c).norm(), l1 = (inertia * w2.c).norm();
        CHECK(e1 <= e0 * (1.0 + 1e-15));  // never gains energy (beyond the rounding of the scale back)
        if (speed * h <= 0.05) {  // (h |w| up to 0.05: every sub-step of a body below 48 rad/s, and more)
          // Round-off of the products in the equation: a few ulps of |I w| (the worst seen: 2e-16 relative).
          CHECK(midpoint_residual<N>(inertia, w, w2, h).norm() <= 4e-15 * l0);
          CHECK((w2 - midpoint_by_newton<N>(inertia, w, h)).norm() <= 4e-15 * speed);
          CHECK(e1 >= e0 * (1.0 - 4e-15));
          CHECK(std::abs(l1 - l0) <= 4e-15 * l0);
          ++cases;
        } else {
          // Beyond, the iteration may give way to Newton's two iterations, accurate to their truncation.
          CHECK(std::isfinite(w2.norm()));
          CHECK(std::abs(l1 - l0) <= 0.1 * l0);
        }
      }
    }
  }
  CHECK(cases >= 60);
}

}  // namespace

TEST_CASE("the implicit midpoint gyroscopic step solves its equation to round-off and keeps w.I w and |I w|",
          "[dynamics][gyroscopic]") {
  check_midpoint<3>();
  check_midpoint<4>();
  check_midpoint<5>();
  check_midpoint<6>();
}

TEST_CASE("the gyroscopic step of a full (non-diagonal) inertia is the same rotation of the diagonal one's",
          "[dynamics][gyroscopic]") {
  // The same body seen from a turned frame: I' = A I A^T, w' = A w for the bivector rotation A of a rotor.
  // The full inertia takes Newton's path (two iterations), the diagonal one the fixed-point iteration; the
  // two agree to the Newton iterations' truncation, O((h |w|)^3) relative, here below 1e-9.
  std::mt19937_64 rng(7);
  const BivMat<5> inertia = box_inertia<5>(rng);
  Bivector<5> turn;
  for (int i = 0; i < kBiv<5>; ++i) turn[i] = 0.3 * (i + 1) / kBiv<5>;
  const Rotor<5> r = wedge::exp(turn);
  BivMat<5> a;
  for (int i = 0; i < kBiv<5>; ++i) {
    Bivector<5> e;
    e[i] = 1.0;
    a.col(i) = rotate(r, e).c;
  }
  const BivMat<5> turned = a * inertia * a.transpose();
  Bivector<5> w;
  for (int i = 0; i < kBiv<5>; ++i) w[i] = std::sin(1.0 + i);
  const double h = 1.0 / 480;
  const Bivector<5> diagonal = gyroscopic_step<5>(inertia, w, h);
  const Bivector<5> full = gyroscopic_step<5>(turned, Bivector<5>::from(a * w.c), h);
  CHECK((Bivector<5>::from(a * diagonal.c) - full).norm() <= 1e-9 * w.norm());
  CHECK((full - Bivector<5>::from(a * w.c)).norm() > 1e-4 * w.norm());  // (the step did turn w)
}

// ------------------------------------------------------------------ advance_alone
// dynamics::advance_alone, the soft step's path for a body nothing else acts on within a step, against
// the sub-step loop it replaces, run here step by step: per sub-step integrate_velocity (world-frame w,
// turned to the body frame and back) then advance_body (R <- exp(-h w / 2) R). In exact arithmetic the two
// are the same map (R exp(B) ~R = exp(R B ~R); parallel turns compose to the exp of their sum), so they
// may differ only by rounding: each sub-step rounds the sandwiches and products at about 1e-16 relative,
// and 60 steps of 8 sub-steps carry a few hundred of them through a rotation that neither grows nor
// shrinks errors, so 1e-12 relative on |w|, |R| and the position's travel is a bound with room; a wrong
// frame, order or sign errs by O(h |w|) = 1e-2 at once.
namespace {

template <int N>
Body<N> alone_body(std::mt19937_64& rng, bool isotropic, bool torque, bool drag) {
  std::normal_distribution<double> normal;
  Body<N> b;
  b.mass = 2.0;
  b.inv_mass = 0.5;
  b.inertia = isotropic ? BivMat<N>(0.4 * BivMat<N>::Identity()) : BivMat<N>(2.0 * box_inertia<N>(rng));
  b.inv_inertia = b.inertia.inverse();
  for (int i = 0; i < N; ++i) b.velocity[i] = normal(rng);
  for (int i = 0; i < kBiv<N>; ++i) b.angular_velocity[i] = 3.0 * normal(rng);
  Bivector<N> turn;
  for (int i = 0; i < kBiv<N>; ++i) turn[i] = normal(rng);
  b.rotor = wedge::exp(turn);
  if (torque)
    for (int i = 0; i < kBiv<N>; ++i) b.torque[i] = normal(rng);
  for (int i = 0; i < N; ++i) b.force[i] = normal(rng);
  if (drag) {
    b.linear_drag = 0.3;
    b.angular_drag = 0.7;
  }
  return b;
}

template <int N>
void check_alone(bool isotropic, bool torque, bool drag) {
  std::mt19937_64 rng(300 + N + 10 * isotropic + 20 * torque + 40 * drag);
  const Body<N> start = alone_body<N>(rng, isotropic, torque, drag);
  dynamics::Motion<N> motion;
  motion.gravity = Vec<N>::Zero();
  motion.gravity[1] = -9.81;
  const dynamics::AngularModel<N> model = dynamics::angular_model(start, motion);
  const bool gyroscopic = !isotropic && N > 2;  // (a 2D body turns in one plane: no gyroscopic term)
  REQUIRE(model.body_frame == (torque || gyroscopic));
  const double h = 1.0 / 480;  // 60 Hz in 8 sub-steps
  Body<N> loop = start, alone = start;
  for (int step = 0; step < 60; ++step) {
    for (int k = 0; k < 8; ++k) {
      dynamics::integrate_velocity(loop, model, motion, h, loop.velocity, loop.angular_velocity);
      dynamics::advance_body(loop, loop.velocity, loop.angular_velocity, h, k == 7);
    }
    dynamics::advance_alone(alone, model, motion, h, 8, true, alone.velocity, alone.angular_velocity);
  }
  INFO("N = " << N << ", isotropic " << isotropic << ", torque " << torque << ", drag " << drag);
  const double w = loop.angular_velocity.norm();
  CHECK((alone.angular_velocity - loop.angular_velocity).norm() <= 1e-12 * w);
  CHECK((alone.rotor - loop.rotor).norm() <= 1e-12);
  CHECK((alone.velocity - loop.velocity).norm() <= 1e-12 * loop.velocity.norm());
  CHECK((alone.center - loop.center).norm() <= 1e-12 * (loop.center - start.center).norm());
  // (and both moved: the comparison is not of two bodies at rest)
  CHECK((loop.rotor - start.rotor).norm() > 0.01);
  if (torque || drag || gyroscopic) CHECK((loop.angular_velocity - start.angular_velocity).norm() > 1e-3 * w);
}

}  // namespace

TEST_CASE("a body alone takes its step's sub-steps at once as the sub-step loop would, to round-off",
          "[dynamics][alone]") {
  for (const bool isotropic : {false, true})
    for (const bool torque : {false, true})
      for (const bool drag : {false, true}) {
        check_alone<2>(isotropic, torque, drag);
        check_alone<3>(isotropic, torque, drag);
        check_alone<4>(isotropic, torque, drag);
        check_alone<5>(isotropic, torque, drag);
        check_alone<6>(isotropic, torque, drag);
      }
}
