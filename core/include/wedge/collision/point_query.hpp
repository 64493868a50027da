// Point queries: whether a world point lies in a placed shape, and how far it is from it. The input
// layer picks what a hand grabs with them (the body that contains the hand's point, else the nearest
// within a grab radius); see docs/architecture.md.
#pragma once

#include "wedge/collision/manifold.hpp"
#include "wedge/shape.hpp"

namespace wedge {

template <int N>
struct PointQuery {
  bool inside = false;             // the point lies in the shape (its boundary included, to round-off)
  double distance = 0.0;           // m, >= 0: from the point to the shape; 0 when inside
  Vec<N> closest = Vec<N>::Zero();  // the shape's point nearest to it (world); the point itself when inside
};

// Any shape, placed by t. Containment is exact for every kind (a mesh counts as its convex hull, as in
// collision); the distance is closed-form for balls and half-spaces and from GJK otherwise (relative
// accuracy 1e-10).
template <int N>
PointQuery<N> point_query(const Shape<N>& shape, const Transform<N>& t, const Vec<N>& point);

}  // namespace wedge
