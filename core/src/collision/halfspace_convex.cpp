// Half-space (ground, walls) against any bounded shape: every point of the shape's support set that lies
// below the plane (within the contact margin) is a contact point. A tesseract resting flat gives the 8
// corners of its bottom cell; a cylinder on its end gives points around the rim of the end disk.
#include "collision/narrow.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::collision {

template <int N>
Manifold<N> halfspace_convex(const Shape<N>& a, const Transform<N>& ta, const Shape<N>& b, const Transform<N>& tb,
                             const CollisionSettings& settings) {
  const auto& h = a.template as<shapes::Halfspace<N>>();
  const Vec<N> n = ta.rotation * h.normal;  // outward of the half-space: from a towards b
  const double offset = h.offset + n.dot(ta.position);
  const Vec<N> down = tb.rotation.transpose() * -n;  // into the half-space, in b's frame
  const Vec<N> deepest = tb.apply(local_support(b, down));
  Manifold<N> m;
  m.normal = n;
  m.depth = offset - n.dot(deepest);
  m.intersecting = m.depth >= 0.0;
  // The margin widened by the round-off band: a cell lying exactly on the plane keeps all its corners.
  // (The face lattice's radius where there is one: shape_scale walks a polytope's vertices every call.)
  const double margin = settings.contact_margin + round_off_band(b.features() ? b.features()->radius : shape_scale(b));
  if (m.depth < -margin) return m;
  thread_local std::vector<SupportPoint<N>> set;
  thread_local std::vector<ContactPoint<N>> points;
  local_support_set(b, down, m.depth + margin, set);
  points.clear();
  for (const SupportPoint<N>& s : set) {
    const Vec<N> x = tb.apply(s.point);
    const double depth = offset - n.dot(x);
    if (depth >= -margin) points.push_back({x + (0.5 * depth) * n, depth, s.id});
  }
  reduce_into(points, m);
  return m;
}

#define WEDGE_INSTANTIATE(N)                                                                         \
  template Manifold<N> halfspace_convex<N>(const Shape<N>&, const Transform<N>&, const Shape<N>&, \
                                           const Transform<N>&, const CollisionSettings&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::collision
