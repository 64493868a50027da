// Continuous collision of fast bodies against static ones, after the solver (ContactSettings::continuous).
//
// The speculative margin lets the solver see a contact that will close during the step, at the points
// the narrow phase found at the step's start. A body that turns fast brings other points to the wall
// within the step (a thin plate flung end over end), and the solver stops only the points it was given:
// the plate ends the step inside or beyond a thin wall. So, as Box2D v3 does for its fast bodies, each
// dynamic body whose points may have moved more than half its inradius is swept from its pose at the
// step's start to its pose at the end against every static shape near its path (time_of_impact). If it
// reached one and the contacts let it through (at the end it lies beyond the wall, or in it deeper than
// continuous_gap), it is put back at the earliest time of impact, continuous_gap short of the wall (its
// angular velocity turned back with it), and collides there: an impulse at its nearest point stops that
// point's approach (Mirtich's impulse-based time of impact). The next step's contacts, found at that
// pose, take it from there. The rest of the step after the impact is lost, which only a body fast
// enough to cross its own size in a step notices. Bodies the contacts stopped, as in ordinary landings,
// are left where the contacts put them.
//
// A static shape the body was already touching at the start (within a tenth of the gap) cannot be swept
// against (the gap is already gone): if the contacts let the body through it, the body goes back to
// where it began the step. A box sliding fast along the ground, which the contacts hold on it, is not
// held back. One it began nearer than the gap it is stopped half as far from.
#include <algorithm>
#include <cmath>

#include "contact/contact_system.hpp"
#include "wedge/dimensions.hpp"
#include "wedge/collision/aabb.hpp"
#include "wedge/collision/narrow_phase.hpp"
#include "wedge/collision/time_of_impact.hpp"
#include "wedge/ga/products.hpp"

