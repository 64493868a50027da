#include "wedge/slicing/slicer.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <limits>
#include <cmath>

#include "wedge/error.hpp"

namespace wedge::slicing {
namespace {

constexpr int local_edge(int n, int i, int j) { return i * n - i * (i + 1) / 2 + (j - i - 1); }

// The case table: for each sign pattern (bit j set: corner j is above the plane) and each orientation
// of the cell in ascending vertex order, the output simplices as lists of local edges. At most
// C(N-2, (N-2)/2) simplices (6 in 6D).
template <int N>
struct CaseTable {
  static constexpr int kMaxSimplices = N <= 4 ? 2 : (N == 5 ? 3 : 6);
  struct Case {
    int count = 0;
    std::array<std::array<std::uint8_t, N - 1>, kMaxSimplices> simplex{};
  };
  std::array<Case, (1 << N) * 2> cases{};  // index: code | flipped << N

  CaseTable() {
    for (int code = 1; code < (1 << N) - 1; ++code) {
      std::vector<int> below, above;
      for (int j = 0; j < N; ++j) (((code >> j) & 1) ? above : below).push_back(j);
      const int k = int(below.size()), m = int(above.size());
      // Staircase paths from (0,0) to (k-1, m-1): vertex (i, j) is the cut of edge below[i]-above[j].
      std::vector<std::vector<std::pair<int, int>>> paths;
      std::vector<std::pair<int, int>> path{{0, 0}};
      auto walk = [&](auto&& self, int i, int j) -> void {
        if (i == k - 1 && j == m - 1) {
          paths.push_back(path);
          return;
        }
        if (i + 1 < k) {
          path.push_back({i + 1, j});
          self(self, i + 1, j);
          path.pop_back();
        }
        if (j + 1 < m) {
          path.push_back({i, j + 1});
          self(self, i, j + 1);
          path.pop_back();
        }
      };
      walk(walk, 0, 0);
      for (int flipped = 0; flipped < 2; ++flipped) {
        Case& c = cases[std::size_t(code | (flipped << N))];
        c.count = int(paths.size());
        for (std::size_t p = 0; p < paths.size(); ++p) {
          // Orientation (docs/slicing.md): the piece [u0 .. u(N-2)] is outward in a right-handed frame
          // iff (-1)^N det B > 0, B the barycentric coordinates of (u0, a, u1, .., u(N-2)) for any
          // corner a above. The sign does not depend on where the edges are cut; take their midpoints.
          Eigen::MatrixXd b = Eigen::MatrixXd::Zero(N, N);
          std::array<int, N - 1> e;
          for (int q = 0; q < N - 1; ++q) {
            const int lo = below[std::size_t(paths[p][std::size_t(q)].first)];
            const int hi = above[std::size_t(paths[p][std::size_t(q)].second)];
            const int col = q == 0 ? 0 : q + 1;
            b(lo, col) += 0.5;
            b(hi, col) += 0.5;
            e[std::size_t(q)] = local_edge(N, std::min(lo, hi), std::max(lo, hi));
          }
          b(above[0], 1) = 1.0;
          const double det = b.determinant() * ((N & 1) ? -1.0 : 1.0);
          const bool swap = (det < 0.0) != (flipped == 1);
          if (swap) std::swap(e[0], e[1]);
          for (int q = 0; q < N - 1; ++q) c.simplex[p][std::size_t(q)] = std::uint8_t(e[std::size_t(q)]);
        }
      }
    }
  }
};

template <int N>
const CaseTable<N>& case_table() {
  static const CaseTable<N> table;
  return table;
}

template <int N>
constexpr std::array<std::array<int, 2>, N * (N - 1) / 2> local_edges() {
  std::array<std::array<int, 2>, N * (N - 1) / 2> e{};
  for (int i = 0; i < N; ++i)
    for (int j = i + 1; j < N; ++j) e[std::size_t(local_edge(N, i, j))] = {i, j};
  return e;
}

}  // namespace

template <int N>
MeshSlicer<N>::MeshSlicer(const DisplayMesh<N>& mesh) {
  const std::size_t nv = mesh.vertices.size();
  if (mesh.normals.size() != mesh.cells.size())
    throw Error("MeshSlicer: the mesh needs one set of corner normals per cell");
  for (auto& c : coords_) c.resize(nv);
  for (std::size_t i = 0; i < nv; ++i)
    for (int k = 0; k < N; ++k) coords_[std::size_t(k)][i] = mesh.vertices[i][k];

  cells_.reserve(mesh.cells.size());
  flipped_.reserve(mesh.cells.size());
  normals_.reserve(mesh.cells.size());
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
    std::array<int, N> order;
    for (int j = 0; j < N; ++j) order[std::size_t(j)] = j;
    const auto& cell = mesh.cells[c];
    for (int v : cell)
      if (v < 0 || std::size_t(v) >= nv) throw Error("MeshSlicer: vertex index out of range");
    std::sort(order.begin(), order.end(), [&](int a, int b) { return cell[std::size_t(a)] < cell[std::size_t(b)]; });
    int inversions = 0;
    for (int i = 0; i < N; ++i)
      for (int j = i + 1; j < N; ++j) inversions += order[std::size_t(i)] > order[std::size_t(j)] ? 1 : 0;
    std::array<int, N> sorted;
    std::array<Vec<N>, N> normals;
    for (int j = 0; j < N; ++j) {
      sorted[std::size_t(j)] = cell[std::size_t(order[std::size_t(j)])];
      normals[std::size_t(j)] = mesh.normals[c][std::size_t(order[std::size_t(j)])];
    }
    cells_.push_back(sorted);
    flipped_.push_back(std::uint8_t(inversions & 1));
    normals_.push_back(normals);
  }

