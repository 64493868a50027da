// Finding contacts: broad phase, the persistent sorted pair list, the narrow phase at the current
// positions (with the speculative margin), waking islands that are touched, the step's constraints; and
// the contact events after the step.
#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>
#include <type_traits>

#include <Eigen/LU>

#include "contact/contact_system.hpp"
#include "collision/shape_extent.hpp"
#include "contact/lane_fill.hpp"
#include "linalg/isotropic.hpp"
#include "wedge/collision/narrow_phase.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::contact {

namespace {

template <int N>
Transform<N> transform_of(const Body<N>& b) {
  return Transform<N>{b.position(), to_matrix(b.rotor)};
}

// Shapes whose contact points stay put on their faces while they touch (see recycling.cpp).
template <int N>
bool flat_faced(const Shape<N>& shape) {
  return shape.features() != nullptr || !shape.bounded();
}

// Moves the proxies of the bodies that can move, then lists the candidate pairs: the broad phase's,
// plus each half-space with every dynamic body whose box reaches within the margin of its plane. Where
// neither changed (a resting scene) the list is left as it is.
template <int N>
void update_broad_phase(ContactState<N>& s, const std::vector<Body<N>>& bodies, const Shapes<N>& shapes, double h) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body<N>& b = bodies[i];
    if (s.proxy[i] < 0 || b.type == BodyType::Static || !s.awake[i]) continue;
    s.box[i] = world_aabb(*shapes[i], b.position(), b.rotor);
    s.broad_phase.move_proxy(s.proxy[i], s.box[i], Vec<N>(b.velocity * h));
  }
  const bool tree_changed = s.broad_phase.update_pairs();
  // The half-space pairs, sorted. (The box is read first: most bodies are far from every plane, and
  // their type need not be read.)
  s.halfspace_pairs.swap(s.previous_halfspace_pairs);
  s.halfspace_pairs.clear();
  const double margin = s.broad_phase.settings().margin;
  for (const std::uint32_t hs : s.halfspaces) {
    const Body<N>& g = bodies[hs];
    const auto& plane = shapes[hs]->template as<shapes::Halfspace<N>>();
    const Vec<N> n = rotate(g.rotor, plane.normal);
    const double offset = plane.offset + n.dot(g.position());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (s.proxy[i] < 0) continue;
      const Aabb<N>& box = s.box[i];
      double low = 0.0;  // the box's lowest point along n
      for (int k = 0; k < N; ++k) low += n[k] * (n[k] > 0.0 ? box.lo[k] : box.hi[k]);
      if (low <= offset + margin && bodies[i].is_dynamic())
        s.halfspace_pairs.emplace_back(std::min<std::uint32_t>(hs, std::uint32_t(i)),
                                       std::max<std::uint32_t>(hs, std::uint32_t(i)));
    }
  }
  std::sort(s.halfspace_pairs.begin(), s.halfspace_pairs.end());
  if (!tree_changed && s.halfspace_pairs == s.previous_halfspace_pairs) return;
  // Merged into the broad phase's sorted list.
  const auto& tree = s.broad_phase.pairs();
  s.candidate_pairs.resize(tree.size() + s.halfspace_pairs.size());
  std::merge(tree.begin(), tree.end(), s.halfspace_pairs.begin(), s.halfspace_pairs.end(), s.candidate_pairs.begin());
}

// The new pair list, carrying each surviving pair's manifold and touching state over; a pair that
// leaves while touching ends.
template <int N>
void merge_pairs(ContactState<N>& s, const std::vector<Body<N>>& bodies) {
  s.ended.clear();
  // Usually (a resting heap) the list is unchanged: keep it rather than copy every pair (4D: kilobytes),
  // which the keys tell without reading the pairs.
  const auto key = [](std::uint32_t a, std::uint32_t b) { return std::uint64_t{a} << 32 | b; };
  const auto unchanged = [&] {
    std::size_t k = 0;
    for (const auto& [a, b] : s.candidate_pairs) {
      if (!bodies[a].is_dynamic() && !bodies[b].is_dynamic()) continue;
      if (k == s.pair_keys.size() || s.pair_keys[k] != key(a, b)) return false;
      ++k;
    }
    return k == s.pair_keys.size();
  };
  if (unchanged()) return;
  s.next_pairs.clear();
  std::size_t old = 0;
  auto drop = [&s](const Pair<N>& p) {
    if (p.touching) s.ended.push_back({BodyId{p.a}, BodyId{p.b}});
  };
  for (const auto& [a, b] : s.candidate_pairs) {
    if (!bodies[a].is_dynamic() && !bodies[b].is_dynamic()) continue;
    while (old < s.pairs.size() && (s.pairs[old].a < a || (s.pairs[old].a == a && s.pairs[old].b < b)))
      drop(s.pairs[old++]);
    if (old < s.pairs.size() && s.pairs[old].a == a && s.pairs[old].b == b) {
      s.next_pairs.push_back(s.pairs[old++]);
    } else {
      Pair<N> p;
      p.a = a;
      p.b = b;
      s.next_pairs.push_back(p);
    }
  }
  for (; old < s.pairs.size(); ++old) drop(s.pairs[old]);
  s.pairs.swap(s.next_pairs);
  s.pair_keys.resize(s.pairs.size());
  for (std::size_t k = 0; k < s.pairs.size(); ++k) s.pair_keys[k] = key(s.pairs[k].a, s.pairs[k].b);
}

// An upper bound of how fast any point of the body moves (m/s): centre speed plus |w| times the radius
// of the sphere about the centre of mass that holds its bounding box (at most the box's diagonal). Zero for a half-space (static).
template <int N>
double speed_bound(const ContactState<N>& s, const Body<N>& b, int i) {
  if (s.proxy[i] < 0) return 0.0;
  return b.velocity.norm() + b.angular_velocity.c.norm() * s.box[i].extents().norm();
}

// One pair's manifold: recycled while the bodies barely move relative to each other, else collided with
// the speculative margin (below). Reads the bodies, writes only the pair.
// (flatten: the bodies' rotation matrices and the recycling test are inlined into it.)
template <int N>
[[gnu::flatten]] void collide_pair(const ContactState<N>& s, Pair<N>& p, const std::vector<Body<N>>& bodies,
                                   const Shapes<N>& shapes, const ContactSettings& settings, double h) {
  const Body<N>& a = bodies[p.a];
  const Body<N>& b = bodies[p.b];
  const double reach = h * (s.speed[p.a] + s.speed[p.b]);
  CollisionSettings cs;
  cs.exact_separation = false;
  cs.face_preference = settings.face_preference;
  cs.contact_margin = settings.contact_margin + reach;
  const Transform<N>& ta = s.pose[p.a];
  const Transform<N>& tb = s.pose[p.b];
  // Recycled only between slow bodies (soft step): a fast one may meet new features within the step.
  const bool flat = settings.solver == ContactSolver::SoftStep && flat_faced(*shapes[p.a]) && flat_faced(*shapes[p.b]);
  // How far a point of a body that moves can be from its centre (0 for static bodies).
  const double extent = std::max(a.type == BodyType::Static ? 0.0 : s.radius[p.a],
                                 b.type == BodyType::Static ? 0.0 : s.radius[p.b]);
  p.recycled = flat && reach <= settings.recycle_distance &&
               recycle_manifold(p, a, b, ta.rotation, tb.rotation, extent, settings);
  if (!p.recycled) {
    p.manifold = collide(*shapes[p.a], ta, *shapes[p.b], tb, cs);
    cache_manifold(p, a, b, ta.rotation, tb.rotation);
    p.cached = flat;
  }
  p.updated = true;
}

// A pair's every cache line, requested ahead of its use: the narrow phase reads all of each pair (its
// manifold, and the recycling's state at the end), in pair order but past the hardware prefetcher's
// reach (a 2D pair is nine lines, of which it reads five or six).
constexpr int kPrefetchAhead = 4;
template <int N>
void prefetch_pair(const Pair<N>& p) {
  const char* bytes = reinterpret_cast<const char*>(&p);
  for (std::size_t at = 0; at < sizeof(Pair<N>); at += 64) __builtin_prefetch(bytes + at);
}

