// Display meshes: a body's closed outward boundary mesh ((n-1)-simplices: tetrahedra in 4D, triangles in
// 3D) with a unit normal at every corner of every cell. Smooth shapes (balls and the round factors of
// cylinders, spherinders, duocylinders, ..) carry the analytic normal of the true surface at each vertex;
// flat cells (boxes, polytopes, meshes, the interval factors of round products) carry the cell's normal
// at all of its corners, so creases stay sharp. Slicing a DisplayMesh<N> gives a DisplayMesh<N-1>
// (slicer.hpp); a DisplayMesh<3> is the triangle mesh the renderer draws.
#pragma once

#include <array>
#include <vector>

#include "wedge/ga/types.hpp"
#include "wedge/mesh.hpp"
#include "wedge/shape.hpp"

namespace wedge::slicing {

template <int N>
struct DisplayMesh {
  std::vector<Vec<N>> vertices;
  std::vector<std::array<int, N>> cells;           // outward oriented, as in wedge::SimplexMesh
  std::vector<std::array<Vec<N>, N>> normals;      // normals[c][j]: unit normal at corner j of cell c

  bool empty() const { return cells.empty(); }
};

// The outward unit normal of the cell [p0 .. p(N-1)] (oriented as in mesh.hpp: det[n, p1-p0, ..] > 0),
// or zero for a degenerate cell. In 3D this is the normalised (p1-p0) x (p2-p0).
template <int N>
Vec<N> cell_normal(const std::array<Vec<N>, N>& corners);

// The display mesh of a bounded shape at the given tessellation level (see wedge::boundary_mesh: boxes
// and polytopes are exact at any level, round shapes get finer with it). Throws wedge::Error for a
// half-space (the renderer draws the ground separately) or an invalid level.
template <int N>
DisplayMesh<N> display_mesh(const Shape<N>& shape, int subdivisions = default_subdivisions(N));

// Flat normals for every cell of a simplicial mesh (no smooth vertices).
template <int N>
DisplayMesh<N> flat_display_mesh(const SimplexMesh<N>& mesh);

}  // namespace wedge::slicing
