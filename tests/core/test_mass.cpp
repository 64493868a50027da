// Mass properties (wedge/mass.hpp) against independent truth, n = 2..6:
//   - the paper's appendix A matrices [r]_* and Delta I, written out literally;
//   - textbook closed forms (box I_ij = m(a_i^2 + a_j^2)/12, ball volume pi^(n/2) r^n / Gamma(n/2+1) and
//     I = 2 m r^2/(n+2), cylinder I_zz = m r^2/2, ...) written out independently of the library;
//   - Monte Carlo estimates for random convex polytopes;
//   - the transformation laws: translation, parallel axes, eq. (4) I' = [Q]_2 I [Q]_2^T.
//
// Tolerances:
//   kExact = 1e-12, relative to the largest entry of the compared quantity: results that are exact in
//     exact arithmetic (a box mesh integrates a box exactly; rotating or translating a mesh changes
//     only the rounding). The library sums the <= 5e4 cell terms with compensated summation, so only
//     the per-cell rounding (a few eps) remains: the observed errors are <= 6e-16. 1e-12 leaves a
//     margin of ~1000 yet catches any wrong factor or term (O(1) errors).
//   Ball and round-product meshes: all mesh vertices lie on the true surface and the mesh is star-shaped
//     about the centre (checked), so with rho = the smallest distance from the centre to a cell's plane
//     (the inscribed radius) the solid P satisfies rho B <= P <= r B. Hence the volume lies in
//     [rho^n, 1] V_ball, every diagonal inertia entry (a non-negative integrand) in
//     [(rho/r)^(n+2), 1] I_ball, and every off-diagonal entry, a covariance of the set difference, is at
//     most (I_ball(r) - I_ball(rho))/2. These are rigorous bounds, not fitted tolerances; in addition
//     the error must shrink (by a factor of at least 1/0.75) when the tessellation is refined: it is
//     O(h^2), a factor ~4 per halving of h asymptotically, less at the coarse 5D/6D levels (6D s = 1 -> 2:
//     0.97 -> 0.70 in inertia).
//   Monte Carlo: |exact - estimate| <= 5 standard errors (fixed seeds), plus 1e-10 of the scale for
//     entries that vanish identically.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>
#include <type_traits>
#include <vector>

#include "dense.hpp"
#include "wedge/error.hpp"
#include "wedge/ga/products.hpp"
#include "wedge/hull.hpp"
#include "wedge/mass.hpp"
#include "wedge/mesh.hpp"
#include "wedge/shape.hpp"
#include "appendix_a.hpp"
#include "test_util.hpp"

namespace {

using wedge::BivMat;
using wedge::Mat;
using wedge::MassProperties;
using wedge::ProductFactor;
using wedge::Shape;
using wedge::SimplexMesh;
using wedge::Vec;


constexpr double kExact = 1e-12;
constexpr double kPi = std::numbers::pi;

template <class A, class B>
double rel_diff(const Eigen::MatrixBase<A>& a, const Eigen::MatrixBase<B>& b) {
  const double scale = std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
  return scale == 0.0 ? 0.0 : (a - b).cwiseAbs().maxCoeff() / scale;
}

// Position of bivector e_ij (i < j) in the lexicographic order e01, e02, .., e12, .. (counted here
// independently of the library).
template <int N>
int biv(int i, int j) {
  int k = 0;
  for (int a = 0; a < N; ++a)
    for (int b = a + 1; b < N; ++b) {
      if (a == i && b == j) return k;
      ++k;
    }
  return -1;
}

template <int N>
Mat<N> random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Mat<N> a;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) a(i, j) = g(rng);
  return dense::haar_rotation(a);
}

template <int N>
SimplexMesh<N> transformed(const SimplexMesh<N>& m, const Mat<N>& q, const Vec<N>& t) {
  SimplexMesh<N> out = m;
  for (Vec<N>& v : out.vertices) v = q * v + t;
  return out;
}

// Random points around an ellipsoid, off centre: a polytope without symmetries.
template <int N>
std::vector<Vec<N>> random_points(std::mt19937_64& rng, int count) {
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.7, 1.0);
  Mat<N> a = Mat<N>::Identity();
  for (int i = 0; i < N; ++i) {
    a(i, i) = 1.0 + 0.15 * i;
    if (i > 0) a(i, i - 1) = 0.3;
  }
  Vec<N> t;
  for (int i = 0; i < N; ++i) t[i] = 0.2 * (i % 2 == 0 ? 1 : -1) + 0.05 * i;
  std::vector<Vec<N>> pts;
  for (int k = 0; k < count; ++k) {
    Vec<N> d;
    for (int i = 0; i < N; ++i) d[i] = g(rng);
    pts.push_back(a * (d.normalized() * u(rng)) + t);
  }
  return pts;
}

