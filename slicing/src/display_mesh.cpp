#include "wedge/slicing/display_mesh.hpp"

#include <Eigen/LU>
#include <cmath>
#include <variant>

#include "wedge/error.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::slicing {

template <int N>
Vec<N> cell_normal(const std::array<Vec<N>, N>& corners) {
  // n_i = cofactor of entry (i, 0) of [n, E] with E = [p1-p0 .. p(N-1)-p0]; then det[n, E] = |n|^2 > 0.
  Eigen::Matrix<double, N, N - 1> e;
  for (int j = 1; j < N; ++j) e.col(j - 1) = corners[std::size_t(j)] - corners[0];
  Vec<N> n;
  for (int i = 0; i < N; ++i) {
    Eigen::Matrix<double, N - 1, N - 1> minor;
    for (int r = 0, k = 0; r < N; ++r)
      if (r != i) minor.row(k++) = e.row(r);
    n[i] = ((i & 1) ? -1.0 : 1.0) * minor.determinant();
  }
  const double len = n.norm();
  return len > 0.0 && std::isfinite(len) ? Vec<N>(n / len) : Vec<N>(Vec<N>::Zero());
}

namespace {

template <int N>
std::array<Vec<N>, N> corners_of(const SimplexMesh<N>& mesh, const std::array<int, N>& cell) {
  std::array<Vec<N>, N> p;
  for (int j = 0; j < N; ++j) p[std::size_t(j)] = mesh.vertices[std::size_t(cell[std::size_t(j)])];
  return p;
}

// The outward unit normal of the factor's boundary at x: x_A / |x_A| for a ball over axes A, +-e_a for
// an interval on axis a. Zero where it is undefined.
template <int N>
Vec<N> factor_normal(const ProductFactor& f, const Vec<N>& x) {
  Vec<N> n = Vec<N>::Zero();
  if (f.kind == ProductFactor::Kind::Interval) {
    n[f.axes[0]] = x[f.axes[0]] >= 0.0 ? 1.0 : -1.0;
    return n;
  }
  for (int a : f.axes) n[a] = x[a];
  const double len = n.norm();
  return len > 0.0 ? Vec<N>(n / len) : Vec<N>(Vec<N>::Zero());
}

// Smooth normals for a round product: each cell lies on the boundary of one factor (the box facet it
// was generated from), found as the factor whose normal at the cell's centroid best matches the flat
// cell normal. Ball factors get the exact surface normal (the gradient of |x_A| - r) at every corner.
template <int N>
DisplayMesh<N> round_display_mesh(const SimplexMesh<N>& mesh, const std::vector<ProductFactor>& factors) {
  DisplayMesh<N> out = flat_display_mesh(mesh);
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
    const std::array<Vec<N>, N> p = corners_of<N>(mesh, mesh.cells[c]);
    Vec<N> centroid = Vec<N>::Zero();
    for (const Vec<N>& v : p) centroid += v / double(N);
    const Vec<N> flat = out.normals[c][0];
    const ProductFactor* best = nullptr;
    double best_dot = -2.0;
    for (const ProductFactor& f : factors) {
      const double d = factor_normal<N>(f, centroid).dot(flat);
      if (d > best_dot) {
        best_dot = d;
        best = &f;
      }
    }
    if (best == nullptr || best->kind != ProductFactor::Kind::Ball) continue;
    for (int j = 0; j < N; ++j) {
      const Vec<N> n = factor_normal<N>(*best, p[std::size_t(j)]);
      if (n.squaredNorm() > 0.0) out.normals[c][std::size_t(j)] = n;
    }
  }
  return out;
}

}  // namespace

template <int N>
DisplayMesh<N> flat_display_mesh(const SimplexMesh<N>& mesh) {
  DisplayMesh<N> out;
  out.vertices = mesh.vertices;
  out.cells = mesh.cells;
  out.normals.resize(mesh.cells.size());
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
    const Vec<N> n = cell_normal<N>(corners_of<N>(mesh, mesh.cells[c]));
    out.normals[c].fill(n);
  }
  return out;
}

template <int N>
DisplayMesh<N> display_mesh(const Shape<N>& shape, int subdivisions) {
  // A box is flat: its coarsest tessellation is exact, and finer ones only multiply the triangles of its
  // slice (a tesseract's slice was 4,352 triangles at the 4D default instead of a few dozen).
  const bool flat = shape.template is<shapes::Box<N>>();
  const SimplexMesh<N> mesh = boundary_mesh<N>(shape, flat ? 1 : subdivisions);  // throws for a half-space
  if (shape.template is<shapes::Ball<N>>()) {
    std::vector<int> all;
    for (int i = 0; i < N; ++i) all.push_back(i);
    return round_display_mesh<N>(mesh, {ProductFactor::ball(all, shape.template as<shapes::Ball<N>>().radius)});
  }
  if (shape.template is<shapes::RoundProduct<N>>())
    return round_display_mesh<N>(mesh, shape.template as<shapes::RoundProduct<N>>().factors);
  return flat_display_mesh<N>(mesh);
}

#define WEDGE_INSTANTIATE_DISPLAY_MESH(N)                                      \
  template struct DisplayMesh<N>;                                              \
  template Vec<N> cell_normal<N>(const std::array<Vec<N>, N>&);                \
  template DisplayMesh<N> display_mesh<N>(const Shape<N>&, int);               \
  template DisplayMesh<N> flat_display_mesh<N>(const SimplexMesh<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE_DISPLAY_MESH)
#undef WEDGE_INSTANTIATE_DISPLAY_MESH

}  // namespace wedge::slicing
