// The constraint build: the solver bodies loaded from the bodies, then each constraint's points from
// its pair's manifold: lever arms, gap, approach speed, friction, the warm start matched to the last
// step's points, and the effective masses (formed, or kept from the last step for a recycled pair).
// The paper's solver keeps them as PointConstraints; the soft step writes them straight into its lanes.
#include <algorithm>
#include <type_traits>

#include <Eigen/LU>

#include "contact/contact_system.hpp"
#include "contact/lane_fill.hpp"
#include "linalg/isotropic.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::contact {

namespace {

// Which of the last step's points each new point continues (-1: none): the one with the same feature
// id, else the nearest one within `distance` (m) that no other point continues. Ids change when the
// narrow phase swaps the reference face between two equal boxes, say, but the points stay put.
template <int N>
void warm_matches(const Pair<N>& p, const Vec<N>& centre_a, double distance,
                  std::array<int, kMaxManifoldPoints<N>>& match) {
  // (The usual case first, the last step's ids in the same order, as a recycled manifold keeps them:
  // each point continues its own, which is what the search below finds for them.)
  int same = 0;
  if (p.warm_count == p.manifold.count)
    while (same < p.manifold.count && p.warm_id[same] == p.manifold.points[same].id) ++same;
  if (same == p.manifold.count && same == p.warm_count) {
    for (int k = 0; k < same; ++k) match[k] = k;
    return;
  }
  std::uint64_t taken = 0;  // bit w: old point w is continued (kMaxManifoldPoints <= 32)
  for (int k = 0; k < p.manifold.count; ++k) {
    match[k] = -1;
    for (int w = 0; w < p.warm_count; ++w)
      if (p.warm_id[w] == p.manifold.points[k].id && !(taken >> w & 1u)) {
        match[k] = w;
        taken |= std::uint64_t{1} << w;
        break;
      }
  }
  for (int k = 0; k < p.manifold.count; ++k) {
    if (match[k] >= 0) continue;
    const Vec<N> arm = p.manifold.points[k].point - centre_a;  // as warm_arm: from a's centre
    double best = distance * distance;
    for (int w = 0; w < p.warm_count; ++w) {
      const double d2 = (p.warm_arm[w] - arm).squaredNorm();
      if (!(taken >> w & 1u) && d2 < best) {
        best = d2;
        match[k] = w;
      }
    }
    if (match[k] >= 0) taken |= std::uint64_t{1} << match[k];
  }
}

// The constraint of pair pi, its points from `first` on: its bodies, normal and materials.
template <int N>
Constraint<N> make_constraint(const ContactState<N>& s, const std::vector<Material>& materials, int pi, int first) {
  const Pair<N>& p = s.list.pairs[pi];
  Constraint<N> c;
  c.first = first;
  c.pair = pi;
  c.a = int(p.a);
  c.b = int(p.b);
  c.normal = p.manifold.normal;
  const Material& ma = materials[p.a];
  const Material& mb = materials[p.b];
  c.friction = mix_friction(ma.friction, mb.friction);
  c.kinetic_friction = std::min(mix_friction(ma.kinetic_friction, mb.kinetic_friction), c.friction);
  c.restitution = mix_restitution(ma.restitution, mb.restitution);
  c.count = p.manifold.count;
  return c;
}

// Where pair p's points were in the last step's build, or -1 (read before this step's build writes them).
template <int N>
int last_first(const ContactState<N>& s, const Pair<N>& p) {
  return p.built + 1 == s.graph.builds ? p.points_first : -1;
}
// The bodies' 1/m and isotropic 1/I, which a recycled pair's masses were formed with (Pair::mass_key).
template <int N>
std::array<double, 4> mass_key(const BodyMass<N>& a, const BodyMass<N>& b) {
  return {a.inv_mass, a.iso_inv_inertia, b.inv_mass, b.iso_inv_inertia};
}
// Where in the last step's masses pair p's points may take theirs from, or -1: a recycled manifold
// keeps its normal and lever arms, and with isotropic bodies of the same masses the effective masses
// and Jacobian rows are then those of the last step, to the bit (the same function of the same
// numbers): copied rather than formed again.
template <int N>
int recycled_masses(const ContactState<N>& s, const Pair<N>& p, const BodyMass<N>& a, const BodyMass<N>& b) {
  if (!(s.graph.built_soft && p.recycled && a.isotropic && b.isotropic && mass_key(a, b) == p.mass_key)) return -1;
  return last_first(s, p);
}

// Point k of constraint c, all but its masses: lever arms, gap, approach speed, friction (static if the
// point was not slipping at the start of the step, else kinetic, against the slip) and the warm start
// from the last step's point w (-1: none).
template <int N>
struct PointStart {
  Vec<N> ra, rb;           // m
  double gap, approach;    // m, m/s
  double friction;
  bool sliding;
  Vec<N> slip_direction;   // unit, or 0 if not sliding
  double warm_normal;      // N s
  Vec<N> warm_tangent;
};
template <int N>
[[gnu::always_inline]] inline PointStart<N> make_point(const ContactState<N>& s, const Pair<N>& p,
                                                       const Constraint<N>& c, int k, int w, double slip_speed) {
  PointStart<N> q;
  q.ra = p.arm_a[k];
  q.rb = p.arm_b[k];
  q.gap = -p.manifold.points[k].depth;
  const Vec<N> u = relative_velocity(s.solver_bodies[c.a], s.solver_bodies[c.b], q);
  q.approach = c.normal.dot(u);
  const Vec<N> slip = u - q.approach * c.normal;
  // (|slip| > slip_speed, its square root taken only where it may be: sqrt is monotonic and correctly
  // rounded, so below a bound a little under slip_speed^2 the answer is no, to the bit.)
  const double slip2 = slip.squaredNorm();
  q.sliding = false;
  q.slip_direction.setZero();
  if (slip2 > slip_speed * slip_speed * (1.0 - 1e-9)) {
    const double slip_norm = std::sqrt(slip2);
    q.sliding = slip_norm > slip_speed;
    if (q.sliding) q.slip_direction = slip / slip_norm;
  }
  q.friction = q.sliding ? c.kinetic_friction : c.friction;
  q.warm_normal = 0.0;
  q.warm_tangent.setZero();
  if (w >= 0) {
    q.warm_normal = p.warm_normal[w];
    q.warm_tangent = p.warm_tangent[w] - p.warm_tangent[w].dot(c.normal) * c.normal;
  }
  return q;
}

// K = delta/m + [r]_*^T I^-1 [r]_* of the point's two bodies (paper section 6), with lever arms ra, rb.
template <int N>
Mat<N> point_k(const BodyMass<N>& a, const BodyMass<N>& b, const Vec<N>& ra, const Vec<N>& rb) {
  return (a.inv_mass + b.inv_mass) * Mat<N>::Identity() + angular_mass_term(a, ra) + angular_mass_term(b, rb);
}

// What the constraint of pair p leaves in it: where its points are, how fast they approached (events),
// and the masses' key.
template <int N>
void note_constraint(Pair<N>& p, const BodyMass<N>& a, const BodyMass<N>& b, int index, int first,
                     double approach_speed, std::uint64_t builds) {
  p.constraint = index;
  p.approach_speed = approach_speed;
  p.points_first = first;
  p.built = builds;
  p.mass_key = mass_key(a, b);
  // (Its impulses until the step's end writes them: 0 past its last point, as for a pair without one.)
  p.normal_impulse.fill(0.0);
}

// The paper's solver: the constraint of pair pi, as constraints[index], its points as points[first] on.
// (Its manifolds are never recycled, collide_pair, so its masses are always formed.)
template <int N>
void build_constraint(ContactState<N>& s, const std::vector<Body<N>>& bodies, const std::vector<Material>& materials,
                      double slip_speed, double match_distance, int pi, int index, int first) {
  Pair<N>& p = s.list.pairs[pi];
  const Constraint<N> c = make_constraint(s, materials, pi, first);
  const BodyMass<N>& sa = s.masses[c.a];
  const BodyMass<N>& sb = s.masses[c.b];
  std::array<int, kMaxManifoldPoints<N>> match;
  warm_matches(p, bodies[c.a].center, match_distance, match);
  double approach_speed = 0.0;
  for (int k = 0; k < c.count; ++k) {
    const PointStart<N> x = make_point(s, p, c, k, match[k], slip_speed);
    approach_speed = std::max(approach_speed, -x.approach);
    // (The array is not cleared and value-initialised each step: that was one more sweep over it.)
    PointConstraint<N>& q = s.paper.points[c.first + k];
    q = PointConstraint<N>{};
    copy_point_start(q, x);
    q.gap = x.gap;
    q.warm_normal = x.warm_normal;
    q.warm_tangent = x.warm_tangent;
    set_effective_masses(q, point_k(sa, sb, q.ra, q.rb), c.normal);
    q.jn_a = outer<N>(q.ra, c.normal).c;
    q.jn_b = outer<N>(q.rb, c.normal).c;
    q.dn_a = inverse_inertia_times(sa, q.jn_a);
    q.dn_b = inverse_inertia_times(sb, q.jn_b);
    q.pseudo_mass = q.normal_mass;
  }
  note_constraint(p, sa, sb, index, first, approach_speed, s.graph.builds);
  s.graph.constraints[index] = c;
}

// The masses of a soft step point with lever arms ra, rb, formed (build_constraint's formulas).
template <int N>
PointMasses<N> form_point_masses(const BodyMass<N>& a, const BodyMass<N>& b, const Vec<N>& ra, const Vec<N>& rb,
                                 const Vec<N>& normal) {
  struct {
    Vec<N> kn;
    double normal_mass;
    Mat<N> tangent_mass;
  } formed;
  set_effective_masses(formed, point_k(a, b, ra, rb), normal);
  PointMasses<N> m;
  m.normal_mass = formed.normal_mass;
  m.tangent_mass = lane_tangent_mass(formed.tangent_mass, normal);
  m.jn_a = outer<N>(ra, normal).c;
  m.jn_b = outer<N>(rb, normal).c;
  return m;
}

// The soft step: the constraints of wide constraint w, each point built, prepared and written straight
// into its lane (no PointConstraint is kept: writing 272 bytes a 2D point and reading them back to pack
// the lanes, and reading the last step's for the recycled masses, was most of the build). A recycled
// pair's masses come from the last step's point_masses, and this step's are kept there.
// Where the graph is kept (ConstraintGraph::graph_kept) each lane of a full wide constraint holds the same
// pair as in the last step, and a recycled pair's lane already holds its masses, Jacobian rows and
// normal (nothing in the sub-steps writes them): only what changes from step to step is written, and
// the header only where some lane's masses changed. (Half of a resting pyramid's build.)
template <int N>
void build_wide(ContactState<N>& s, const std::vector<Body<N>>& bodies, const std::vector<Material>& materials,
                const ContactSettings& settings, WideConstraint<N>& w) {
  using Biv = typename PointMasses<N>::Biv;
  // (With the graph kept a constraint is the last step's pair, bodies and points, and its materials,
  // which are fixed per body (World has no setter): only the normal of a pair collided afresh is new.)
  for (int l = 0; l < kLanes<N>; ++l) {
    const int index = w.constraint[l];
    if (index < 0) continue;
    Constraint<N>& c = s.graph.constraints[index];
    if (s.graph.graph_kept)
      c.normal = s.list.pairs[c.pair].manifold.normal;
    else
      c = make_constraint(s, materials, s.graph.constraint_pairs[index], c.first);
  }
  // (Every field of an occupied lane is written below, so the slots are cleared first only where a
  // lane is empty: the last wide constraint of a colour, and the uncoloured group's.)
  bool full = true;
  for (int l = 0; l < kLanes<N>; ++l) full = full && w.constraint[l] >= 0;
  if (!full) clear_slots(s, w);
  // The last step's masses: where this step's go when the graph is kept (the same places), else the
  // other buffer (build_constraints).
  const std::vector<PointMasses<N>>& previous = s.graph.graph_kept ? s.soft.point_masses : s.soft.previous_masses;
  const PointMasses<N>* last[kLanes<N>];
  bool header_kept = s.graph.graph_kept && full && w.inertia < 0;
  for (int l = 0; l < kLanes<N>; ++l) {
    last[l] = nullptr;
    if (w.constraint[l] < 0) continue;
    const Constraint<N>& c = s.graph.constraints[w.constraint[l]];
    const Pair<N>& p = s.list.pairs[c.pair];
    const int first = recycled_masses(s, p, s.masses[c.a], s.masses[c.b]);
    if (first >= 0) last[l] = &previous[first];
    header_kept = header_kept && last[l];
  }
  if (!header_kept) fill_wide_header(s, w);
  const bool inertia = w.inertia >= 0;
  static const LanePoint<N> none{};
  for (int l = 0; l < kLanes<N>; ++l) {
    if (w.constraint[l] < 0) continue;
    const Constraint<N>& c = s.graph.constraints[w.constraint[l]];
    Pair<N>& p = s.list.pairs[c.pair];
    const BodyMass<N>& sa = s.masses[c.a];
    const BodyMass<N>& sb = s.masses[c.b];
    std::array<int, kMaxManifoldPoints<N>> match;
    warm_matches(p, bodies[c.a].center, settings.contact_margin, match);
    keep_warm_keys(p, c.count);  // (matched: the next step's keys now)
    const bool lane_kept = s.graph.graph_kept && full && !inertia && last[l];
    double approach_speed = 0.0;
    for (int k = 0; k < c.count; ++k) {
      const PointStart<N> x = make_point(s, p, c, k, match[k], settings.static_slip_speed);
      approach_speed = std::max(approach_speed, -x.approach);
      LanePoint<N> q;
      copy_point_start(q, x);
      prepare_point(q, c.normal, x.gap, settings.warm_start, x.warm_normal, x.warm_tangent);
      put_lane_state(s, w, k, l, c.normal, q);
      if (lane_kept) continue;  // (its masses are in point_masses and in the lane)
      PointMasses<N>& m = s.soft.point_masses[c.first + k];
      m = last[l] ? last[l][k] : form_point_masses(sa, sb, x.ra, x.rb, c.normal);
      const Biv dn_a = inertia ? Biv(inverse_inertia_times(sa, m.jn_a)) : Biv::Zero();
      const Biv dn_b = inertia ? Biv(inverse_inertia_times(sb, m.jn_b)) : Biv::Zero();
      put_lane_masses(s, w, k, l, c.normal, q, m, dn_a, dn_b);
    }
    // (Past its last point, zero points, as fill_wide's: in 2D their friction fields are t . 0.)
    if (c.count < w.count) {
      PointMasses<N> pad;
      pad.tangent_mass = lane_tangent_mass(Mat<N>(Mat<N>::Zero()), c.normal);
      const Biv zero = Biv::Zero();
      for (int k = c.count; k < w.count; ++k) put_lane_point(s, w, k, l, c.normal, none, pad, zero, zero);
    }
    note_constraint(p, sa, sb, w.constraint[l], c.first, approach_speed, s.graph.builds);
  }
}

}  // namespace

