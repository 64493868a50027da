#include "wedge/mass.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>

#include "linalg/decompositions.hpp"
#include "linalg/fixed_size.hpp"
#include "wedge/error.hpp"
#include "wedge/ga/products.hpp"
#include "wedge/dimensions.hpp"

namespace wedge {
namespace {

void require_density(double density) {
  if (!(std::isfinite(density) && density > 0.0)) {
    std::ostringstream s;
    s << "density must be positive and finite (got " << density << ")";
    throw Error(s.str());
  }
}

template <int N>
MassProperties<N> from_diagonal(double volume, double density, const Vec<N>& second_moment_per_mass) {
  MassProperties<N> p;
  p.volume = volume;
  p.mass = density * volume;
  p.center = Vec<N>::Zero();
  p.covariance = (p.mass * second_moment_per_mass).asDiagonal();
  p.inertia = inertia_from_covariance<N>(p.covariance);
  return p;
}

// Neumaier's compensated summation: the sums below run over up to millions of cells of one sign, where
// plain summation loses ~ (number of cells) * eps relative accuracy.
struct CompensatedSum {
  double sum = 0.0, comp = 0.0;
  void add(double x) {
    const double t = sum + x;
    comp += std::abs(sum) >= std::abs(x) ? (sum - t) + x : (x - t) + sum;
    sum = t;
  }
  double value() const { return sum + comp; }
};

// Section 5 on a mesh assumed valid.
template <int N>
MassProperties<N> mesh_mass_properties(const SimplexMesh<N>& mesh, double density) {
  require_density(density);
  double n_fact = 1.0;
  for (int i = 2; i <= N; ++i) n_fact *= i;
  const double n2_fact = n_fact * (N + 1) * (N + 2);

  // Reference point: the mean of the used vertices.
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const auto& c : mesh.cells)
    for (int v : c) used[std::size_t(v)] = 1;
  Vec<N> p = Vec<N>::Zero();
  int count = 0;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (used[i]) {
      p += mesh.vertices[i];
      ++count;
    }
  p /= double(count);

  CompensatedSum det_sum;                     // sum det(M)                -> volume * N!
  std::array<CompensatedSum, N> first_sum;    // sum det(M) * colsum       -> first moment * N! (N+1)
  std::array<CompensatedSum, N * N> second_sum;  // sum det(M)(M M^T + s s^T) -> second moment * (N+2)!
  for (const auto& c : mesh.cells) {
    Mat<N> m;
    for (int j = 0; j < N; ++j) m.col(j) = mesh.vertices[std::size_t(c[j])] - p;
    const double d = linalg::determinant<N>(m);
    Vec<N> s = Vec<N>::Zero();
    for (int j = 0; j < N; ++j) s += m.col(j);
    det_sum.add(d);
    for (int i = 0; i < N; ++i) first_sum[std::size_t(i)].add(d * s[i]);
    for (int i = 0; i < N; ++i)
      for (int j = i; j < N; ++j) {
        double t = s[i] * s[j];
        for (int k = 0; k < N; ++k) t += m(i, k) * m(j, k);
        second_sum[std::size_t(i * N + j)].add(d * t);
      }
  }
  Vec<N> first;
  Mat<N> second;
  for (int i = 0; i < N; ++i) {
    first[i] = first_sum[std::size_t(i)].value();
    for (int j = i; j < N; ++j) second(i, j) = second(j, i) = second_sum[std::size_t(i * N + j)].value();
  }

  const double volume = det_sum.value() / n_fact;
  if (!(volume > 0.0)) throw Error("mass properties: the mesh encloses no positive volume");
  const Vec<N> offset = first / (n_fact * (N + 1)) / volume;  // centre - p
  const Mat<N> second_about_p = second / n2_fact;
  Mat<N> cov = second_about_p - volume * offset * offset.transpose();
  cov = 0.5 * (cov + cov.transpose()).eval();

  MassProperties<N> out;
  out.volume = volume;
  out.mass = density * volume;
  out.center = p + offset;
  out.covariance = density * cov;
  out.inertia = inertia_from_covariance<N>(out.covariance);
  return out;
}

}  // namespace

template <int N>
BivMat<N> inertia_from_covariance(const Mat<N>& covariance) {
  std::array<WedgeMat<N>, N> e;  // [e_i]_*
  for (int i = 0; i < N; ++i) e[std::size_t(i)] = wedge_matrix<N>(Vec<N>::Unit(i));
  BivMat<N> out = BivMat<N>::Zero();
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j)
      if (covariance(i, j) != 0.0)
        out += covariance(i, j) * (e[std::size_t(i)] * e[std::size_t(j)].transpose());
  return 0.5 * (out + out.transpose());
}

double ball_volume(int d, double radius) {
  return std::pow(std::numbers::pi, 0.5 * d) * std::pow(radius, d) / std::tgamma(0.5 * d + 1.0);
}

template <int N>
MassProperties<N> box_mass_properties(const Vec<N>& half_extents, double density) {
  require_density(density);
  double volume = 1.0;
  Vec<N> per_mass;
  for (int i = 0; i < N; ++i) {
    const double h = half_extents[i];
    if (!(std::isfinite(h) && h > 0.0)) {
      std::ostringstream s;
      s << "box half-extent " << i << " must be positive and finite (got " << h << ")";
      throw Error(s.str());
    }
    volume *= 2.0 * h;
    per_mass[i] = (2.0 * h) * (2.0 * h) / 12.0;
  }
  return from_diagonal<N>(volume, density, per_mass);
}

template <int N>
MassProperties<N> ball_mass_properties(double radius, double density) {
  require_density(density);
  if (!(std::isfinite(radius) && radius > 0.0)) {
    std::ostringstream s;
    s << "ball radius must be positive and finite (got " << radius << ")";
    throw Error(s.str());
  }
  return from_diagonal<N>(ball_volume(N, radius), density, Vec<N>::Constant(radius * radius / (N + 2)));
}

template <int N>
MassProperties<N> round_product_mass_properties(const std::vector<ProductFactor>& factors, double density) {
  require_density(density);
  validate_factors<N>(factors);
  double volume = 1.0;
  Vec<N> per_mass;
  for (const ProductFactor& f : factors) {
    const int d = int(f.axes.size());
    if (f.kind == ProductFactor::Kind::Ball) {
      volume *= ball_volume(d, f.size);
      for (int a : f.axes) per_mass[a] = f.size * f.size / (d + 2);
    } else {
      volume *= 2.0 * f.size;
      per_mass[f.axes[0]] = (2.0 * f.size) * (2.0 * f.size) / 12.0;
    }
  }
  return from_diagonal<N>(volume, density, per_mass);
}

template <int N>
MassProperties<N> mass_properties(const SimplexMesh<N>& mesh, double density) {
  require_density(density);
  validate(mesh);
  return mesh_mass_properties<N>(mesh, density);
}

template <int N>
MassProperties<N> mass_properties(const Shape<N>& shape, double density) {
  require_density(density);
  return std::visit(
      [&](const auto& s) -> MassProperties<N> {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, shapes::Box<N>>) {
          return box_mass_properties<N>(s.half_extents, density);
        } else if constexpr (std::is_same_v<T, shapes::Ball<N>>) {
          return ball_mass_properties<N>(s.radius, density);
        } else if constexpr (std::is_same_v<T, shapes::Polytope<N>>) {
          return mesh_mass_properties<N>(shape.hull().mesh, density);
        } else if constexpr (std::is_same_v<T, shapes::Mesh<N>>) {
          return mesh_mass_properties<N>(s.mesh, density);  // validated when the shape was made
        } else if constexpr (std::is_same_v<T, shapes::RoundProduct<N>>) {
          return round_product_mass_properties<N>(s.factors, density);
        } else {
          throw Error("a half-space has no finite mass: it can only be a static body");
        }
      },
      shape.description());
}

