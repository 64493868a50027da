// Closed oriented simplicial boundary meshes of n-D solids ((n-1)-simplices: segments in 2D, triangles
// in 3D, tetrahedra in 4D), their validation, and generators for boxes and round products (n-balls,
// cylinders, spherinders, duocylinders, ...). The mass properties of section 5 of the paper integrate them.
#pragma once

#include <array>
#include <utility>
#include <vector>

#include "wedge/ga/types.hpp"

namespace wedge {

// Cells are oriented outward: for a point c inside the solid, det[v0 - c, .., v(N-1) - c] > 0 for every
// cell (in 2D: counter-clockwise). Vertices not used by any cell are allowed and ignored.
template <int N>
struct SimplexMesh {
  std::vector<Vec<N>> vertices;
  std::vector<std::array<int, N>> cells;
};

// Throws wedge::Error naming the first problem found: no cells, vertex index out of range, a vertex
// repeated in a cell, a non-finite coordinate, a zero-volume (degenerate) cell, an open or non-manifold
// boundary or inconsistently oriented neighbours (every (N-2)-face must be shared by exactly two cells
// inducing opposite orientations), a body of negligible volume, or an inside-out (negative volume) mesh.
template <int N>
void validate(const SimplexMesh<N>& mesh);

// sum over cells of det[v0 .. v(N-1)] / N!: the enclosed volume of a closed outward mesh.
template <int N>
double signed_volume(const SimplexMesh<N>& mesh);

// One factor of a round product: a ball over `axes` (a disk for two axes, a 3-ball for three) or an
// interval [-size, size] along a single axis. The factors of a product partition the axes 0..N-1.
struct ProductFactor {
  enum class Kind { Ball, Interval };
  std::vector<int> axes;
  Kind kind = Kind::Ball;
  double size = 0.0;  // the radius of a ball, the half-length of an interval

  static ProductFactor ball(std::vector<int> axes, double radius) { return {std::move(axes), Kind::Ball, radius}; }
  static ProductFactor interval(int axis, double half_length) { return {{axis}, Kind::Interval, half_length}; }
};

// Throws wedge::Error unless the factors partition 0..N-1, every size is positive and finite and every
// interval has exactly one axis.
template <int N>
void validate_factors(const std::vector<ProductFactor>& factors);

// The tessellation level: every edge of the box is cut into `subdivisions` equal parts, each (N-1)-face
// gridded accordingly and every grid cube split into (N-1)! simplices (Kuhn/Freudenthal). The mesh has
// 2N * subdivisions^(N-1) * (N-1)! cells; see box_mesh_cell_count. A generator refuses levels above
// max_mesh_cells() cells.
inline constexpr long long max_mesh_cells() { return 20'000'000; }
long long box_mesh_cell_count(int n, int subdivisions);
// A default level for round shapes that keeps meshes near or below 10^4 cells in 2D..5D (46080 in 6D).
constexpr int default_subdivisions(int n) { return n <= 3 ? 8 : (n == 4 ? 4 : 2); }

// The boundary of the box [-h, h] (h = half_extents), centred at the origin, oriented outward.
template <int N>
SimplexMesh<N> box_mesh(const Vec<N>& half_extents, int subdivisions = 1);

// The box-grid mesh with half-extent `size` on each factor's axes, mapped factor by factor through
// x -> x |x|_inf / |x|_2 (the d-cube onto the d-ball) for ball factors. All vertices lie on the true
// surface; the solid is exactly the product of the factors' inscribed polytopes. One factor over all
// axes gives the n-ball, disk x interval the cylinder, disk x disk the duocylinder, and so on.
template <int N>
SimplexMesh<N> round_product_mesh(const std::vector<ProductFactor>& factors, int subdivisions);

// The n-ball of radius r as a round product with one factor.
template <int N>
SimplexMesh<N> ball_mesh(double radius, int subdivisions);

}  // namespace wedge
