// GJK (wedge/collision/detail/gjk.hpp) for n = 2..6 against independent truth:
//   - random convex polytopes: the distance from the origin to the Qhull hull of the Minkowski difference
//     {a_i - b_j}, by brute-force projection onto every face (tests/support/convex_oracle.hpp), and the
//     overlap status from the hull's facet offsets;
//   - boxes (support c + R (h .* sign(R^T d))) against the hull of their corner differences;
//   - balls: the analytic distance |c_b - c_a| - r_a - r_b along the centre line;
//   - degenerate input: touching faces, identical shapes, points and segments, a zero initial direction.
// Tolerances (all relative to the size of A - B, which is O(1) here):
//   distance 1e-9 relative + 1e-12: GJK stops when its upper and lower bounds agree to 1e-10 relative
//     (GjkSettings::tolerance), the oracle's KKT projection is exact to ~1e-14 (well-conditioned random
//     faces; the error in the distance is second order in the error of lambda); polytopes usually stop
//     earlier and exactly, when the support repeats a vertex;
//   witnesses 1e-9: they are the same barycentric combination as v, in A and B up to round-off;
//   cases within 1e-6 of touching are left out of the status checks (the oracle's own round-off there
//     is ~1e-15, the margin only keeps the classification unambiguous), and counted so that the tests
//     still cover both outcomes.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "wedge/collision/detail/gjk.hpp"
#include "wedge/hull.hpp"
#include "convex_oracle.hpp"
#include "test_util.hpp"

namespace {

using oracle::BallSupport;
using oracle::BoxSupport;
using oracle::PointsSupport;
using wedge::Vec;

constexpr double kDist = 1e-9;      // relative distance accuracy (see above)
constexpr double kWitness = 1e-9;   // witness consistency and membership
constexpr double kAmbiguous = 1e-6;  // closer than this to touching: status not checked

template <int N>
bool finite(const wedge::GjkResult<N>& r) {
  return std::isfinite(r.distance) && r.point_a.allFinite() && r.point_b.allFinite();
}

// Checks one pair against the Minkowski hull; returns +1 separated, -1 overlapping, 0 ambiguous.
template <int N, class SA, class SB>
int check_against_hull(const SA& sa, const SB& sb, const std::vector<Vec<N>>& pa, const std::vector<Vec<N>>& pb,
                       const Vec<N>& dir, bool check_distance) {
  const auto hull = wedge::convex_hull<N>(oracle::minkowski_difference<N>(pa, pb));
  const auto hull_a = wedge::convex_hull<N>(pa);
  const auto hull_b = wedge::convex_hull<N>(pb);
  const double inside = oracle::min_offset<N>(hull);  // > 0 iff the origin is interior
  const auto r = wedge::gjk<N>(sa, sb, dir);
  REQUIRE(finite(r));
  CHECK(r.distance >= 0.0);
  CHECK((r.point_a - r.point_b).norm() == Approx(r.distance).margin(kWitness));
  CHECK(oracle::hull_excess<N>(hull_a, r.point_a) <= kWitness);
  CHECK(oracle::hull_excess<N>(hull_b, r.point_b) <= kWitness);
  if (inside > kAmbiguous) {
    CHECK(r.intersecting);
    CHECK(r.distance == 0.0);
    CHECK((r.point_a - r.point_b).norm() <= kWitness);  // a common point
    return -1;
  }
  if (inside < 0.0 && oracle::hull_excess<N>(hull, Vec<N>::Zero()) > kAmbiguous) {
    CHECK_FALSE(r.intersecting);
    if (check_distance) {
      const double d = oracle::brute_distance<N>(hull);
      CHECK(std::abs(r.distance - d) <= kDist * d + 1e-12);
    }
    return 1;
  }
  return 0;
}

}  // namespace

