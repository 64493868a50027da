// The collision oracles (tests/support/oracles.hpp) against cases whose answers are known in closed form,
// before the collision tests trust them: axis-aligned boxes (exact L-inf and Euclidean gaps, overlaps
// and normals), a rotated square whose corner pokes into a face, points against the corner simplex
// (closest point on a vertex, an edge, a face, the slanted facet, inside), the optimality certificate of
// every brute-force closest point, and Bullet on axis-aligned 3D boxes.
//
// Tolerances: the inputs are exact small decimals; the oracles do a few dozen flops per answer (LP
// pivots, Qhull's hyperplanes, one least-squares projection), so round-off stays below 1e-13 for
// coordinates of order 1. 1e-9 is used throughout, comfortably above round-off and far below any
// real error (the smallest quantity tested is 0.1). Bullet's GJK distance is exact to round-off for
// separated boxes (checked to 1e-9); its EPA depth is approximate (see the Bullet case).
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "oracles.hpp"

namespace {

namespace oracle = wedge::oracle;
using oracle::Point;
using oracle::Points;

Point vec(std::initializer_list<double> xs) {
  Point p(Eigen::Index(xs.size()));
  int i = 0;
  for (double x : xs) p[i++] = x;
  return p;
}

Points axis_box(const Point& centre, const Point& half) {
  return oracle::box_vertices(half, centre, Eigen::MatrixXd::Identity(centre.size(), centre.size()));
}

// The corner simplex {0, e_0, .., e_(n-1)}.
Points corner_simplex(int n) {
  Points v{Point::Zero(n)};
  for (int k = 0; k < n; ++k) v.push_back(Point::Unit(n, k));
  return v;
}

bool has_normal(const std::vector<Point>& normals, const Point& want, double tol) {
  for (const Point& n : normals)
    if ((n - want).norm() <= tol) return true;
  return false;
}

}  // namespace

TEST_CASE("LP separation: the L-inf distance between axis-aligned boxes, n = 2..6", "[oracles]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(-1.0, 1.0), size(0.1, 1.0);
  int overlapping = 0, separated = 0;
  for (int n = 2; n <= 6; ++n)
    for (int trial = 0; trial < 200; ++trial) {
      Point ca(n), cb(n), ha(n), hb(n), gap(n);
      for (int k = 0; k < n; ++k) {
        ca[k] = pos(rng), cb[k] = pos(rng), ha[k] = size(rng), hb[k] = size(rng);
        gap[k] = std::max(0.0, std::abs(ca[k] - cb[k]) - ha[k] - hb[k]);
      }
      const double want = gap.lpNorm<Eigen::Infinity>();
      const Points a = axis_box(ca, ha), b = axis_box(cb, hb);
      const oracle::LpSeparation lp = oracle::lp_separation(a, b);
      REQUIRE(lp.optimal);
      CHECK(std::abs(lp.distance - want) <= 1e-9);
      // The witnesses lie in their boxes and realise the distance.
      CHECK(((lp.point_a - ca).cwiseAbs() - ha).maxCoeff() <= 1e-9);
      CHECK(((lp.point_b - cb).cwiseAbs() - hb).maxCoeff() <= 1e-9);
      CHECK(std::abs((lp.point_a - lp.point_b).lpNorm<Eigen::Infinity>() - want) <= 1e-9);
      (want == 0.0 ? overlapping : separated) += 1;
    }
  CHECK(overlapping > 100);  // both kinds are exercised
  CHECK(separated > 100);
}

TEST_CASE("LP separation: touching and just-separated boxes", "[oracles]") {
  const Point half = Point::Constant(4, 0.5);
  // Sharing the face x = 0.5 exactly.
  const oracle::LpSeparation touching =
      oracle::lp_separation(axis_box(Point::Zero(4), half), axis_box(vec({1.0, 0.3, -0.2, 0.1}), half));
  REQUIRE(touching.optimal);
  CHECK(touching.distance <= 1e-12);
  // 2^-30 = 9.3e-10 apart along x: resolved to round-off, 1e-12 (measured 1.1e-12 worst over 10,000
  // random box pairs of this size, see oracles.hpp).
  const double gap = std::ldexp(1.0, -30);
  const oracle::LpSeparation apart =
      oracle::lp_separation(axis_box(Point::Zero(4), half), axis_box(vec({1.0 + gap, 0.3, -0.2, 0.1}), half));
  REQUIRE(apart.optimal);
  CHECK(std::abs(apart.distance - gap) <= 1e-12);
  CHECK(apart.feasibility_tolerance == 1e-12);
}

