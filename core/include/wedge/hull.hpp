// Convex hulls of n-D point sets (Qhull, reentrant library), as a closed outward simplicial boundary
// mesh plus the hull's facet half-spaces. Used for Polytope shapes: their mass properties integrate
// the mesh (paper section 5), collision detection can use the vertices and planes.
#pragma once

#include <vector>

#include "wedge/ga/types.hpp"
#include "wedge/mesh.hpp"

namespace wedge {

template <int N>
struct ConvexHull {
  // The hull's vertices (the extreme input points, in input order) and its triangulated boundary.
  SimplexMesh<N> mesh;
  // For each input point, its index in mesh.vertices, or -1 if it is not a hull vertex.
  std::vector<int> vertex_of_point;
  // The facets as half-spaces: x is inside iff normals[f] . x <= offsets[f] for every f. Coplanar
  // input points share one facet (so a 4-cube has 8), each normal has unit length.
  std::vector<Vec<N>> normals;
  std::vector<double> offsets;
};

// Throws wedge::Error for fewer than N+1 points, non-finite coordinates, or points that do not span
// N dimensions (all coincident, collinear, coplanar, .. to a relative 1e-10), or if Qhull fails.
// Facets with more than N vertices (coplanar points) are triangulated consistently across their
// neighbours by pulling from the lowest-numbered vertex, so every cell has positive volume.
template <int N>
ConvexHull<N> convex_hull(const std::vector<Vec<N>>& points);

template <int N>
SimplexMesh<N> convex_hull_mesh(const std::vector<Vec<N>>& points);

}  // namespace wedge
