#include "collision/shape_extent.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "wedge/dimensions.hpp"
#include "wedge/collision/aabb.hpp"

namespace wedge::collision {

template <int N>
double shape_radius(const Shape<N>& shape, const Vec<N>& local_center) {
  double r2 = 0.0;
  if (const ConvexFeatures<N>* f = shape.features()) {
    for (const Vec<N>& v : f->vertices) r2 = std::max(r2, (v - local_center).squaredNorm());
  } else if (shape.bounded()) {
    const Aabb<N> box = world_aabb<N>(shape, Vec<N>(Vec<N>::Zero()), Mat<N>(Mat<N>::Identity()));
    const Vec<N> far = (box.lo - local_center).cwiseAbs().cwiseMax((box.hi - local_center).cwiseAbs());
    r2 = far.squaredNorm();
  }
  return std::sqrt(r2);
}

template <int N>
double shape_inradius(const Shape<N>& shape, const Vec<N>& local_center) {
  double r = 0.0;
  if (const ConvexFeatures<N>* f = shape.features()) {
    r = std::numeric_limits<double>::infinity();
    for (const auto& facet : f->facets) r = std::min(r, facet.offset - facet.normal.dot(local_center));
  } else if (shape.template is<shapes::Ball<N>>()) {
    r = shape.template as<shapes::Ball<N>>().radius - local_center.norm();
  } else if (shape.template is<shapes::RoundProduct<N>>()) {
    r = std::numeric_limits<double>::infinity();
    for (const ProductFactor& factor : shape.template as<shapes::RoundProduct<N>>().factors)
      r = std::min(r, factor.size);
    r -= local_center.norm();
  }
  return std::max(r, 0.0);
}

template <int N>
double turning_radius(const Shape<N>& shape, const Vec<N>& local_center) {
  if (shape.template is<shapes::Ball<N>>()) return local_center.norm();
  return shape_radius(shape, local_center);
}

#define WEDGE_INSTANTIATE(N)                                              \
  template double shape_radius<N>(const Shape<N>&, const Vec<N>&);        \
  template double shape_inradius<N>(const Shape<N>&, const Vec<N>&);      \
  template double turning_radius<N>(const Shape<N>&, const Vec<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::collision
