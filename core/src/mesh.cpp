#include "wedge/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "linalg/fixed_size.hpp"
#include "wedge/error.hpp"
#include "wedge/dimensions.hpp"

namespace wedge {
namespace {

template <class Range>
std::string join(const Range& r) {
  std::ostringstream s;
  s << '{';
  bool first = true;
  for (int v : r) {
    s << (first ? "" : ", ") << v;
    first = false;
  }
  s << '}';
  return s.str();
}

// Sign of a permutation of 0..m-1 by counting inversions.
template <class P>
int permutation_sign(const P& p) {
  int inv = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) inv += p[i] > p[j] ? 1 : 0;
  return (inv & 1) ? -1 : 1;
}

// Mean of the vertices used by cells: a reference point for volume sums (translation invariant for a
// closed mesh, and near the body it keeps cancellation small).
template <int N>
Vec<N> used_vertex_mean(const SimplexMesh<N>& mesh) {
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const auto& c : mesh.cells)
    for (int v : c) used[std::size_t(v)] = 1;
  Vec<N> sum = Vec<N>::Zero();
  int n = 0;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (used[i]) {
      sum += mesh.vertices[i];
      ++n;
    }
  return n > 0 ? Vec<N>(sum / double(n)) : Vec<N>(Vec<N>::Zero());
}

template <int N>
double signed_volume_about(const SimplexMesh<N>& mesh, const Vec<N>& p) {
  double factorial = 1.0;
  for (int i = 2; i <= N; ++i) factorial *= i;
  double sum = 0.0, comp = 0.0;  // Neumaier's compensated sum: accurate for any number of cells
  for (const auto& c : mesh.cells) {
    Mat<N> m;
    for (int j = 0; j < N; ++j) m.col(j) = mesh.vertices[std::size_t(c[j])] - p;
    const double d = linalg::determinant<N>(m), t = sum + d;
    comp += std::abs(sum) >= std::abs(d) ? (sum - t) + d : (d - t) + sum;
    sum = t;
  }
  return (sum + comp) / factorial;
}

}  // namespace

template <int N>
double signed_volume(const SimplexMesh<N>& mesh) {
  for (const auto& c : mesh.cells)
    for (int v : c)
      if (v < 0 || std::size_t(v) >= mesh.vertices.size()) throw Error("signed_volume: vertex index out of range");
  return signed_volume_about(mesh, used_vertex_mean(mesh));
}