// Collides every pair with an awake dynamic body (or a moving kinematic one against a dynamic body).
// Each pair's margin is the speculative contact_margin plus how far the two can close in one step, so a
// contact that will close during the step is seen now (Guendelman's predicted positions, to first
// order). Each round collides the pairs needed now, split over the workers, then wakes the sleeping
// islands they touch, in pair order; the woken islands' pairs are collided in the next round.
template <int N>
void narrow_phase(ContactState<N>& s, const std::vector<Body<N>>& bodies, const Shapes<N>& shapes,
                  const ContactSettings& settings, double h) {
  auto active = [&](std::uint32_t i) { return moves(s, bodies, i); };
  auto sleeps = [&](std::uint32_t i) { return bodies[i].is_dynamic() && !s.awake[i]; };
  // (Every body's: waking in a later round moves none.)
  s.pose.resize(bodies.size());
  s.speed.resize(bodies.size());
  s.start_center.resize(bodies.size());
  s.start_rotor.resize(bodies.size());
  for_each_body(s, int(bodies.size()), [&](int i) {
    s.pose[i] = transform_of(bodies[i]);
    s.speed[i] = speed_bound(s, bodies[i], i);
    s.start_center[i] = bodies[i].center;
    s.start_rotor[i] = bodies[i].rotor;
  });
  for (bool again = true, first = true; again; first = false) {
    again = false;
    s.narrow_list.clear();
    for (std::size_t pi = 0; pi < s.pairs.size(); ++pi) {
      Pair<N>& p = s.pairs[pi];
      if (first) p.updated = false;  // (in the same sweep: the pairs are kilobytes)
      const Body<N>& a = bodies[p.a];
      const Body<N>& b = bodies[p.b];
      if (!p.updated && (active(p.a) || active(p.b) || (moving_kinematic(a) && b.is_dynamic()) ||
                         (moving_kinematic(b) && a.is_dynamic())))
        s.narrow_list.push_back(int(pi));
    }
    // (Whether a pair touches a sleeping body is noted as it is collided, and only those pairs are
    // read again, in order, to wake: reading every pair again was a sweep over kilobytes of pairs.)
    s.narrow_wakes.resize(s.narrow_list.size());
    s.workers.for_ranges(int(s.narrow_list.size()), kConstraintGrain, [&](int begin, int end) {
      for (int k = begin; k < end; ++k) {
        if (k + kPrefetchAhead < end) prefetch_pair(s.pairs[s.narrow_list[k + kPrefetchAhead]]);
        Pair<N>& p = s.pairs[s.narrow_list[k]];
        collide_pair(s, p, bodies, shapes, settings, h);
        s.narrow_wakes[k] = p.manifold.count > 0 && (sleeps(p.a) || sleeps(p.b));
      }
    });
    for (std::size_t k = 0; k < s.narrow_list.size(); ++k) {
      if (!s.narrow_wakes[k]) continue;
      const Pair<N>& p = s.pairs[s.narrow_list[k]];
      for (const std::uint32_t i : {p.a, p.b})
        if (sleeps(i)) {  // (unless a pair before it woke it)
          s.wake_island(int(i));
          again = true;
        }
    }
  }
}

// Before the step's first stage: inverse world inertia of every awake dynamic body, and velocities.
// The soft step freezes the bodies that do not move: they are only read (writing their unchanged
// velocities would chain every contact with the ground through one memory location, and two workers
// through one cache line). Shock propagation freezes bodies level by level instead.
template <int N>
void load_solver_bodies(ContactState<N>& s, const std::vector<Body<N>>& bodies, bool soft) {
  for_each_body(s, int(bodies.size()), [&](int i) {
    const Body<N>& b = bodies[i];
    SolverBody<N>& sb = s.solver_bodies[i];
    sb.v = b.velocity;
    sb.w = b.angular_velocity;
    sb.vp.setZero();
    sb.wp = Bivector<N>{};
    sb.frozen = soft && !moves(s, bodies, i);
    sb.advances = b.type != BodyType::Static && s.awake[i];
    if (moves(s, bodies, i)) {
      sb.inv_mass = b.inv_mass;
      sb.isotropic = linalg::is_isotropic(b.inv_inertia);
      sb.iso_inv_inertia = b.inv_inertia(0, 0);
      if (sb.isotropic)
        sb.inv_inertia = sb.iso_inv_inertia * BivMat<N>::Identity();  // (turning it changes nothing)
      else
        sb.inv_inertia = b.world_inv_inertia();
    } else {
      sb.inv_mass = 0.0;
      sb.isotropic = true;
      sb.iso_inv_inertia = 0.0;
      sb.inv_inertia.setZero();
    }
  });
}

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

