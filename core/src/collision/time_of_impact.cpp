// Time of impact by conservative advancement (see wedge/collision/time_of_impact.hpp for the bound).
#include "wedge/collision/time_of_impact.hpp"

#include <algorithm>
#include <cmath>

#include "collision/narrow.hpp"
#include "collision/shape_extent.hpp"
#include "wedge/dimensions.hpp"
#include "wedge/collision/aabb.hpp"
#include "wedge/collision/detail/gjk.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/factorize.hpp"
#include "wedge/ga/products.hpp"

namespace wedge {

template <int N>
Sweep<N> Sweep<N>::still(const Vec<N>& center, const Rotor<N>& rotor, const Vec<N>& local_center) {
  Sweep s;
  s.local_center = local_center;
  s.c0 = s.c1 = center;
  s.q0 = rotor;
  return s;
}

template <int N>
Sweep<N> Sweep<N>::between(const Vec<N>& c0, const Rotor<N>& q0, const Vec<N>& c1, const Rotor<N>& q1,
                           const Vec<N>& local_center) {
  Sweep s;
  s.local_center = local_center;
  s.c0 = c0;
  s.c1 = c1;
  s.q0 = q0;
  // q1 q0~ and -q1 q0~ are the same rotation; the one with a non-negative scalar part has the smaller
  // angles.
  Rotor<N> d = q1 * reverse(q0);
  if (d[0] < 0.0) d.c = -d.c;
  s.turn = log<N>(d);
  return s;
}

template <int N>
Rotor<N> Sweep<N>::rotor(double t) const {
  if (t == 0.0) return q0;
  return repair(Rotor<N>(exp<N>(turn * t) * q0));
}

template <int N>
Transform<N> Sweep<N>::transform(double t) const {
  const Rotor<N> q = rotor(t);
  Transform<N> x;
  x.rotation = to_matrix(q);
  x.position = center(t) - x.rotation * local_center;
  return x;
}

namespace {

// A bounded shape's gap to a half-space: how far its lowest point along the plane's normal lies above
// the plane (0 when it reaches into it); the normal returned points from the shape towards the plane.
template <int N>
ShapeDistance<N> distance_to_halfspace(const Shape<N>& shape, const Transform<N>& t, const Shape<N>& plane,
                                       const Transform<N>& tp) {
  const auto& h = plane.template as<shapes::Halfspace<N>>();
  const Vec<N> n = tp.rotation * h.normal;
  const double offset = h.offset + n.dot(tp.position);
  const Vec<N> low = collision::world_support(shape, t, Vec<N>(-n));
  const double gap = std::max(0.0, n.dot(low) - offset);
  return {gap, low, Vec<N>(low - gap * n), Vec<N>(-n)};
}

}  // namespace

template <int N>
ShapeDistance<N> shape_distance(const Shape<N>& a, const Transform<N>& ta, const Shape<N>& b, const Transform<N>& tb) {
  if (!b.bounded()) return distance_to_halfspace(a, ta, b, tb);
  if (!a.bounded()) {
    const ShapeDistance<N> d = distance_to_halfspace(b, tb, a, ta);
    return {d.distance, d.point_b, d.point_a, Vec<N>(-d.normal)};
  }
  const auto sa = [&](const Vec<N>& d) { return collision::world_support(a, ta, d); };
  const auto sb = [&](const Vec<N>& d) { return collision::world_support(b, tb, d); };
  const GjkResult<N> g = gjk<N>(sa, sb, Vec<N>(tb.position - ta.position));
  if (g.intersecting || !(g.distance > 0.0)) return {0.0, g.point_a, g.point_b, Vec<N>::Zero()};
  return {g.distance, g.point_a, g.point_b, Vec<N>((g.point_b - g.point_a) / g.distance)};
}

template <int N>
TimeOfImpact<N> time_of_impact(const Shape<N>& a, const Sweep<N>& sweep_a, const Shape<N>& b, const Sweep<N>& sweep_b,
                               const TimeOfImpactSettings& settings) {
  const Vec<N> dc = (sweep_a.c1 - sweep_a.c0) - (sweep_b.c1 - sweep_b.c0);  // a's displacement relative to b
  const double turning = 2.0 * sweep_a.turn.norm() * collision::turning_radius(a, sweep_a.local_center) +
                         2.0 * sweep_b.turn.norm() * collision::turning_radius(b, sweep_b.local_center);
  const double target = settings.target;
  TimeOfImpact<N> out;
  double t = 0.0;
  while (true) {
    const ShapeDistance<N> d = shape_distance(a, sweep_a.transform(t), b, sweep_b.transform(t));
    out.distance = d.distance;
    out.point_a = d.point_a;
    out.point_b = d.point_b;
    out.normal = d.normal;
    if (out.iterations == settings.max_iterations) {  // (at a t that is still safe)
      out.state = ImpactState::OutOfIterations;
      out.t = t;
      return out;
    }
    ++out.iterations;
    if (d.distance <= target + settings.tolerance) {
      out.state = t == 0.0 && d.distance <= target ? ImpactState::Overlapping : ImpactState::Hit;
      out.t = t;
      return out;
    }
    // The fastest the gap along the fixed normal can close, per unit of t.
    const double closing = dc.dot(d.normal) + turning;
    if (!(closing > 0.0)) break;  // the projections move apart along n: never closer
    t += (d.distance - target) / closing;
    if (!(t < 1.0)) break;
  }
  out.state = ImpactState::Separated;
  out.t = 1.0;
  return out;
}

#define WEDGE_INSTANTIATE(N)                                                                                   \
  template struct Sweep<N>;                                                                                    \
  template TimeOfImpact<N> time_of_impact<N>(const Shape<N>&, const Sweep<N>&, const Shape<N>&, const Sweep<N>&, \
                                             const TimeOfImpactSettings&);                                     \
  template ShapeDistance<N> shape_distance<N>(const Shape<N>&, const Transform<N>&, const Shape<N>&,          \
                                              const Transform<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge
