// The bodies as the contact solvers see them (internal): velocities and the soft step's per-sub-step
// state (SolverBody), masses (BodyMass), the paper solver's extra state (PaperBody), and the algebra of
// an impulse on a body.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "wedge/body.hpp"
#include "wedge/ga/products.hpp"

namespace wedge::contact {

// A body's velocities as the solvers see them, and for the soft step what its sub-steps integrate and
// how far it has moved: all that the soft step's sweeps over the bodies touch, and nothing else (its
// masses are in BodyMass, the paper's solver's pseudo velocities and levels in PaperBody). What the
// sweeps read most comes first: the passes gather v and w, the sweeps between them these and the warm
// start, the snapshot and the velocity integration.
template <int N>
struct alignas(64) SolverBody {
  Vec<N> v = Vec<N>::Zero();
  Bivector<N> w{};
  bool frozen = false;  // infinite mass for the current shock-propagation level (soft step: does not move)
  bool integrates = false;  // moves, with neither a torque nor a gyroscopic term (else it is apart)
  bool advances = false;    // not static and awake: the soft step's position update moves it
  bool apart = false;       // soft step: moves, and integrate_velocities_apart integrates its velocities
  // Soft step: advances, and no constraint or grab uses it this step: integrate_alone takes it through
  // every sub-step at once (its advances, integrates and apart are false through the sub-steps).
  bool alone = false;
  // Soft step: the velocity change that the contacts' accumulated impulses make, the warm start of the
  // next sub-step (soft_step.cpp, warm_start_substep).
  Vec<N> warm_v = Vec<N>::Zero();
  Bivector<N> warm_w{};
  Vec<N> v0 = Vec<N>::Zero();  // velocities before the stage (its energy check) or soft-step pass
  Bivector<N> w0{};
  // Soft step: a sub-step's velocity integration, the same for each of the step's sub-steps
  // (prepare_soft_step, integrate_substep_velocity): v = (v + dv) decay_v, w = w decay_w, where integrates.
  Vec<N> dv = Vec<N>::Zero();
  double decay_v = 1.0, decay_w = 1.0;
  // Then what the position update reads and writes of it (integrate_substep_positions).
  // Soft step: where the body was when the step began, and how far it has moved and turned since
  // (the turn as a matrix, dq = R R0^-1), so the sub-steps see each contact's current separation.
  Vec<N> x0 = Vec<N>::Zero();
  Mat<N> r0_inverse = Mat<N>::Identity();
  Vec<N> dp = Vec<N>::Zero();
  Mat<N> dq = Mat<N>::Identity();
};

// A body's inverse mass and inertia in this step (load_solver_bodies, build.cpp), 0 for one that does
// not move: what forming effective masses and applying impulses outside the soft step's lanes read
// (ContactState::masses).
template <int N>
struct BodyMass {
  double inv_mass = 0.0;
  // The inverse inertia is iso_inv_inertia times the identity in every frame (a body whose inertia is
  // the same about every plane: a cube, a ball). The impulse passes then scale r ^ j instead of
  // multiplying it by the matrix, and inv_inertia is that exactly.
  bool isotropic = false;
  double iso_inv_inertia = 0.0;
  BivMat<N> inv_inertia = BivMat<N>::Zero();  // world frame
  // A non-isotropic body's inv_inertia is turned into the world frame only if a constraint or a grab
  // uses it this step (load_world_inertias): until then it is stale.
  bool world_pending = false;
};

// What the paper's solver keeps of a body beside its SolverBody (PaperSolver::bodies).
template <int N>
struct PaperBody {
  Vec<N> vp = Vec<N>::Zero();  // pseudo velocity (split impulse): moves the position this step, then is dropped
  Bivector<N> wp{};
  int level = 0;               // contact-graph level (shock propagation)
  std::uint64_t moved = 0;     // shock propagation: the visit that last changed its velocity beyond tolerance
};

// I^-1 t for a bivector t (world frame): a scale for an isotropic body.
template <int N>
inline Eigen::Matrix<double, kBiv<N>, 1> inverse_inertia_times(const BodyMass<N>& b,
                                                               const Eigen::Matrix<double, kBiv<N>, 1>& t) {
  if (b.isotropic) return b.iso_inv_inertia * t;
  return b.inv_inertia * t;
}
// The change of the body's angular velocity per impulse j at lever arm r: I^-1 (r ^ j). Formed here
// rather than kept per point as the k x N matrix I^-1 [r]_*, which would be most of a point's size;
// for an isotropic body it is a scale.
template <int N>
inline Eigen::Matrix<double, kBiv<N>, 1> angular_change(const BodyMass<N>& b, const Vec<N>& r, const Vec<N>& j) {
  return inverse_inertia_times(b, outer<N>(r, j).c);
}

// The body's part of K = delta/m + [r]_*^T I^-1 [r]_* without the 1/m: [r]_*^T I^-1 [r]_*, which for an
// isotropic body is s (|r|^2 1 - r r^T) (r . (r ^ a) = |r|^2 a - (r . a) r).
template <int N>
inline Mat<N> angular_mass_term(const BodyMass<N>& b, const Vec<N>& r) {
  if (b.isotropic) return b.iso_inv_inertia * (r.squaredNorm() * Mat<N>::Identity() - r * r.transpose());
  const WedgeMat<N> jr = wedge_matrix<N>(r);
  return jr.transpose() * (b.inv_inertia * jr);
}

// Relative velocity of b with respect to a at the point: (v_b + r_b . w_b) - (v_a + r_a . w_a).
template <int N, class P>  // (P: a PointConstraint, or anything with its lever arms ra, rb)
inline Vec<N> relative_velocity(const SolverBody<N>& a, const SolverBody<N>& b, const P& p) {
  return b.v + dot<N>(p.rb, b.w) - a.v - dot<N>(p.ra, a.w);
}

}  // namespace wedge::contact