TEST_CASE("LP separation: rotated boxes a hair apart stay within the Euclidean bounds, n = 3..5", "[oracles]") {
  // B is A moved by (1 + g) along A's first axis u: the gap is g along u, so the L-inf distance t
  // satisfies g / sqrt(n) <= t <= g. Down to g = 2^-28 = 3.7e-9 (the band stated in oracles.hpp).
  std::mt19937_64 rng(13);
  for (int n = 3; n <= 5; ++n)
    for (int e = 10; e <= 28; e += 2)
      for (int trial = 0; trial < 10; ++trial) {
        const Eigen::MatrixXd rot = oracle::random_rotation(n, rng);
        const Point half = Point::Constant(n, 0.5);
        const double g = std::ldexp(1.0, -e);
        const oracle::LpSeparation lp = oracle::lp_separation(oracle::box_vertices(half, Point::Zero(n), rot),
                                                              oracle::box_vertices(half, rot.col(0) * (1.0 + g), rot));
        INFO("n = " << n << ", gap 2^-" << e);
        REQUIRE(lp.optimal);
        CHECK(lp.distance <= g * (1 + 1e-6));
        CHECK(lp.distance >= g / std::sqrt(double(n)) * (1 - 1e-6));
      }
}

TEST_CASE("Minkowski MTD: axis-aligned boxes have the known depth, normal and distance", "[oracles]") {
  for (int n = 2; n <= 5; ++n) {
    INFO("n = " << n);
    const Point half = Point::Ones(n);
    const Points a = axis_box(Point::Zero(n), half);
    Point offset = Point::Constant(n, 0.1);
    offset[0] = 1.5;  // B to the right of A, overlapping by 2 - 1.5 = 0.5 along x (1.9 along the rest)
    oracle::MinkowskiMtd m = oracle::minkowski_mtd(a, axis_box(offset, half));
    CHECK(m.intersecting);
    CHECK(std::abs(m.depth - 0.5) <= 1e-9);
    CHECK((m.normal - Point::Unit(n, 0)).norm() <= 1e-9);  // from A to B: +x
    CHECK(m.tied_normals.size() == 1);
    // B to the left: normal -x.
    offset[0] = -1.5;
    m = oracle::minkowski_mtd(a, axis_box(offset, half));
    CHECK(std::abs(m.depth - 0.5) <= 1e-9);
    CHECK((m.normal + Point::Unit(n, 0)).norm() <= 1e-9);
    // B above along the last axis, the smallest overlap there (0.3).
    offset = Point::Constant(n, -0.2);
    offset[n - 1] = 1.7;
    m = oracle::minkowski_mtd(a, axis_box(offset, half));
    CHECK(std::abs(m.depth - 0.3) <= 1e-9);
    CHECK((m.normal - Point::Unit(n, n - 1)).norm() <= 1e-9);

    // Separated along x by 1: depth -1, normal +x.
    offset = Point::Constant(n, 0.2);
    offset[0] = 3.0;
    m = oracle::minkowski_mtd(a, axis_box(offset, half));
    CHECK_FALSE(m.intersecting);
    CHECK(std::abs(m.depth + 1.0) <= 1e-9);
    CHECK((m.normal - Point::Unit(n, 0)).norm() <= 1e-9);
    // Separated diagonally, gaps (1, 1.5, 0, ..): the closest points are edge to edge (or corner to
    // corner in 2D); distance sqrt(1 + 2.25), normal along the gap.
    offset = Point::Zero(n);
    offset[0] = 3.0;
    offset[1] = 3.5;
    m = oracle::minkowski_mtd(a, axis_box(offset, half));
    Point gap = Point::Zero(n);
    gap[0] = 1.0;
    gap[1] = 1.5;
    CHECK(std::abs(m.depth + gap.norm()) <= 1e-9);
    CHECK((m.normal - gap.normalized()).norm() <= 1e-9);

    // Concentric equal boxes: depth 2 along any of the 2n axis directions, all of them tied.
    m = oracle::minkowski_mtd(a, a);
    CHECK(std::abs(m.depth - 2.0) <= 1e-9);
    CHECK(m.tied_normals.size() == std::size_t(2 * n));
    for (int k = 0; k < n; ++k) {
      CHECK(has_normal(m.tied_normals, Point::Unit(n, k), 1e-9));
      CHECK(has_normal(m.tied_normals, -Point::Unit(n, k), 1e-9));
    }
  }
}