// Graph colouring (Box2D v3's constraint graph): each constraint takes the lowest colour that neither of
// its moving bodies has yet, and the constraints are solved colour by colour, in pair order within a
// colour. No two constraints of a colour share a moving body, so consecutive ones are independent and
// the processor overlaps them instead of waiting on one body's velocities. Static and sleeping bodies
// are only read and take no colour. A body in more than kColours constraints sends the rest to a last,
// uncoloured group. Deterministic: a function of the pair order alone.
template <int N>
void colour_constraints(ContactState<N>& s, std::size_t bodies) {
  constexpr int kColours = 32;  // the bits of a body's mask: countr_one gives kColours when all are taken
  static_assert(kColours == std::numeric_limits<std::uint32_t>::digits);
  s.colour_mask.assign(bodies, 0);
  s.colour_of.resize(s.seeds.size());
  std::array<int, kColours + 3> start{};
  for (std::size_t k = 0; k < s.seeds.size(); ++k) {
    const auto& e = s.seeds[k];
    const std::uint32_t used = (e.move_a ? s.colour_mask[e.a] : 0u) | (e.move_b ? s.colour_mask[e.b] : 0u);
    const int c = std::countr_one(used);
    if (c < kColours) {
      if (e.move_a) s.colour_mask[e.a] |= 1u << c;
      if (e.move_b) s.colour_mask[e.b] |= 1u << c;
    }
    s.colour_of[k] = c;
    ++start[c + 2];
  }
  for (int c = 2; c < kColours + 3; ++c) start[c] += start[c - 1];  // start[c + 1]: where colour c begins
  s.colour_start.assign(start.begin() + 1, start.end());
  s.colour_order.resize(s.seeds.size());  // (of the seeds)
  for (std::size_t k = 0; k < s.seeds.size(); ++k) s.colour_order[start[s.colour_of[k] + 1]++] = int(k);
}

