// Axis-aligned boxes (wedge/collision/aabb.hpp): the box algebra on hand-checked values, and the world
// box of every bounded shape kind under random rotations in 2D..6D against independent oracles:
//   * box, polytope, mesh: brute force over the corners / input points / mesh vertices, transformed one
//     by one (every point inside, every face touched, to round-off);
//   * ball and round products: containment of points sampled on the true surface and of the vertices
//     of wedge::boundary_mesh, and tightness through an explicit witness point of the solid on each face
//     (the Cauchy-Schwarz maximiser of x -> e_i . (p + R x) over each factor).
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "test_util.hpp"
#include "uniform_vec.hpp"
#include "wedge/collision/aabb.hpp"
#include "wedge/error.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/products.hpp"

namespace {

using wedge::Aabb;
using wedge::Mat;
using wedge::ProductFactor;
using wedge::Shape;
using wedge::Vec;

// Round-off allowance for comparing world coordinates of magnitude <= ~20 computed in different orders
// (sums of N <= 6 products): 1e-12 is ~5000 ulps at that size, and far below any real error (>= 1e-6).
constexpr double kRoundOff = 1e-12;

// A general rotation (exp of a random bivector with components of size ~2: double and triple
// rotations from 4D on), with its matrix.
template <int N>
Mat<N> random_rotation(std::mt19937_64& rng) {
  return wedge::to_matrix(wedge::exp<N>(random_bivector<N>(rng, 2.0)));
}

// Every point inside the box (to round-off), and every face touched by some point.
template <int N>
void check_tight_over_points(const Aabb<N>& box, const std::vector<Vec<N>>& world_points) {
  Vec<N> lo = Vec<N>::Constant(1e300), hi = Vec<N>::Constant(-1e300);
  for (const Vec<N>& w : world_points) {
    lo = lo.cwiseMin(w);
    hi = hi.cwiseMax(w);
  }
  for (int i = 0; i < N; ++i) {
    CHECK(box.lo[i] == Approx(lo[i]).margin(kRoundOff));
    CHECK(box.hi[i] == Approx(hi[i]).margin(kRoundOff));
  }
}

template <int N>
std::vector<Vec<N>> placed(const std::vector<Vec<N>>& body_points, const Vec<N>& p, const Mat<N>& r) {
  std::vector<Vec<N>> out;
  for (const Vec<N>& x : body_points) out.push_back(p + r * x);
  return out;
}

// A random partition of the axes into round-product factors: groups of 1..3 axes, a single axis an
// interval, larger groups balls; sizes in [0.2, 1.5].
template <int N>
std::vector<ProductFactor> random_factors(std::mt19937_64& rng) {
  std::vector<int> axes(N);
  std::iota(axes.begin(), axes.end(), 0);
  std::shuffle(axes.begin(), axes.end(), rng);
  std::uniform_real_distribution<double> size(0.2, 1.5);
  std::vector<ProductFactor> factors;
  for (int start = 0; start < N;) {
    const int len = std::min<int>(N - start, 1 + int(rng() % 3));
    std::vector<int> group(axes.begin() + start, axes.begin() + start + len);
    factors.push_back(len == 1 ? ProductFactor::interval(group[0], size(rng))
                               : ProductFactor::ball(group, size(rng)));
    start += len;
  }
  return factors;
}

// A point of the product solid: every ball factor on its sphere (a random direction), every interval
// factor at a random end or inside.
template <int N>
Vec<N> sample_surface(const std::vector<ProductFactor>& factors, std::mt19937_64& rng) {
  std::normal_distribution<double> nd;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec<N> x = Vec<N>::Zero();
  for (const ProductFactor& f : factors) {
    if (f.kind == ProductFactor::Kind::Interval) {
      const double t = u(rng);
      x[f.axes[0]] = f.size * (std::abs(t) > 0.5 ? (t > 0 ? 1.0 : -1.0) : t);
    } else {
      double norm2 = 0.0;
      for (int a : f.axes) norm2 += (x[a] = nd(rng)) * x[a];
      for (int a : f.axes) x[a] *= f.size / std::sqrt(norm2);
    }
  }
  return x;
}

// The point of the product solid that maximises s * (R x)_i: per factor, the Cauchy-Schwarz maximiser
// of s u . x_A with u the row i of R restricted to the factor's axes.
template <int N>
Vec<N> witness(const std::vector<ProductFactor>& factors, const Mat<N>& r, int i, double s) {
  Vec<N> x = Vec<N>::Zero();
  for (const ProductFactor& f : factors) {
    double norm2 = 0.0;
    for (int a : f.axes) norm2 += r(i, a) * r(i, a);
    const double norm = std::sqrt(norm2);
    if (norm == 0.0) continue;
    for (int a : f.axes) x[a] = s * f.size * r(i, a) / (f.kind == ProductFactor::Kind::Interval ? std::abs(r(i, a)) : norm);
  }
  return x;
}

// True if x lies in the product solid (each ball factor's part within its radius, each interval within
// its half-length), to round-off.
template <int N>
bool in_product(const std::vector<ProductFactor>& factors, const Vec<N>& x) {
  for (const ProductFactor& f : factors) {
    double norm2 = 0.0;
    for (int a : f.axes) norm2 += x[a] * x[a];
    if (std::sqrt(norm2) > f.size * (1.0 + kRoundOff)) return false;
  }
  return true;
}

template <int N>
void check_round_product(const Shape<N>& shape, const std::vector<ProductFactor>& factors, std::mt19937_64& rng) {
  const Vec<N> p = uniform_vec<N>(rng, -10.0, 10.0);
  const Mat<N> r = random_rotation<N>(rng);
  const Aabb<N> box = wedge::world_aabb<N>(shape, p, r);
  REQUIRE(box.valid());
  // Tight: on each face a point of the solid touches it.
  for (int i = 0; i < N; ++i) {
    const Vec<N> top = witness<N>(factors, r, i, 1.0), bottom = witness<N>(factors, r, i, -1.0);
    REQUIRE(in_product<N>(factors, top));
    REQUIRE(in_product<N>(factors, bottom));
    CHECK((p + r * top)[i] == Approx(box.hi[i]).margin(kRoundOff));
    CHECK((p + r * bottom)[i] == Approx(box.lo[i]).margin(kRoundOff));
  }
  // Bounding: random points of the true surface lie inside.
  for (int k = 0; k < 2000; ++k) {
    const Vec<N> w = p + r * sample_surface<N>(factors, rng);
    for (int i = 0; i < N; ++i) {
      CHECK(w[i] >= box.lo[i] - kRoundOff);
      CHECK(w[i] <= box.hi[i] + kRoundOff);
    }
  }
  // The tessellated boundary (vertices exactly on the true surface) lies inside, and reaches each face
  // to within its tessellation error. A ball factor of d axes meshed at s subdivisions (cube map) has a
  // vertex direction within |q - g| <= sqrt(d-1)/s of any direction's cube point q (|q| >= 1), so the
  // support it misses is at most r (1 - cos) = r |q^ - g^|^2 / 2 <= r 2 (d-1)/s^2 per factor.
  const int s = N <= 4 ? 6 : 3;
  double gap = 0.0;
  for (const ProductFactor& f : factors)
    if (f.kind == ProductFactor::Kind::Ball) gap += f.size * 2.0 * double(f.axes.size() - 1) / double(s * s);
  const std::vector<Vec<N>> world = placed<N>(wedge::boundary_mesh<N>(shape, s).vertices, p, r);
  Vec<N> lo = Vec<N>::Constant(1e300), hi = Vec<N>::Constant(-1e300);
  for (const Vec<N>& w : world) {
    lo = lo.cwiseMin(w);
    hi = hi.cwiseMax(w);
  }
  for (int i = 0; i < N; ++i) {
    CHECK(lo[i] >= box.lo[i] - kRoundOff);
    CHECK(hi[i] <= box.hi[i] + kRoundOff);
    CHECK(lo[i] - box.lo[i] <= gap + kRoundOff);
    CHECK(box.hi[i] - hi[i] <= gap + kRoundOff);
  }
}

}  // namespace

TEST_CASE("aabb: overlap, union, containment, fattening and cost on hand-checked boxes", "[aabb]") {
  const Aabb<3> a{Vec<3>(0, 0, 0), Vec<3>(1, 2, 3)};
  const Aabb<3> touching{Vec<3>(1, 0, 0), Vec<3>(2, 1, 1)};  // shares the face x = 1
  const Aabb<3> apart{Vec<3>(0, 0, 3.5), Vec<3>(1, 1, 4)};   // separated along z only
  CHECK(wedge::overlaps(a, touching));
  CHECK(wedge::overlaps(touching, a));
  CHECK_FALSE(wedge::overlaps(a, apart));
  CHECK_FALSE(wedge::overlaps(apart, a));
  const Aabb<3> u = wedge::merged(a, apart);
  CHECK(u.lo == Vec<3>(0, 0, 0));
  CHECK(u.hi == Vec<3>(1, 2, 4));
  CHECK(wedge::contains(u, a));
  CHECK(wedge::contains(a, a));
  CHECK_FALSE(wedge::contains(a, u));
  const Aabb<3> f = wedge::fattened(a, 0.5);
  CHECK(f.lo == Vec<3>(-0.5, -0.5, -0.5));
  CHECK(f.hi == Vec<3>(1.5, 2.5, 3.5));
  CHECK(wedge::cost(a) == 6.0);  // 1 + 2 + 3
  CHECK(a.center() == Vec<3>(0.5, 1, 1.5));
  CHECK(a.half_extents() == Vec<3>(0.5, 1, 1.5));
  CHECK(a.valid());
  CHECK_FALSE((Aabb<3>{Vec<3>(0, 0, 0), Vec<3>(1, -1, 1)}.valid()));
  CHECK_FALSE((Aabb<3>{Vec<3>(0, 0, 0), Vec<3>(1, NAN, 1)}.valid()));
  // A flat box has a non-zero cost (the (n-1)-face measure would vanish once two sides are zero).
  CHECK(wedge::cost(Aabb<4>{Vec<4>::Zero(), Vec<4>(1, 0, 0, 0)}) == 1.0);
}