// Before the step's first stage: inverse world inertia of every awake dynamic body, and velocities.
// The soft step freezes the bodies that do not move: they are only read (writing their unchanged
// velocities would chain every contact with the ground through one memory location, and two workers
// through one cache line). Shock propagation freezes bodies level by level instead.
template <int N>
void load_solver_bodies(ContactState<N>& s, const std::vector<Body<N>>& bodies, bool soft) {
  s.paper.bodies.assign(soft ? 0 : bodies.size(), PaperBody<N>{});
  for_each_body(s, int(bodies.size()), [&](int i) {
    const Body<N>& b = bodies[i];
    SolverBody<N>& sb = s.solver_bodies[i];
    sb.v = b.velocity;
    sb.w = b.angular_velocity;
    sb.frozen = soft && !moves(s, bodies, i);
    sb.advances = b.type != BodyType::Static && s.islands.awake[i];
    BodyMass<N>& m = s.masses[i];
    if (moves(s, bodies, i)) {
      m.inv_mass = b.inv_mass;
      m.isotropic = linalg::is_isotropic(b.inv_inertia);
      m.iso_inv_inertia = b.inv_inertia(0, 0);
      m.world_pending = !m.isotropic;  // (load_world_inertias, for the bodies constraints use)
      if (m.isotropic) m.inv_inertia = m.iso_inv_inertia * BivMat<N>::Identity();  // (turning it changes nothing)
    } else {
      m.world_pending = false;
      m.inv_mass = 0.0;
      m.isotropic = true;
      m.iso_inv_inertia = 0.0;
      m.inv_inertia.setZero();
    }
  });
}