TEMPLATE_TEST_CASE("gjk: random polytopes against the Minkowski hull (distance, witnesses, status)", "[gjk]", D2, D3,
                   D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(700 + N);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int trials = N <= 4 ? 60 : 16;
  int separated = 0, overlapping = 0;
  for (int t = 0; t < trials; ++t) {
    // Centres 0.2-2 m apart, and in every other pair of runs under 0.3 m, so that both outcomes come up
    // in every dimension (thin random polytopes in 5D and 6D rarely meet otherwise). One draw per
    // statement: the operands of * are evaluated in an order each compiler picks.
    const double distance = t % 4 < 2 ? 0.2 + 1.8 * u(rng) : 0.3 * u(rng);
    const Vec<N> ca = Vec<N>::Zero(), cb = distance * oracle::unit<N>(rng);
    const auto a = oracle::random_polytope<N>(rng, N + 1 + t % 5, ca, 1.0);
    const auto b = oracle::random_polytope<N>(rng, N + 1 + (t / 5) % 4, cb, 0.3 + 1.2 * u(rng));
    // Half the runs start from the centre line, half from an arbitrary direction.
    const Vec<N> dir = t % 2 ? Vec<N>(cb - ca) : oracle::gaussian<N>(rng);
    const int status = check_against_hull<N>(a, b, a.points, b.points, dir, true);
    separated += status > 0;
    overlapping += status < 0;
  }
  INFO("separated " << separated << ", overlapping " << overlapping);
  CHECK(separated >= trials / 8);  // both outcomes covered
  CHECK(overlapping >= trials / 8);
}

TEMPLATE_TEST_CASE("gjk: rotated boxes against the hull of their corner differences", "[gjk]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(900 + N);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // 5D: fewer trials (the hull has 1024 points). 6D: the 4096-point hull is too slow, the status comes
  // from the exact separating-axis test instead (oracle::box_sat), whose separation is also a lower
  // bound of the distance; the 6D distance itself is covered by the polytope test.
  const int trials = N <= 4 ? 40 : (N == 5 ? 12 : 30);
  int separated = 0, overlapping = 0;
  for (int t = 0; t < trials; ++t) {
    const BoxSupport<N> a = oracle::random_box<N>(rng, Vec<N>::Zero());
    const double distance = 0.5 + 2.5 * u(rng);  // (one draw per statement)
    const BoxSupport<N> b = oracle::random_box<N>(rng, Vec<N>(distance * oracle::unit<N>(rng)));
    int status = 0;
    if constexpr (N <= 5) {
      status = check_against_hull<N>(a, b, a.corners(), b.corners(), Vec<N>(b.centre - a.centre), true);
    } else {
      const double inside = oracle::box_sat<N>(a, b);
      const auto r = wedge::gjk<N>(a, b, Vec<N>(b.centre - a.centre));
      REQUIRE(finite(r));
      if (inside > kAmbiguous) {
        CHECK(r.intersecting);
        status = -1;
      } else if (inside < -kAmbiguous) {
        CHECK_FALSE(r.intersecting);
        CHECK(r.distance >= -inside - kWitness);
        CHECK((r.point_a - r.point_b).norm() == Approx(r.distance).margin(kWitness));
        status = 1;
      }
    }
    separated += status > 0;
    overlapping += status < 0;
  }
  INFO("separated " << separated << ", overlapping " << overlapping);
  CHECK(separated >= trials / 5);
  CHECK(overlapping >= trials / 5);
}

TEMPLATE_TEST_CASE("gjk: balls at the analytic distance along the centre line", "[gjk]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(1100 + N);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int t = 0; t < 50; ++t) {
    BallSupport<N> a, b;
    a.centre = oracle::gaussian<N>(rng);
    a.radius = 0.2 + u(rng);
    b.radius = 0.2 + u(rng);
    const double gap = t % 2 ? 1e-3 + 2.0 * u(rng) : -1e-3 - 0.9 * std::min(a.radius, b.radius) * u(rng);
    const Vec<N> axis = oracle::unit<N>(rng);
    b.centre = a.centre + (a.radius + b.radius + gap) * axis;
    const auto r = wedge::gjk<N>(a, b, oracle::gaussian<N>(rng));
    REQUIRE(finite(r));
    if (gap < 0.0) {
      CHECK(r.intersecting);
      continue;
    }
    CHECK_FALSE(r.intersecting);
    // 1e-9 relative: GJK's bound gap (1e-10 relative), as for polytopes.
    CHECK(std::abs(r.distance - gap) <= kDist * gap + 1e-12);
    // The witnesses are points of the balls at |v| within delta = 1e-10 |v| of the true distance d;
    // such points of the Minkowski ball (radius R) lie within an angle sqrt(2 delta R / (d (d + R)))
    // <= sqrt(2e-10 R / (d + R)) < 1.5e-5 of the centre line: 3e-5 on the unit normal.
    const Vec<N> normal = (r.point_b - r.point_a) / r.distance;
    CHECK((normal - axis).norm() <= 3e-5);
    CHECK((r.point_a - a.centre).norm() <= a.radius + kWitness);
    CHECK((r.point_b - b.centre).norm() <= b.radius + kWitness);
  }
}

