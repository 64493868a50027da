// The step's contact constraints (internal): a constraint per pair with points, its points in the paper
// solver's form (PointConstraint) and the masses the soft step keeps (PointMasses), the grabs' slots, and
// the constraint graph's state (constraint_graph.cpp places the constraints, build.cpp builds them).
#pragma once

#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "linalg/fixed_size.hpp"  // set_effective_masses: the tangent mass
#include "wedge/body.hpp"
#include "wedge/collision/manifold.hpp"
#include "wedge/grab.hpp"

namespace wedge::contact {

// One contact point: lever arms, what it needs of K = delta/m + [r]_*^T I^-1 [r]_* (summed over the
// bodies that can move), the effective masses along the normal and in the tangent space, and the
// accumulated impulses of the current stage.
template <int N>
struct PointConstraint {
  // (The soft step builds no PointConstraints: its points go straight into the lanes, wide.hpp and
  // build_wide in build.cpp; fill_wide packs these the same way, for the tests. After the last
  // sub-step the lanes' impulses go to the pairs: unpack_wide.)
  double separation = 0.0;       // m, soft step: the separation when the step began (the lanes follow it)
  double normal_mass = 0.0;      // 1 / (n^T K n), of the bodies that can move
  double normal_impulse = 0.0;   // N s, accumulated in the current stage
  double normal_total = 0.0;     // N s, over all stages (events, ContactInfo)
  // Soft step: the normal's rows of the Jacobian, n . (r . w) = jn . w, and the angular velocity change
  // per unit normal impulse, I^-1 jn (the normal passes need no more of ra, rb; restitution reads them;
  // the lanes keep I^-1 jn only for non-isotropic bodies, and form it from jn for the rest).
  Eigen::Matrix<double, kBiv<N>, 1> jn_a = Eigen::Matrix<double, kBiv<N>, 1>::Zero(), jn_b = jn_a, dn_a = jn_a,
                                    dn_b = jn_a;
  // Friction (and both passes of the paper's solver).
  double friction = 0.0;  // the coefficient in use: static if the point was not slipping at the start
  bool sliding = false;   // it was slipping: kinetic friction, against the slip
  Vec<N> tangent_impulse = Vec<N>::Zero();          // N s, accumulated in the current stage
  Vec<N> slip_direction = Vec<N>::Zero();  // unit, the tangential slip when the step began (if sliding)
  Vec<N> ra = Vec<N>::Zero(), rb = Vec<N>::Zero();  // m, from the centres of mass
  // (P K P + n n^T)^-1 with P = 1 - n n^T: maps a tangential velocity change to the tangential impulse
  // that makes it (of the pair, or of the unfrozen body during shock propagation).
  Mat<N> tangent_mass = Mat<N>::Zero();
  // K n, of the bodies that can move (the pair's, or the unfrozen body's in shock propagation): how a
  // friction impulse j_t changes the normal velocity, n . K j_t = (K n) . j_t.
  Vec<N> kn = Vec<N>::Zero();
  double gap = 0.0;                                 // m, -depth at the start of the step
  double approach = 0.0;                            // m/s, normal velocity at the start (< 0 closing)
  double warm_normal = 0.0;                         // N s, last step's contact-stage impulses (warm start)
  Vec<N> warm_tangent = Vec<N>::Zero();
  double base_separation = 0.0;  // m, soft step: gap - n . (rb - ra), so that the current separation is
                                 // base + n . (dp_b + dq_b rb - dp_a - dq_a ra)
  double pseudo = 0.0;                              // split impulse along the normal
  double pseudo_mass = 0.0;                         // 1 / (n^T K n) of the pair (kept through shock propagation)
};

// What the soft step's lanes take of a point's effective masses and Jacobian (the rest of its lanes come
// from its LanePoint, lane_fill.hpp): formed from K, or, for a recycled pair of isotropic bodies, the last step's
// (SoftSolver::point_masses, Pair::points_first and built). 2D keeps the tangent mass along t alone (wide.hpp).
template <int N>
struct PointMasses {
  using Biv = Eigen::Matrix<double, kBiv<N>, 1>;
  using Tangent = std::conditional_t<N == 2, double, Mat<N>>;
  double normal_mass = 0.0;
  Biv jn_a = Biv::Zero(), jn_b = Biv::Zero();
  Tangent tangent_mass = zero_tangent();

