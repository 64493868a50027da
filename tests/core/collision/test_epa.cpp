// EPA (wedge/collision/detail/epa.hpp) for n = 2..6 against independent truth:
//   - overlapping random polytopes and rotated boxes: the exact penetration depth of the Qhull hull of the
//     Minkowski difference (the smallest facet offset, tests/support/convex_oracle.hpp); the normal is
//     checked through what it must satisfy rather than against one facet, so that ties (several facets
//     at the minimum) accept any of them: the support of A - B along it equals the depth, and the
//     witnesses give depth * normal as a point of A - B;
//   - round shapes: two balls (depth r_a + r_b - d along the centre line) and a ball against a box
//     (depth and normal from the closest-point formula, centre inside and outside the box);
//   - degenerate input: touching faces, identical shapes, a point inside a box, a segment through a box,
//     flat Minkowski differences, a point against itself.
// Tolerances (sizes are O(1)): polytopes 1e-9: EPA stops when the support repeats a facet's plane to
// 1e-10 of the size of A - B (EpaSettings::tolerance), the oracle's offsets are exact to ~1e-15; round
// shapes: the lower/upper bound argument given in each test.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "wedge/collision/detail/epa.hpp"
#include "wedge/collision/detail/gjk.hpp"
#include "wedge/hull.hpp"
#include "convex_oracle.hpp"
#include "test_util.hpp"

namespace {

using oracle::BallSupport;
using oracle::BoxSupport;
using oracle::PointsSupport;
using wedge::Vec;

constexpr double kDepth = 1e-9;
constexpr double kInside = 1e-6;  // overlaps shallower than this are left to the degenerate tests

template <int N>
bool finite(const wedge::EpaResult<N>& r) {
  return std::isfinite(r.depth) && r.normal.allFinite() && r.point_a.allFinite() && r.point_b.allFinite();
}

template <int N>
double support_value(const std::vector<Vec<N>>& pts, const Vec<N>& d) {
  double h = -INFINITY;
  for (const Vec<N>& p : pts) h = std::max(h, p.dot(d));
  return h;
}

// One overlapping polytope pair against the exact depth (the Minkowski hull's smallest facet offset, or
// for 6D boxes the separating-axis test); false if the overlap is too shallow to use.
template <int N, class SA, class SB>
bool check_depth(const SA& sa, const SB& sb, const std::vector<Vec<N>>& pa, const std::vector<Vec<N>>& pb,
                 const Vec<N>& dir, double depth = NAN) {
  const std::vector<Vec<N>> m = oracle::minkowski_difference<N>(pa, pb);
  if (std::isnan(depth)) depth = oracle::min_offset<N>(wedge::convex_hull<N>(m));
  if (depth <= kInside) return false;
  const auto g = wedge::gjk<N>(sa, sb, dir);
  REQUIRE(g.intersecting);
  const auto r = wedge::epa<N>(sa, sb, g.simplex);
  REQUIRE(finite(r));
  CHECK(r.ok);
  CHECK(std::abs(r.depth - depth) <= kDepth);
  CHECK(std::abs(r.normal.norm() - 1.0) <= 1e-12);
  // h_{A-B}(n) >= depth for every unit n, with equality exactly along the minimising facets' normals.
  CHECK(std::abs(support_value<N>(m, r.normal) - depth) <= kDepth);
  // depth * normal = point_a - point_b with point_a extreme in A along n, point_b extreme in B along -n.
  CHECK((r.point_a - r.point_b - r.depth * r.normal).norm() <= kDepth);
  CHECK(oracle::hull_excess<N>(wedge::convex_hull<N>(pa), r.point_a) <= kDepth);
  CHECK(oracle::hull_excess<N>(wedge::convex_hull<N>(pb), r.point_b) <= kDepth);
  CHECK(r.normal.dot(r.point_a) >= support_value<N>(pa, r.normal) - kDepth);
  CHECK(-r.normal.dot(r.point_b) >= support_value<N>(pb, Vec<N>(-r.normal)) - kDepth);
  return true;
}

}  // namespace

