// The dispatch table: one entry per pair of shape kinds. Each entry names the family function and
// whether the pair is passed swapped (the function wants its shapes in the other order; the manifold's
// normal is then reversed).
#include <algorithm>
#include <array>
#include <limits>

#include "collision/narrow.hpp"
#include "wedge/collision/detail/gjk.hpp"
#include "wedge/dimensions.hpp"

namespace wedge {
namespace {

using collision::PairFn;

template <int N>
struct Entry {
  PairFn<N> fn = nullptr;  // null: the pair never collides (two half-spaces)
  bool swap = false;
};

template <int N>
constexpr auto make_table() {
  using namespace collision;
  constexpr int K = int(ShapeKind::Count);
  std::array<std::array<Entry<N>, K>, K> t{};
  auto set = [&](ShapeKind x, ShapeKind y, PairFn<N> fn) {
    t[int(x)][int(y)] = {fn, false};
    t[int(y)][int(x)] = {fn, x != y};
  };
  const ShapeKind Box = ShapeKind::Box, Ball = ShapeKind::Ball, Poly = ShapeKind::Polytope, Mesh = ShapeKind::Mesh,
                  Half = ShapeKind::Halfspace, Round = ShapeKind::RoundProduct;
  set(Ball, Ball, &ball_ball<N>);
  for (ShapeKind k : {Box, Poly, Mesh, Round}) set(Ball, k, &ball_convex<N>);
  for (ShapeKind k : {Box, Ball, Poly, Mesh, Round}) set(Half, k, &halfspace_convex<N>);
  set(Box, Box, &box_box<N>);
  for (ShapeKind x : {Box, Poly, Mesh})
    for (ShapeKind y : {Poly, Mesh}) set(x, y, &polytope_polytope<N>);
  for (ShapeKind k : {Box, Poly, Mesh, Round}) set(Round, k, &convex_convex<N>);
  return t;
}

}  // namespace

template <int N>
Manifold<N> collide(const Shape<N>& a, const Transform<N>& ta, const Shape<N>& b, const Transform<N>& tb,
                    const CollisionSettings& settings) {
  static const auto table = make_table<N>();
  const Entry<N>& e = table[int(kind_of(a))][int(kind_of(b))];
  if (!e.fn) {
    Manifold<N> none;
    none.depth = -std::numeric_limits<double>::infinity();
    return none;
  }
  Manifold<N> m = e.swap ? collision::flipped(e.fn(b, tb, a, ta, settings)) : e.fn(a, ta, b, tb, settings);
  if (settings.exact_separation && !m.intersecting && a.features() && b.features() &&
      m.depth < -collision::round_off_band(std::max(a.features()->radius, b.features()->radius))) {
    // The separating axis test only bounds the distance from below; GJK gives it exactly. Not for pairs
    // that touch to round-off: there GJK's direction is arbitrary, the separating axis's is the face's.
    const auto sa = [&](const Vec<N>& d) { return collision::world_support(a, ta, d); };
    const auto sb = [&](const Vec<N>& d) { return collision::world_support(b, tb, d); };
    const GjkResult<N> g = gjk<N>(sa, sb, Vec<N>(tb.position - ta.position));
    if (!g.intersecting && g.distance > 0.0) {
      m.depth = -g.distance;
      m.normal = (g.point_b - g.point_a) / g.distance;
    }
  }
  return m;
}

#define WEDGE_INSTANTIATE(N)                                                                                 \
  template Manifold<N> collide<N>(const Shape<N>&, const Transform<N>&, const Shape<N>&, const Transform<N>&, \
                                  const CollisionSettings&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge
