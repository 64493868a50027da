// Ball against box, round product, polytope and mesh: the closest point of the shape to the ball's
// centre (paper section 7.1). That point may lie on a facet or on a face of any lower dimension down to a
// vertex. Boxes and round products have it in closed form (each factor is clamped on its own); for
// polytopes GJK finds it when the centre is outside, and the nearest facet when it is inside.
#include <cmath>
#include <limits>

#include "collision/narrow.hpp"
#include "wedge/collision/detail/gjk.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::collision {
namespace {

template <int N>
struct Closest {
  Vec<N> point;    // on the shape's surface (body frame)
  bool inside;     // the centre is inside the shape
};

// The closest surface point of a product of balls and intervals to x; inside, the nearest exit.
template <int N>
Closest<N> closest_on_product(const std::vector<ProductFactor>& factors, const Vec<N>& x) {
  Closest<N> c{x, true};
  for (const ProductFactor& f : factors) {
    double len2 = 0.0;
    for (int a : f.axes) len2 += x[a] * x[a];
    const double len = std::sqrt(len2);
    if (len > f.size) {
      c.inside = false;
      for (int a : f.axes) c.point[a] = x[a] * (f.size / len);
    }
  }
  if (!c.inside) return c;
  // Inside: leave through the factor with the least room.
  const ProductFactor* best = nullptr;
  double room = std::numeric_limits<double>::infinity(), best_len = 0.0;
  for (const ProductFactor& f : factors) {
    double len2 = 0.0;
    for (int a : f.axes) len2 += x[a] * x[a];
    const double len = std::sqrt(len2);
    if (f.size - len < room) room = f.size - len, best = &f, best_len = len;
  }
  if (best_len > 0.0) {
    for (int a : best->axes) c.point[a] = x[a] * (best->size / best_len);
  } else {  // at the factor's centre: every exit is as near; take the first axis, positive side
    for (int a : best->axes) c.point[a] = 0.0;
    c.point[best->axes[0]] = best->size;
  }
  return c;
}

template <int N>
Closest<N> closest_on_polytope(const Shape<N>& shape, const Vec<N>& x) {
  const ConvexFeatures<N>& f = *shape.features();
  int nearest = -1;
  double room = std::numeric_limits<double>::infinity();
  for (int i = 0; i < int(f.facets.size()); ++i) {
    const double r = f.facets[i].offset - f.facets[i].normal.dot(x);
    if (r < room) room = r, nearest = i;
  }
  if (room >= 0.0) return {Vec<N>(x + room * f.facets[nearest].normal), true};
  const auto point = [&](const Vec<N>&) { return x; };
  const auto poly = [&](const Vec<N>& d) { return local_support(shape, d); };
  const GjkResult<N> g = gjk<N>(point, poly, Vec<N>(f.centroid - x));
  return {g.point_b, false};
}

}  // namespace

template <int N>
Manifold<N> ball_convex(const Shape<N>& a, const Transform<N>& ta, const Shape<N>& b, const Transform<N>& tb,
                        const CollisionSettings& settings) {
  const double r = a.template as<shapes::Ball<N>>().radius;
  const Vec<N> x = tb.apply_inverse(ta.position);  // the ball's centre in b's frame
  Closest<N> c;
  switch (kind_of(b)) {
    case ShapeKind::Box:
    case ShapeKind::RoundProduct:
      c = closest_on_product<N>(product_factors(b), x);
      break;
    default:
      c = closest_on_polytope(b, x);
  }
  const Vec<N> q = tb.apply(c.point);
  const Vec<N> d = q - ta.position;
  const double dist = d.norm();
  Manifold<N> m;
  if (dist > 1e-12 * r) {
    // Outside, the normal runs from the centre to the surface; inside, the shape must move the other way.
    m.normal = c.inside ? Vec<N>(-d / dist) : Vec<N>(d / dist);
  } else {  // the centre is on the surface: use the direction towards b's centre
    const Vec<N> to_b = tb.position - ta.position;
    m.normal = to_b.norm() > 0.0 ? Vec<N>(to_b.normalized()) : Vec<N>(Vec<N>::Unit(0));
  }
  m.depth = c.inside ? r + dist : r - dist;
  m.intersecting = m.depth >= 0.0;
  if (m.depth >= -settings.contact_margin)
    m.add({Vec<N>(0.5 * (ta.position + r * m.normal + q)), m.depth, 0});
  return m;
}

#define WEDGE_INSTANTIATE(N)                                                                                    \
  template Manifold<N> ball_convex<N>(const Shape<N>&, const Transform<N>&, const Shape<N>&, const Transform<N>&, \
                                      const CollisionSettings&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::collision