TEMPLATE_TEST_CASE("epa: random overlapping polytopes against the depth of the Minkowski hull", "[epa]", D2, D3, D4,
                   D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(1500 + N);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int trials = N <= 4 ? 50 : 20;
  int used = 0;
  for (int t = 0; t < trials; ++t) {
    const double distance = 0.8 * u(rng);  // (one draw per statement: same order in every compiler)
    const Vec<N> cb = distance * oracle::unit<N>(rng);
    const auto a = oracle::random_polytope<N>(rng, N + 2 + t % 6, Vec<N>::Zero(), 1.0);
    const auto b = oracle::random_polytope<N>(rng, N + 2 + (t / 6) % 5, cb, 0.4 + u(rng));
    used += check_depth<N>(a, b, a.points, b.points, Vec<N>(cb));
  }
  CHECK(used >= trials / 2);
}

TEMPLATE_TEST_CASE("epa: overlapping rotated boxes against the depth of the Minkowski hull", "[epa]", D2, D3, D4, D5,
                   D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(1700 + N);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // 6D: the exact depth from the separating-axis test (the 4096-point hull is too slow).
  const int trials = N <= 4 ? 30 : (N == 5 ? 10 : 20);
  int used = 0;
  for (int t = 0; t < trials; ++t) {
    const BoxSupport<N> a = oracle::random_box<N>(rng, Vec<N>(0.3 * oracle::gaussian<N>(rng)));
    const double distance = 0.6 * u(rng);  // (one draw per statement)
    const BoxSupport<N> b = oracle::random_box<N>(rng, Vec<N>(a.centre + distance * oracle::unit<N>(rng)));
    const double depth = N == 6 ? oracle::box_sat<N>(a, b) : NAN;
    used += check_depth<N>(a, b, a.corners(), b.corners(), Vec<N>(b.centre - a.centre), depth);
  }
  CHECK(used >= trials / 2);
}

TEMPLATE_TEST_CASE("epa: two overlapping balls, depth r_a + r_b - d along the centre line", "[epa]", D2, D3, D4, D5,
                   D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(1900 + N);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // EPA converges only linearly on a ball, more slowly as N grows (measured: tolerance 1e-3 within ~300
  // iterations up to 4D; 1e-2 within 1000 iterations for most 5D/6D cases). From 5D on a run may stop
  // at the iteration cap (ok == false); it must still return a lower bound of the depth, and at most a
  // quarter of the runs may do so.
  wedge::EpaSettings settings;
  settings.tolerance = N <= 4 ? 1e-3 : 1e-2;
  settings.max_iterations = 1000;
  wedge::EpaWorkspace<N> ws;
  int capped = 0;
  for (int t = 0; t < 20; ++t) {
    BallSupport<N> a, b;
    a.centre = oracle::gaussian<N>(rng);
    a.radius = 0.5 + u(rng);
    b.radius = 0.5 + u(rng);
    const Vec<N> axis = oracle::unit<N>(rng);
    const double d = (0.1 + 0.8 * u(rng)) * (a.radius + b.radius);
    b.centre = a.centre + d * axis;
    const auto g = wedge::gjk<N>(a, b, Vec<N>(b.centre - a.centre));
    REQUIRE(g.intersecting);
    const auto r = wedge::epa<N>(a, b, g.simplex, settings, ws);
    REQUIRE(finite(r));
    // The polytope lies inside A - B, so its facet distance is a lower bound of the depth (always), and
    // on convergence the support along the facet normal, within tol * scale of it (scale <= |c| + R <=
    // 2R), an upper bound: true depth - 2 tol R <= depth <= true depth (+ round-off).
    const double big_r = a.radius + b.radius, truth = big_r - d;
    CHECK(r.depth <= truth + 1e-12);
    CHECK(std::abs(r.normal.norm() - 1.0) <= 1e-12);
    CHECK((r.point_a - a.centre).norm() <= a.radius + 1e-12);
    CHECK((r.point_b - b.centre).norm() <= b.radius + 1e-12);
    if (!r.ok) {
      ++capped;
      continue;
    }
    CHECK((r.point_a - r.point_b - r.depth * r.normal).norm() <= 1e-9);
    CHECK(r.depth >= truth - 2.0 * settings.tolerance * big_r - 1e-12);
    // h(n) - depth_true = d (1 - cos angle) <= 2 tol R, so |n - axis| <= angle <= sqrt(4 tol R / d).
    CHECK((r.normal - axis).norm() <= std::sqrt(4.0 * settings.tolerance * big_r / d) + 1e-9);
  }
  CHECK(capped <= (N <= 4 ? 0 : 5));
}

TEMPLATE_TEST_CASE("epa: a ball overlapping a box, against the closest-point formula", "[epa]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(2100 + N);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  wedge::EpaSettings settings;
  settings.tolerance = 1e-6;  // measured: <= ~250 iterations up to 6D
  settings.max_iterations = 1000;
  wedge::EpaWorkspace<N> ws;
  int inside = 0, outside = 0, capped = 0;
  for (int t = 0; t < 30; ++t) {
    BoxSupport<N> box;
    box.rotation = oracle::rotation<N>(rng);
    box.centre = oracle::gaussian<N>(rng);
    for (int i = 0; i < N; ++i) box.half[i] = 0.3 + u(rng);
    BallSupport<N> ball;
    ball.radius = 0.3 + u(rng);
    // Ball centre in box coordinates: inside the box on even trials, outside (but within the radius)
    // on odd ones.
    Vec<N> local;
    for (int i = 0; i < N; ++i) local[i] = (2.0 * u(rng) - 1.0) * box.half[i];
    if (t % 2) {
      const double depth = (0.05 + 0.8 * u(rng)) * ball.radius;  // (one draw per statement)
      local += depth * oracle::unit<N>(rng).cwiseAbs().cwiseProduct(local.cwiseSign());
    }
    const Vec<N> clamped = local.cwiseMax(-box.half).cwiseMin(box.half);
    double truth;
    Vec<N> normal_local;
    if (clamped == local) {  // inside: out through the nearest face
      int m = 0;
      for (int i = 1; i < N; ++i)
        if (box.half[i] - std::abs(local[i]) < box.half[m] - std::abs(local[m])) m = i;
      truth = ball.radius + box.half[m] - std::abs(local[m]);
      normal_local = (local[m] >= 0 ? 1.0 : -1.0) * Vec<N>::Unit(m);
      ++inside;
    } else {
      const double dist = (local - clamped).norm();
      if (dist >= ball.radius - 1e-3) continue;
      truth = ball.radius - dist;
      normal_local = (local - clamped) / dist;
      ++outside;
    }
    ball.centre = box.centre + box.rotation * local;
    const Vec<N> normal = box.rotation * normal_local;
    const auto g = wedge::gjk<N>(box, ball, Vec<N>(ball.centre - box.centre));
    REQUIRE(g.intersecting);
    const auto r = wedge::epa<N>(box, ball, g.simplex, settings, ws);
    REQUIRE(finite(r));
    CHECK(r.depth <= truth + 1e-12);  // a lower bound, converged or not
    if (!r.ok) {  // stopped early (cap or round-off breakdown): allowed from 5D on, counted below
      ++capped;
      continue;
    }
    // Lower/upper bound as for two balls: scale <= |centre offset| + box diagonal + radius < 10 here.
    CHECK(r.depth <= truth + 1e-12);
    CHECK(r.depth >= truth - 1e-5);
    // Inside: the support of the rounded box grows at least linearly away from the face normal unless
    // another face is nearly as close; outside: the curved part bounds the angle by sqrt(2 tol / r).
    // 1e-2 separates right from wrong faces/directions without depending on near-ties.
    CHECK((r.normal - normal).norm() <= 1e-2);
    CHECK((r.point_a - r.point_b - r.depth * r.normal).norm() <= 1e-9);
  }
  CHECK(inside >= 5);
  CHECK(outside >= 5);
  CHECK(capped <= (N <= 4 ? 0 : 3));
}