  // Unique edges: sort the (lower, higher, cell, local edge) uses, number the distinct pairs.
  struct Use {
    std::array<int, 2> e;
    std::uint32_t cell;
    std::uint8_t local;
  };
  std::vector<Use> uses;
  uses.reserve(cells_.size() * kCellEdges);
  constexpr auto le = local_edges<N>();
  for (std::size_t c = 0; c < cells_.size(); ++c)
    for (int l = 0; l < kCellEdges; ++l)
      uses.push_back({{cells_[c][std::size_t(le[std::size_t(l)][0])], cells_[c][std::size_t(le[std::size_t(l)][1])]},
                      std::uint32_t(c), std::uint8_t(l)});
  std::sort(uses.begin(), uses.end(), [](const Use& a, const Use& b) { return a.e < b.e; });
  cell_edges_.resize(cells_.size());
  for (std::size_t i = 0; i < uses.size(); ++i) {
    if (i == 0 || uses[i].e != uses[i - 1].e) edges_.push_back(uses[i].e);
    cell_edges_[uses[i].cell][uses[i].local] = int(edges_.size()) - 1;
  }

  vertex_normals_.assign(nv, Vec<N>::Zero());
  std::vector<char> has_normal(nv, 0);
  normal_kind_.resize(cells_.size());
  for (std::size_t c = 0; c < cells_.size(); ++c) {
    std::uint8_t kind = 0x80;
    for (int j = 0; j < N; ++j) {
      const std::size_t v = std::size_t(cells_[c][std::size_t(j)]);
      if (!has_normal[v]) {
        vertex_normals_[v] = normals_[c][std::size_t(j)];
        has_normal[v] = 1;
      }
      if (normals_[c][std::size_t(j)] == vertex_normals_[v]) kind |= std::uint8_t(1u << j);
      if (normals_[c][std::size_t(j)] != normals_[c][0]) kind &= std::uint8_t(0x7f);
    }
    normal_kind_[c] = kind;
    any_smooth_ = any_smooth_ || !(kind & 0x80);
  }

  for (std::size_t c0 = 0; c0 < cells_.size(); c0 += kChunk) {
    const std::size_t c1 = std::min(cells_.size(), c0 + kChunk);
    Vec<N> lo = Vec<N>::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (std::size_t c = c0; c < c1; ++c)
      for (int v : cells_[c]) {
        lo = lo.cwiseMin(mesh.vertices[std::size_t(v)]);
        hi = hi.cwiseMax(mesh.vertices[std::size_t(v)]);
      }
    const Vec<N> center = 0.5 * (lo + hi);
    double r = 0.0;
    for (std::size_t c = c0; c < c1; ++c)
      for (int v : cells_[c]) r = std::max(r, (mesh.vertices[std::size_t(v)] - center).norm());
    chunk_center_.push_back(center);
    chunk_radius_.push_back(r);
  }

  dist_.resize(nv);
  above_.resize(nv);
  edge_vertex_.assign(edges_.size(), -1);
  edge_t_.resize(edges_.size());
  edge_normal_.resize(edges_.size());
  (void)case_table<N>();
}