template <int N>
void validate(const SimplexMesh<N>& mesh) {
  const std::size_t nv = mesh.vertices.size();
  if (mesh.cells.empty()) throw Error("mesh has no cells");
  for (std::size_t i = 0; i < nv; ++i)
    if (!all_finite(mesh.vertices[i]))
      throw Error("mesh vertex " + std::to_string(i) + " has a non-finite coordinate");

  // Indices, repeated vertices, zero-volume cells.
  for (std::size_t ci = 0; ci < mesh.cells.size(); ++ci) {
    const auto& c = mesh.cells[ci];
    for (int j = 0; j < N; ++j) {
      if (c[j] < 0 || std::size_t(c[j]) >= nv)
        throw Error("mesh cell " + std::to_string(ci) + " refers to vertex " + std::to_string(c[j]) +
                    ", out of range (the mesh has " + std::to_string(nv) + " vertices)");
      for (int k = 0; k < j; ++k)
        if (c[k] == c[j])
          throw Error("mesh cell " + std::to_string(ci) + " repeats vertex " + std::to_string(c[j]) +
                      " (a cell needs " + std::to_string(N) + " distinct vertices)");
    }
    // (N-1)-volume * (N-1)! = the product of the edge vectors' lengths after Gram-Schmidt (|prod diag R|
    // of a QR of the edge matrix), against the longest edge^(N-1).
    std::array<Vec<N>, N - 1> e;
    double longest = 0.0, vol = 1.0;
    for (int j = 1; j < N; ++j) {
      Vec<N> x = mesh.vertices[std::size_t(c[j])] - mesh.vertices[std::size_t(c[0])];
      for (int k = 0; k < j - 1; ++k) x -= e[std::size_t(k)].dot(x) * e[std::size_t(k)];
      const double len = x.norm();
      vol *= len;
      e[std::size_t(j - 1)] = len > 0.0 ? Vec<N>(x / len) : Vec<N>::Zero();
      for (int k = 0; k < j; ++k)
        longest = std::max(longest, (mesh.vertices[std::size_t(c[j])] - mesh.vertices[std::size_t(c[k])]).norm());
    }
    if (!(vol > 1e-12 * std::pow(longest, N - 1)))
      throw Error("mesh cell " + std::to_string(ci) + " " + join(c) +
                  " is degenerate (zero " + std::to_string(N - 1) + "-volume: its vertices " +
                  (N == 2 ? "coincide" : "are affinely dependent") + ")");
  }

  // Closedness and consistent orientation: the face opposite vertex j of a cell has induced orientation
  // (-1)^j times the sign of the permutation that sorts its vertices.
  struct FaceUse {
    std::array<int, N - 1> v;
    int sign;
    int cell;
  };
  std::vector<FaceUse> uses;
  uses.reserve(mesh.cells.size() * N);
  for (std::size_t ci = 0; ci < mesh.cells.size(); ++ci) {
    const auto& c = mesh.cells[ci];
    for (int j = 0; j < N; ++j) {
      FaceUse u;
      int k = 0;
      for (int l = 0; l < N; ++l)
        if (l != j) u.v[std::size_t(k++)] = c[l];
      int s = permutation_sign(u.v) * ((j & 1) ? -1 : 1);
      std::sort(u.v.begin(), u.v.end());
      u.sign = s;
      u.cell = int(ci);
      uses.push_back(u);
    }
  }
  std::sort(uses.begin(), uses.end(), [](const FaceUse& a, const FaceUse& b) {
    if (a.v != b.v) return a.v < b.v;
    if (a.sign != b.sign) return a.sign < b.sign;
    return a.cell < b.cell;
  });
  const std::string face_name = std::to_string(N - 2) + "-face";
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].v == uses[i].v) ++j;
    const std::size_t count = j - i;
    if (count == 1)
      throw Error("open mesh: " + face_name + " " + join(uses[i].v) + " of cell " + std::to_string(uses[i].cell) +
                  " is not shared with any other cell (the boundary must be closed)");
    if (count > 2) {
      std::vector<int> cells;
      for (std::size_t k = i; k < j; ++k) cells.push_back(uses[k].cell);
      throw Error("non-manifold mesh: " + face_name + " " + join(uses[i].v) + " is shared by " +
                  std::to_string(count) + " cells " + join(cells) + " (it must be shared by exactly two)");
    }
    if (uses[i].sign == uses[i + 1].sign)
      throw Error("inconsistently oriented mesh: cells " + std::to_string(uses[i].cell) + " and " +
                  std::to_string(uses[i + 1].cell) + " induce the same orientation on their shared " + face_name +
                  " " + join(uses[i].v) + " (a flipped cell?); neighbouring cells must induce opposite ones");
    i = j;
  }

  // The body: non-negligible and positive volume.
  Vec<N> lo = Vec<N>::Constant(INFINITY), hi = Vec<N>::Constant(-INFINITY);
  for (const auto& c : mesh.cells)
    for (int v : c) {
      lo = lo.cwiseMin(mesh.vertices[std::size_t(v)]);
      hi = hi.cwiseMax(mesh.vertices[std::size_t(v)]);
    }
  const double diag = (hi - lo).norm();
  const double volume = signed_volume_about(mesh, used_vertex_mean(mesh));
  if (!(std::abs(volume) > 1e-12 * std::pow(diag, N))) {
    std::ostringstream s;
    s << "degenerate body: the mesh encloses a negligible volume (" << volume
      << ") for its bounding box (diagonal " << diag << "); it is flat or folded onto itself";
    throw Error(s.str());
  }
  if (volume < 0.0) {
    std::ostringstream s;
    s << "inside-out mesh: the enclosed signed volume is negative (" << volume
      << "); cells must be oriented outward (counter-clockwise in 2D)";
    throw Error(s.str());
  }
}

long long box_mesh_cell_count(int n, int subdivisions) {
  double cells = 2.0 * n;
  for (int i = 0; i < n - 1; ++i) cells *= subdivisions;
  for (int i = 2; i <= n - 1; ++i) cells *= i;
  return cells > 9e18 ? (long long)9e18 : (long long)cells;
}

template <int N>
SimplexMesh<N> box_mesh(const Vec<N>& half_extents, int subdivisions) {
  for (int i = 0; i < N; ++i)
    if (!(std::isfinite(half_extents[i]) && half_extents[i] > 0.0)) {
      std::ostringstream s;
      s << "box half-extent " << i << " must be positive and finite (got " << half_extents[i] << ")";
      throw Error(s.str());
    }
  if (subdivisions < 1) throw Error("mesh subdivisions must be at least 1 (got " + std::to_string(subdivisions) + ")");
  if (box_mesh_cell_count(N, subdivisions) > max_mesh_cells())
    throw Error("mesh subdivisions " + std::to_string(subdivisions) + " would make " +
                std::to_string(box_mesh_cell_count(N, subdivisions)) + " cells in " + std::to_string(N) +
                "D (limit " + std::to_string(max_mesh_cells()) + ")");
  const int s = subdivisions;

  // Grid points {0..s}^N; the boundary ones become vertices, in lexicographic order (axis 0 fastest).
  std::size_t total = 1;
  for (int i = 0; i < N; ++i) total *= std::size_t(s + 1);
  std::vector<int> id(total, -1);
  SimplexMesh<N> mesh;
  for (std::size_t lin = 0; lin < total; ++lin) {
    std::size_t r = lin;
    bool boundary = false;
    Vec<N> x;
    for (int i = 0; i < N; ++i) {
      const int g = int(r % std::size_t(s + 1));
      r /= std::size_t(s + 1);
      boundary = boundary || g == 0 || g == s;
      // (2g - s)/s is exactly antisymmetric in g <-> s - g and exactly +-1 on the boundary.
      x[i] = half_extents[i] * (double(2 * g - s) / double(s));
    }
    if (boundary) {
      id[lin] = int(mesh.vertices.size());
      mesh.vertices.push_back(x);
    }
  }

  // Permutations of the N-1 in-facet directions and their signs (Kuhn simplices of a grid cube).
  std::vector<std::array<int, N - 1>> perms;
  std::vector<int> perm_sign;
  std::array<int, N - 1> p;
  for (int i = 0; i < N - 1; ++i) p[std::size_t(i)] = i;
  do {
    perms.push_back(p);
    perm_sign.push_back(permutation_sign(p));
  } while (std::next_permutation(p.begin(), p.end()));

  std::array<std::size_t, N> stride;
  stride[0] = 1;
  for (int i = 1; i < N; ++i) stride[std::size_t(i)] = stride[std::size_t(i - 1)] * std::size_t(s + 1);

  std::size_t cells_per_facet = perms.size();
  for (int i = 0; i < N - 1; ++i) cells_per_facet *= std::size_t(s);
  mesh.cells.reserve(cells_per_facet * 2 * N);

  for (int a = 0; a < N; ++a) {
    std::array<int, N - 1> other;
    for (int i = 0, k = 0; i < N; ++i)
      if (i != a) other[std::size_t(k++)] = i;
    for (int side : {0, s}) {
      // Subtracting successive columns, det[x(w0) .. x(w_{N-1})] = x(w0)_a * (positive steps) *
      // det[e_a, e_other[perm]..], whose sign is (side ? +1 : -1) * sign(perm) * (-1)^a.
      const int base_sign = (side == s ? 1 : -1) * ((a & 1) ? -1 : 1);
      std::array<int, N - 1> c{};  // grid cube in the facet
      while (true) {
        std::size_t corner = std::size_t(side) * stride[std::size_t(a)];
        for (int i = 0; i < N - 1; ++i) corner += std::size_t(c[std::size_t(i)]) * stride[std::size_t(other[std::size_t(i)])];
        for (std::size_t q = 0; q < perms.size(); ++q) {
          std::array<int, N> cell;
          std::size_t w = corner;
          cell[0] = id[w];
          for (int k = 0; k < N - 1; ++k) {
            w += stride[std::size_t(other[std::size_t(perms[q][std::size_t(k)])])];
            cell[std::size_t(k + 1)] = id[w];
          }
          if (base_sign * perm_sign[q] < 0) std::swap(cell[0], cell[1]);
          mesh.cells.push_back(cell);
        }
        int i = 0;
        for (; i < N - 1; ++i) {
          if (++c[std::size_t(i)] < s) break;
          c[std::size_t(i)] = 0;
        }
        if (i == N - 1) break;
      }
    }
  }
  return mesh;
}

