#include "wedge/hull.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <sstream>
#include <string>

#include "linalg/decompositions.hpp"
#include "linalg/fixed_size.hpp"
#include "wedge/error.hpp"
#include "wedge/dimensions.hpp"

// Qhull's C headers last: they define many macros.
#include <libqhull_r/qhull_ra.h>

namespace wedge {
namespace {

struct RawFacet {
  std::vector<int> vertices;  // input point indices, sorted
  std::vector<double> normal;  // unit, outward
  double offset = 0.0;         // normal . x + offset = 0 on the facet, < 0 inside
};

// Captures what Qhull writes to its error stream (it must never reach our stderr).
class ErrStream {
 public:
  ErrStream() : file_(open_memstream(&buf_, &len_)) {}
  ~ErrStream() {
    if (file_) std::fclose(file_);
    std::free(buf_);
  }
  ErrStream(const ErrStream&) = delete;
  ErrStream& operator=(const ErrStream&) = delete;
  FILE* file() const { return file_; }
  std::string first_line() {
    if (!file_) return {};
    std::fflush(file_);
    std::string s = buf_ ? std::string(buf_, len_) : std::string();
    const std::size_t a = s.find_first_not_of(" \n");
    if (a == std::string::npos) return {};
    return s.substr(a, s.find('\n', a) - a);
  }

