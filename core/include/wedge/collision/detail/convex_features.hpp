// The face lattice of a convex polytope, as the separating axis test (paper section 7.2) and face
// clipping need it: vertices; facets as half-spaces with their vertices and ridge neighbours; and for
// every dimension k = 1..N-2 the distinct direction spaces of the k-faces (parallel faces share one,
// which is what keeps a box's SAT at 56 axes in 4D rather than thousands).
#pragma once

#include <vector>

#include "wedge/ga/types.hpp"
#include "wedge/hull.hpp"

namespace wedge {

template <int N>
struct ConvexFeatures {
  struct Facet {
    Vec<N> normal;                // unit, outward
    double offset = 0.0;          // normal . x <= offset inside
    std::vector<int> vertices;    // indices into `vertices`, ascending
    std::vector<int> neighbours;  // facets sharing a ridge ((N-2)-face) with this one, ascending
  };
  // A k-dimensional direction space: k orthonormal vectors.
  struct Directions {
    std::vector<Vec<N>> basis;
  };

  std::vector<Vec<N>> vertices;
  std::vector<Facet> facets;
  // directions[k] for k = 0..N-1; only 1..N-2 are filled (vertices have no direction, facets have
  // their normals). Distinct up to 1e-9.
  std::vector<std::vector<Directions>> directions;
  Vec<N> centroid = Vec<N>::Zero();  // the mean of the vertices: an interior point
  double radius = 0.0;               // max |v - centroid|: the length scale for tolerances
};

// From a hull (wedge::convex_hull); the faces are the intersections of the facets' vertex sets.
template <int N>
ConvexFeatures<N> convex_features(const ConvexHull<N>& hull);

// The box [-h, h] directly (no hull needed): 2N facets, direction spaces spanned by k axes.
template <int N>
ConvexFeatures<N> box_features(const Vec<N>& half_extents);

}  // namespace wedge