template <int N>
void validate_factors(const std::vector<ProductFactor>& factors) {
  if (factors.empty()) throw Error("round product has no factors");
  std::array<int, N> owner;
  owner.fill(-1);
  for (std::size_t f = 0; f < factors.size(); ++f) {
    const ProductFactor& fac = factors[f];
    const std::string name = "round product factor " + std::to_string(f);
    if (fac.axes.empty()) throw Error(name + " has no axes");
    if (fac.kind == ProductFactor::Kind::Interval && fac.axes.size() != 1)
      throw Error(name + " is an interval but has " + std::to_string(fac.axes.size()) + " axes (it needs exactly one)");
    if (!(std::isfinite(fac.size) && fac.size > 0.0)) {
      std::ostringstream s;
      s << name << " has a non-positive or non-finite " << (fac.kind == ProductFactor::Kind::Ball ? "radius" : "half-length")
        << " (" << fac.size << "); it must be positive and finite";
      throw Error(s.str());
    }
    for (int a : fac.axes) {
      if (a < 0 || a >= N)
        throw Error(name + " has axis " + std::to_string(a) + ", out of range 0.." + std::to_string(N - 1));
      if (owner[std::size_t(a)] >= 0)
        throw Error("round product: axis " + std::to_string(a) + " appears in factors " +
                    std::to_string(owner[std::size_t(a)]) + " and " + std::to_string(f) +
                    " (the factors must partition the axes)");
      owner[std::size_t(a)] = int(f);
    }
  }
  for (int a = 0; a < N; ++a)
    if (owner[std::size_t(a)] < 0)
      throw Error("round product: axis " + std::to_string(a) + " is not covered by any factor (the factors must partition the axes 0.." +
                  std::to_string(N - 1) + ")");
}

template <int N>
SimplexMesh<N> round_product_mesh(const std::vector<ProductFactor>& factors, int subdivisions) {
  validate_factors<N>(factors);
  Vec<N> h;
  for (const ProductFactor& f : factors)
    for (int a : f.axes) h[a] = f.size;
  SimplexMesh<N> mesh = box_mesh<N>(h, subdivisions);
  for (Vec<N>& x : mesh.vertices)
    for (const ProductFactor& f : factors) {
      if (f.kind != ProductFactor::Kind::Ball || f.axes.size() < 2) continue;
      double inf = 0.0, two = 0.0;
      for (int a : f.axes) {
        inf = std::max(inf, std::abs(x[a]));
        two += x[a] * x[a];
      }
      two = std::sqrt(two);
      if (two == 0.0) continue;
      const double scale = inf / two;
      for (int a : f.axes) x[a] *= scale;
    }
  return mesh;
}

template <int N>
SimplexMesh<N> ball_mesh(double radius, int subdivisions) {
  std::vector<int> axes;
  for (int i = 0; i < N; ++i) axes.push_back(i);
  return round_product_mesh<N>({ProductFactor::ball(axes, radius)}, subdivisions);
}

#define WEDGE_INSTANTIATE_MESH(N)                                                            \
  template void validate<N>(const SimplexMesh<N>&);                                          \
  template double signed_volume<N>(const SimplexMesh<N>&);                                   \
  template void validate_factors<N>(const std::vector<ProductFactor>&);                      \
  template SimplexMesh<N> box_mesh<N>(const Vec<N>&, int);                                   \
  template SimplexMesh<N> round_product_mesh<N>(const std::vector<ProductFactor>&, int);     \
  template SimplexMesh<N> ball_mesh<N>(double, int);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE_MESH)
#undef WEDGE_INSTANTIATE_MESH

}  // namespace wedge