TEMPLATE_TEST_CASE("gjk: degenerate input gives sane answers and no NaN", "[gjk]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  // Unit boxes touching face to face (exactly representable): distance 0 within round-off, either
  // reported as touching (intersecting) or as a distance <= 1e-12.
  BoxSupport<N> a, b;
  b.centre = 2.0 * Vec<N>::Unit(0);
  b.centre[1] = 0.5;
  for (const Vec<N>& dir : {Vec<N>(Vec<N>::Unit(0)), Vec<N>(Vec<N>::Ones()), Vec<N>(Vec<N>::Zero())}) {
    const auto r = wedge::gjk<N>(a, b, dir);
    REQUIRE(finite(r));
    CHECK(r.distance <= 1e-12);
    CHECK(r.point_a[0] == Approx(1.0).margin(1e-12));
    CHECK(r.point_b[0] == Approx(1.0).margin(1e-12));
  }
  // Identical boxes at the same place, in an arbitrary pose.
  std::mt19937_64 rng(1300 + N);
  BoxSupport<N> c;
  c.rotation = oracle::rotation<N>(rng);
  c.centre = oracle::gaussian<N>(rng);
  for (int i = 0; i < N; ++i) c.half[i] = 0.3 + 0.1 * i;
  {
    const auto r = wedge::gjk<N>(c, c, Vec<N>::Zero());
    REQUIRE(finite(r));
    CHECK(r.intersecting);
    CHECK(r.distance == 0.0);
  }
  // A point (a box with zero extent) against a box: outside, the distance to the box (axis-aligned
  // box, so the clamp formula is exact); inside, intersecting.
  BoxSupport<N> point;
  point.half = Vec<N>::Zero();
  point.centre = Vec<N>::Constant(1.5);  // 0.5 from each face of the unit box: distance 0.5 sqrt(N)
  {
    const auto r = wedge::gjk<N>(a, point, Vec<N>::Ones());
    REQUIRE(finite(r));
    CHECK_FALSE(r.intersecting);
    CHECK(r.distance == Approx(0.5 * std::sqrt(double(N))).epsilon(1e-12));
    CHECK((r.point_a - Vec<N>::Ones()).norm() <= 1e-12);
    CHECK((r.point_b - point.centre).norm() == 0.0);
  }
  point.centre = Vec<N>::Constant(0.25);
  CHECK(wedge::gjk<N>(a, point, Vec<N>::Ones()).intersecting);
  // Two points: the same (intersecting), or apart (their distance).
  BoxSupport<N> other = point;
  CHECK(wedge::gjk<N>(point, other, Vec<N>::Zero()).intersecting);
  other.centre[N - 1] += 0.75;
  {
    const auto r = wedge::gjk<N>(point, other, Vec<N>::Unit(0));
    REQUIRE(finite(r));
    CHECK(r.distance == Approx(0.75).epsilon(1e-14));
  }
  // A segment (one nonzero extent) crossing a box, and passing beside it at distance 0.25.
  BoxSupport<N> segment;
  segment.half = Vec<N>::Zero();
  segment.half[0] = 3.0;
  segment.rotation = oracle::rotation<N>(rng);
  CHECK(wedge::gjk<N>(a, segment, Vec<N>::Ones()).intersecting);
  segment.rotation.setIdentity();
  segment.centre = Vec<N>::Zero();
  segment.centre[1] = 1.25;
  {
    const auto r = wedge::gjk<N>(a, segment, Vec<N>::Unit(1));
    REQUIRE(finite(r));
    CHECK_FALSE(r.intersecting);
    CHECK(r.distance == Approx(0.25).epsilon(1e-12));
  }
}