 private:
  char* buf_ = nullptr;
  std::size_t len_ = 0;
  FILE* file_ = nullptr;
};

std::vector<RawFacet> run_qhull(int dim, std::vector<double> coords) {
  ErrStream err;
  if (!err.file()) throw Error("convex hull: cannot open a buffer for Qhull's messages");
  auto qh_storage = std::make_unique<qhT>();
  qhT* qh = qh_storage.get();
  QHULL_LIB_CHECK
  qh_zero(qh, err.file());
  // Default options: Qhull merges coplanar facets (we triangulate them ourselves, see below).
  char cmd[] = "qhull";
  const int npoints = int(coords.size()) / dim;
  const int code = qh_new_qhull(qh, dim, npoints, coords.data(), False, cmd, nullptr, err.file());
  std::vector<RawFacet> out;
  if (code == 0) {
    facetT* facet;
    vertexT *vertex, **vertexp;
    FORALLfacets {
      RawFacet f;
      FOREACHvertex_(facet->vertices) f.vertices.push_back(qh_pointid(qh, vertex->point));
      std::sort(f.vertices.begin(), f.vertices.end());
      f.normal.assign(facet->normal, facet->normal + dim);
      f.offset = facet->offset;
      out.push_back(std::move(f));
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  if (code != 0) {
    const std::string msg = err.first_line();
    throw Error("convex hull: Qhull failed (error " + std::to_string(code) + ")" + (msg.empty() ? "" : ": " + msg));
  }
  return out;
}

// The pulling triangulation of the hull boundary: a face with vertex set S is a simplex if it has
// dim + 1 vertices; otherwise it is the union of the cones from its lowest vertex v over the
// triangulations of its facets not containing v. A face's triangulation depends only on the face, so
// neighbouring facets agree on their common ridges. The facets of a face S are the maximal proper
// intersections of S with the hull's facets.
class Triangulator {
 public:
  explicit Triangulator(const std::vector<RawFacet>& facets) : facets_(facets) {}

  const std::vector<std::vector<int>>& triangulate(const std::vector<int>& s, int dim) {
    auto it = memo_.find(s);
    if (it != memo_.end()) return it->second;
    std::vector<std::vector<int>> cells;
    if (int(s.size()) == dim + 1) {
      cells.push_back(s);
    } else {
      if (dim < 1 || int(s.size()) < dim + 1) throw Error("convex hull: inconsistent face structure from Qhull");
      std::vector<std::vector<int>> cand;
      for (const RawFacet& f : facets_) {
        std::vector<int> t;
        std::set_intersection(s.begin(), s.end(), f.vertices.begin(), f.vertices.end(), std::back_inserter(t));
        if (t.size() < s.size() && int(t.size()) >= dim) cand.push_back(std::move(t));
      }
      std::sort(cand.begin(), cand.end());
      cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
      const int apex = s.front();
      for (std::size_t i = 0; i < cand.size(); ++i) {
        bool maximal = true;
        for (std::size_t j = 0; j < cand.size() && maximal; ++j)
          if (j != i && cand[j].size() > cand[i].size() &&
              std::includes(cand[j].begin(), cand[j].end(), cand[i].begin(), cand[i].end()))
            maximal = false;
        if (!maximal || std::binary_search(cand[i].begin(), cand[i].end(), apex)) continue;
        for (const std::vector<int>& sub : triangulate(cand[i], dim - 1)) {
          std::vector<int> cell{apex};
          cell.insert(cell.end(), sub.begin(), sub.end());
          cells.push_back(std::move(cell));
        }
      }
      if (cells.empty()) throw Error("convex hull: inconsistent face structure from Qhull");
    }
    return memo_.emplace(s, std::move(cells)).first->second;
  }

 private:
  const std::vector<RawFacet>& facets_;
  std::map<std::vector<int>, std::vector<std::vector<int>>> memo_;
};

}  // namespace

template <int N>
ConvexHull<N> convex_hull(const std::vector<Vec<N>>& points) {
  const int n = int(points.size());
  if (n < N + 1)
    throw Error("convex hull in " + std::to_string(N) + "D needs at least " + std::to_string(N + 1) +
                " points (got " + std::to_string(n) + ")");
  // Qhull's determinants multiply N coordinates: beyond 1e30 m (10^180 in 6D) they overflow, and Qhull
  // then reads facets it never made (a crash, found by fuzzing a 24-cell of circumradius 2e235 m).
  constexpr double kMaxCoordinate = 1e30;
  for (int i = 0; i < n; ++i) {
    if (!all_finite(points[std::size_t(i)]))
      throw Error("convex hull: point " + std::to_string(i) + " has a non-finite coordinate");
    if (!(points[std::size_t(i)].cwiseAbs().maxCoeff() <= kMaxCoordinate)) {
      std::ostringstream s;
      s << "convex hull: point " << i << " has a coordinate of " << points[std::size_t(i)].cwiseAbs().maxCoeff()
        << " m; at most " << kMaxCoordinate << " m is supported";
      throw Error(s.str());
    }
  }

  // The points must span R^N: singular values of the centred point matrix, relative to the largest.
  Vec<N> mean = Vec<N>::Zero();
  for (const Vec<N>& p : points) mean += p;
  mean /= double(n);
  Eigen::MatrixXd a(N, n);
  for (int i = 0; i < n; ++i) a.col(i) = points[std::size_t(i)] - mean;
  const Eigen::VectorXd sv = linalg::singular_values(a);
  if (!(sv[0] > 0.0)) throw Error("convex hull: all " + std::to_string(n) + " points coincide");
  int rank = 0;
  for (int i = 0; i < N; ++i) rank += sv[i] > 1e-10 * sv[0] ? 1 : 0;
  if (rank < N)
    throw Error("convex hull: the points are flat: they span only a " + std::to_string(rank) +
                "-dimensional affine subspace of R^" + std::to_string(N) + " (collinear, coplanar or coincident)");

  std::vector<double> coords(std::size_t(n) * N);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < N; ++j) coords[std::size_t(i) * N + std::size_t(j)] = points[std::size_t(i)][j];
  const std::vector<RawFacet> facets = run_qhull(N, std::move(coords));
  if (facets.size() < std::size_t(N + 1)) throw Error("convex hull: Qhull returned too few facets");

  ConvexHull<N> hull;
  hull.vertex_of_point.assign(std::size_t(n), -1);
  for (const RawFacet& f : facets)
    for (int v : f.vertices) hull.vertex_of_point[std::size_t(v)] = 0;
  for (int i = 0; i < n; ++i)
    if (hull.vertex_of_point[std::size_t(i)] == 0) {
      hull.vertex_of_point[std::size_t(i)] = int(hull.mesh.vertices.size());
      hull.mesh.vertices.push_back(points[std::size_t(i)]);
    }
  Vec<N> inside = Vec<N>::Zero();
  for (const Vec<N>& v : hull.mesh.vertices) inside += v;
  inside /= double(hull.mesh.vertices.size());

  Triangulator tri(facets);
  for (const RawFacet& f : facets) {
    Vec<N> normal;
    for (int j = 0; j < N; ++j) normal[j] = f.normal[std::size_t(j)];
    hull.normals.push_back(normal);
    hull.offsets.push_back(-f.offset);
    for (const std::vector<int>& c : tri.triangulate(f.vertices, N - 1)) {
      std::array<int, N> cell;
      Mat<N> m;
      for (int j = 0; j < N; ++j) {
        cell[std::size_t(j)] = hull.vertex_of_point[std::size_t(c[std::size_t(j)])];
        m.col(j) = points[std::size_t(c[std::size_t(j)])] - inside;
      }
      if (linalg::determinant<N>(m) < 0.0) std::swap(cell[0], cell[1]);
      hull.mesh.cells.push_back(cell);
    }
  }
  try {
    validate(hull.mesh);
  } catch (const Error& e) {
    throw Error(std::string("convex hull: the triangulated hull is invalid (nearly degenerate input?): ") + e.what());
  }
  return hull;
}

template <int N>
SimplexMesh<N> convex_hull_mesh(const std::vector<Vec<N>>& points) {
  return convex_hull<N>(points).mesh;
}

#define WEDGE_INSTANTIATE_HULL(N)                                               \
  template ConvexHull<N> convex_hull<N>(const std::vector<Vec<N>>&);            \
  template SimplexMesh<N> convex_hull_mesh<N>(const std::vector<Vec<N>>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE_HULL)
#undef WEDGE_INSTANTIATE_HULL

}  // namespace wedge