// The constraint of pair pi, its points from `first` on: its bodies, normal and materials.
template <int N>
Constraint<N> make_constraint(const ContactState<N>& s, const std::vector<Material>& materials, int pi, int first) {
  const Pair<N>& p = s.pairs[pi];
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
  return p.built + 1 == s.builds ? p.points_first : -1;
}
// The bodies' 1/m and isotropic 1/I, which a recycled pair's masses were formed with (Pair::mass_key).
template <int N>
std::array<double, 4> mass_key(const SolverBody<N>& a, const SolverBody<N>& b) {
  return {a.inv_mass, a.iso_inv_inertia, b.inv_mass, b.iso_inv_inertia};
}
// Where in the last step's masses pair p's points may take theirs from, or -1: a recycled manifold
// keeps its normal and lever arms, and with isotropic bodies of the same masses the effective masses
// and Jacobian rows are then those of the last step, to the bit (the same function of the same
// numbers): copied rather than formed again.
template <int N>
int recycled_masses(const ContactState<N>& s, const Pair<N>& p, const SolverBody<N>& a, const SolverBody<N>& b) {
  if (!(s.built_soft && p.recycled && a.isotropic && b.isotropic && mass_key(a, b) == p.mass_key)) return -1;
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
Mat<N> point_k(const SolverBody<N>& a, const SolverBody<N>& b, const Vec<N>& ra, const Vec<N>& rb) {
  return (a.inv_mass + b.inv_mass) * Mat<N>::Identity() + angular_mass_term(a, ra) + angular_mass_term(b, rb);
}

// What the constraint of pair p leaves in it: where its points are, how fast they approached (events),
// and the masses' key.
template <int N>
void note_constraint(Pair<N>& p, const SolverBody<N>& a, const SolverBody<N>& b, int index, int first,
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
  Pair<N>& p = s.pairs[pi];
  const Constraint<N> c = make_constraint(s, materials, pi, first);
  const SolverBody<N>& sa = s.solver_bodies[c.a];
  const SolverBody<N>& sb = s.solver_bodies[c.b];
  std::array<int, kMaxManifoldPoints<N>> match;
  warm_matches(p, bodies[c.a].center, match_distance, match);
  double approach_speed = 0.0;
  for (int k = 0; k < c.count; ++k) {
    const PointStart<N> x = make_point(s, p, c, k, match[k], slip_speed);
    approach_speed = std::max(approach_speed, -x.approach);
    // (The array is not cleared and value-initialised each step: that was one more sweep over it.)
    PointConstraint<N>& q = s.points[c.first + k];
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
  note_constraint(p, sa, sb, index, first, approach_speed, s.builds);
  s.constraints[index] = c;
}

// The masses of a soft step point with lever arms ra, rb, formed (build_constraint's formulas).
template <int N>
PointMasses<N> form_point_masses(const SolverBody<N>& a, const SolverBody<N>& b, const Vec<N>& ra, const Vec<N>& rb,
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
// Where the graph is kept (ContactState::graph_kept) each lane of a full wide constraint holds the same
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
    Constraint<N>& c = s.constraints[index];
    if (s.graph_kept)
      c.normal = s.pairs[c.pair].manifold.normal;
    else
      c = make_constraint(s, materials, s.constraint_pairs[index], c.first);
  }
  // (Every field of an occupied lane is written below, so the slots are cleared first only where a
  // lane is empty: the last wide constraint of a colour, and the uncoloured group's.)
  bool full = true;
  for (int l = 0; l < kLanes<N>; ++l) full = full && w.constraint[l] >= 0;
  if (!full) clear_slots(s, w);
  // The last step's masses: where this step's go when the graph is kept (the same places), else the
  // other buffer (build_constraints).
  const std::vector<PointMasses<N>>& previous = s.graph_kept ? s.point_masses : s.previous_masses;
  const PointMasses<N>* last[kLanes<N>];
  bool header_kept = s.graph_kept && full && w.inertia < 0;
  for (int l = 0; l < kLanes<N>; ++l) {
    last[l] = nullptr;
    if (w.constraint[l] < 0) continue;
    const Constraint<N>& c = s.constraints[w.constraint[l]];
    const Pair<N>& p = s.pairs[c.pair];
    const int first = recycled_masses(s, p, s.solver_bodies[c.a], s.solver_bodies[c.b]);
    if (first >= 0) last[l] = &previous[first];
    header_kept = header_kept && last[l];
  }
  if (!header_kept) fill_wide_header(s, w);
  const bool inertia = w.inertia >= 0;
  static const LanePoint<N> none{};
  for (int l = 0; l < kLanes<N>; ++l) {
    if (w.constraint[l] < 0) continue;
    const Constraint<N>& c = s.constraints[w.constraint[l]];
    Pair<N>& p = s.pairs[c.pair];
    const SolverBody<N>& sa = s.solver_bodies[c.a];
    const SolverBody<N>& sb = s.solver_bodies[c.b];
    std::array<int, kMaxManifoldPoints<N>> match;
    warm_matches(p, bodies[c.a].center, settings.contact_margin, match);
    keep_warm_keys(p, c.count);  // (matched: the next step's keys now)
    const bool lane_kept = s.graph_kept && full && !inertia && last[l];
    double approach_speed = 0.0;
    for (int k = 0; k < c.count; ++k) {
      const PointStart<N> x = make_point(s, p, c, k, match[k], settings.static_slip_speed);
      approach_speed = std::max(approach_speed, -x.approach);
      LanePoint<N> q;
      copy_point_start(q, x);
      prepare_point(q, c.normal, x.gap, settings.warm_start, x.warm_normal, x.warm_tangent);
      put_lane_state(s, w, k, l, c.normal, q);
      if (lane_kept) continue;  // (its masses are in point_masses and in the lane)
      PointMasses<N>& m = s.point_masses[c.first + k];
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
    note_constraint(p, sa, sb, w.constraint[l], c.first, approach_speed, s.builds);
  }
}

// Where each constraint's points go (and its bodies and count, which the lanes are assigned by), in
// colour order (soft step) or pair order, from the seeds, and for the soft step the lanes. (Not
// cleared first: the build writes each constraint whole, and value-initialising them all was a tenth
// of the build's time.)
template <int N>
void place_constraints(ContactState<N>& s, std::size_t bodies, bool soft) {
  s.colour_start.clear();
  if (soft) colour_constraints(s, bodies);
  const std::size_t count = s.seeds.size();
  s.constraints.resize(count);
  s.constraint_pairs.resize(count);
  int total = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const auto& e = s.seeds[soft ? std::size_t(s.colour_order[k]) : k];
    s.constraint_pairs[k] = e.pair;
    Constraint<N>& c = s.constraints[k];
    c.first = total;
    c.count = e.count;
    c.a = int(e.a);
    c.b = int(e.b);
    total += c.count;
  }
  if (soft) {
    s.point_masses.resize(total);
    assign_lanes(s);
  } else {
    s.points.resize(total);
  }
}

// One constraint per pair with contact points and an awake dynamic body. For the soft step, in colour
// order and built wide constraint by wide constraint, straight into the lanes (build_wide).
template <int N>
void build_constraints(ContactState<N>& s, const std::vector<Body<N>>& bodies, const std::vector<Material>& materials,
                       const ContactSettings& settings) {
  const bool soft = settings.solver == ContactSolver::SoftStep;
  ++s.builds;
  s.seeds.swap(s.previous_seeds);
  s.seeds.clear();
  for (std::size_t pi = 0; pi < s.pairs.size(); ++pi) {
    Pair<N>& p = s.pairs[pi];
    p.constraint = -1;
    if (!p.updated) continue;
    if (p.manifold.count == 0) {
      p.warm_count = 0;
      continue;
    }
    const bool da = moves(s, bodies, p.a), db = moves(s, bodies, p.b);
    if (!da && !db) continue;
    s.seeds.push_back({int(pi), p.a, p.b, p.manifold.count, da, db, !da || s.solver_bodies[p.a].isotropic,
                       !db || s.solver_bodies[p.b].isotropic});
  }
  // The same seeds as the last soft step's: the same colours and lanes, and the constraints' places.
  static_assert(std::has_unique_object_representations_v<typename ContactState<N>::Seed>);  // (memcmp is ==)
  s.graph_kept = soft && s.built_soft && s.seeds.size() == s.previous_seeds.size() &&
                 (s.seeds.empty() ||
                  std::memcmp(s.seeds.data(), s.previous_seeds.data(), s.seeds.size() * sizeof(s.seeds[0])) == 0);
  // (The last step's masses are kept for the recycled pairs; the build writes every one it uses. With
  // the graph kept they stay where they are: each constraint's points are where they were.)
  if (soft && !s.graph_kept) s.point_masses.swap(s.previous_masses);
  if (!s.graph_kept) place_constraints(s, bodies.size(), soft);
  if (soft) {
    s.workers.for_ranges(int(s.wide.size()), kConstraintGrain / kLanes<N>, [&](int begin, int end) {
      for (int i = begin; i < end; ++i) build_wide(s, bodies, materials, settings, s.wide[i]);
    });
  } else {
    s.workers.for_ranges(int(s.constraints.size()), kConstraintGrain, [&](int k0, int k1) {
      for (int k = k0; k < k1; ++k)
        build_constraint(s, bodies, materials, settings.static_slip_speed, settings.contact_margin,
                         s.constraint_pairs[k], k, s.constraints[k].first);
    });
  }
  s.built_soft = soft;
}

}  // namespace

template <int N>
void add_body(ContactState<N>& s, const std::vector<Body<N>>& bodies, const Shapes<N>& shapes, int index) {
  s.awake.push_back(1);
  s.sleep_time.push_back(0.0);
  s.island.push_back(-1);
  s.proxy.push_back(-1);
  s.box.push_back(Aabb<N>{});
  s.solver_bodies.emplace_back();
  s.radius.push_back(0.0);
  s.inradius.push_back(0.0);
  const Shape<N>* shape = shapes[index].get();
  if (!shape) return;
  s.radius[index] = collision::shape_radius(*shape, bodies[index].local_center);
  s.inradius[index] = collision::shape_inradius(*shape, bodies[index].local_center);
  if (!shape->bounded()) {
    s.halfspaces.push_back(std::uint32_t(index));
    return;
  }
  s.box[index] = world_aabb(*shape, bodies[index].position(), bodies[index].rotor);
  s.proxy[index] = s.broad_phase.create_proxy(s.box[index], std::uint32_t(index));
}

template <int N>
void find_contacts(ContactState<N>& s, std::vector<Body<N>>& bodies, const Shapes<N>& shapes,
                   const std::vector<Material>& materials, const ContactSettings& settings, double h,
                   StepProfile* profile) {
  StageClock clock;
  update_broad_phase(s, bodies, shapes, h);
  merge_pairs(s, bodies);
  const double broad = clock.lap();
  narrow_phase(s, bodies, shapes, settings, h);
  const double narrow = clock.lap();
  load_solver_bodies(s, bodies, settings.solver == ContactSolver::SoftStep);
  build_constraints(s, bodies, materials, settings);
  if (settings.solver == ContactSolver::Paper && settings.shock_iterations > 0) compute_levels(s, bodies);
  if (profile) {
    profile->broad_phase = broad;
    profile->narrow_phase = narrow;
    profile->constraints = clock.lap();
  }
}