TEST_CASE("Minkowski MTD: a rotated square's corner poking 0.3 into a face, extruded to n = 2..5", "[oracles]") {
  // B is the unit-half-size square turned 45 deg in the xy plane, its left corner at x = 0.7, inside A's
  // face x = 1 by 0.3. Other candidate directions need more: along B's face normal (1, 1)/sqrt2 the
  // overlap is sqrt2 - (2.1142/sqrt2 - 1) = 0.92; along y or the extra axes 2 or more.
  for (int n = 2; n <= 5; ++n) {
    INFO("n = " << n);
    Eigen::MatrixXd rot = Eigen::MatrixXd::Identity(n, n);
    const double c = std::cos(M_PI / 4), s = std::sin(M_PI / 4);
    rot(0, 0) = c, rot(0, 1) = -s, rot(1, 0) = s, rot(1, 1) = c;
    Point pos = Point::Zero(n);
    pos[0] = 0.7 + std::sqrt(2.0);
    const Points a = axis_box(Point::Zero(n), Point::Ones(n));
    const Points b = oracle::box_vertices(Point::Ones(n), pos, rot);
    const oracle::MinkowskiMtd m = oracle::minkowski_mtd(a, b);
    CHECK(m.intersecting);
    CHECK(std::abs(m.depth - 0.3) <= 1e-9);
    CHECK((m.normal - Point::Unit(n, 0)).norm() <= 1e-9);
    // Moving B by depth * normal leaves the two touching: the LP distance is then 0 and any further
    // step separates them.
    Points moved = b;
    for (Point& p : moved) p += (m.depth + 1e-6) * m.normal;
    CHECK(oracle::lp_separation(a, moved).distance >= 0.9e-6);
    for (Point& p : moved) p -= 2e-6 * m.normal;
    CHECK(oracle::lp_separation(a, moved).distance <= 1e-9);
  }
}

TEST_CASE("Brute-force closest point: the corner simplex, on a vertex, an edge, a face, the slanted facet, inside",
          "[oracles]") {
  const Points t3 = corner_simplex(3);
  struct Case {
    Point p, point;
    double distance;
    int face_dim;
  };
  const double third = 1.0 / 3.0;
  const Case cases[] = {
      {vec({-1, -1, -1}), vec({0, 0, 0}), std::sqrt(3.0), 0},         // the origin vertex
      {vec({2, -1, -1}), vec({1, 0, 0}), std::sqrt(3.0), 0},          // vertex e0
      {vec({0.5, -1, -1}), vec({0.5, 0, 0}), std::sqrt(2.0), 1},      // edge 0-e0
      {vec({1, 1, -1}), vec({0.5, 0.5, 0}), std::sqrt(1.5), 1},        // edge e0-e1
      {vec({0.3, 0.3, -1}), vec({0.3, 0.3, 0}), 1.0, 2},               // face z = 0
      {vec({1, 1, 1}), vec({third, third, third}), 2.0 / std::sqrt(3.0), 2},  // facet x + y + z = 1
  };
  for (const Case& c : cases) {
    INFO("p = " << c.p.transpose());
    const oracle::ClosestPoint r = oracle::closest_point_brute_force(t3, c.p);
    CHECK_FALSE(r.inside);
    CHECK((r.point - c.point).norm() <= 1e-9);
    CHECK(std::abs(r.distance - c.distance) <= 1e-9);
    CHECK(r.face_dim == c.face_dim);
    CHECK(r.face.size() == std::size_t(c.face_dim + 1));
  }
  // Inside: distance 0; the boundary is nearest across x = 0 (0.1 away; the slanted facet is
  // (1 - 0.6)/sqrt3 = 0.23 away).
  const oracle::ClosestPoint in = oracle::closest_point_brute_force(t3, vec({0.1, 0.2, 0.3}));
  CHECK(in.inside);
  CHECK(in.distance == 0.0);
  CHECK(in.face_dim == 3);
  CHECK(std::abs(in.boundary_distance - 0.1) <= 1e-9);
  CHECK((in.boundary_point - vec({0, 0.2, 0.3})).norm() <= 1e-9);
  CHECK((in.boundary_normal - vec({-1, 0, 0})).norm() <= 1e-9);

  // 5D: the 2-face {0, e0, e1} and the 4-facet sum x = 1.
  const Points t5 = corner_simplex(5);
  oracle::ClosestPoint r = oracle::closest_point_brute_force(t5, vec({0.2, 0.3, -1, -2, -0.5}));
  CHECK((r.point - vec({0.2, 0.3, 0, 0, 0})).norm() <= 1e-9);
  CHECK(r.face_dim == 2);
  r = oracle::closest_point_brute_force(t5, Point::Ones(5));
  CHECK((r.point - Point::Constant(5, 0.2)).norm() <= 1e-9);
  CHECK(std::abs(r.distance - 4.0 / std::sqrt(5.0)) <= 1e-9);
  CHECK(r.face_dim == 4);
}

TEST_CASE("Brute-force closest point: every answer carries its optimality certificate, n = 2..6", "[oracles]") {
  // q is the closest point of a convex set P to p iff (p - q) . (v - q) <= 0 for every v in P, i.e. for
  // every vertex. A missed face would show as a vertex v with (p - q) . (v - q) > 0. The L-inf distance
  // of the LP bounds the Euclidean one: t <= d <= sqrt(n) t.
  std::mt19937_64 rng(11);
  for (int n = 2; n <= 6; ++n)
    for (int trial = 0; trial < 30; ++trial) {
      const Points v = oracle::random_points_in_ball(n, n + 1 + trial % 12, 1.0, Point::Zero(n), rng);
      const Point p = oracle::random_points_in_ball(n, 1, 2.0, Point::Zero(n), rng)[0];
      const oracle::ClosestPoint r = oracle::closest_point_brute_force(v, p);
      INFO("n = " << n << ", trial " << trial);
      for (const Point& x : v) CHECK((p - r.point).dot(x - r.point) <= 1e-9);
      CHECK(std::abs((p - r.point).norm() - r.distance) <= 1e-12);
      const double t = oracle::lp_separation(v, {p}).distance;
      CHECK(t <= r.distance + 1e-9);
      CHECK(r.distance <= std::sqrt(double(n)) * t + 1e-9);
      if (r.inside) CHECK(t <= 1e-9);
    }
}

TEST_CASE("LP and Minkowski difference agree on intersection of random polytopes, n = 3..5", "[oracles]") {
  std::mt19937_64 rng(3);
  int agree = 0, both_ways[2] = {0, 0};
  for (int n = 3; n <= 5; ++n)
    for (int trial = 0; trial < 40; ++trial) {
      const Point centre = oracle::random_points_in_ball(n, 1, 1.3, Point::Zero(n), rng)[0];
      const Points a = oracle::random_points_in_ball(n, n + 4, 1.0, Point::Zero(n), rng);
      const Points b = oracle::random_points_in_ball(n, n + 4, 1.0, centre, rng);
      const oracle::LpSeparation lp = oracle::lp_separation(a, b);
      const oracle::MinkowskiMtd m = oracle::minkowski_mtd(a, b);
      REQUIRE(lp.optimal);
      if (std::abs(m.depth) < 1e-9) continue;  // touching to round-off: either answer is right
      CHECK((lp.distance <= 1e-9) == m.intersecting);
      if (!m.intersecting) {
        // Euclidean and L-inf distances bound each other.
        CHECK(lp.distance <= -m.depth + 1e-9);
        CHECK(-m.depth <= std::sqrt(double(n)) * lp.distance + 1e-9);
      }
      ++agree;
      both_ways[m.intersecting ? 1 : 0] += 1;
    }
  CHECK(agree >= 115);
  CHECK(both_ways[0] > 20);
  CHECK(both_ways[1] > 20);
}

TEST_CASE("Bullet box-box: axis-aligned 3D boxes give the analytic overlap, normal and distance", "[oracles]") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> pos(-1.5, 1.5), size(0.2, 1.0);
  const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
  int overlapping = 0, separated = 0;
  for (int trial = 0; trial < 400; ++trial) {
    Eigen::Vector3d ca, cb, ha, hb, overlap;
    for (int k = 0; k < 3; ++k) {
      ca[k] = pos(rng), cb[k] = pos(rng), ha[k] = size(rng), hb[k] = size(rng);
      overlap[k] = ha[k] + hb[k] - std::abs(ca[k] - cb[k]);  // < 0: a gap
    }
    const oracle::BulletBoxBox r = oracle::bullet_box_box(ha, ca, id, hb, cb, id);
    REQUIRE(r.gjk_ok);
    INFO("trial " << trial << ", overlap " << overlap.transpose());
    if (overlap.minCoeff() > 1e-6) {
      ++overlapping;
      int k;
      const double depth = overlap.minCoeff(&k);
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      normal[k] = cb[k] >= ca[k] ? 1.0 : -1.0;
      REQUIRE(r.intersecting);
      CHECK(std::abs(r.depth - depth) <= 1e-9);
      CHECK((r.normal - normal).norm() <= 1e-9);
      REQUIRE(!r.contact_points.empty());
      for (std::size_t i = 0; i < r.contact_points.size(); ++i) {
        // Pairs of points on B and on A, the one on A deeper along the normal by that point's depth.
        const Eigen::Vector3d& pb = r.contact_points[i];
        const Eigen::Vector3d& pa = r.contact_points_on_a[i];
        CHECK(((pb - cb).cwiseAbs() - hb).maxCoeff() <= 1e-9);
        CHECK(((pa - ca).cwiseAbs() - ha).maxCoeff() <= 1e-9);
        CHECK(r.contact_depths[i] <= depth + 1e-9);
        CHECK(r.contact_depths[i] >= -1e-9);
      }
      // EPA is approximate: measured up to 2.5% here, so 5% (its normal may then pick another axis).
      CHECK(std::abs(-r.gjk_distance - depth) <= 0.05 * depth);
    } else if (overlap.minCoeff() < -1e-6) {
      ++separated;
      CHECK_FALSE(r.intersecting);
      Eigen::Vector3d gap;  // from A towards B, per axis
      for (int k = 0; k < 3; ++k) gap[k] = std::max(0.0, -overlap[k]) * (cb[k] >= ca[k] ? 1.0 : -1.0);
      CHECK(std::abs(r.gjk_distance - gap.norm()) <= 1e-9);
      CHECK((r.gjk_normal - gap.normalized()).norm() <= 1e-9);
    }
  }
  CHECK(overlapping > 50);
  CHECK(separated > 50);
}

TEST_CASE("Bullet box-box and the Minkowski difference agree on rotated 3D boxes", "[oracles]") {
  // dBoxBox tests the 15 separating axes, which is exact for box pairs in 3D, so the intersection
  // verdicts agree away from touching. It prefers a face axis to an edge-edge axis unless the latter is
  // 5% shallower (fudge_factor 1.05 in btBoxBoxDetector.cpp), so its depth lies in [1, 1.05] x the exact
  // minimum. (Its depth is the deepest clipped contact point's, which can differ from the boxes' overlap
  // along its normal: measured -5e-5 .. +0.035 here; so that is not asserted.)
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> pos(-1.2, 1.2), size(0.2, 1.0);
  int intersecting = 0, exact_normal = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Eigen::Vector3d ca, cb, ha, hb;
    for (int k = 0; k < 3; ++k) ca[k] = pos(rng), cb[k] = pos(rng), ha[k] = size(rng), hb[k] = size(rng);
    const Eigen::Matrix3d ra = oracle::random_rotation(3, rng), rb = oracle::random_rotation(3, rng);
    const Points a = oracle::box_vertices(ha, ca, ra), b = oracle::box_vertices(hb, cb, rb);
    const oracle::BulletBoxBox r = oracle::bullet_box_box(ha, ca, ra, hb, cb, rb);
    const oracle::MinkowskiMtd m = oracle::minkowski_mtd(a, b);
    INFO("trial " << trial << ", exact depth " << m.depth);
    if (std::abs(m.depth) < 1e-9) continue;
    CHECK(r.intersecting == m.intersecting);
    if (!m.intersecting || !r.intersecting) continue;
    ++intersecting;
    CHECK(r.depth >= m.depth - 1e-9);
    CHECK(r.depth <= 1.05 * m.depth + 1e-9);
    if ((r.normal - Eigen::Vector3d(m.normal)).norm() <= 1e-9) ++exact_normal;
  }
  CHECK(intersecting > 100);
  CHECK(exact_normal > intersecting / 2);  // mostly the very same axis
}

