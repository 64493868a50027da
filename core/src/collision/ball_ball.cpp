// Ball against ball: the centre line.
#include <cmath>

#include "collision/narrow.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::collision {

template <int N>
Manifold<N> ball_ball(const Shape<N>& a, const Transform<N>& ta, const Shape<N>& b, const Transform<N>& tb,
                      const CollisionSettings& settings) {
  const double ra = a.template as<shapes::Ball<N>>().radius, rb = b.template as<shapes::Ball<N>>().radius;
  const Vec<N> d = tb.position - ta.position;
  const double dist = d.norm();
  Manifold<N> m;
  // Concentric balls have no preferred direction; any unit vector is a valid normal, take e0.
  m.normal = dist > 1e-12 * (ra + rb) ? Vec<N>(d / dist) : Vec<N>(Vec<N>::Unit(0));
  m.depth = ra + rb - dist;
  m.intersecting = m.depth >= 0.0;
  if (m.depth >= -settings.contact_margin) m.add({ta.position + (ra - 0.5 * m.depth) * m.normal, m.depth, 0});
  return m;
}

#define WEDGE_INSTANTIATE(N)                                                                                  \
  template Manifold<N> ball_ball<N>(const Shape<N>&, const Transform<N>&, const Shape<N>&, const Transform<N>&, \
                                    const CollisionSettings&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::collision