// A pair is touching when some point received a normal impulse or penetrates; pairs not collided in
// this step (asleep) keep their state.
template <int N>
void report_events(ContactState<N>& s) {
  s.begin_events.clear();
  s.end_events = s.ended;
  for (Pair<N>& p : s.pairs) {
    if (!p.updated) continue;
    // A penetrating pair touches whatever its impulses: those are read only where they decide, or
    // for a begin event (most resting pairs penetrate a little, and need not read them).
    const bool penetrating = p.manifold.count > 0 && p.manifold.depth > 0.0;
    if (p.constraint < 0) p.normal_impulse.fill(0.0);
    if (penetrating && p.touching) continue;  // (touching, and it was: no event)
    double total = 0.0;  // (its points' totals are in normal_impulse: unpack_wide, keep_totals)
    if (p.constraint >= 0)
      for (int k = 0; k < p.manifold.count; ++k) total += p.normal_impulse[k];
    const bool touching = total > 0.0 || penetrating;
    if (touching && !p.touching) {
      Vec<N> weighted = Vec<N>::Zero();
      if (p.constraint >= 0)
        for (int k = 0; k < p.manifold.count; ++k) weighted += p.normal_impulse[k] * p.manifold.points[k].point;
      const double approach = p.constraint >= 0 ? p.approach_speed : 0.0;
      ContactBeginEvent<N> e;
      e.a = BodyId{p.a};
      e.b = BodyId{p.b};
      e.normal = p.manifold.normal;
      e.normal_impulse = total;
      e.point = total > 0.0 ? Vec<N>(weighted / total) : p.manifold.points[0].point;
      e.approach_speed = approach;
      s.begin_events.push_back(e);
    } else if (!touching && p.touching) {
      s.end_events.push_back({BodyId{p.a}, BodyId{p.b}});
    }
    p.touching = touching;
  }
  std::sort(s.end_events.begin(), s.end_events.end(), [](const ContactEndEvent& x, const ContactEndEvent& y) {
    return x.a.index != y.a.index ? x.a.index < y.a.index : x.b.index < y.b.index;
  });
}

#define WEDGE_INSTANTIATE(N)                                                                                  \
  template void add_body<N>(ContactState<N>&, const std::vector<Body<N>>&, const Shapes<N>&, int);           \
  template void find_contacts<N>(ContactState<N>&, std::vector<Body<N>>&, const Shapes<N>&,                   \
                                 const std::vector<Material>&, const ContactSettings&, double, StepProfile*); \
  template void report_events<N>(ContactState<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