TEMPLATE_TEST_CASE_SIG("aabb: box and polytope world boxes equal brute force over corners and points", "[aabb]",
                       ((int N), N), 2, 3, 4, 5, 6) {
  std::mt19937_64 rng(100 + N);
  for (int trial = 0; trial < 20; ++trial) {
    const Vec<N> p = uniform_vec<N>(rng, -10.0, 10.0);
    const Mat<N> r = random_rotation<N>(rng);
    // Box: the 2^N corners.
    const Vec<N> h = uniform_vec<N>(rng, 0.1, 2.0);
    std::vector<Vec<N>> corners;
    for (int m = 0; m < (1 << N); ++m) {
      Vec<N> c;
      for (int i = 0; i < N; ++i) c[i] = (m >> i & 1) ? h[i] : -h[i];
      corners.push_back(c);
    }
    check_tight_over_points<N>(wedge::world_aabb<N>(Shape<N>::box(h), p, r), placed<N>(corners, p, r));
    // Polytope: every input point, including the interior ones the hull drops.
    std::vector<Vec<N>> points;
    for (int k = 0; k < 3 * N + 4; ++k) points.push_back(uniform_vec<N>(rng, -1.0, 1.0));
    const Shape<N> poly = Shape<N>::polytope(points);
    check_tight_over_points<N>(wedge::world_aabb<N>(poly, p, r), placed<N>(points, p, r));
    // The rotor overload agrees with the matrix one.
    const wedge::Rotor<N> rotor = wedge::exp<N>(random_bivector<N>(rng, 1.0));
    const Aabb<N> by_rotor = wedge::world_aabb<N>(poly, p, rotor);
    const Aabb<N> by_matrix = wedge::world_aabb<N>(poly, p, wedge::to_matrix(rotor));
    CHECK(by_rotor.lo == by_matrix.lo);
    CHECK(by_rotor.hi == by_matrix.hi);
  }
}

TEMPLATE_TEST_CASE_SIG("aabb: mesh world boxes equal brute force over the mesh vertices", "[aabb]", ((int N), N), 2,
                       3, 4, 5, 6) {
  std::mt19937_64 rng(200 + N);
  // A box mesh (subdivided, so most vertices are not corners) and the boundary of a random hull.
  const wedge::SimplexMesh<N> box = wedge::box_mesh<N>(uniform_vec<N>(rng, 0.2, 1.5), 2);
  std::vector<Vec<N>> points;
  for (int k = 0; k < 3 * N + 4; ++k) points.push_back(uniform_vec<N>(rng, -1.0, 1.0));
  const wedge::SimplexMesh<N> hull = wedge::convex_hull_mesh<N>(points);
  for (const auto& mesh : {box, hull}) {
    const Shape<N> shape = Shape<N>::mesh(mesh);
    for (int trial = 0; trial < 10; ++trial) {
      const Vec<N> p = uniform_vec<N>(rng, -10.0, 10.0);
      const Mat<N> r = random_rotation<N>(rng);
      check_tight_over_points<N>(wedge::world_aabb<N>(shape, p, r), placed<N>(mesh.vertices, p, r));
    }
  }
}

TEMPLATE_TEST_CASE_SIG("aabb: ball and round product world boxes against the true surface", "[aabb]", ((int N), N),
                       2, 3, 4, 5, 6) {
  std::mt19937_64 rng(300 + N);
  const std::vector<ProductFactor> ball{ProductFactor::ball([] {
    std::vector<int> a(N);
    std::iota(a.begin(), a.end(), 0);
    return a;
  }(), 0.8)};
  check_round_product<N>(Shape<N>::ball(0.8), ball, rng);
  for (int trial = 0; trial < 6; ++trial) {
    const std::vector<ProductFactor> factors = random_factors<N>(rng);
    check_round_product<N>(Shape<N>::round_product(factors), factors, rng);
  }
  if constexpr (N >= 3) {
    const Shape<N> cylinder = Shape<N>::cylinder(0.5, 1.25);
    check_round_product<N>(cylinder, cylinder.template as<wedge::shapes::RoundProduct<N>>().factors, rng);
  }
}

TEST_CASE("aabb: a half-space has no world box", "[aabb]") {
  const Shape<3> ground = Shape<3>::halfspace(Vec<3>(0, 0, 1), 0.0);
  REQUIRE_THROWS_AS(wedge::world_aabb<3>(ground, Vec<3>::Zero(), Mat<3>::Identity()), wedge::Error);
  REQUIRE_THROWS_WITH(wedge::world_aabb<3>(ground, Vec<3>::Zero(), Mat<3>::Identity()), Catch::Contains("unbounded"));
  REQUIRE_THROWS_AS(wedge::points_aabb<3>({}, Vec<3>::Zero(), Mat<3>::Identity()), wedge::Error);
}