TEMPLATE_TEST_CASE("epa: degenerate input gives sane answers and no NaN", "[epa]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(2300 + N);
  // Unit boxes touching face to face: depth 0 within round-off, a unit normal.
  BoxSupport<N> a, b;
  b.centre = 2.0 * Vec<N>::Unit(0);
  b.centre[1] = 0.5;
  {
    const auto g = wedge::gjk<N>(a, b, Vec<N>::Unit(0));
    if (g.intersecting) {
      const auto r = wedge::epa<N>(a, b, g.simplex);
      REQUIRE(finite(r));
      CHECK(r.depth <= 1e-12);
      CHECK(std::abs(r.normal.norm() - 1.0) <= 1e-12);
    }
  }
  // Identical boxes at the same place: A - B is the box of half extents 2h, depth 2 min h along the
  // shortest axis (unique here), either sign.
  BoxSupport<N> c;
  c.rotation = oracle::rotation<N>(rng);
  c.centre = oracle::gaussian<N>(rng);
  for (int i = 0; i < N; ++i) c.half[i] = 0.3 + 0.1 * i;
  {
    const auto g = wedge::gjk<N>(c, c, Vec<N>::Zero());
    REQUIRE(g.intersecting);
    const auto r = wedge::epa<N>(c, c, g.simplex);
    REQUIRE(finite(r));
    CHECK(r.ok);
    CHECK(r.depth == Approx(0.6).epsilon(1e-12));
    CHECK(std::abs(r.normal.dot(c.rotation.col(0))) == Approx(1.0).epsilon(1e-12));
  }
  // A point inside the unit box: depth = distance to the nearest face, normal out through it.
  BoxSupport<N> point;
  point.half = Vec<N>::Zero();
  point.centre = Vec<N>::Constant(0.1);
  point.centre[N - 1] = -0.7;
  {
    const auto g = wedge::gjk<N>(a, point, Vec<N>::Ones());
    REQUIRE(g.intersecting);
    const auto r = wedge::epa<N>(a, point, g.simplex);
    REQUIRE(finite(r));
    CHECK(r.ok);
    CHECK(r.depth == Approx(0.3).epsilon(1e-12));
    CHECK((r.normal + Vec<N>::Unit(N - 1)).norm() <= 1e-12);
    CHECK((r.point_b - point.centre).norm() <= 1e-15);  // a convex combination of copies of it
  }
  // A point against itself: A - B = {0}, depth 0 and some unit normal.
  {
    const auto g = wedge::gjk<N>(point, point, Vec<N>::Zero());
    REQUIRE(g.intersecting);
    const auto r = wedge::epa<N>(point, point, g.simplex);
    REQUIRE(finite(r));
    CHECK(r.depth == 0.0);
    CHECK(std::abs(r.normal.norm() - 1.0) <= 1e-12);
  }
  // A segment of half length 3 along e0 through the unit box, offset 0.3 along e1: A - B is the box of
  // half extents (4, 1, .., 1) centred at -offset, depth 0.7 along +e1.
  BoxSupport<N> segment;
  segment.half = Vec<N>::Zero();
  segment.half[0] = 3.0;
  segment.centre = 0.3 * Vec<N>::Unit(1);
  {
    const auto g = wedge::gjk<N>(a, segment, Vec<N>::Unit(1));
    REQUIRE(g.intersecting);
    const auto r = wedge::epa<N>(a, segment, g.simplex);
    REQUIRE(finite(r));
    CHECK(r.ok);
    CHECK(r.depth == Approx(0.7).epsilon(1e-12));
    CHECK((r.normal - Vec<N>::Unit(1)).norm() <= 1e-12);
  }
  // Two segments crossing at the origin along e0 and e1. From 3D on A - B is a flat square through the
  // origin: depth 0, normal orthogonal to it. In 2D it is the full square [-1, 1]^2: depth 1 (tie
  // between four facets).
  BoxSupport<N> s0, s1;
  s0.half = Vec<N>::Zero();
  s1.half = Vec<N>::Zero();
  s0.half[0] = 1.0;
  s1.half[1] = 1.0;
  {
    const auto g = wedge::gjk<N>(s0, s1, Vec<N>::Ones());
    REQUIRE(g.intersecting);
    const auto r = wedge::epa<N>(s0, s1, g.simplex);
    REQUIRE(finite(r));
    CHECK(r.ok);
    CHECK(std::abs(r.normal.norm() - 1.0) <= 1e-12);
    if (N == 2) {
      CHECK(r.depth == Approx(1.0).epsilon(1e-12));
    } else {
      CHECK(r.depth <= 1e-12);
      CHECK(std::abs(r.normal[0]) <= 1e-12);
      CHECK(std::abs(r.normal[1]) <= 1e-12);
    }
  }
}

TEMPLATE_TEST_CASE("epa: a reused workspace gives bit-identical results", "[epa]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(2500 + N);
  wedge::EpaWorkspace<N> ws;
  for (int t = 0; t < 10; ++t) {
    const auto a = oracle::random_polytope<N>(rng, N + 4, Vec<N>::Zero(), 1.0);
    const auto b = oracle::random_polytope<N>(rng, N + 4, Vec<N>(0.3 * oracle::unit<N>(rng)), 1.0);
    const auto g = wedge::gjk<N>(a, b, Vec<N>::Ones());
    if (!g.intersecting) continue;
    const auto fresh = wedge::epa<N>(a, b, g.simplex);
    const auto reused = wedge::epa<N>(a, b, g.simplex, {}, ws);
    CHECK(fresh.depth == reused.depth);
    CHECK(fresh.normal == reused.normal);
    CHECK(fresh.point_a == reused.point_a);
    CHECK(fresh.iterations == reused.iterations);
  }
}
