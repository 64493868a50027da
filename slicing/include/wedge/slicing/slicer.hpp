// The slicer (paper section 8): the intersection of a body's boundary mesh, placed in the world, with a
// hyperplane. Each (N-1)-simplex of the boundary that the hyperplane cuts contributes a piece of the
// cross-section's boundary: in 4D each tetrahedron gives nothing, a triangle or a quad (two triangles);
// in general the cut of a simplex with k vertices below and m above is the prism Delta(k-1) x Delta(m-1),
// split into C(k+m-2, k-1) simplices by the staircase triangulation in global vertex order, so
// neighbouring cells split their shared faces alike. Cut points are shared between cells (one per cut
// edge), so the result is an indexed, closed, consistently outward-oriented DisplayMesh<N-1> in the
// hyperplane's frame; corner normals are interpolated along the cut edges and projected into the frame.
// The orientation rule and its derivation are in docs/slicing.md.
//
// Vertices exactly on the hyperplane count as above it, for every cell alike: the mesh stays closed
// (zero-area pieces can appear, never holes).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "wedge/slicing/display_mesh.hpp"
#include "wedge/slicing/hyperplane.hpp"

namespace wedge::slicing {

// A rigid placement x_world = rotation * x_body + translation (rotation = to_matrix(body.rotor),
// translation = body.position()).
template <int N>
struct Placement {
  Mat<N> rotation = Mat<N>::Identity();
  Vec<N> translation = Vec<N>::Zero();
};

// Prepares one display mesh for repeated slicing (vertex coordinates as structure of arrays, cells
// sorted by vertex index, the edge list) and keeps the scratch space, so slicing allocates nothing once
// the output has grown. Not thread-safe: one MeshSlicer per thread.
template <int N>
class MeshSlicer {
 public:
  static_assert(N >= 3, "slicing needs N >= 3 (the slice of a 2D body is a set of points)");
  static constexpr int kCellEdges = N * (N - 1) / 2;

  explicit MeshSlicer(const DisplayMesh<N>& mesh);

  // Replaces `out` by the slice of the placed mesh with `plane`, in the plane's frame. Empty when the
  // plane misses the body.
  void slice(const Placement<N>& placement, const Hyperplane<N>& plane, DisplayMesh<N - 1>& out);
  DisplayMesh<N - 1> slice(const Placement<N>& placement, const Hyperplane<N>& plane) {
    DisplayMesh<N - 1> out;
    slice(placement, plane, out);
    return out;
  }

  std::size_t cell_count() const { return cells_.size(); }
  std::size_t vertex_count() const { return dist_.size(); }

 private:
  std::array<std::vector<double>, N> coords_;          // coords_[k][i]: coordinate k of vertex i
  std::vector<std::array<int, N>> cells_;              // vertex indices ascending
  std::vector<std::uint8_t> flipped_;                  // 1 if the ascending order is inward
  std::vector<std::array<int, kCellEdges>> cell_edges_;
  std::vector<std::array<int, 2>> edges_;              // (lower, higher) vertex index
  std::vector<std::array<Vec<N>, N>> normals_;         // in ascending corner order
  // Shading shortcuts: bit j set if corner j's normal is its vertex's normal (smooth surfaces: the cut
  // point's normal then depends on the edge alone and is made once per edge); bit 7 if all corners
  // carry one normal (a flat cell: one projected normal per cell).
  std::vector<std::uint8_t> normal_kind_;
  std::vector<Vec<N>> vertex_normals_;
  bool any_smooth_ = false;
  // Runs of kChunk consecutive cells (neighbours, in the mesh's vertex order) with a ball holding their
  // vertices: a run whose ball the plane misses is skipped whole, which leaves the output unchanged.
  static constexpr std::size_t kChunk = 16;
  std::vector<Vec<N>> chunk_center_;
  std::vector<double> chunk_radius_;
  // Scratch.
  std::vector<double> dist_;
  std::vector<std::uint8_t> above_;
  std::vector<int> edge_vertex_;  // output vertex of a cut edge, -1 if not made yet
  std::vector<double> edge_t_;    // its parameter from edges_[e][0] to edges_[e][1]
  std::vector<Eigen::Matrix<double, N - 1, 1>> edge_normal_;  // its normal from the vertex normals
  std::vector<int> touched_;
};

// The 3-flat a chain of slices ends in: slice coordinates y are the world point origin + frame * y.
template <int N>
struct Flat3 {
  Vec<N> origin = Vec<N>::Zero();
  Eigen::Matrix<double, N, 3> frame = Eigen::Matrix<double, N, 3>::Identity();
};

// Slices from N down to 3 dimensions: the first plane cuts the placed N-mesh, the next one cuts the
// (N-1)-dimensional result in the first plane's frame, and so on. SliceChain<3> is empty.
template <int N>
struct SliceChain {
  Hyperplane<N> plane;
  SliceChain<N - 1> rest;
  // x_{N-1} = w[0] in the world, then x_{N-2} = w[1] in that slice's frame, ..: the default slices.
  static SliceChain axes(const std::array<double, std::size_t(N - 3)>& w);
  Flat3<N> flat() const;
};
template <>
struct SliceChain<3> {
  static SliceChain axes(const std::array<double, 0>&) { return {}; }
  Flat3<3> flat() const { return {}; }
};

// A body's mesh sliced down to 3D: for N = 3 the placed mesh itself, for N = 4 one slice, for N = 5, 6
// repeated slices (the later ones of small meshes, prepared on the fly).
template <int N>
class BodySlicer {
 public:
  explicit BodySlicer(const DisplayMesh<N>& mesh);
  // Replaces `out` by the slice, reusing its storage (in 3D and 4D nothing is allocated once it has grown).
  void slice(const Placement<N>& placement, const SliceChain<N>& chain, DisplayMesh<3>& out);
  DisplayMesh<3> slice(const Placement<N>& placement, const SliceChain<N>& chain) {
    DisplayMesh<3> out;
    slice(placement, chain, out);
    return out;
  }

 private:
  DisplayMesh<N> mesh_;  // kept for N = 3 only
  std::vector<MeshSlicer<N>> first_;  // one element for N >= 4
};

// Convenience: the slice of a display mesh under a placement by a chain (prepares and slices once).
template <int N>
DisplayMesh<3> slice_to_3d(const DisplayMesh<N>& mesh, const Placement<N>& placement, const SliceChain<N>& chain);

}  // namespace wedge::slicing