template <int N>
MassProperties<N> with_mass(const MassProperties<N>& props, double mass) {
  if (!(std::isfinite(mass) && mass > 0.0)) {
    std::ostringstream s;
    s << "mass must be positive and finite (got " << mass << ")";
    throw Error(s.str());
  }
  if (!(props.mass > 0.0)) throw Error("cannot rescale mass properties of zero mass");
  const double f = mass / props.mass;
  MassProperties<N> out = props;
  out.mass = mass;
  out.covariance *= f;
  out.inertia *= f;
  return out;
}

template <int N>
BivMat<N> inertia_about(const MassProperties<N>& props, const Vec<N>& point) {
  const WedgeMat<N> w = wedge_matrix<N>(Vec<N>(props.center - point));
  return props.inertia + props.mass * (w * w.transpose());
}

template <int N>
PrincipalFrame<N> principal_frame(const MassProperties<N>& props) {
  const Mat<N>& c = props.covariance;
  if (!all_finite(c) || !(c.trace() > 0.0)) throw Error("principal frame: the covariance is not positive");
  double off = 0.0;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j)
      if (i != j) off = std::max(off, std::abs(c(i, j)));

  PrincipalFrame<N> out;
  out.center = props.center;
  if (off <= 1e-12 * c.trace()) {
    out.axes = Mat<N>::Identity();
  } else {
    linalg::SmallVector values;
    linalg::SmallMatrix vectors;
    if (!linalg::symmetric_eigen(c, values, vectors)) throw Error("principal frame: eigen-decomposition failed");
    Mat<N> q = vectors;
    for (int j = 0; j < N; ++j) {
      int big = 0;
      for (int i = 1; i < N; ++i)
        if (std::abs(q(i, j)) > std::abs(q(big, j))) big = i;
      if (q(big, j) < 0.0) q.col(j) = -q.col(j);
    }
    if (linalg::determinant<N>(q) < 0.0) q.col(N - 1) = -q.col(N - 1);
    out.axes = q;
  }
  const Mat<N> cq = out.axes.transpose() * c * out.axes;
  out.covariance = cq.diagonal();
  const BivMat<N> b = bivector_matrix<N>(out.axes);
  BivMat<N> inertia = b.transpose() * props.inertia * b;
  const double scale = inertia.diagonal().cwiseAbs().maxCoeff();
  for (int i = 0; i < kBiv<N>; ++i)
    for (int j = 0; j < kBiv<N>; ++j)
      if (i != j) {
        if (!(std::abs(inertia(i, j)) <= 1e-9 * scale))
          throw Error("principal frame: the inertia is not diagonal in the covariance's eigenbasis");
        inertia(i, j) = 0.0;
      }
  out.inertia = inertia;
  return out;
}

#define WEDGE_INSTANTIATE_MASS(N)                                                                       \
  template BivMat<N> inertia_from_covariance<N>(const Mat<N>&);                                         \
  template MassProperties<N> box_mass_properties<N>(const Vec<N>&, double);                             \
  template MassProperties<N> ball_mass_properties<N>(double, double);                                   \
  template MassProperties<N> round_product_mass_properties<N>(const std::vector<ProductFactor>&, double); \
  template MassProperties<N> mass_properties<N>(const SimplexMesh<N>&, double);                         \
  template MassProperties<N> mass_properties<N>(const Shape<N>&, double);                               \
  template MassProperties<N> with_mass<N>(const MassProperties<N>&, double);                            \
  template BivMat<N> inertia_about<N>(const MassProperties<N>&, const Vec<N>&);                         \
  template PrincipalFrame<N> principal_frame<N>(const MassProperties<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE_MASS)
#undef WEDGE_INSTANTIATE_MASS

}  // namespace wedge