// The world inverse inertia [R]_2 I^-1 [R]_2^T (two k x k products) of each non-isotropic body that a
// constraint, a live grab or a live joint uses this step; a body alone in the air needs none. Marked serially, turned
// body by body.
template <int N>
void load_world_inertias(ContactState<N>& s, const std::vector<Body<N>>& bodies) {
  std::vector<char>& used = s.inertia_used;
  used.assign(bodies.size(), 0);
  for (const Constraint<N>& c : s.graph.constraints) used[c.a] = used[c.b] = 1;
  for (const GrabConstraint<N>& g : s.grabs)
    if (g.live) used[g.def.body.index] = 1;
  for (const JointConstraint<N>& j : s.joints.slots)
    if (j.live) {
      used[j.b] = 1;
      if (j.a >= 0) used[j.a] = 1;
    }
  for_each_body(s, int(bodies.size()), [&](int i) {
    BodyMass<N>& m = s.masses[i];
    if (!m.world_pending || !used[i]) return;
    m.inv_inertia = bodies[i].world_inv_inertia();
    m.world_pending = false;
  });
}

// One constraint per pair with contact points and an awake dynamic body (update_constraint_graph
// places them). For the soft step, in colour order and built wide constraint by wide constraint,
// straight into the lanes (build_wide).
template <int N>
void build_constraints(ContactState<N>& s, const std::vector<Body<N>>& bodies, const std::vector<Material>& materials,
                       const ContactSettings& settings) {
  const bool soft = settings.solver == ContactSolver::SoftStep;
  ++s.graph.builds;
  update_constraint_graph(s, bodies, soft);
  load_world_inertias(s, bodies);
  if (!s.graph.graph_kept) {
    const int total = s.graph.constraints.empty() ? 0 : s.graph.constraints.back().first + s.graph.constraints.back().count;
    // (The last step's masses are kept for the recycled pairs; the build writes every one it uses. With
    // the graph kept they stay where they are: each constraint's points are where they were.)
    if (soft) {
      s.soft.point_masses.swap(s.soft.previous_masses);
      s.soft.point_masses.resize(total);
    } else {
      s.paper.points.resize(total);
    }
  }
  if (soft) {
    s.workers.for_ranges(int(s.soft.wide.size()), kConstraintGrain / kLanes<N>, [&](int begin, int end) {
      for (int i = begin; i < end; ++i) build_wide(s, bodies, materials, settings, s.soft.wide[i]);
    });
  } else {
    s.workers.for_ranges(int(s.graph.constraints.size()), kConstraintGrain, [&](int k0, int k1) {
      for (int k = k0; k < k1; ++k)
        build_constraint(s, bodies, materials, settings.static_slip_speed, settings.contact_margin,
                         s.graph.constraint_pairs[k], k, s.graph.constraints[k].first);
    });
  }
  s.graph.built_soft = soft;
}

#define WEDGE_INSTANTIATE(N)                                                                         \
  template void load_solver_bodies<N>(ContactState<N>&, const std::vector<Body<N>>&, bool);         \
  template void build_constraints<N>(ContactState<N>&, const std::vector<Body<N>>&,                 \
                                     const std::vector<Material>&, const ContactSettings&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
