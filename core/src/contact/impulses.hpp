// Impulse helpers shared by the two contact solvers (solver.cpp: the paper's; soft_step.cpp: the soft
// step): applying an impulse at a point, friction in the Coulomb cone, and moving velocities and
// warm-start impulses between the bodies, the solver and the pairs (internal).
#pragma once

#include <cmath>

#include "contact/contact_system.hpp"

namespace wedge::contact {

// The impulse j at the point (lever arms p.ra, p.rb): -j to a, +j to b, each with its masses ma, mb.
template <int N>
void apply_impulse(SolverBody<N>& a, const BodyMass<N>& ma, SolverBody<N>& b, const BodyMass<N>& mb,
                   const PointConstraint<N>& p, const Vec<N>& j) {
  if (!a.frozen) {
    a.v -= ma.inv_mass * j;
    a.w.c -= angular_change(ma, p.ra, j);
  }
  if (!b.frozen) {
    b.v += mb.inv_mass * j;
    b.w.c += angular_change(mb, p.rb, j);
  }
}

// An impulse of `change` along the normal n at a point whose I^-1 jn are dn_a and dn_b.
template <int N, class Biv>
inline void apply_normal_impulse(SolverBody<N>& a, const BodyMass<N>& ma, SolverBody<N>& b, const BodyMass<N>& mb,
                                 const Vec<N>& n, double change, const Biv& dn_a, const Biv& dn_b) {
  if (!a.frozen) {
    a.v -= (ma.inv_mass * change) * n;
    a.w.c -= change * dn_a;
  }
  if (!b.frozen) {
    b.v += (mb.inv_mass * change) * n;
    b.w.c += change * dn_b;
  }
}

// The friction impulse in the cone |j| <= limit nearest to the unconstrained one, j*, in the metric of
// the point's tangential effective mass M = (P K P + n n^T): min (j - j*)^T M (j - j*). This is the exact
// minimiser of the point's share of the kinetic energy, so the passes over the points are block
// coordinate descent and settle where friction holds if any distribution of it over the points can.
// Scaling j* radially instead (the Euclidean projection) is that only when M is isotropic; with 4, 8, 16
// corners of a box on an incline, whose lightly loaded uphill corners saturate first, the radially
// scaled impulses stalled short of the cones' total, and a 4D box slid at 0.95 mu_s.
// KKT: (M + lambda 1) j = M j*, i.e. j(lambda) = (1 + lambda T)^-1 j* with T = M^-1 (tangent_mass), and
// lambda >= 0 where |j(lambda)| = limit: Newton on 1/|j(lambda)| - 1/limit, which is concave and
// increasing, converges from lambda = 0 monotonically (the trust-region secular equation).
// (Compiled once, in cone.cpp: the rare slow path, and its LLT for N = 2..6 had been compiled again in
// every file that includes this one.)
template <int N>
Vec<N> project_to_cone(const Mat<N>& tangent_mass, const Vec<N>& n, const Vec<N>& unconstrained, double limit);

// The friction impulse a point should hold after a pass, given its tangential slip velocity: the
// impulse that stops the slip if it lies in the cone |j_t| <= mu j_n (mu static or kinetic, chosen when
// the step began), else mu j_n against the slip.
// The paper's solver's (soft_step.cpp does the same on its lanes, clamp_to_cones for the slow branch).
// (Forced inline, its rare slow path project_to_cone kept out: called, it spilled the slip to the stack,
// read back as wider loads that stall on the narrower stores they follow.)
template <int N>
[[gnu::always_inline]] inline Vec<N> friction_update(const PointConstraint<N>& p, const Vec<N>& n, const Vec<N>& slip) {
  const Vec<N> old = p.tangent_impulse;
  Vec<N> next = old - p.tangent_mass * slip;
  const double t2 = next.squaredNorm(), limit = p.friction * p.normal_impulse;
  if (t2 > limit * limit) {  // (no square root for the usual point that sticks)
    // Outside the cone. Kinetic friction opposes the slip the point had when the step began
    // (Coulomb; Guendelman et al.). Not the slip left after the last pass: once nearly stopped, that
    // points anywhere, and the full mu_k j_n swinging after it shook piles by 0.1 m/s per pass. A
    // point that was sticking keeps the clamped direction until it slips for real (the clamped
    // sticking impulse does not oppose the slip: K couples the tangent directions through rotation).
    // Once the slip has turned against its first direction, that impulse would push it on and do
    // work: such a point is clamped like a sticking one (in heaps it had kept boxes jittering).
    const bool forward = p.sliding && slip.dot(p.slip_direction) > 0.0;
    next = forward ? Vec<N>(p.slip_direction * -limit) : project_to_cone(p.tangent_mass, n, next, limit);
  }
  return next;
}

template <int N>
void load_velocities(ContactState<N>& s, const std::vector<Body<N>>& bodies) {
  for_each_body(s, int(bodies.size()), [&](int i) {
    s.solver_bodies[i].v = bodies[i].velocity;
    s.solver_bodies[i].w = bodies[i].angular_velocity;
  });
}

// v0, w0 = v, w for every body: what a stage (the paper's solver) or a pass (the soft step) starts from.
template <int N>
void snapshot_velocities(ContactState<N>& s) {
  for_each_body(s, int(s.solver_bodies.size()), [&](int i) {
    SolverBody<N>& b = s.solver_bodies[i];
    b.v0 = b.v;
    b.w0 = b.w;
  });
}

template <int N>
void store_velocities(ContactState<N>& s, std::vector<Body<N>>& bodies) {
  for_each_body(s, int(bodies.size()), [&](int i) {
    if (!bodies[i].is_dynamic() || !s.islands.awake[i]) return;
    bodies[i].velocity = s.solver_bodies[i].v;
    bodies[i].angular_velocity = s.solver_bodies[i].w;
  });
}

// Applies point k's accumulated impulses, normal and friction, to the constraint's solver bodies.
template <int N>
void apply_accumulated_point(ContactState<N>& s, const Constraint<N>& c, int k) {
  const PointConstraint<N>& p = s.paper.points[c.first + k];
  apply_impulse(s.solver_bodies[c.a], s.masses[c.a], s.solver_bodies[c.b], s.masses[c.b], p,
                Vec<N>(p.normal_impulse * c.normal + p.tangent_impulse));
}
// The same for every point of the constraint.
template <int N>
void apply_accumulated(ContactState<N>& s, const Constraint<N>& c) {
  for (int k = 0; k < c.count; ++k) apply_accumulated_point(s, c, k);
}

// Keeps this step's impulses, per feature, to start the next step from (warm start), with the keys
// they are matched by (keep_warm_keys: a point's ra is its pair's arm_a). (The soft step keeps the keys
// as it builds and the impulses as it unpacks its lanes: unpack_lane.)
template <int N>
void keep_for_warm_start(ContactState<N>& s) {
  for_each_constraint(s, [&](const Constraint<N>& c) {
    Pair<N>& pair = s.list.pairs[c.pair];
    keep_warm_keys(pair, c.count);
    for (int k = 0; k < c.count; ++k) {
      const PointConstraint<N>& p = s.paper.points[c.first + k];
      pair.warm_normal[k] = p.normal_impulse;
      pair.warm_tangent[k] = p.tangent_impulse;
    }
  });
}

// Each point's normal impulse over the step, kept in its pair for the events and ContactInfo.
template <int N>
void keep_totals(ContactState<N>& s) {
  for_each_constraint(s, [&](const Constraint<N>& c) {
    Pair<N>& pair = s.list.pairs[c.pair];
    for (int k = 0; k < c.count; ++k) pair.normal_impulse[k] = s.paper.points[c.first + k].normal_total;
  });
}

}  // namespace wedge::contact