template <int N>
void MeshSlicer<N>::slice(const Placement<N>& placement, const Hyperplane<N>& plane, DisplayMesh<N - 1>& out) {
  constexpr int M = N - 1;
  out.vertices.clear();
  out.cells.clear();
  out.normals.clear();

  // Signed distance of every vertex in body coordinates: n.(R x + p) - d = (R^T n).x + (n.p - d).
  const Vec<N> a = placement.rotation.transpose() * plane.normal;
  const double b = plane.normal.dot(placement.translation) - plane.offset;
  const std::size_t nv = dist_.size();
  {
    double* __restrict d = dist_.data();
    std::uint8_t* __restrict up = above_.data();
    for (std::size_t i = 0; i < nv; ++i) {
      double s = b;
      for (int k = 0; k < N; ++k) s += a[k] * coords_[std::size_t(k)][i];
      d[i] = s;
      up[i] = s >= 0.0 ? 1 : 0;
    }
  }
  // Slice coordinates y = F^T (R x + p) = G x + g0.
  const Eigen::Matrix<double, M, N> g = plane.frame.transpose() * placement.rotation;
  const Eigen::Matrix<double, M, 1> g0 = plane.frame.transpose() * placement.translation;
  Mat<N> handed;
  handed << plane.frame, plane.normal;
  const int left_handed = handed.determinant() < 0.0 ? 1 : 0;

  const CaseTable<N>& table = case_table<N>();
  constexpr auto le = local_edges<N>();
  constexpr unsigned kAll = (1u << N) - 1u;
  const std::uint8_t* up = above_.data();

  auto project = [&](const Vec<N>& n_body) -> Eigen::Matrix<double, M, 1> {
    const Eigen::Matrix<double, M, 1> n = g * n_body;
    const double len2 = n.squaredNorm();
    return len2 > 1e-24 ? Eigen::Matrix<double, M, 1>(n * (1.0 / std::sqrt(len2))) : Eigen::Matrix<double, M, 1>::Zero();
  };
  auto cut_vertex = [&](int e) {
    int& v = edge_vertex_[std::size_t(e)];
    if (v >= 0) return v;
    const int i = edges_[std::size_t(e)][0], j = edges_[std::size_t(e)][1];
    // Interpolate from the vertex below, so the same edge gives the same bits in every cell.
    const bool i_below = dist_[std::size_t(i)] < 0.0;
    const int lo = i_below ? i : j, hi = i_below ? j : i;
    const double t = dist_[std::size_t(lo)] / (dist_[std::size_t(lo)] - dist_[std::size_t(hi)]);
    Vec<N> x;
    for (int k = 0; k < N; ++k) {
      const double xl = coords_[std::size_t(k)][std::size_t(lo)], xh = coords_[std::size_t(k)][std::size_t(hi)];
      x[k] = xl + t * (xh - xl);
    }
    v = int(out.vertices.size());
    out.vertices.push_back(g * x + g0);
    const double ti = i_below ? t : 1.0 - t;
    edge_t_[std::size_t(e)] = ti;
    if (any_smooth_) {
      const Vec<N>& ni = vertex_normals_[std::size_t(i)];
      edge_normal_[std::size_t(e)] = project(ni + ti * (vertex_normals_[std::size_t(j)] - ni));
    }
    touched_.push_back(e);
    return v;
  };

  const std::size_t nc = cells_.size();
  // A chunk is skipped only when its ball lies beyond the plane by a margin far above the round-off of
  // the vertex distances (about 1e-16 of the coordinates), so no cut cell is ever skipped.
  const double margin = 1e-9 * (1.0 + std::abs(b));
  const double a_len = a.norm();  // (1 to round-off: R^T n)
  for (std::size_t c = 0; c < nc; ++c) {
    if (c % kChunk == 0) {
      const std::size_t k = c / kChunk;
      if (std::abs(a.dot(chunk_center_[k]) + b) > chunk_radius_[k] * a_len + margin) {
        c += kChunk - 1;
        continue;
      }
    }
    const std::array<int, N>& cell = cells_[c];
    unsigned code = 0;
    for (int j = 0; j < N; ++j) code |= unsigned(up[cell[std::size_t(j)]]) << j;
    if (code == 0 || code == kAll) continue;
    const auto& cs = table.cases[code | (unsigned(flipped_[c] ^ left_handed) << N)];
    const unsigned kind = normal_kind_[c];
    Eigen::Matrix<double, M, 1> flat;
    if (kind & 0x80u) flat = project(normals_[c][0]);
    for (int s = 0; s < cs.count; ++s) {
      std::array<int, M> tri;
      std::array<Eigen::Matrix<double, M, 1>, M> nrm;
      for (int q = 0; q < M; ++q) {
        const int l = cs.simplex[std::size_t(s)][std::size_t(q)];
        const int e = cell_edges_[c][std::size_t(l)];
        tri[std::size_t(q)] = cut_vertex(e);
        const int ca = le[std::size_t(l)][0], cb = le[std::size_t(l)][1];
        if (kind & 0x80u) {
          nrm[std::size_t(q)] = flat;
        } else if ((kind >> ca) & (kind >> cb) & 1u) {
          nrm[std::size_t(q)] = edge_normal_[std::size_t(e)];
        } else {
          const double t = edge_t_[std::size_t(e)];
          const Vec<N>& n0 = normals_[c][std::size_t(ca)];
          nrm[std::size_t(q)] = project(n0 + t * (normals_[c][std::size_t(cb)] - n0));
        }
      }
      out.cells.push_back(tri);
      out.normals.push_back(nrm);
    }
  }
  for (int e : touched_) edge_vertex_[std::size_t(e)] = -1;
  touched_.clear();

  // Corners whose interpolated normal vanished (the surface tangent to the plane there): the piece's
  // own normal.
  for (std::size_t c = 0; c < out.cells.size(); ++c)
    for (int q = 0; q < M; ++q)
      if (out.normals[c][std::size_t(q)].squaredNorm() == 0.0) {
        std::array<Eigen::Matrix<double, M, 1>, M> p;
        for (int r = 0; r < M; ++r) p[std::size_t(r)] = out.vertices[std::size_t(out.cells[c][std::size_t(r)])];
        out.normals[c][std::size_t(q)] = cell_normal<M>(p);
      }
}

