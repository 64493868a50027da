#include "wedge/collision/detail/convex_features.hpp"

#include <algorithm>
#include <iterator>
#include <set>

#include "linalg/decompositions.hpp"
#include "wedge/dimensions.hpp"

namespace wedge {
namespace {

// The orthonormal basis of the affine span of the points (its size is the face's dimension).
template <int N>
std::vector<Vec<N>> span_basis(const std::vector<Vec<N>>& pts, const std::vector<int>& idx, double tol) {
  if (idx.size() < 2) return {};
  Eigen::MatrixXd d(N, Eigen::Index(idx.size() - 1));
  for (std::size_t i = 1; i < idx.size(); ++i) d.col(Eigen::Index(i - 1)) = pts[idx[i]] - pts[idx[0]];
  std::vector<Vec<N>> basis;
  for (const Eigen::VectorXd& u : linalg::column_space_basis(d, tol)) basis.push_back(u);
  return basis;
}

template <int N>
bool same_space(const std::vector<Vec<N>>& a, const std::vector<Vec<N>>& b) {
  if (a.size() != b.size()) return false;
  for (const Vec<N>& v : b) {
    Vec<N> r = v;
    for (const Vec<N>& u : a) r -= u.dot(v) * u;
    if (r.norm() > 1e-9) return false;
  }
  return true;
}

template <int N>
void add_direction(std::vector<typename ConvexFeatures<N>::Directions>& list, std::vector<Vec<N>> basis) {
  for (const auto& d : list)
    if (same_space<N>(d.basis, basis)) return;
  list.push_back({std::move(basis)});
}

std::vector<int> intersect(const std::vector<int>& a, const std::vector<int>& b) {
  std::vector<int> r;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(r));
  return r;
}

}  // namespace

template <int N>
ConvexFeatures<N> convex_features(const ConvexHull<N>& hull) {
  ConvexFeatures<N> f;
  f.vertices = hull.mesh.vertices;
  for (const Vec<N>& v : f.vertices) f.centroid += v;
  f.centroid /= double(f.vertices.size());
  for (const Vec<N>& v : f.vertices) f.radius = std::max(f.radius, (v - f.centroid).norm());
  const double tol = 1e-9 * f.radius;

  // Facets and their vertex sets.
  std::vector<std::vector<int>> faces;  // vertex sets of the current dimension, starting with facets
  for (std::size_t i = 0; i < hull.normals.size(); ++i) {
    typename ConvexFeatures<N>::Facet facet;
    facet.normal = hull.normals[i];
    facet.offset = hull.offsets[i];
    for (int v = 0; v < int(f.vertices.size()); ++v)
      if (std::abs(facet.normal.dot(f.vertices[v]) - facet.offset) <= tol + 1e-12 * std::abs(facet.offset))
        facet.vertices.push_back(v);
    faces.push_back(facet.vertices);
    f.facets.push_back(std::move(facet));
  }

  // Faces of dimension k-1 are the intersections of two k-faces that have exactly that dimension.
  f.directions.assign(N, {});
  for (int k = N - 1; k >= 1; --k) {
    std::set<std::vector<int>> lower;
    for (std::size_t i = 0; i < faces.size(); ++i)
      for (std::size_t j = i + 1; j < faces.size(); ++j) {
        std::vector<int> common = intersect(faces[i], faces[j]);
        if (int(common.size()) < k || lower.count(common)) continue;
        if (int(span_basis<N>(f.vertices, common, tol).size()) != k - 1) continue;
        if (k == N - 1) {  // a ridge: the two facets are neighbours
          f.facets[i].neighbours.push_back(int(j));
          f.facets[j].neighbours.push_back(int(i));
        }
        lower.insert(std::move(common));
      }
    if (k == N - 1)  // facets sharing a ridge with several others were found once per pair
      for (auto& facet : f.facets) std::sort(facet.neighbours.begin(), facet.neighbours.end());
    faces.assign(lower.begin(), lower.end());
    if (k - 1 >= 1)
      for (const auto& face : faces) add_direction<N>(f.directions[k - 1], span_basis<N>(f.vertices, face, tol));
  }
  return f;
}

template <int N>
ConvexFeatures<N> box_features(const Vec<N>& h) {
  ConvexFeatures<N> f;
  constexpr int corners = 1 << N;
  for (int c = 0; c < corners; ++c) {
    Vec<N> v;
    for (int i = 0; i < N; ++i) v[i] = (c >> i & 1) ? h[i] : -h[i];
    f.vertices.push_back(v);
  }
  f.radius = h.norm();
  for (int i = 0; i < N; ++i)
    for (int s = 0; s < 2; ++s) {  // facet 2i + s: x_i = -h_i (s = 0) or +h_i (s = 1)
      typename ConvexFeatures<N>::Facet facet;
      facet.normal = Vec<N>::Unit(i) * (s ? 1.0 : -1.0);
      facet.offset = h[i];
      for (int c = 0; c < corners; ++c)
        if ((c >> i & 1) == s) facet.vertices.push_back(c);
      for (int g = 0; g < 2 * N; ++g)
        if (g / 2 != i) facet.neighbours.push_back(g);
      f.facets.push_back(std::move(facet));
    }
  f.directions.assign(N, {});
  for (int mask = 1; mask < corners; ++mask) {
    const int k = __builtin_popcount(unsigned(mask));
    if (k > N - 2) continue;
    typename ConvexFeatures<N>::Directions d;
    for (int i = 0; i < N; ++i)
      if (mask >> i & 1) d.basis.push_back(Vec<N>::Unit(i));
    f.directions[k].push_back(std::move(d));
  }
  return f;
}

#define WEDGE_INSTANTIATE(N)                                                     \
  template ConvexFeatures<N> convex_features<N>(const ConvexHull<N>& hull); \
  template ConvexFeatures<N> box_features<N>(const Vec<N>& half_extents);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge
