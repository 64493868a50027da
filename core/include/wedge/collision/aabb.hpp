// Axis-aligned bounding boxes in n-D, and the tight world box of a placed shape. The broad phase
// (broadphase.hpp) keeps one fattened box per body in a dynamic tree.
#pragma once

#include <vector>

#include "wedge/ga/types.hpp"
#include "wedge/shape.hpp"

namespace wedge {

// The closed box lo <= x <= hi (componentwise). A box with lo_i == hi_i on some axis is flat, not empty.
template <int N>
struct Aabb {
  Vec<N> lo = Vec<N>::Zero();
  Vec<N> hi = Vec<N>::Zero();

  Vec<N> center() const { return 0.5 * (lo + hi); }
  Vec<N> half_extents() const { return 0.5 * (hi - lo); }
  // hi - lo: the side lengths.
  Vec<N> extents() const { return hi - lo; }
  // Finite and lo <= hi on every axis.
  bool valid() const { return all_finite(lo) && all_finite(hi) && (lo.array() <= hi.array()).all(); }

  static Aabb from_center(const Vec<N>& center, const Vec<N>& half_extents) {
    return {center - half_extents, center + half_extents};
  }
};

// Closed boxes: touching faces count as overlapping.
template <int N>
inline bool overlaps(const Aabb<N>& a, const Aabb<N>& b) {
  for (int i = 0; i < N; ++i)
    if (a.hi[i] < b.lo[i] || b.hi[i] < a.lo[i]) return false;
  return true;
}

// The smallest box containing both.
template <int N>
inline Aabb<N> merged(const Aabb<N>& a, const Aabb<N>& b) {
  return {a.lo.cwiseMin(b.lo), a.hi.cwiseMax(b.hi)};
}

// True if `inner` lies inside `outer` (boundaries may touch).
template <int N>
inline bool contains(const Aabb<N>& outer, const Aabb<N>& inner) {
  return (outer.lo.array() <= inner.lo.array()).all() && (inner.hi.array() <= outer.hi.array()).all();
}

// The box grown by `margin` (m) on every side.
template <int N>
inline Aabb<N> fattened(const Aabb<N>& a, double margin) {
  return {(a.lo.array() - margin).matrix(), (a.hi.array() + margin).matrix()};
}

// The tree's cost of a box: the sum of its side lengths (in 2D half the perimeter, in any n 2^(1-n)
// times the total length of the box's edges). Not the (n-1)-face measure ("surface area"): that is a
// product of n-1 sides, which vanishes for a box flat on two axes and mixes sides of very different
// sizes badly in 5D and 6D, so the insertion heuristic would stop seeing growth along the other axes.
// The sum of sides is the first-order term in the query box size s of the overlap probability of a
// node, prod_i (e_i + s), is never zero for a box of nonzero size, and costs N - 1 additions.
template <int N>
inline double cost(const Aabb<N>& a) {
  return (a.hi - a.lo).sum();
}

// The tight axis-aligned box of the shape placed with x_world = position + rotation * x_body.
// Box: extent_i = sum_j |R_ij| h_j. Ball: the radius on every axis. Round product: per factor, a ball
// over axes A adds radius * |row i of R restricted to A|, an interval on axis a adds half_length * |R_ia|.
// Polytope: the hull vertices; mesh: every vertex of the mesh (tight when every vertex is used by a
// cell, as for every generated or validated-and-loaded mesh; otherwise still a bound). `rotation` need
// not be exactly orthogonal: the formulas bound the image of the shape under any linear map, except
// the ball's, which assumes a rotation. Throws wedge::Error for a half-space (unbounded).
template <int N>
Aabb<N> world_aabb(const Shape<N>& shape, const Vec<N>& position, const Mat<N>& rotation);
template <int N>
Aabb<N> world_aabb(const Shape<N>& shape, const Vec<N>& position, const Rotor<N>& rotor);

// The box of position + rotation * p over the points p (non-empty; throws wedge::Error if empty).
template <int N>
Aabb<N> points_aabb(const std::vector<Vec<N>>& points, const Vec<N>& position, const Mat<N>& rotation);

}  // namespace wedge