// The inscribed radius about the origin of a mesh after checking it is star-shaped about it (every cell
// has positive orientation seen from the origin; with a closed manifold of total degree 1 every ray
// then crosses the boundary once).
template <int N>
double inscribed_radius(const SimplexMesh<N>& m) {
  double rho = INFINITY;
  for (const auto& c : m.cells) {
    Mat<N> vm;
    for (int j = 0; j < N; ++j) vm.col(j) = m.vertices[std::size_t(c[j])];
    REQUIRE(det(vm) > 0.0);
    Eigen::Matrix<double, N - 1, N> e;
    for (int j = 1; j < N; ++j) e.row(j - 1) = (vm.col(j) - vm.col(0)).transpose();
    Eigen::VectorXd kernel;
    REQUIRE(dense::kernel_vector(e, kernel));
    const Vec<N> n = kernel;
    rho = std::min(rho, std::abs(n.dot(vm.col(0))));
  }
  return rho;
}

}  // namespace

// ------------------------------------------------------------------------------------------ appendix A
TEST_CASE("Appendix A: [r]_* and Delta I = sum C_ij [e_i]_*[e_j]_*^T for a point mass, 2D/3D/4D", "[mass]") {
  // A point mass at r has covariance r r^T; its inertia must be the paper's Delta I (appendix_a.hpp).
  const Vec<4> r4(0.7, -1.3, 2.1, -0.4);
  const Vec<2> r2 = r4.head<2>();
  const Vec<3> r3 = r4.head<3>();
  CHECK(rel_diff(wedge::wedge_matrix<2>(r2), paper::wedge_matrix(r2)) == 0.0);
  CHECK(rel_diff(wedge::inertia_from_covariance<2>(r2 * r2.transpose()), paper::delta_i(r2)) < 1e-15);
  CHECK(rel_diff(wedge::wedge_matrix<3>(r3), paper::wedge_matrix(r3)) == 0.0);
  CHECK(rel_diff(wedge::inertia_from_covariance<3>(r3 * r3.transpose()), paper::delta_i(r3)) < 1e-15);
  CHECK(rel_diff(wedge::wedge_matrix<4>(r4), paper::wedge_matrix(r4)) == 0.0);
  CHECK(rel_diff(wedge::inertia_from_covariance<4>(r4 * r4.transpose()), paper::delta_i(r4)) < 1e-15);
}

// ------------------------------------------------------------------------------------------ boxes
TEMPLATE_TEST_CASE("n-box: closed form is V = prod a_i, I_ij = m (a_i^2 + a_j^2)/12", "[mass]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  Vec<N> h;
  for (int i = 0; i < N; ++i) h[i] = 0.5 + 0.3 * i;
  const double density = 2.5;
  double volume = 1.0;
  for (int i = 0; i < N; ++i) volume *= 2.0 * h[i];
  const double m = density * volume;
  BivMat<N> truth = BivMat<N>::Zero();
  for (int i = 0; i < N; ++i)
    for (int j = i + 1; j < N; ++j) {
      const double ai = 2.0 * h[i], aj = 2.0 * h[j];
      truth(biv<N>(i, j), biv<N>(i, j)) = m * (ai * ai + aj * aj) / 12.0;
    }
  Mat<N> cov = Mat<N>::Zero();
  for (int i = 0; i < N; ++i) cov(i, i) = m * (2.0 * h[i]) * (2.0 * h[i]) / 12.0;

  const MassProperties<N> p = wedge::mass_properties<N>(Shape<N>::box(h), density);
  CHECK(p.volume == Approx(volume).epsilon(1e-14));
  CHECK(p.mass == Approx(m).epsilon(1e-14));
  CHECK(p.center.isZero(0.0));
  CHECK(rel_diff(p.covariance, cov) < 1e-15);
  CHECK(rel_diff(p.inertia, truth) < 1e-15);

  // The box mesh integrates the box exactly: only round-off, at two tessellation levels, and off centre.
  const Vec<N> t = Vec<N>::LinSpaced(-0.7, 1.1);
  for (int s : {1, 2}) {
    INFO("subdivisions " << s);
    SimplexMesh<N> mesh = wedge::box_mesh<N>(h, s);
    for (Vec<N>& v : mesh.vertices) v += t;
    const MassProperties<N> q = wedge::mass_properties<N>(mesh, density);
    CHECK(std::abs(q.volume - volume) <= kExact * volume);
    CHECK(std::abs(q.mass - m) <= kExact * m);
    CHECK((q.center - t).cwiseAbs().maxCoeff() <= kExact * t.norm());
    CHECK(rel_diff(q.covariance, cov) <= kExact);
    CHECK(rel_diff(q.inertia, truth) <= kExact);
  }
}