TEST_CASE("Directional overlap: axis-aligned boxes along the axes and a diagonal", "[oracles]") {
  const Points a = axis_box(vec({0, 0, 0}), vec({1, 1, 1}));
  const Points b = axis_box(vec({1.5, 0.2, 0}), vec({1, 1, 1}));
  CHECK(std::abs(oracle::directional_overlap(a, b, vec({1, 0, 0})) - 0.5) <= 1e-12);   // 1 - 0.5
  CHECK(std::abs(oracle::directional_overlap(a, b, vec({-1, 0, 0})) - 3.5) <= 1e-12);  // 1 + 2.5
  CHECK(std::abs(oracle::directional_overlap(a, b, vec({0, 1, 0})) - 1.8) <= 1e-12);   // 1 - (-0.8)
  // Along (1, 1, 0)/sqrt2: A reaches 2/sqrt2, B starts at (0.5 - 0.8)/sqrt2.
  const double s = 1.0 / std::sqrt(2.0);
  CHECK(std::abs(oracle::directional_overlap(a, b, vec({s, s, 0})) - 2.3 * s) <= 1e-12);
}

TEST_CASE("Minkowski MTD: random overlapping polytopes carry the certificate of a minimum, n = 3..5", "[oracles]") {
  // For convex A and B the penetration depth is min over unit u of the overlap of their projections,
  // max_a a.u - min_b b.u (directional_overlap). So the MTD must (1) equal the overlap along its own
  // normal, (2) be no larger than the overlap along any other direction (2000 random ones and every
  // tied normal), and (3) moving B by (depth + 1e-6) along the normal must separate the two (LP
  // distance >= 1e-6 / sqrt(n), minus the LP's 1e-9 band) while (depth - 1e-6) must not.
  std::mt19937_64 rng(17);
  int checked = 0;
  for (int n = 3; n <= 5; ++n)
    for (int trial = 0; trial < 20; ++trial) {
      const Point centre = oracle::random_points_in_ball(n, 1, 0.8, Point::Zero(n), rng)[0];
      const Points a = oracle::random_points_in_ball(n, n + 5, 1.0, Point::Zero(n), rng);
      const Points b = oracle::random_points_in_ball(n, n + 5, 0.7, centre, rng);
      const oracle::MinkowskiMtd m = oracle::minkowski_mtd(a, b);
      if (!m.intersecting || m.depth < 1e-3) continue;
      ++checked;
      INFO("n = " << n << ", trial " << trial << ", depth " << m.depth);
      CHECK(std::abs(oracle::directional_overlap(a, b, m.normal) - m.depth) <= 1e-9);
      for (const Point& u : oracle::random_points_in_ball(n, 2000, 1.0, Point::Zero(n), rng))
        CHECK(oracle::directional_overlap(a, b, u.normalized()) >= m.depth - 1e-9);
      for (const Point& t : m.tied_normals) CHECK(std::abs(oracle::directional_overlap(a, b, t) - m.depth) <= 2e-9);
      for (const double step : {m.depth + 1e-6, m.depth - 1e-6}) {
        Points moved = b;
        for (Point& p : moved) p += step * m.normal;
        const double t = oracle::lp_separation(a, moved).distance;
        if (step > m.depth)
          CHECK(t >= 1e-6 / std::sqrt(double(n)) - 1e-9);
        else
          CHECK(t <= 1e-9);
      }
    }
  CHECK(checked >= 30);  // of 60 pairs; the rest overlap too little or not at all
}
