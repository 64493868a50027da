// point_query (collision/point_query.hpp) against independent truth, 2D-6D:
//   - boxes and round products (cylinders, duocylinders, spherinders): a product of balls and intervals,
//     so the distance from x is sqrt(sum over factors of max(|x_factor| - size, 0)^2) and the closest
//     point clamps each factor: closed form, per factor;
//   - balls and half-spaces: closed form;
//   - convex polytopes: brute-force projection onto every face of Qhull's hull (tests/support/oracles).
// Tolerances: the distance comes from GJK at relative accuracy 1e-10 for O(1) shapes, so 1e-8 m; its
// witness point converges as the square root of that gap, so 1e-4 m for the closest point where it is
// unique. Containment is exact (the points are random, none within 1e-9 of a boundary in practice).
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "oracles.hpp"
#include "test_util.hpp"
#include "wedge/collision/point_query.hpp"

using namespace wedge;

namespace {

constexpr double kDistanceTol = 1e-8, kPointTol = 1e-4;

template <int N>
Transform<N> random_place(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Transform<N> t;
  t.position = Vec<N>::NullaryExpr([&] { return u(rng); });
  t.rotation = Mat<N>(oracle::random_rotation(N, rng));
  return t;
}

// The product-of-factors truth: distance and closest point of x (body frame).
template <int N>
std::pair<double, Vec<N>> product_truth(const std::vector<ProductFactor>& factors, const Vec<N>& x) {
  double d2 = 0.0;
  Vec<N> c = x;
  for (const ProductFactor& f : factors) {
    double len2 = 0.0;
    for (int a : f.axes) len2 += x[a] * x[a];
    const double len = std::sqrt(len2);
    if (len <= f.size) continue;
    d2 += (len - f.size) * (len - f.size);
    for (int a : f.axes) c[a] = x[a] * (f.size / len);
  }
  return {std::sqrt(d2), c};
}

template <int N>
void check_product(const Shape<N>& shape, const std::vector<ProductFactor>& factors, std::mt19937_64& rng,
                   int& inside_count) {
  std::uniform_real_distribution<double> u(-2.5, 2.5);
  for (int trial = 0; trial < 200; ++trial) {
    const Transform<N> t = random_place<N>(rng);
    // Half the points anywhere around the shape, half within 0.29 m of its centre (inside: every factor
    // is at least 0.3 in size), so both answers are exercised in every dimension.
    const Vec<N> x = trial % 2 ? Vec<N>(t.position + Vec<N>::NullaryExpr([&] { return u(rng); }))
                               : Vec<N>(t.position + 0.29 * std::abs(u(rng)) / 2.5 * Vec<N>(t.rotation.col(0)));
    const auto [dist, closest] = product_truth<N>(factors, t.apply_inverse(x));
    const PointQuery<N> q = point_query(shape, t, x);
    CHECK(q.inside == (dist == 0.0));
    CHECK(q.distance == Approx(dist).margin(kDistanceTol));
    CHECK((q.closest - t.apply(closest)).norm() <= kPointTol);
    inside_count += q.inside;
  }
}

}  // namespace

TEMPLATE_TEST_CASE("point_query: boxes against the closed form", "[collision][point_query]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(1000 + N);
  Vec<N> h;
  for (int i = 0; i < N; ++i) h[i] = 0.3 + 0.2 * i;
  std::vector<ProductFactor> factors;
  for (int i = 0; i < N; ++i) factors.push_back(ProductFactor::interval(i, h[i]));
  int inside = 0;
  check_product<N>(Shape<N>::box(h), factors, rng, inside);
  CHECK(inside > 0);  // both outcomes were exercised
  CHECK(inside < 200);
}

TEMPLATE_TEST_CASE("point_query: round products against the closed form", "[collision][point_query]", D3, D4, D5,
                   D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(1100 + N);
  // A disk of radius 0.9 times intervals, and a ball over the first three axes times intervals.
  for (const bool wide : {false, true}) {
    std::vector<ProductFactor> factors{wide ? ProductFactor::ball({0, 1, 2}, 1.1) : ProductFactor::ball({0, 1}, 0.9)};
    for (int i = wide ? 3 : 2; i < N; ++i) factors.push_back(ProductFactor::interval(i, 0.4 + 0.1 * i));
    if (wide && N == 3) continue;  // a ball in 3D: the ball test
    int inside = 0;
    check_product<N>(Shape<N>::round_product(factors), factors, rng, inside);
    CHECK(inside > 0);
  }
  if constexpr (N == 4) {  // the duocylinder: two disks
    const std::vector<ProductFactor> f{ProductFactor::ball({0, 1}, 0.8), ProductFactor::ball({2, 3}, 0.5)};
    int inside = 0;
    check_product<4>(Shape<4>::round_product(f), f, rng, inside);
    CHECK(inside > 0);
  }
}

TEMPLATE_TEST_CASE("point_query: balls and half-spaces against the closed form", "[collision][point_query]", D2, D3,
                   D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(1200 + N);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  const Shape<N> ball = Shape<N>::ball(1.3);
  const Vec<N> n = Mat<N>(oracle::random_rotation(N, rng)).col(0);  // a random unit normal
  const Shape<N> half = Shape<N>::halfspace(n, 0.25);
  for (int trial = 0; trial < 200; ++trial) {
    const Transform<N> t = random_place<N>(rng);
    const Vec<N> x = t.position + Vec<N>::NullaryExpr([&] { return u(rng); });
    const double r = (x - t.position).norm();
    const PointQuery<N> b = point_query(ball, t, x);
    CHECK(b.inside == (r <= 1.3));
    CHECK(b.distance == Approx(std::max(r - 1.3, 0.0)).margin(1e-12));
    if (!b.inside) CHECK((b.closest - (t.position + (x - t.position) * (1.3 / r))).norm() <= 1e-12);
    const Vec<N> wn = t.rotation * n;
    const double above = wn.dot(x - t.position) - 0.25;
    const PointQuery<N> s = point_query(half, t, x);
    CHECK(s.inside == (above <= 0.0));
    CHECK(s.distance == Approx(std::max(above, 0.0)).margin(1e-12));
    CHECK((s.closest - (x - std::max(above, 0.0) * wn)).norm() <= 1e-12);
  }
}

TEMPLATE_TEST_CASE("point_query: convex polytopes against brute-force projection onto every face",
                   "[collision][point_query]", D2, D3, D4, D5) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(1300 + N);
  std::uniform_real_distribution<double> u(-1.8, 1.8);
  int inside = 0, outside = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const oracle::Points pts = oracle::random_points_in_ball(N, N + 4 + trial % 5, 1.0, oracle::Point::Zero(N), rng);
    std::vector<Vec<N>> local;
    for (const auto& p : pts) local.push_back(Vec<N>(p));
    const Shape<N> poly = Shape<N>::polytope(local);
    const Transform<N> t = random_place<N>(rng);
    oracle::Points world;
    for (const Vec<N>& v : local) world.push_back(oracle::Point(t.apply(v)));
    Vec<N> mean = Vec<N>::Zero();
    for (const Vec<N>& v : local) mean += v;
    mean /= double(local.size());
    for (int k = 0; k < 6; ++k) {
      // Odd k: anywhere around; even k: between the vertices' mean and a vertex (inside, by convexity).
      const Vec<N>& vertex = local[std::size_t(k) % local.size()];
      const Vec<N> x = k % 2 ? Vec<N>(t.position + Vec<N>::NullaryExpr([&] { return u(rng); }))
                             : t.apply(Vec<N>(mean + 0.45 * (1.0 + u(rng) / 1.8) * (vertex - mean)));
      const oracle::ClosestPoint truth = oracle::closest_point_brute_force(world, oracle::Point(x));
      const PointQuery<N> q = point_query(poly, t, x);
      INFO("trial " << trial << " oracle distance " << truth.distance << " boundary " << truth.boundary_distance);
      if (truth.distance == 0.0 && truth.boundary_distance < 1e-9) continue;  // on the boundary: either answer
      CHECK(q.inside == (truth.distance == 0.0));
      CHECK(q.distance == Approx(truth.distance).margin(kDistanceTol));
      if (!q.inside) CHECK((q.closest - Vec<N>(truth.point)).norm() <= kPointTol);
      (q.inside ? inside : outside)++;
    }
  }
  CHECK(inside > 10);
  CHECK(outside > 10);
}