// ------------------------------------------------------------------------------------------ balls
TEMPLATE_TEST_CASE("n-ball: closed form V = pi^(n/2) r^n / Gamma(n/2+1), I = 2 m r^2/(n+2)", "[mass]", D2, D3, D4, D5,
                   D6) {
  constexpr int N = TestType::value;
  const double r = 0.8, density = 3.0;
  // Textbook volumes of the n-ball, written out.
  const double unit[7] = {0, 0, kPi, 4.0 / 3.0 * kPi, kPi * kPi / 2.0, 8.0 * kPi * kPi / 15.0, kPi * kPi * kPi / 6.0};
  const double volume = unit[N] * std::pow(r, N);
  const double m = density * volume;
  const MassProperties<N> p = wedge::mass_properties<N>(Shape<N>::ball(r), density);
  CHECK(p.volume == Approx(volume).epsilon(1e-14));
  CHECK(wedge::ball_volume(N, r) == Approx(volume).epsilon(1e-14));
  CHECK(p.mass == Approx(m).epsilon(1e-14));
  CHECK(p.center.isZero(0.0));
  const BivMat<N> truth = BivMat<N>::Identity() * (2.0 * m * r * r / (N + 2));
  CHECK(rel_diff(p.inertia, truth) < 1e-15);
  if (N == 2) CHECK(p.inertia(0, 0) == Approx(0.5 * m * r * r));        // the disk: m r^2 / 2
  if (N == 3) CHECK(p.inertia(0, 0) == Approx(2.0 / 5.0 * m * r * r));  // the solid sphere: 2/5 m r^2
}

TEMPLATE_TEST_CASE("n-ball mesh: within the inscribed/circumscribed bounds, converging under refinement", "[mass]", D2,
                   D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  const double r = 1.3, density = 0.9;
  const std::vector<int> levels = N == 2 ? std::vector<int>{8, 16}
                                  : N == 3 ? std::vector<int>{4, 8}
                                  : N == 4 ? std::vector<int>{4, 8}
                                  : N == 5 ? std::vector<int>{2, 4}
                                           : std::vector<int>{1, 2};
  const MassProperties<N> exact = wedge::ball_mass_properties<N>(r, density);
  double previous_error = INFINITY;
  for (int s : levels) {
    INFO("subdivisions " << s);
    const SimplexMesh<N> mesh = wedge::ball_mesh<N>(r, s);
    for (const Vec<N>& v : mesh.vertices) REQUIRE(std::abs(v.norm() - r) <= 1e-14 * r);
    const double rho = inscribed_radius(mesh);
    const double k = rho / r;
    const MassProperties<N> p = wedge::mass_properties<N>(mesh, density);
    CHECK(p.center.norm() <= kExact * r);  // the tessellation is centrally symmetric
    CHECK(p.volume <= exact.volume);
    CHECK(p.volume >= std::pow(k, N) * exact.volume);
    const BivMat<N> io = wedge::inertia_about<N>(p, Vec<N>::Zero());
    const double i_ball = exact.inertia(0, 0), i_inner = std::pow(k, N + 2) * i_ball;
    for (int a = 0; a < wedge::kBiv<N>; ++a)
      for (int b = 0; b < wedge::kBiv<N>; ++b) {
        if (a == b) {
          CHECK(io(a, a) <= i_ball);
          CHECK(io(a, a) >= i_inner);
        } else {
          CHECK(std::abs(io(a, b)) <= 0.5 * (i_ball - i_inner));
        }
      }
    const double error = std::max(1.0 - p.volume / exact.volume, rel_diff(p.inertia, exact.inertia));
    CHECK(error < 0.75 * previous_error);
    previous_error = error;
  }
  // The finest 2D/3D levels are accurate to a few percent (2D s = 16: 0.4%, 3D s = 8: 3.1%, inertia).
  if (N <= 3) CHECK(previous_error < 0.035);
}

// ------------------------------------------------------------------------------------------ round products
TEST_CASE("Round products: closed forms against textbook values", "[mass]") {
  const double r = 0.7, r2 = 0.45, h = 1.3, L = 2.0 * h, rho = 1.7;
  SECTION("3D cylinder: V = pi r^2 L, I_xy = m r^2/2, I_xz = I_yz = m (3 r^2 + L^2)/12") {
    const auto p = wedge::mass_properties<3>(Shape<3>::cylinder(r, h), rho);
    const double m = rho * kPi * r * r * L;
    CHECK(p.volume == Approx(kPi * r * r * L).epsilon(1e-14));
    CHECK(p.inertia(0, 0) == Approx(m * r * r / 2.0).epsilon(1e-14));
    CHECK(p.inertia(1, 1) == Approx(m * (3 * r * r + L * L) / 12.0).epsilon(1e-14));
    CHECK(p.inertia(2, 2) == Approx(m * (3 * r * r + L * L) / 12.0).epsilon(1e-14));
    CHECK(p.inertia.isDiagonal(0.0));
  }
  SECTION("4D spherinder: V = 4/3 pi r^3 L, second moments r^2/5 (ball axes) and L^2/12") {
    const auto p = wedge::mass_properties<4>(Shape<4>::spherinder(r, h), rho);
    const double m = rho * 4.0 / 3.0 * kPi * r * r * r * L;
    CHECK(p.mass == Approx(m).epsilon(1e-14));
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const double si = i < 3 ? r * r / 5.0 : L * L / 12.0, sj = j < 3 ? r * r / 5.0 : L * L / 12.0;
        CHECK(p.inertia(biv<4>(i, j), biv<4>(i, j)) == Approx(m * (si + sj)).epsilon(1e-14));
      }
  }
  SECTION("4D duocylinder: V = pi^2 r1^2 r2^2, second moments r1^2/4 and r2^2/4") {
    const auto p = wedge::mass_properties<4>(Shape<4>::duocylinder(r, r2), rho);
    const double m = rho * kPi * kPi * r * r * r2 * r2;
    CHECK(p.mass == Approx(m).epsilon(1e-14));
    CHECK(p.inertia(biv<4>(0, 1), biv<4>(0, 1)) == Approx(m * r * r / 2.0).epsilon(1e-14));
    CHECK(p.inertia(biv<4>(2, 3), biv<4>(2, 3)) == Approx(m * r2 * r2 / 2.0).epsilon(1e-14));
    CHECK(p.inertia(biv<4>(0, 2), biv<4>(0, 2)) == Approx(m * (r * r + r2 * r2) / 4.0).epsilon(1e-14));
    CHECK(p.inertia(biv<4>(1, 3), biv<4>(1, 3)) == Approx(m * (r * r + r2 * r2) / 4.0).epsilon(1e-14));
  }
  SECTION("4D cubinder: V = pi r^2 L^2") {
    const auto p = wedge::mass_properties<4>(Shape<4>::cubinder(r, h), rho);
    const double m = rho * kPi * r * r * L * L;
    CHECK(p.mass == Approx(m).epsilon(1e-14));
    CHECK(p.inertia(biv<4>(0, 1), biv<4>(0, 1)) == Approx(m * r * r / 2.0).epsilon(1e-14));
    CHECK(p.inertia(biv<4>(0, 2), biv<4>(0, 2)) == Approx(m * (r * r / 4.0 + L * L / 12.0)).epsilon(1e-14));
    CHECK(p.inertia(biv<4>(2, 3), biv<4>(2, 3)) == Approx(m * L * L / 6.0).epsilon(1e-14));
  }
  SECTION("6D 3-ball x 3-ball: V = (4/3 pi)^2 r1^3 r2^3; a ball factor over one axis is an interval") {
    const auto p = wedge::mass_properties<6>(
        Shape<6>::round_product({ProductFactor::ball({0, 2, 4}, r), ProductFactor::ball({1, 3, 5}, r2)}), rho);
    const double m = rho * (4.0 / 3.0 * kPi) * (4.0 / 3.0 * kPi) * std::pow(r * r2, 3);
    CHECK(p.mass == Approx(m).epsilon(1e-14));
    CHECK(p.covariance(0, 0) == Approx(m * r * r / 5.0).epsilon(1e-14));
    CHECK(p.covariance(1, 1) == Approx(m * r2 * r2 / 5.0).epsilon(1e-14));
    const auto a = wedge::mass_properties<2>(Shape<2>::round_product({ProductFactor::ball({0}, h), ProductFactor::interval(1, h)}), rho);
    const auto b = wedge::mass_properties<2>(Shape<2>::box(Vec<2>(h, h)), rho);
    CHECK(rel_diff(a.inertia, b.inertia) < 1e-15);
  }
}

namespace {

// A round product mesh is exactly the product of the factors' inscribed polytopes P_f (the tessellation
// of a product of cube grids is a product of tessellations, mapped factor by factor), and
// rho_f B_f <= P_f <= r_f B_f with rho_f the inscribed radius of the factor's own d-ball mesh at the same
// level. So, with s_a the per-mass second moment of axis a, V and every diagonal inertia entry lie
// between their values for the factor radii rho_f and r_f.
struct FactorBound {
  std::vector<int> axes;
  double r, rho;  // rho = r for intervals
};

template <int N>
void check_product_bounds(const MassProperties<N>& p, const std::vector<FactorBound>& factors, double density) {
  auto moments = [&](bool inner, double& volume, Vec<N>& s) {
    volume = 1.0;
    for (const FactorBound& f : factors) {
      const int d = int(f.axes.size());
      const double rr = inner ? f.rho : f.r;
      volume *= d == 1 ? 2.0 * rr : (d == 2 ? kPi * rr * rr : 4.0 / 3.0 * kPi * rr * rr * rr);
      for (int a : f.axes) s[a] = rr * rr / (d + 2);
    }
  };
  double v_in, v_out;
  Vec<N> s_in, s_out;
  moments(true, v_in, s_in);
  moments(false, v_out, s_out);
  CHECK(p.volume <= v_out * (1 + 1e-14));
  CHECK(p.volume >= v_in);
  CHECK(p.center.norm() <= 1e-12);
  const BivMat<N> io = wedge::inertia_about<N>(p, Vec<N>::Zero());
  for (int i = 0; i < N; ++i)
    for (int j = i + 1; j < N; ++j) {
      const int k = biv<N>(i, j);
      CHECK(io(k, k) <= density * v_out * (s_out[i] + s_out[j]) * (1 + 1e-14));
      CHECK(io(k, k) >= density * v_in * (s_in[i] + s_in[j]));
    }
}

template <int D>
double factor_rho(double r, int s) {
  return inscribed_radius(wedge::ball_mesh<D>(r, s));
}

}  // namespace

TEST_CASE("Round product meshes: cylinder, spherinder, duocylinder, cubinder within rigorous bounds, converging",
          "[mass]") {
  const double r = 0.9, r2 = 0.6, h = 0.8, rho = 1.1;
  SECTION("3D cylinder") {
    const auto exact = wedge::mass_properties<3>(Shape<3>::cylinder(r, h), rho);
    double prev = INFINITY;
    for (int s : {4, 8, 16}) {
      const auto mesh = wedge::boundary_mesh<3>(Shape<3>::cylinder(r, h), s);
      const auto p = wedge::mass_properties<3>(mesh, rho);
      check_product_bounds<3>(p, {{{0, 1}, r, factor_rho<2>(r, s)}, {{2}, h, h}}, rho);
      const double err = std::max(std::abs(1 - p.mass / exact.mass), rel_diff(p.inertia, exact.inertia));
      CHECK(err < 0.75 * prev);
      prev = err;
    }
    CHECK(prev < 0.01);  // s = 16: 0.4% in mass, 0.6% in inertia
  }
  SECTION("4D spherinder") {
    const auto exact = wedge::mass_properties<4>(Shape<4>::spherinder(r, h), rho);
    double prev = INFINITY;
    for (int s : {2, 4, 8}) {
      const auto p = wedge::mass_properties<4>(wedge::boundary_mesh<4>(Shape<4>::spherinder(r, h), s), rho);
      check_product_bounds<4>(p, {{{0, 1, 2}, r, factor_rho<3>(r, s)}, {{3}, h, h}}, rho);
      const double err = std::max(std::abs(1 - p.mass / exact.mass), rel_diff(p.inertia, exact.inertia));
      CHECK(err < 0.75 * prev);
      prev = err;
    }
  }
  SECTION("4D duocylinder") {
    const auto exact = wedge::mass_properties<4>(Shape<4>::duocylinder(r, r2), rho);
    double prev = INFINITY;
    for (int s : {2, 4, 8}) {
      const auto p = wedge::mass_properties<4>(wedge::boundary_mesh<4>(Shape<4>::duocylinder(r, r2), s), rho);
      check_product_bounds<4>(p, {{{0, 1}, r, factor_rho<2>(r, s)}, {{2, 3}, r2, factor_rho<2>(r2, s)}}, rho);
      const double err = std::max(std::abs(1 - p.mass / exact.mass), rel_diff(p.inertia, exact.inertia));
      CHECK(err < 0.75 * prev);
      prev = err;
    }
  }
  SECTION("4D cubinder and a 5D disk x 3-ball") {
    const auto p4 = wedge::mass_properties<4>(wedge::boundary_mesh<4>(Shape<4>::cubinder(r, h), 4), rho);
    check_product_bounds<4>(p4, {{{0, 1}, r, factor_rho<2>(r, 4)}, {{2}, h, h}, {{3}, h, h}}, rho);
    const Shape<5> s5 = Shape<5>::round_product({ProductFactor::ball({3, 4}, r2), ProductFactor::ball({0, 1, 2}, r)});
    const auto p5 = wedge::mass_properties<5>(wedge::boundary_mesh<5>(s5, 2), rho);
    check_product_bounds<5>(p5, {{{3, 4}, r2, factor_rho<2>(r2, 2)}, {{0, 1, 2}, r, factor_rho<3>(r, 2)}}, rho);
  }
}

// ------------------------------------------------------------------------------------------ Monte Carlo
TEMPLATE_TEST_CASE("Random convex polytope: volume, centre and inertia agree with Monte Carlo (5 sigma)", "[mass]", D3,
                   D4, D5) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(20200701 + N);
  const std::vector<Vec<N>> pts = random_points<N>(rng, 10 + 4 * N);
  const wedge::ConvexHull<N> hull = wedge::convex_hull<N>(pts);
  const double density = 1.0;
  const MassProperties<N> p = wedge::mass_properties<N>(Shape<N>::polytope(pts), density);

  // Uniform samples in the bounding box; inside iff inside every facet half-space of the hull.
  Vec<N> lo = pts[0], hi = pts[0];
  for (const Vec<N>& v : pts) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const double box = (hi - lo).prod();
  const int samples = 1000000;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec<N>> inside;
  for (int k = 0; k < samples; ++k) {
    Vec<N> x;
    for (int i = 0; i < N; ++i) x[i] = lo[i] + (hi[i] - lo[i]) * u(rng);
    bool in = true;
    for (std::size_t f = 0; f < hull.normals.size() && in; ++f) in = hull.normals[f].dot(x) <= hull.offsets[f];
    if (in) inside.push_back(x);
  }
  const double n_in = double(inside.size());
  const double frac = n_in / samples;
  INFO("fraction inside " << frac);

  const double v_mc = box * frac, v_se = box * std::sqrt(frac * (1 - frac) / samples);
  CHECK(std::abs(p.volume - v_mc) <= 5 * v_se);

  Vec<N> c = Vec<N>::Zero();
  for (const Vec<N>& x : inside) c += x;
  c /= n_in;
  for (int i = 0; i < N; ++i) {
    double var = 0.0;
    for (const Vec<N>& x : inside) var += (x[i] - c[i]) * (x[i] - c[i]);
    const double se = std::sqrt(var / n_in / n_in);
    CHECK(std::abs(p.center[i] - c[i]) <= 5 * se);
  }

  // The definition of section 4: I = integral of [r]_* [r]_*^T dV, r = x - c, as a mean over all samples.
  BivMat<N> sum = BivMat<N>::Zero(), sum2 = BivMat<N>::Zero();
  for (const Vec<N>& x : inside) {
    const auto w = wedge::wedge_matrix<N>(Vec<N>(x - c));
    const BivMat<N> g = box * (w * w.transpose());
    sum += g;
    sum2 += g.cwiseProduct(g);
  }
  const BivMat<N> mean = sum / samples;
  const double scale = p.inertia.cwiseAbs().maxCoeff();
  for (int a = 0; a < wedge::kBiv<N>; ++a)
    for (int b = 0; b < wedge::kBiv<N>; ++b) {
      const double se = std::sqrt(std::max(0.0, sum2(a, b) / samples - mean(a, b) * mean(a, b)) / samples);
      INFO("entry " << a << "," << b << ": exact " << p.inertia(a, b) << " MC " << mean(a, b) << " se " << se);
      CHECK(std::abs(p.inertia(a, b) - mean(a, b)) <= 5 * se + 1e-10 * scale);
    }
}

// ------------------------------------------------------------------------------------------ transformations
TEMPLATE_TEST_CASE("Translation moves the centre only, rotation gives I' = [Q]_2 I [Q]_2^T (eq. 4)", "[mass]", D2, D3,
                   D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(77 + N);
  const SimplexMesh<N> mesh = wedge::convex_hull_mesh<N>(random_points<N>(rng, 4 * N));
  const double density = 1.7;
  const MassProperties<N> p = wedge::mass_properties<N>(mesh, density);
  REQUIRE(p.inertia.cwiseAbs().maxCoeff() > 0.0);
  // A polytope without symmetries: its covariance is not diagonal.
  REQUIRE(std::abs(p.covariance(0, 1)) > 1e-3 * p.covariance.trace());

  Vec<N> t;
  for (int i = 0; i < N; ++i) t[i] = 3.0 - 1.1 * i;
  const MassProperties<N> pt = wedge::mass_properties<N>(transformed<N>(mesh, Mat<N>::Identity(), t), density);
  CHECK(std::abs(pt.mass - p.mass) <= kExact * p.mass);
  CHECK((pt.center - (p.center + t)).norm() <= kExact * (p.center + t).norm());
  CHECK(rel_diff(pt.covariance, p.covariance) <= 1e-11);  // t is ~5x the size of the body
  CHECK(rel_diff(pt.inertia, p.inertia) <= 1e-11);

  for (int trial = 0; trial < 3; ++trial) {
    const Mat<N> q = random_rotation<N>(rng);
    REQUIRE(det(q) == Approx(1.0));
    const MassProperties<N> pr = wedge::mass_properties<N>(transformed<N>(mesh, q, Vec<N>::Zero()), density);
    const BivMat<N> q2 = wedge::bivector_matrix<N>(q);
    CHECK(std::abs(pr.mass - p.mass) <= kExact * p.mass);
    CHECK((pr.center - q * p.center).norm() <= kExact * p.center.norm() + 1e-15);
    CHECK(rel_diff(pr.covariance, Mat<N>(q * p.covariance * q.transpose())) <= kExact);
    CHECK(rel_diff(pr.inertia, BivMat<N>(q2 * p.inertia * q2.transpose())) <= kExact);
  }
}

TEST_CASE("Parallel axes: I_origin = I_centre + m Delta I(c), with the paper's Delta I (2D, 3D, 4D)", "[mass]") {
  const double density = 1.3;
  {
    const Vec<2> h(0.4, 0.9), t(1.5, -0.6);
    SimplexMesh<2> mesh = wedge::box_mesh<2>(h, 2);
    for (auto& v : mesh.vertices) v += t;
    const auto p = wedge::mass_properties<2>(mesh, density);
    const auto box = wedge::box_mass_properties<2>(h, density);
    const double x = t[0], y = t[1], m = box.mass;
    CHECK(rel_diff(p.inertia, box.inertia) <= kExact);
    CHECK(wedge::inertia_about<2>(p, Vec<2>::Zero())(0, 0) == Approx(box.inertia(0, 0) + m * (x * x + y * y)).epsilon(1e-12));
  }
  {
    const Vec<3> h(0.4, 0.9, 0.6), t(1.5, -0.6, 2.2);
    SimplexMesh<3> mesh = wedge::box_mesh<3>(h, 2);
    for (auto& v : mesh.vertices) v += t;
    const auto p = wedge::mass_properties<3>(mesh, density);
    const auto box = wedge::box_mass_properties<3>(h, density);
    const double m = box.mass;
    const Mat<3> di = paper::delta_i(t);
    CHECK(rel_diff(p.inertia, box.inertia) <= kExact);
    CHECK(rel_diff(wedge::inertia_about<3>(p, Vec<3>::Zero()), Mat<3>(box.inertia + m * di)) <= kExact);
  }
  {
    Vec<4> h, t;
    h << 0.4, 0.9, 0.6, 0.3;
    t << 1.5, -0.6, 2.2, -1.1;
    SimplexMesh<4> mesh = wedge::box_mesh<4>(h, 1);
    for (auto& v : mesh.vertices) v += t;
    const auto p = wedge::mass_properties<4>(mesh, density);
    const auto box = wedge::box_mass_properties<4>(h, density);
    const double m = box.mass;
    const wedge::BivMat<4> di = paper::delta_i(t);
    CHECK(rel_diff(p.inertia, box.inertia) <= kExact);
    CHECK(rel_diff(wedge::inertia_about<4>(p, Vec<4>::Zero()), BivMat<4>(box.inertia + m * di)) <= kExact);
    // About an arbitrary point p0: Delta I of c - p0.
    Vec<4> p0;
    p0 << 0.3, 0.2, -0.5, 0.7;
    const Vec<4> d = t - p0;
    const auto star = wedge::wedge_matrix<4>(d);
    CHECK(rel_diff(wedge::inertia_about<4>(p, p0), BivMat<4>(box.inertia + m * star * star.transpose())) <= kExact);
  }
}

// ------------------------------------------------------------------------------------------ principal frame
TEMPLATE_TEST_CASE("Principal frame of a rotated, translated box mesh: the box's axes and diagonal inertia", "[mass]",
                   D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(5 + N);
  Vec<N> h;
  for (int i = 0; i < N; ++i) h[i] = 0.5 + 0.25 * i;  // distinct extents: a unique frame up to signs
  const Mat<N> q = random_rotation<N>(rng);
  const Vec<N> t = Vec<N>::LinSpaced(1.0, -2.0);
  const double density = 0.8;
  const MassProperties<N> p = wedge::mass_properties<N>(transformed<N>(wedge::box_mesh<N>(h, 1), q, t), density);
  const wedge::PrincipalFrame<N> f = wedge::principal_frame<N>(p);

  CHECK((f.center - t).norm() <= kExact * t.norm());
  CHECK(det(f.axes) == Approx(1.0).epsilon(1e-12));
  CHECK((f.axes.transpose() * f.axes - Mat<N>::Identity()).cwiseAbs().maxCoeff() <= 1e-12);
  // Each principal axis is +-one column of q; perm[j] = which.
  std::vector<int> perm(N, -1);
  for (int j = 0; j < N; ++j)
    for (int k = 0; k < N; ++k)
      if (std::abs(std::abs(f.axes.col(j).dot(q.col(k))) - 1.0) <= 1e-9) perm[std::size_t(j)] = k;
  std::vector<int> sorted = perm;
  std::sort(sorted.begin(), sorted.end());
  for (int j = 0; j < N; ++j) REQUIRE(sorted[std::size_t(j)] == j);

  const double m = p.mass;
  for (int i = 0; i < N; ++i)
    for (int j = i + 1; j < N; ++j) {
      const double ai = 2.0 * h[perm[std::size_t(i)]], aj = 2.0 * h[perm[std::size_t(j)]];
      const int k = biv<N>(i, j);
      CHECK(std::abs(f.inertia(k, k) - m * (ai * ai + aj * aj) / 12.0) <= kExact * m * 4.0 * h.maxCoeff() * h.maxCoeff());
    }
  for (int a = 0; a < wedge::kBiv<N>; ++a)
    for (int b = 0; b < wedge::kBiv<N>; ++b)
      if (a != b) CHECK(f.inertia(a, b) == 0.0);
  for (int i = 0; i < N; ++i)
    CHECK(f.covariance[i] == Approx(m * 4.0 * h[perm[std::size_t(i)]] * h[perm[std::size_t(i)]] / 12.0).epsilon(1e-11));
  // The inertia of the principal frame is that of the body seen in its frame: [Q]_2^T I [Q]_2.
  const BivMat<N> b = wedge::bivector_matrix<N>(f.axes);
  CHECK(rel_diff(BivMat<N>(b * f.inertia * b.transpose()), p.inertia) <= 1e-11);
}

