// World::query_point and World::ray_cast: candidates from the broad phase's tree (and the half-spaces,
// which have no box), then the exact point query on each shape.
#include <algorithm>
#include <cmath>

#include "contact/contact_system.hpp"
#include "wedge/dimensions.hpp"
#include "wedge/collision/point_query.hpp"
#include "wedge/error.hpp"
#include "wedge/world.hpp"

namespace wedge {

namespace {
template <int N>
Transform<N> placement(const Body<N>& b) {
  return Transform<N>{b.position(), to_matrix(b.rotor)};
}

// Calls f(body index) for every body with a shape whose box meets `box` (each once, in an order fixed by
// the tree, then the half-spaces).
template <int N, class F>
void candidates(const contact::ContactState<N>& s, const Aabb<N>& box, F&& f) {
  s.list.broad_phase.query(box, [&](int proxy) { f(s.list.broad_phase.user_id(proxy)); });
  for (std::uint32_t i : s.list.halfspaces) f(i);
}
}  // namespace

template <int N>
std::optional<BodyPointHit<N>> World<N>::query_point(const Vec<N>& x, double max_distance, bool include_static) const {
  if (!all_finite(x) || !(max_distance >= 0.0) || !std::isfinite(max_distance))
    throw Error("query_point: the point must be finite and max_distance finite and >= 0");
  std::optional<BodyPointHit<N>> best;
  const Aabb<N> box = Aabb<N>::from_center(x, Vec<N>::Constant(max_distance));
  candidates(*contact_, box, [&](std::uint32_t i) {
    if (!include_static && bodies_[i].type == BodyType::Static) return;
    const PointQuery<N> q = point_query(*shapes_[i], placement(bodies_[i]), x);
    if (!q.inside && q.distance > max_distance) return;
    // Inside beats outside; then the smaller distance; then the lower index (the tree's order is not it).
    const bool better = !best || (q.inside && !best->inside) ||
                        (q.inside == best->inside && (q.distance < best->distance ||
                                                      (q.distance == best->distance && i < best->body.index)));
    if (better) best = BodyPointHit<N>{BodyId{i}, q.inside, q.inside ? 0.0 : q.distance, q.closest};
  });
  return best;
}

// Sphere tracing: from a point outside a convex shape, the ball of radius `distance` is free of it, so
// the ray can advance that far without passing it; the steps shrink as the ray closes in. It stops
// within kHitTolerance (1e-12 m) of the surface, or once it has gone past max_distance (or the nearest hit).
template <int N>
std::optional<RayHit<N>> World<N>::ray_cast(const Vec<N>& origin, const Vec<N>& direction, double max_distance,
                                            bool include_static) const {
  const double length = direction.norm();
  if (!all_finite(origin) || !all_finite(direction) || !(length > 0.0) || !(max_distance >= 0.0) ||
      !std::isfinite(max_distance))
    throw Error("ray_cast: origin and direction must be finite, direction non-zero, max_distance finite and >= 0");
  constexpr double kHitTolerance = 1e-12;  // m
  constexpr int kMaxSteps = 4000;  // (a ray grazing a face at angle a closes in by a factor 1 - sin a per step)
  const Vec<N> d = direction / length;
  const Vec<N> end = origin + max_distance * d;
  Aabb<N> box;
  box.lo = origin.cwiseMin(end);
  box.hi = origin.cwiseMax(end);
  std::optional<RayHit<N>> best;
  candidates(*contact_, box, [&](std::uint32_t i) {
    if (!include_static && bodies_[i].type == BodyType::Static) return;
    const Shape<N>& shape = *shapes_[i];
    const Transform<N> t = placement(bodies_[i]);
    const double limit = best ? std::min(best->distance, max_distance) : max_distance;
    double s = 0.0;
    PointQuery<N> q = point_query(shape, t, origin);
    if (q.inside) {
      if (!best || 0.0 < best->distance || (best->distance == 0.0 && i < best->body.index))
        best = RayHit<N>{BodyId{i}, 0.0, origin, -d};
      return;
    }
    auto take = [&](double at, const Vec<N>& normal) {
      if (at <= limit && (!best || at < best->distance || (at == best->distance && i < best->body.index)))
        best = RayHit<N>{BodyId{i}, at, Vec<N>(origin + at * d), normal};
    };
    for (int k = 0; k < kMaxSteps; ++k) {
      const Vec<N> x = origin + s * d;
      if (q.inside) return take(s, Vec<N>(-d));  // (round-off: stepped onto the surface; rare)
      if (q.distance <= kHitTolerance) return take(s, Vec<N>((x - q.closest) / q.distance));
      s += q.distance;
      if (s > limit) return;
      q = point_query(shape, t, Vec<N>(origin + s * d));
    }
  });
  return best;
}

#define WEDGE_INSTANTIATE(N)                                                                                    \
  template std::optional<BodyPointHit<N>> World<N>::query_point(const Vec<N>&, double, bool) const;            \
  template std::optional<RayHit<N>> World<N>::ray_cast(const Vec<N>&, const Vec<N>&, double, bool) const;
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge
