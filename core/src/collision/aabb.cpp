#include "wedge/collision/aabb.hpp"

#include <cmath>
#include <type_traits>
#include <variant>

#include "wedge/error.hpp"
#include "wedge/ga/products.hpp"
#include "wedge/dimensions.hpp"

namespace wedge {

template <int N>
Aabb<N> points_aabb(const std::vector<Vec<N>>& points, const Vec<N>& position, const Mat<N>& rotation) {
  if (points.empty()) throw Error("points_aabb: no points");
  Vec<N> lo = rotation * points.front(), hi = lo;
  for (const Vec<N>& p : points) {
    const Vec<N> w = rotation * p;
    lo = lo.cwiseMin(w);
    hi = hi.cwiseMax(w);
  }
  return {lo + position, hi + position};
}

template <int N>
Aabb<N> world_aabb(const Shape<N>& shape, const Vec<N>& position, const Mat<N>& rotation) {
  return std::visit(
      [&](const auto& s) -> Aabb<N> {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, shapes::Box<N>>) {
          return Aabb<N>::from_center(position, rotation.cwiseAbs() * s.half_extents);
        } else if constexpr (std::is_same_v<T, shapes::Ball<N>>) {
          return Aabb<N>::from_center(position, Vec<N>::Constant(s.radius));
        } else if constexpr (std::is_same_v<T, shapes::RoundProduct<N>>) {
          // The support of a product in direction u is the sum of its factors' supports; with
          // u = R^T e_i, a ball over axes A contributes r |(R_ia)_{a in A}|, an interval h |R_ia|.
          Vec<N> e = Vec<N>::Zero();
          for (const ProductFactor& f : s.factors)
            for (int i = 0; i < N; ++i) {
              double sq = 0.0;
              for (int a : f.axes) sq += rotation(i, a) * rotation(i, a);
              e[i] += f.size * std::sqrt(sq);
            }
          return Aabb<N>::from_center(position, e);
        } else if constexpr (std::is_same_v<T, shapes::Polytope<N>>) {
          return points_aabb<N>(shape.hull().mesh.vertices, position, rotation);
        } else if constexpr (std::is_same_v<T, shapes::Mesh<N>>) {
          return points_aabb<N>(s.mesh.vertices, position, rotation);
        } else {
          static_assert(std::is_same_v<T, shapes::Halfspace<N>>);
          throw Error("world_aabb: a half-space is unbounded and has no bounding box");
        }
      },
      shape.description());
}

template <int N>
Aabb<N> world_aabb(const Shape<N>& shape, const Vec<N>& position, const Rotor<N>& rotor) {
  return world_aabb<N>(shape, position, to_matrix(rotor));
}

#define WEDGE_INSTANTIATE_AABB(N)                                                                         \
  template Aabb<N> points_aabb<N>(const std::vector<Vec<N>>&, const Vec<N>&, const Mat<N>&);             \
  template Aabb<N> world_aabb<N>(const Shape<N>&, const Vec<N>&, const Mat<N>&);                         \
  template Aabb<N> world_aabb<N>(const Shape<N>&, const Vec<N>&, const Rotor<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE_AABB)
#undef WEDGE_INSTANTIATE_AABB

}  // namespace wedge