TEMPLATE_TEST_CASE("Principal frame: identity for axis-aligned bodies, diagonal for a random polytope", "[mass]", D2,
                   D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  Vec<N> h;
  for (int i = 0; i < N; ++i) h[i] = 1.5 - 0.2 * i;
  const auto f = wedge::principal_frame<N>(wedge::box_mass_properties<N>(h, 1.0));
  CHECK(f.axes == Mat<N>::Identity());
  std::mt19937_64 rng(99 + N);
  const auto p = wedge::mass_properties<N>(Shape<N>::polytope(random_points<N>(rng, 3 * N + 2)), 2.0);
  const auto g = wedge::principal_frame<N>(p);
  CHECK(g.inertia.isDiagonal(0.0));
  CHECK(det(g.axes) == Approx(1.0).epsilon(1e-12));
  // The covariance in the frame is diag(g.covariance), and its inertia is g.inertia.
  const Mat<N> cf = g.axes.transpose() * p.covariance * g.axes;
  CHECK(rel_diff(cf, Mat<N>(g.covariance.asDiagonal())) <= 1e-12);
  CHECK(rel_diff(wedge::inertia_from_covariance<N>(g.covariance.asDiagonal()), g.inertia) <= 1e-12);
  for (int i = 1; i < N; ++i) CHECK(g.covariance[i] >= g.covariance[i - 1]);
}

// ------------------------------------------------------------------------------------------ dispatch, errors
TEST_CASE("mass_properties dispatch: polytope and mesh shapes, with_mass", "[mass]") {
  const Vec<3> h(0.5, 1.0, 1.5);
  std::vector<Vec<3>> corners;
  for (int m = 0; m < 8; ++m) corners.push_back(Vec<3>((m & 1 ? 1 : -1) * h[0], (m & 2 ? 1 : -1) * h[1], (m & 4 ? 1 : -1) * h[2]));
  corners.push_back(Vec<3>(0.1, 0.2, 0.3));  // interior: ignored by the hull
  const auto box = wedge::box_mass_properties<3>(h, 2.0);
  const auto poly = wedge::mass_properties<3>(Shape<3>::polytope(corners), 2.0);
  const auto mesh = wedge::mass_properties<3>(Shape<3>::mesh(wedge::box_mesh<3>(h, 3)), 2.0);
  CHECK(std::abs(poly.mass - box.mass) <= kExact * box.mass);
  CHECK(rel_diff(poly.inertia, box.inertia) <= kExact);
  CHECK(rel_diff(mesh.inertia, box.inertia) <= kExact);
  const auto scaled = wedge::with_mass<3>(box, 3.0);
  CHECK(scaled.mass == 3.0);
  CHECK(rel_diff(scaled.inertia, BivMat<3>(box.inertia * (3.0 / box.mass))) <= 1e-15);
}

TEST_CASE("mass errors: non-positive density or mass, half-spaces, bad sizes", "[mass]") {
  const Shape<3> ball = Shape<3>::ball(1.0);
  REQUIRE_THROWS_AS(wedge::mass_properties<3>(ball, 0.0), wedge::Error);
  REQUIRE_THROWS_WITH(wedge::mass_properties<3>(ball, 0.0), Catch::Contains("density must be positive"));
  REQUIRE_THROWS_WITH(wedge::mass_properties<3>(ball, -2.0), Catch::Contains("density must be positive"));
  REQUIRE_THROWS_WITH(wedge::mass_properties<3>(ball, NAN), Catch::Contains("density must be positive"));
  REQUIRE_THROWS_WITH(wedge::mass_properties<3>(wedge::box_mesh<3>(Vec<3>::Ones(), 1), 0.0),
                      Catch::Contains("density must be positive"));
  REQUIRE_THROWS_WITH(wedge::mass_properties<3>(Shape<3>::halfspace(Vec<3>(0, 0, 1), 0.0), 1.0),
                      Catch::Contains("half-space has no finite mass"));
  const auto p = wedge::mass_properties<3>(ball, 1.0);
  REQUIRE_THROWS_WITH(wedge::with_mass<3>(p, 0.0), Catch::Contains("mass must be positive"));
  REQUIRE_THROWS_WITH(wedge::with_mass<3>(p, -1.0), Catch::Contains("mass must be positive"));
  REQUIRE_THROWS_WITH(wedge::box_mass_properties<3>(Vec<3>(1, 0, 1), 1.0), Catch::Contains("half-extent 1 must be positive"));
  REQUIRE_THROWS_WITH(wedge::ball_mass_properties<4>(-1.0, 1.0), Catch::Contains("radius must be positive"));
  REQUIRE_THROWS_WITH(wedge::round_product_mass_properties<3>({ProductFactor::ball({0, 1}, 1.0)}, 1.0),
                      Catch::Contains("axis 2 is not covered"));
  // An invalid mesh is refused before integrating.
  SimplexMesh<3> open = wedge::box_mesh<3>(Vec<3>::Ones(), 1);
  open.cells.pop_back();
  REQUIRE_THROWS_WITH(wedge::mass_properties<3>(open, 1.0), Catch::Contains("open mesh"));
}
