// The narrow phase: every pair of shapes collides through one dispatch table indexed by the two shapes'
// kinds (narrow_phase.cpp). Each family of pairs has its own source file in core/src/collision/:
//   ball_ball.cpp          ball - ball
//   ball_convex.cpp        ball - box, round product, polytope, mesh (closest point, paper section 7.1)
//   halfspace_convex.cpp   half-space - any bounded shape (the shape's support set below the plane)
//   box_box.cpp            box - box (separating axes, Eberly's test extended to nD, section 7.2)
//   polytope_polytope.cpp  polytope/box/mesh pairs (the general SAT of section 7.2 over k-face x
//                          (N-1-k)-face axes)
//   convex_convex.cpp      anything else, e.g. round product - polytope (GJK + EPA on support functions)
// A mesh shape collides as its convex hull. Two half-spaces never collide (both are static).
#pragma once

#include "wedge/collision/manifold.hpp"
#include "wedge/shape.hpp"

namespace wedge {

// The kinds, in the order of Shape<N>::Variant; the dispatch table is indexed by them.
enum class ShapeKind : int { Box, Ball, Polytope, Mesh, Halfspace, RoundProduct, Count };

template <int N>
ShapeKind kind_of(const Shape<N>& shape) {
  return ShapeKind(shape.description().index());
}

// The contact between shape a placed by ta and shape b placed by tb. The normal points from a to b.
template <int N>
Manifold<N> collide(const Shape<N>& a, const Transform<N>& ta, const Shape<N>& b, const Transform<N>& tb,
                    const CollisionSettings& settings = {});

}  // namespace wedge