namespace wedge::contact {

namespace {

// Whether the body's points may have moved more than half its inradius in the step: by the centre's
// displacement, and by its speed bound (centre speed plus |w| times its radius) at the start and at the
// end of the step, times h.
template <int N>
bool moved_fast(const ContactState<N>& s, const Body<N>& b, int i, double h) {
  const double limit = 0.5 * s.list.inradius[i];
  const double end_speed = b.velocity.norm() + b.angular_velocity.c.norm() * s.list.radius[i];
  return (b.center - s.narrow.start_center[i]).norm() > limit || h * std::max(s.narrow.speed[i], end_speed) > limit;
}

// A box around every pose of the sweep: each point of the body stays within its radius of the centre,
// whose path is the segment from c0 to c1.
template <int N>
Aabb<N> swept_box(const Sweep<N>& sweep, double radius) {
  return Aabb<N>{Vec<N>(sweep.c0.cwiseMin(sweep.c1).array() - radius),
                 Vec<N>(sweep.c0.cwiseMax(sweep.c1).array() + radius)};
}

// A static shape the swept body reaches, where and when (t = 1: none).
template <int N>
struct Impact {
  double t = 1.0;
  int wall = -1;
  Vec<N> point = Vec<N>::Zero();   // m, world: the body's point nearest to the wall at t
  Vec<N> normal = Vec<N>::Zero();  // unit, from the body towards the wall
};

// Whether the soft contacts let the body through the wall it reached in the sweep: at the end of the
// step it lies beyond it (its nearest direction to the wall has turned against the one at the impact),
// or, for a wall it reached within the step, in it deeper than continuous_gap or a quarter of the
// thinner one's inradius (a body half way through a 1 cm wall is in it by 5 mm at most). A body the
// contacts stopped or turned away, as they do for ordinary landings, is left where they put it, and so
// is one that was touching the wall from the start and only sank into it (a ball rolling fast on the
// ground): that is the contacts' to push out.
template <int N>
bool contacts_failed(const ContactState<N>& s, const std::vector<Body<N>>& bodies, const Shapes<N>& shapes, int i,
                     const Impact<N>& hit, const ContactSettings& settings) {
  const Body<N>& b = bodies[i];
  const Body<N>& wall = bodies[hit.wall];
  const Transform<N> tb{b.position(), to_matrix(b.rotor)};
  const Transform<N> tw{wall.position(), to_matrix(wall.rotor)};
  const Manifold<N> m = collide(*shapes[i], tb, *shapes[hit.wall], tw);  // (normal from the body to the wall)
  if (m.normal.dot(hit.normal) < 0.0) return true;
  if (hit.t == 0.0) return false;  // (touching from the start: the contacts' own penetration, not a pass)
  double thin = s.list.inradius[i];
  if (shapes[hit.wall]->bounded()) thin = std::min(thin, s.list.inradius[hit.wall]);
  return m.intersecting && m.depth > std::min(settings.continuous_gap, 0.25 * thin);
}

// The earliest impact of the swept body i with a static body in `hits` that the contacts let it through
// (t = 1: none). The body is stopped continuous_gap short of a shape, or half as far from it as it
// began if that is nearer. A shape it began touching (within a tenth of the gap) gives an impact at
// t = 0, along the contact's normal then: if the contacts let the body through, it goes back to where
// it began the step.
template <int N>
Impact<N> first_failed_impact(const ContactState<N>& s, const std::vector<Body<N>>& bodies, const Shapes<N>& shapes,
                              int i, const Sweep<N>& sweep, const std::vector<int>& hits,
                              const ContactSettings& settings) {
  const Transform<N> start = sweep.transform(0.0);
  Impact<N> first;
  for (const int j : hits) {
    const Body<N>& wall = bodies[j];
    const Sweep<N> still = Sweep<N>::still(wall.center, wall.rotor, wall.local_center);
    const Transform<N> at = still.transform(0.0);
    const ShapeDistance<N> d0 = shape_distance(*shapes[i], start, *shapes[j], at);
    Impact<N> impact;
    if (d0.distance < 0.1 * settings.continuous_gap) {
      CollisionSettings near;
      near.contact_margin = settings.continuous_gap;  // (points up to the gap apart)
      const Manifold<N> m = collide(*shapes[i], start, *shapes[j], at, near);
      if (m.count == 0) continue;
      impact = Impact<N>{0.0, j, m.points[0].point, m.normal};
    } else {
      TimeOfImpactSettings toi;
      toi.target = std::min(settings.continuous_gap, 0.5 * d0.distance);
      toi.tolerance = 0.25 * toi.target;
      const TimeOfImpact<N> r = time_of_impact(*shapes[i], sweep, *shapes[j], still, toi);
      if (r.state != ImpactState::Hit && r.state != ImpactState::OutOfIterations) continue;
      impact = Impact<N>{r.t, j, r.point_a, r.normal};
    }
    if (impact.t < first.t && contacts_failed(s, bodies, shapes, i, impact, settings)) first = impact;
  }
  return first;
}

// The impact's collision: the impulse along the normal at the body's point that stops its approach
// there, or reverses it with the pair's restitution above the restitution threshold (frictionless; the
// next step's contacts add friction):
//     j = (1 + e) u_n / (1/m + (r ^ n) . I'^-1 (r ^ n)),   v -= j n / m,   w -= j I'^-1 (r ^ n),
// u_n the point's approach speed along n, r the point less the centre. It takes kinetic energy away
// (e < 1) or keeps it (e = 1).
template <int N>
void collide_at_impact(Body<N>& b, const Impact<N>& hit, double restitution, const ContactSettings& settings) {
  const Vec<N>& n = hit.normal;
  const double approach = b.velocity_at(hit.point).dot(n);
  if (!(approach > 0.0)) return;
  const BivMat<N> inv_inertia = b.world_inv_inertia();
  const Eigen::Matrix<double, kBiv<N>, 1> rn = wedge_matrix<N>(Vec<N>(hit.point - b.center)) * n;
  const Eigen::Matrix<double, kBiv<N>, 1> turn = inv_inertia * rn;
  const double e = approach > settings.restitution_threshold ? restitution : 0.0;
  const double j = (1.0 + e) * approach / (b.inv_mass + rn.dot(turn));
  b.velocity -= (j * b.inv_mass) * n;
  b.angular_velocity.c -= j * turn;
}

// Caps the body's spin at max_turn per step: |w| h <= max_turn, its direction kept (|w| bounds the
// fastest rate in any of its planes). The sub-steps integrate rotation and the gyroscopic term as if the
// turn per step were moderate; a thin rod struck off its axis can be given thousands of rad/s about it
// (its inertia there is tiny), and at several radians per step that integration gains energy without
// bound. Box2D v3 and Jolt cap rotation likewise (a quarter turn per sub-step; 47 rad/s by default).
template <int N>
void limit_spin(Body<N>& b, double h, const ContactSettings& settings) {
  const double w2 = b.angular_velocity.c.squaredNorm();
  const double limit = settings.max_turn / h;
  if (w2 > limit * limit) b.angular_velocity.c *= limit / std::sqrt(w2);
}


// One fast body swept from where the step began to where it ended; put back and collided at the
// earliest impact with a static shape, if any.
template <int N>
void sweep_body(ContactState<N>& s, std::vector<Body<N>>& bodies, const Shapes<N>& shapes,
                const std::vector<Material>& materials, const ContactSettings& settings, int i) {
  Body<N>& b = bodies[i];
  const Sweep<N> sweep = Sweep<N>::between(s.narrow.start_center[i], s.narrow.start_rotor[i], b.center, b.rotor, b.local_center);
  // The static bodies near the path: from the broad phase, and every half-space (in creation order, so
  // that the result does not depend on the tree's order).
  std::vector<int>& hits = s.narrow.continuous_hits;
  hits.clear();
  s.list.broad_phase.query(swept_box(sweep, s.list.radius[i]), [&](int proxy) {
    const std::uint32_t j = s.list.broad_phase.user_id(proxy);
    if (bodies[j].type == BodyType::Static) hits.push_back(int(j));
  });
  for (const std::uint32_t j : s.list.halfspaces) hits.push_back(int(j));
  std::sort(hits.begin(), hits.end());
  const Impact<N> hit = first_failed_impact(s, bodies, shapes, i, sweep, hits, settings);
  if (hit.t >= 1.0) return;
  // Put back, turning the angular velocity back with the body: the same in the body frame, so the
  // kinetic energy stays as it was (the world inertia turns with the body).
  const Rotor<N> back = sweep.rotor(hit.t);
  b.angular_velocity = rotate(Rotor<N>(back * reverse(b.rotor)), b.angular_velocity);
  b.center = sweep.center(hit.t);
  b.rotor = back;
  collide_at_impact(b, hit, mix_restitution(materials[i].restitution, materials[hit.wall].restitution), settings);
}

}  // namespace

template <int N>
void solve_continuous(ContactState<N>& s, std::vector<Body<N>>& bodies, const Shapes<N>& shapes,
                      const std::vector<Material>& materials, const ContactSettings& settings, double h) {
  for (int i = 0; i < int(bodies.size()); ++i) {
    Body<N>& b = bodies[i];
    if (!b.is_dynamic() || !s.islands.awake[i]) continue;
    if (settings.continuous && s.list.proxy[i] >= 0 && moved_fast(s, b, i, h))
      sweep_body(s, bodies, shapes, materials, settings, i);
    limit_spin(b, h, settings);
  }
}

#define WEDGE_INSTANTIATE(N)                                                                              \
  template void solve_continuous<N>(ContactState<N>&, std::vector<Body<N>>&, const Shapes<N>&,            \
                                    const std::vector<Material>&, const ContactSettings&, double);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
