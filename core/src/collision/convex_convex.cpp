// Any other pair of convex shapes (round products against boxes, polytopes or each other): GJK on the
// support functions for the distance, EPA for the penetration depth and normal. The manifold: the
// points of each shape's support set along the normal that project into the other shape's supporting
// face (a cylinder standing on a box gives points around its end disk; a box on a duocylinder's flat
// side gives the box's corners), or the EPA witness point when no face touches a face.
#include <cmath>

#include "collision/narrow.hpp"
#include "wedge/collision/detail/epa.hpp"
#include "wedge/collision/detail/gjk.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::collision {

template <int N>
Manifold<N> convex_convex(const Shape<N>& a, const Transform<N>& ta, const Shape<N>& b, const Transform<N>& tb,
                          const CollisionSettings& settings) {
  const auto sa = [&](const Vec<N>& d) { return world_support(a, ta, d); };
  const auto sb = [&](const Vec<N>& d) { return world_support(b, tb, d); };
  const double scale = std::max(shape_scale(a), shape_scale(b));
  const double margin = settings.contact_margin;
  Manifold<N> m;
  const GjkResult<N> g = gjk<N>(sa, sb, Vec<N>(tb.position - ta.position));
  Vec<N> witness;
  if (!g.intersecting) {
    const Vec<N> d = g.point_b - g.point_a;
    m.intersecting = false;
    m.depth = -g.distance;
    m.normal = g.distance > 0.0 ? Vec<N>(d / g.distance) : Vec<N>(Vec<N>::Unit(0));
    witness = 0.5 * (g.point_a + g.point_b);
  } else {
    const EpaResult<N> e = epa<N>(sa, sb, g.simplex);
    m.intersecting = true;
    m.depth = e.ok ? e.depth : 0.0;
    m.normal = e.ok ? e.normal : Vec<N>(Vec<N>::Unit(0));
    witness = 0.5 * (e.point_a + e.point_b);
  }
  if (m.depth < -margin) return m;

  const Vec<N>& n = m.normal;
  const double top_a = n.dot(sa(n)), bottom_b = n.dot(sb(Vec<N>(-n)));
  const double flat = std::max(m.depth, 0.0) + margin + 1e-6 * scale;
  const double inside_tol = 1e-6 * scale;
  thread_local std::vector<SupportPoint<N>> set;
  thread_local std::vector<ContactPoint<N>> points;
  points.clear();
  local_support_set(b, Vec<N>(tb.rotation.transpose() * -n), flat, set);
  for (const SupportPoint<N>& s : set) {  // b's points under a's supporting plane, over a's face
    const Vec<N> q = tb.apply(s.point);
    const double depth = top_a - n.dot(q);
    if (depth >= -margin && local_contains(a, ta.apply_inverse(Vec<N>(q + depth * n)), inside_tol))
      points.push_back({q + (0.5 * depth) * n, depth, mix_id(2, s.id)});
  }
  local_support_set(a, Vec<N>(ta.rotation.transpose() * n), flat, set);
  for (const SupportPoint<N>& s : set) {  // a's points over b's supporting plane, under b's face
    const Vec<N> p = ta.apply(s.point);
    const double depth = n.dot(p) - bottom_b;
    if (depth >= -margin && local_contains(b, tb.apply_inverse(Vec<N>(p - depth * n)), inside_tol))
      points.push_back({p - (0.5 * depth) * n, depth, mix_id(1, s.id)});
  }
  if (points.empty()) points.push_back({witness, m.depth, 0});
  reduce_into(points, m);
  return m;
}

#define WEDGE_INSTANTIATE(N)                                                                                      \
  template Manifold<N> convex_convex<N>(const Shape<N>&, const Transform<N>&, const Shape<N>&, const Transform<N>&, \
                                        const CollisionSettings&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::collision
