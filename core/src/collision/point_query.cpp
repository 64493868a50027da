#include "wedge/collision/point_query.hpp"

#include <algorithm>

#include "collision/narrow.hpp"
#include "wedge/dimensions.hpp"
#include "wedge/collision/detail/gjk.hpp"

namespace wedge {

template <int N>
PointQuery<N> point_query(const Shape<N>& shape, const Transform<N>& t, const Vec<N>& point) {
  PointQuery<N> q;
  const Vec<N> local = t.apply_inverse(point);
  if (shape.template is<shapes::Halfspace<N>>()) {
    const auto& h = shape.template as<shapes::Halfspace<N>>();
    const double above = h.normal.dot(local) - h.offset;  // the normal is unit (the loader normalises it)
    q.inside = above <= 0.0;
    q.distance = std::max(above, 0.0);
    q.closest = t.apply(Vec<N>(local - q.distance * h.normal));
    return q;
  }
  // Round-off band for containment: a point on the boundary counts as inside.
  const double band = collision::round_off_band(collision::shape_scale(shape));
  if (collision::local_contains(shape, local, band)) {
    q.inside = true;
    q.closest = point;
    return q;
  }
  if (shape.template is<shapes::Ball<N>>()) {
    const double r = shape.template as<shapes::Ball<N>>().radius, len = local.norm();
    q.distance = len - r;
    q.closest = t.apply(Vec<N>(local * (r / len)));
    return q;
  }
  const auto support = [&](const Vec<N>& d) { return collision::world_support(shape, t, d); };
  const auto at_point = [&](const Vec<N>&) { return point; };
  const GjkResult<N> g = gjk<N>(support, at_point, Vec<N>(point - t.position));
  q.distance = g.intersecting ? 0.0 : g.distance;  // inside by GJK only within its touching tolerance
  q.closest = g.point_a;
  return q;
}

#define WEDGE_INSTANTIATE(N) template PointQuery<N> point_query<N>(const Shape<N>&, const Transform<N>&, const Vec<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge
