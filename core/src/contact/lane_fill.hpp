// Writing the soft step's lanes (wide.hpp) one lane at a time (internal): a wide constraint's header
// from its constraints and bodies, and lane l of a slot from one point. find_contacts builds each point
// straight into its lane (build.cpp, build_wide); fill_wide packs points already built as
// PointConstraints (soft_step.cpp; the tests' reference). Both write through these, so the two give
// the same lanes to the bit.
#pragma once

#include "contact/contact_system.hpp"

namespace wedge::contact {

// The tangent mass as the lanes keep it: in 2D along t = tangent_2d(n) alone (wide.hpp), else whole.
template <int N>
typename PointMasses<N>::Tangent lane_tangent_mass(const Mat<N>& tangent_mass, const Vec<N>& normal) {
  if constexpr (N == 2) {
    const Vec<2> t = tangent_2d(normal);
    return t.dot(tangent_mass * t);
  } else {
    return tangent_mass;
  }
}

// What the lanes take of a point's masses, from the point.
template <int N>
PointMasses<N> masses_of(const PointConstraint<N>& x, const Vec<N>& normal) {
  PointMasses<N> m;
  m.normal_mass = x.normal_mass;
  m.jn_a = x.jn_a;
  m.jn_b = x.jn_b;
  m.tangent_mass = lane_tangent_mass(x.tangent_mass, normal);
  return m;
}

// A point as the lanes take it, but for its masses: what find_contacts builds for each point of the
// soft step (build.cpp), and what fill_wide takes of a PointConstraint (lane_point).
template <int N>
struct LanePoint {
  Vec<N> ra = Vec<N>::Zero(), rb = Vec<N>::Zero();  // m
  double separation = 0.0, base_separation = 0.0;     // m
  double approach = 0.0;                              // m/s
  double friction = 0.0;
  bool sliding = false;
  Vec<N> slip_direction = Vec<N>::Zero();
  double normal_impulse = 0.0, normal_total = 0.0;  // N s
  Vec<N> tangent_impulse = Vec<N>::Zero();
};
// What every form of a point (PointConstraint, LanePoint, build.cpp's PointStart) takes from the one
// it is made from when the step begins: lever arms, approach speed and friction.
template <class To, class From>
void copy_point_start(To& to, const From& from) {
  to.ra = from.ra;
  to.rb = from.rb;
  to.approach = from.approach;
  to.friction = from.friction;
  to.sliding = from.sliding;
  to.slip_direction = from.slip_direction;
}
template <int N>
LanePoint<N> lane_point(const PointConstraint<N>& x) {
  LanePoint<N> q;
  copy_point_start(q, x);
  q.separation = x.separation;
  q.base_separation = x.base_separation;
  q.normal_impulse = x.normal_impulse;
  q.normal_total = x.normal_total;
  q.tangent_impulse = x.tangent_impulse;
  return q;
}

// Zeroes the slots of a wide constraint: a lane without a constraint, or past its constraint's points,
// keeps zero in every field (it has no mass and takes no impulse).
template <int N>
void clear_slots(ContactState<N>& s, const WideConstraint<N>& w) {
  for (int k = w.first; k < w.first + w.count; ++k) {
    s.soft.wide_points[k] = WidePoint<N>{};
    s.soft.wide_cold[k] = WidePointCold<N>{};
    s.soft.wide_approach[k] = Wide<N>{};
  }
  if (w.inertia < 0) return;
  WideInertia<N>& m = s.soft.wide_inertia[w.inertia];
  for (int k = 0; k < w.count; ++k)
    for (int i = 0; i < kBiv<N>; ++i) m.dn_a[k][i] = m.dn_b[k][i] = Wide<N>{};
}

// The header's lanes: each lane's normal, and its bodies' inverse masses and inertias (0 for a body that
// does not move), from its Constraint and the solver bodies.
template <int N>
void fill_wide_header(ContactState<N>& s, WideConstraint<N>& w) {
  constexpr int K = kBiv<N>;
  const Constraint<N>* c[kLanes<N>];
  const BodyMass<N>* a[kLanes<N>];
  const BodyMass<N>* b[kLanes<N>];
  for (int l = 0; l < kLanes<N>; ++l) {
    c[l] = w.constraint[l] >= 0 ? &s.graph.constraints[w.constraint[l]] : nullptr;
    a[l] = c[l] && (w.move_a >> l & 1u) ? &s.masses[w.a[l]] : nullptr;
    b[l] = c[l] && (w.move_b >> l & 1u) ? &s.masses[w.b[l]] : nullptr;
  }
  for (int i = 0; i < N; ++i) w.normal[i] = make_wide<Wide<N>>([&](int l) { return c[l] ? c[l]->normal[i] : 0.0; });
  w.inv_mass_a = make_wide<Wide<N>>([&](int l) { return a[l] ? a[l]->inv_mass : 0.0; });
  w.inv_mass_b = make_wide<Wide<N>>([&](int l) { return b[l] ? b[l]->inv_mass : 0.0; });
  w.iso_a = make_wide<Wide<N>>([&](int l) { return a[l] ? a[l]->iso_inv_inertia : 0.0; });
  w.iso_b = make_wide<Wide<N>>([&](int l) { return b[l] ? b[l]->iso_inv_inertia : 0.0; });
  if (w.inertia < 0) return;
  WideInertia<N>& m = s.soft.wide_inertia[w.inertia];
  for (int i = 0; i < K * K; ++i) {
    m.a[i] = make_wide<Wide<N>>([&](int l) { return a[l] ? a[l]->inv_inertia.data()[i] : 0.0; });
    m.b[i] = make_wide<Wide<N>>([&](int l) { return b[l] ? b[l]->inv_inertia.data()[i] : 0.0; });
  }
}

// Lane l of slot k (0-based within w) from a point of the lane's constraint, with normal `normal`, in
// two parts. put_lane_state writes what changes from step to step: separations, approach, friction and
// the warm start. put_lane_masses writes what the masses give: from m, and dn_a and dn_b (I^-1 jn) only
// where the wide constraint keeps them (w.inertia >= 0); in 2D jt from x's lever arms, else the arms.
// A lane kept from the last step (build.cpp, build_wide) takes the first alone. A constraint with fewer
// points than the slots puts a zero point (LanePoint{}) in the slots past its last: in 2D its friction
// fields are then t . 0, as the point's own would be.
template <int N>
[[gnu::always_inline]] inline void put_lane_state(ContactState<N>& s, const WideConstraint<N>& w, int k, int l,
                                                  const Vec<N>& normal, const LanePoint<N>& x) {
  WidePoint<N>& q = s.soft.wide_points[w.first + k];
  WidePointCold<N>& cold = s.soft.wide_cold[w.first + k];
  s.soft.wide_approach[w.first + k].set(l, x.approach);
  q.separation.set(l, x.separation);
  cold.base_separation.set(l, x.base_separation);
  q.normal_impulse.set(l, x.normal_impulse);
  q.normal_total.set(l, x.normal_total);
  q.friction.set(l, x.friction);
  cold.sliding.set(l, x.sliding ? 1.0 : 0.0);
  for (int i = 0; i < N; ++i) cold.slip_direction[i].set(l, x.slip_direction[i]);
  if constexpr (N == 2) {  // friction along t alone (wide.hpp)
    q.tangent_impulse.set(l, x.tangent_impulse.dot(tangent_2d(normal)));
  } else {
    for (int i = 0; i < N; ++i) q.tangent_impulse[i].set(l, x.tangent_impulse[i]);
  }
}
template <int N>
[[gnu::always_inline]] inline void put_lane_masses(ContactState<N>& s, const WideConstraint<N>& w, int k, int l,
                                                   const Vec<N>& normal, const LanePoint<N>& x,
                                                   const PointMasses<N>& m, const typename PointMasses<N>::Biv& dn_a,
                                                   const typename PointMasses<N>::Biv& dn_b) {
  constexpr int K = kBiv<N>;
  WidePoint<N>& q = s.soft.wide_points[w.first + k];
  q.normal_mass.set(l, m.normal_mass);
  for (int i = 0; i < K; ++i) {
    q.jn_a[i].set(l, m.jn_a[i]);
    q.jn_b[i].set(l, m.jn_b[i]);
  }
  if (w.inertia >= 0) {
    WideInertia<N>& in = s.soft.wide_inertia[w.inertia];
    for (int i = 0; i < K; ++i) {
      in.dn_a[k][i].set(l, dn_a[i]);
      in.dn_b[k][i].set(l, dn_b[i]);
    }
  }
  if constexpr (N == 2) {
    q.tangent_mass.set(l, m.tangent_mass);
    q.jt_a.set(l, normal.dot(x.ra));
    q.jt_b.set(l, normal.dot(x.rb));
  } else {
    for (int i = 0; i < N; ++i) {
      q.ra[i].set(l, x.ra[i]);
      q.rb[i].set(l, x.rb[i]);
    }
    for (int i = 0; i < N * N; ++i) q.tangent_mass[i].set(l, m.tangent_mass.data()[i]);
  }
}
template <int N>
[[gnu::always_inline]] inline void put_lane_point(ContactState<N>& s, const WideConstraint<N>& w, int k, int l,
                                                  const Vec<N>& normal, const LanePoint<N>& x,
                                                  const PointMasses<N>& m, const typename PointMasses<N>::Biv& dn_a,
                                                  const typename PointMasses<N>::Biv& dn_b) {
  put_lane_state(s, w, k, l, normal, x);
  put_lane_masses(s, w, k, l, normal, x, m, dn_a, dn_b);
}

// A point at the start of the soft step: the separation to follow through the sub-steps, and the
// warm-start impulses. (P: a PointConstraint, or a LanePoint with the gap as its separation; warm_normal
// and warm_tangent the last step's impulses.)
template <int N, class P>
inline void prepare_point(P& p, const Vec<N>& normal, double gap, bool warm_start, double warm_normal,
                          const Vec<N>& warm_tangent) {
  p.base_separation = gap - normal.dot(p.rb - p.ra);
  p.separation = gap;
  p.normal_impulse = warm_start ? warm_normal : 0.0;
  p.tangent_impulse = warm_start ? warm_tangent : Vec<N>::Zero();
  p.normal_total = 0.0;
}

}  // namespace wedge::contact
