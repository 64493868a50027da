// Internal: how far a shape reaches from a point in its own frame (its centre of mass), for the
// speculative margin, the continuous stage's choice of fast bodies and the time of impact's rotational
// bound.
#pragma once

#include "wedge/shape.hpp"

namespace wedge::collision {

// The distance from the point to the farthest point of the shape (m): exact over the vertices of a shape
// with a face lattice, else a bound from its box in its own frame; 0 for a half-space.
template <int N>
double shape_radius(const Shape<N>& shape, const Vec<N>& local_center);

// The distance from the point to the nearest point of the shape's surface (m): over the facets' planes
// for a shape with a face lattice; for a ball its radius less the point's offset; for a round product
// its thinnest factor less the offset; 0 for a half-space, or a point outside the shape.
template <int N>
double shape_inradius(const Shape<N>& shape, const Vec<N>& local_center);

// How far the shape's surface moves at most when it turns about the point by an angle a: a times this
// (m per rad). shape_radius, except for a ball, whose surface turned about its own centre does not move:
// only the point's offset from the centre counts.
template <int N>
double turning_radius(const Shape<N>& shape, const Vec<N>& local_center);

}  // namespace wedge::collision