 private:
  static Tangent zero_tangent() {
    if constexpr (N == 2) {
      return 0.0;
    } else {
      return Mat<N>::Zero();
    }
  }
};

// The effective masses of K for a contact with normal n.
// A point whose K is not finite and positive (a lever arm from a broken manifold point) gets zero
// effective masses, so it never receives an impulse instead of turning the bodies' velocities to NaN.
// (P: a PointConstraint, or anything with its kn, normal_mass and tangent_mass.)
template <int N, class P>
inline void set_effective_masses(P& p, const Mat<N>& k, const Vec<N>& n) {
  p.kn = k * n;
  p.normal_mass = 1.0 / n.dot(p.kn);
  const Mat<N> proj = Mat<N>::Identity() - n * n.transpose();
  p.tangent_mass = linalg::inverse<N>(Mat<N>(proj * k * proj + n * n.transpose()));
  if (!(std::isfinite(p.normal_mass) && p.normal_mass >= 0.0) || !all_finite(p.tangent_mass)) {
    p.normal_mass = 0.0;
    p.tangent_mass.setZero();
    p.kn.setZero();
  }
}

template <int N>
struct Constraint {
  int pair = 0;   // index into pairs
  int a = 0, b = 0;
  Vec<N> normal = Vec<N>::Zero();
  double friction = 0.0, kinetic_friction = 0.0, restitution = 0.0;
  int first = 0, count = 0;  // points[first .. first + count)
  int level = 0;             // max of the bodies' levels (shock propagation order)
  std::uint64_t shock_tick = 0;  // shock propagation: its last visit (see SolverBody::moved)
  double shock_change = 0.0;     // m/s, the largest normal velocity change of that visit
};

// A grab slot: the definition, and what the current step derived from it (see wedge/grab.hpp).
template <int N>
struct GrabConstraint {
  GrabDef<N> def;
  std::uint32_t generation = 0;
  bool live = false;
  bool active = false;                       // live, on an awake dynamic body, in this step
  double inv_mass = 0.0;                     // 1/kg, the body's in this step
  Vec<N> r = Vec<N>::Zero();                 // m, grab point from the centre of mass (world)
  Eigen::Matrix<double, kBiv<N>, N> w = Eigen::Matrix<double, kBiv<N>, N>::Zero();  // I'^-1 [r]_*
  Mat<N> mass = Mat<N>::Zero();              // K^-1
  Vec<N> bias = Vec<N>::Zero();              // m/s, bias_rate C
  double mass_scale = 0.0, impulse_scale = 0.0, max_impulse = 0.0;
  Vec<N> impulse = Vec<N>::Zero();           // N s, accumulated (kept between steps: warm start)
};

// The step's constraints (constraint_graph.cpp places them, build.cpp builds them): in pair order (the
// paper's solver) or colour order (soft step).
template <int N>
struct ConstraintGraph {
  std::vector<Constraint<N>> constraints;
  std::vector<int> constraint_pairs;         // the pairs that make them, in that order
  std::vector<std::uint32_t> colour_mask;    // per body: the colours its constraints took this step
  std::vector<int> colour_of, colour_order;  // colouring scratch (colour_order: the seeds in colour order)
  // Per constraint-to-be, in pair order: what colouring and placing its points need of its pair, read in
  // the one sweep over the pairs that finds them (the pairs are large, and read in colour order each
  // of their lines is a cache miss).
  // Colouring and the lanes are a function of the seeds alone (with which moving bodies are isotropic),
  // so a step whose seeds are the last step's keeps the last step's colours and lanes (graph_kept).
  struct Seed {
    int pair = 0;
    std::uint32_t a = 0, b = 0;
    int count = 0;
    bool move_a = false, move_b = false;
    bool iso_a = true, iso_b = true;  // the body is isotropic, or does not move
  };
  std::vector<Seed> seeds, previous_seeds;
  bool graph_kept = false;  // this step's constraints, colours and lanes are placed as the last step's
  // Soft step: where each colour's constraints begin, the uncoloured group's last, then the end (empty
  // for the paper's solver, whose constraints are in pair order).
  std::vector<int> colour_start;
  bool built_soft = false;   // the last step's constraints were the soft step's (previous_masses is theirs)
  std::uint64_t builds = 0;  // the builds so far, this step's included (Pair::built)
};

}  // namespace wedge::contact