template <int N>
SliceChain<N> SliceChain<N>::axes(const std::array<double, std::size_t(N - 3)>& w) {
  SliceChain<N> chain;
  chain.plane = Hyperplane<N>::axis(w[0]);
  std::array<double, std::size_t(N - 4)> rest;
  for (int i = 0; i < N - 4; ++i) rest[std::size_t(i)] = w[std::size_t(i + 1)];
  chain.rest = SliceChain<N - 1>::axes(rest);
  return chain;
}

template <int N>
Flat3<N> SliceChain<N>::flat() const {
  const Flat3<N - 1> inner = rest.flat();
  Flat3<N> f;
  f.origin = plane.offset * plane.normal + plane.frame * inner.origin;
  f.frame = plane.frame * inner.frame;
  return f;
}

template <int N>
BodySlicer<N>::BodySlicer(const DisplayMesh<N>& mesh) {
  if constexpr (N == 3)
    mesh_ = mesh;
  else
    first_.emplace_back(mesh);
}

namespace {
template <int N>
DisplayMesh<3> finish_chain(const DisplayMesh<N>& mesh, const SliceChain<N>& chain) {
  if constexpr (N == 3) {
    (void)chain;
    return mesh;
  } else {
    if (mesh.empty()) return {};
    MeshSlicer<N> slicer(mesh);
    return finish_chain<N - 1>(slicer.slice(Placement<N>{}, chain.plane), chain.rest);
  }
}
}  // namespace

template <int N>
void BodySlicer<N>::slice(const Placement<N>& placement, const SliceChain<N>& chain, DisplayMesh<3>& out) {
  if constexpr (N == 3) {
    (void)chain;
    out.vertices.assign(mesh_.vertices.begin(), mesh_.vertices.end());
    out.cells.assign(mesh_.cells.begin(), mesh_.cells.end());
    out.normals.assign(mesh_.normals.begin(), mesh_.normals.end());
    for (Vec<3>& v : out.vertices) v = placement.rotation * v + placement.translation;
    for (auto& cell : out.normals)
      for (Vec<3>& n : cell) n = placement.rotation * n;
  } else if constexpr (N == 4) {
    first_[0].slice(placement, chain.plane, out);
  } else {
    out = finish_chain<N - 1>(first_[0].slice(placement, chain.plane), chain.rest);
  }
}

template <int N>
DisplayMesh<3> slice_to_3d(const DisplayMesh<N>& mesh, const Placement<N>& placement, const SliceChain<N>& chain) {
  BodySlicer<N> slicer(mesh);
  return slicer.slice(placement, chain);
}

template class MeshSlicer<3>;
template class MeshSlicer<4>;
template class MeshSlicer<5>;
template class MeshSlicer<6>;
template struct SliceChain<4>;
template struct SliceChain<5>;
template struct SliceChain<6>;
template class BodySlicer<3>;
template class BodySlicer<4>;
template class BodySlicer<5>;
template class BodySlicer<6>;
template DisplayMesh<3> slice_to_3d<3>(const DisplayMesh<3>&, const Placement<3>&, const SliceChain<3>&);
template DisplayMesh<3> slice_to_3d<4>(const DisplayMesh<4>&, const Placement<4>&, const SliceChain<4>&);
template DisplayMesh<3> slice_to_3d<5>(const DisplayMesh<5>&, const Placement<5>&, const SliceChain<5>&);
template DisplayMesh<3> slice_to_3d<6>(const DisplayMesh<6>&, const Placement<6>&, const SliceChain<6>&);

}  // namespace wedge::slicing
