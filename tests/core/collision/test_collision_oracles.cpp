// The narrow phase against independent oracles (tests/support/oracles.hpp, which shares no code with
// core/src/collision):
//   - intersection: 10,000 random pairs each of boxes and of convex polytopes in 3D, 4D and 5D against
//     LP feasibility (GLPK);
//   - depth and normal: against the exact minimum translation distance from Qhull's hull of the
//     Minkowski difference; for pairs apart, against the brute-force distance to that hull;
//   - ball-polytope: against brute-force projection onto every face of every dimension;
//   - 3D boxes: against Bullet (btGjkEpaPenetrationDepthSolver and btBoxBoxDetector).
#include <catch2/catch.hpp>
#include <cmath>

#include "oracles.hpp"
#include "test_util.hpp"
#include "wedge/collision/narrow_phase.hpp"

using namespace wedge;

namespace {

// The band where the engine and the LP may disagree: the engine's |depth| and the LP's L-inf distance
// are both below it. Coordinates are O(1); the engine's SAT and GJK work to ~1e-12, GLPK's simplex
// meets its bounds to ~1e-12 (oracles.hpp), so 1e-9 is far above either and far below any real overlap.
constexpr double kBand = 1e-9;

template <int N>
Transform<N> random_transform(std::mt19937_64& rng, double spread) {
  std::normal_distribution<double> nd;
  Transform<N> t;
  t.position = Vec<N>::NullaryExpr([&] { return spread * nd(rng); });
  t.rotation = oracle::random_rotation(N, rng);
  return t;
}

template <int N>
oracle::Points world_points(const std::vector<Vec<N>>& local, const Transform<N>& t) {
  oracle::Points p;
  for (const Vec<N>& v : local) p.push_back(oracle::Point(t.apply(v)));
  return p;
}

template <int N>
std::vector<Vec<N>> box_corners(const Vec<N>& h) {
  std::vector<Vec<N>> c;
  for (int m = 0; m < (1 << N); ++m) {
    Vec<N> v;
    for (int i = 0; i < N; ++i) v[i] = (m >> i & 1) ? h[i] : -h[i];
    c.push_back(v);
  }
  return c;
}

// A shape, its points (for the oracles) and a placement.
template <int N>
struct Body {
  const Shape<N>* shape;
  std::vector<Vec<N>> points;
  Transform<N> where;
};

struct Tally {
  int pairs = 0, intersecting = 0, disagreements = 0, in_band = 0;
};

// Intersection status against the LP, for every pair.
template <int N>
void check_against_lp(const Body<N>& a, const Body<N>& b, Tally& t) {
  const Manifold<N> m = collide(*a.shape, a.where, *b.shape, b.where);
  REQUIRE(std::isfinite(m.depth));
  const oracle::LpSeparation lp = oracle::lp_separation(world_points(a.points, a.where), world_points(b.points, b.where));
  REQUIRE(lp.optimal);
  const bool lp_hit = lp.distance <= kBand;
  ++t.pairs;
  t.intersecting += m.intersecting;
  if (m.intersecting == lp_hit) return;
  if (std::abs(m.depth) < kBand && lp.distance < kBand) {
    ++t.in_band;
    return;
  }
  ++t.disagreements;
  UNSCOPED_INFO("engine depth " << m.depth << " intersecting " << m.intersecting << ", LP distance " << lp.distance);
}

// Depth and normal against the Minkowski-difference hull.
template <int N>
void check_against_mtd(const Body<N>& a, const Body<N>& b) {
  const Manifold<N> m = collide(*a.shape, a.where, *b.shape, b.where);
  const oracle::MinkowskiMtd mtd = oracle::minkowski_mtd(world_points(a.points, a.where), world_points(b.points, b.where));
  // Depth: the SAT's overlap is a difference of O(1) projections (round-off ~1e-15 each); GJK's
  // distance meets its relative tolerance 1e-10 of the O(1) sizes. 1e-8 absolute covers both.
  CHECK(m.depth == Approx(mtd.depth).margin(1e-8));
  if (std::abs(mtd.depth) < 1e-6) return;  // touching: the normal is not defined
  double best = -1.0;
  for (const oracle::Point& n : mtd.tied_normals) best = std::max(best, m.normal.dot(Vec<N>(n)));
  // Normals: unit vectors from the same facet agree to round-off; GJK's witness direction is good to
  // about sqrt(tolerance) relative to the distance, so 1e-5 in the cosine.
  CHECK(best > 1.0 - 1e-5);
}

template <int N>
void random_boxes(int pairs, int mtd_pairs, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> size(0.1, 1.0);
  Tally t;
  for (int i = 0; i < pairs; ++i) {
    const Vec<N> ha = Vec<N>::NullaryExpr([&] { return size(rng); });
    const Vec<N> hb = Vec<N>::NullaryExpr([&] { return size(rng); });
    const Shape<N> sa = Shape<N>::box(ha), sb = Shape<N>::box(hb);
    // Centres about one box size apart: roughly half the pairs overlap.
    const Body<N> a{&sa, box_corners<N>(ha), random_transform<N>(rng, 0.0)};
    const Body<N> b{&sb, box_corners<N>(hb), random_transform<N>(rng, 0.45 * std::sqrt(double(N)))};
    check_against_lp(a, b, t);
    if (i < mtd_pairs) check_against_mtd(a, b);
  }
  INFO(N << "D boxes: " << t.pairs << " pairs, " << t.intersecting << " intersecting, " << t.in_band << " within "
         << kBand);
  CHECK(t.disagreements == 0);
  CHECK(t.intersecting > pairs / 5);  // both outcomes are well represented
  CHECK(t.intersecting < pairs * 4 / 5);
}

template <int N>
void random_polytopes(int pairs, int mtd_pairs, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  // A pool of random polytopes (N+2 to N+5 points in the unit ball), placed anew for every pair.
  std::vector<Shape<N>> pool;
  std::vector<std::vector<Vec<N>>> points;
  for (int i = 0; i < 60; ++i) {
    const int count = N + 2 + i % 4;
    std::vector<Vec<N>> p;
    for (const oracle::Point& q : oracle::random_points_in_ball(N, count, 1.0, oracle::Point::Zero(N), rng))
      p.push_back(Vec<N>(q));
    pool.push_back(Shape<N>::polytope(p));
    points.push_back(p);
  }
  std::uniform_int_distribution<int> pick(0, int(pool.size()) - 1);
  Tally t;
  for (int i = 0; i < pairs; ++i) {
    const int ia = pick(rng), ib = pick(rng);
    const Body<N> a{&pool[ia], points[ia], random_transform<N>(rng, 0.0)};
    // Random polytopes fill less of the unit ball as N grows: bring them closer so both outcomes stay common.
    const Body<N> b{&pool[ib], points[ib], random_transform<N>(rng, 0.6 * 3.0 / N)};
    check_against_lp(a, b, t);
    if (i < mtd_pairs) check_against_mtd(a, b);
  }
  INFO(N << "D polytopes: " << t.pairs << " pairs, " << t.intersecting << " intersecting, " << t.in_band
         << " within " << kBand);
  CHECK(t.disagreements == 0);
  CHECK(t.intersecting > pairs / 5);
  CHECK(t.intersecting < pairs * 4 / 5);
}

}  // namespace

TEST_CASE("Box-box intersection agrees with LP on 10000 random pairs in 3D, 4D and 5D", "[oracle][box]") {
  random_boxes<3>(10000, 1000, 31);
  random_boxes<4>(10000, 300, 41);
  random_boxes<5>(10000, 60, 51);
}

TEST_CASE("Polytope-polytope intersection agrees with LP on 10000 random pairs in 3D, 4D and 5D", "[oracle][polytope]") {
  random_polytopes<3>(10000, 1000, 32);
  random_polytopes<4>(10000, 300, 42);
  random_polytopes<5>(10000, 100, 52);
}

TEMPLATE_TEST_CASE("Ball-polytope closest points agree with brute-force projection onto every face", "[oracle][ball]",
                   D3, D4, D5) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(60 + N);
  std::normal_distribution<double> nd;
  int inside = 0;
  for (int i = 0; i < 300; ++i) {
    oracle::Points pts = oracle::random_points_in_ball(N, N + 3 + i % 5, 1.0, oracle::Point::Zero(N), rng);
    std::vector<Vec<N>> local;
    for (const auto& q : pts) local.push_back(Vec<N>(q));
    const Shape<N> poly = Shape<N>::polytope(local);
    const Transform<N> tp = random_transform<N>(rng, 0.3);
    // Every other centre near the polytope's own centre, so that inside and outside both occur.
    const Vec<N> c = (i % 2 ? tp.apply(Vec<N>(poly.features()->centroid)) : Vec<N>::Zero()) +
                     Vec<N>::NullaryExpr([&] { return (i % 2 ? 0.1 : 0.8) * nd(rng); });
    const double r = 0.25;
    const Manifold<N> m = collide(Shape<N>::ball(r), Transform<N>{c, Mat<N>::Identity()}, poly, tp);
    const oracle::ClosestPoint cp = oracle::closest_point_brute_force(world_points(local, tp), oracle::Point(c));
    // GJK's distance and witness are good to its relative tolerance (1e-10) of O(1) sizes; 1e-8 margin.
    if (cp.inside) {
      ++inside;
      CHECK(m.depth == Approx(r + cp.boundary_distance).margin(1e-8));
      CHECK(m.normal.dot(-Vec<N>(cp.boundary_normal)) > 1.0 - 1e-8);
    } else {
      CHECK(m.depth == Approx(r - cp.distance).margin(1e-8));
      if (cp.distance > 1e-6) CHECK(m.normal.dot(Vec<N>((cp.point - oracle::Point(c)) / cp.distance)) > 1.0 - 1e-6);
    }
  }
  CHECK(inside > 10);
  CHECK(inside < 290);
}

TEST_CASE("3D box-box agrees with Bullet", "[oracle][bullet]") {
  std::mt19937_64 rng(70);
  std::uniform_real_distribution<double> size(0.1, 1.0);
  int compared = 0, bullet_epa_wrong = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec<3> ha = Vec<3>::NullaryExpr([&] { return size(rng); });
    const Vec<3> hb = Vec<3>::NullaryExpr([&] { return size(rng); });
    const Transform<3> ta = random_transform<3>(rng, 0.0), tb = random_transform<3>(rng, 0.6);
    const Manifold<3> m = collide(Shape<3>::box(ha), ta, Shape<3>::box(hb), tb);
    const oracle::BulletBoxBox bt = oracle::bullet_box_box(ha, ta.position, ta.rotation, hb, tb.position, tb.rotation);
    REQUIRE(bt.gjk_ok);
    // btBoxBoxDetector (ODE's dBoxBox) sees the same overlaps, outside a band of 1e-6 m where its
    // float-style tolerances decide.
    if (m.depth > 1e-6) CHECK(bt.intersecting);
    if (m.depth < -1e-6) CHECK(!bt.intersecting);
    if (std::abs(m.depth) < 1e-3) continue;  // near touching the normal is ill-defined
    ++compared;
    // Bullet's GJK-EPA stops at a relative accuracy of about 1e-4 of the sizes in double precision (its
    // EPA accuracy constant), so depth and distance agree to 1e-4 m and the normals to ~1e-2 rad...
    if (std::abs(m.depth + bt.gjk_distance) <= 1e-4) {
      CHECK(m.normal.dot(bt.gjk_normal) > 0.999);
      continue;
    }
    // ...except where Bullet's GJK-EPA itself is wrong: then Bullet's box-box detector and the exact
    // Minkowski difference must both side with the engine.
    ++bullet_epa_wrong;
    const oracle::MinkowskiMtd mtd = oracle::minkowski_mtd(oracle::box_vertices(ha, ta.position, ta.rotation),
                                                           oracle::box_vertices(hb, tb.position, tb.rotation));
    WARN("pair " << i << ": engine depth " << m.depth << ", Bullet GJK-EPA " << -bt.gjk_distance
                 << ", Bullet box-box intersecting " << bt.intersecting << ", exact (Minkowski) " << mtd.depth);
    CHECK(m.depth == Approx(mtd.depth).margin(1e-8));
    CHECK(bt.intersecting == m.intersecting);
  }
  CHECK(compared > 1500);
  CHECK(bullet_epa_wrong <= compared / 100);  // seen: 1 in 2000
}

// ---- exactly touching features (issue: two face-touching tesseracts gave a non-finite depth, and one
// contact point instead of eight). Touching pairs are built so that their faces coincide to round-off.
namespace {

// A rotation that fixes axis `keep` and turns the other N-1 axes at random (a turn "about the normal").
template <int N>
Mat<N> turn_about_axis(int keep, std::mt19937_64& rng) {
  Mat<N> t = Mat<N>::Identity();
  if constexpr (N > 2) {
    const Eigen::MatrixXd r = oracle::random_rotation(N - 1, rng);
    for (int i = 0, ri = 0; i < N; ++i) {
      if (i == keep) continue;
      for (int j = 0, rj = 0; j < N; ++j) {
        if (j == keep) continue;
        t(i, j) = r(ri, rj++);
      }
      ++ri;
    }
  }
  return t;
}

// Whether the world point lies in the box placed by t, grown by tol.
template <int N>
bool in_box(const Vec<N>& h, const Transform<N>& t, const Vec<N>& x, double tol) {
  return ((t.apply_inverse(x)).cwiseAbs() - h).maxCoeff() <= tol;
}

}  // namespace

TEMPLATE_TEST_CASE("Exactly face-touching boxes give a finite zero depth, the face normal and the full manifold, "
                   "and touch by LP",
                   "[oracle][touching]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(700 + N);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  // Round-off band: coordinates are O(1), every computation here is a few operations deep (1e-15), and
  // the engine treats gaps below 1e-9 of the size as touching; anything larger is a real error.
  constexpr double kTol = 1e-9;
  for (int trial = 0; trial < 100; ++trial) {
    Vec<N> ha, hb;
    for (int i = 0; i < N; ++i) ha[i] = 0.2 + 0.8 * u01(rng), hb[i] = 0.2 + 0.8 * u01(rng);
    const int axis = trial % N;         // the touching faces are a's +axis face and b's -axis face
    const bool general = trial % 2 == 1;  // a axis-aligned (the fig1 case), or turned at random
    const Shape<N> a = Shape<N>::box(ha), b = Shape<N>::box(hb);
    Transform<N> ta, tb;
    ta.position = Vec<N>::NullaryExpr([&] { return u01(rng) - 0.5; });
    if (general) ta.rotation = Mat<N>(oracle::random_rotation(N, rng));
    // b on a's face, turned about the face normal, shifted along the face by less than a's extent.
    Vec<N> shift = Vec<N>::Zero();
    for (int i = 0; i < N; ++i)
      if (i != axis) shift[i] = (u01(rng) - 0.5) * ha[i];
    shift[axis] = ha[axis] + hb[axis];
    tb.position = ta.position + ta.rotation * shift;
    tb.rotation = ta.rotation * turn_about_axis<N>(axis, rng);
    const Vec<N> normal = ta.rotation.col(axis);
    INFO("trial " << trial << " axis " << axis);

    const oracle::LpSeparation lp =
        oracle::lp_separation(world_points(box_corners<N>(ha), ta), world_points(box_corners<N>(hb), tb));
    REQUIRE(lp.optimal);
    CHECK(lp.distance <= kBand);  // the construction does touch

    CollisionSettings settings;  // margin 0, exact separation on: the `wedge collide` settings
    const Manifold<N> m = collide(a, ta, b, tb, settings);
    REQUIRE(std::isfinite(m.depth));
    CHECK(std::abs(m.depth) <= kTol);
    CHECK((m.normal - normal).norm() <= kTol);
    // The same pair pressed 1e-7 m together (which always worked) gives the contact region's points:
    // the touching pair must give as many, every one on both boxes' faces.
    Transform<N> pressed = tb;
    pressed.position -= 1e-7 * normal;
    const Manifold<N> ref = collide(a, ta, b, pressed, settings);
    CHECK(ref.count >= N);  // an (N-1)-dimensional contact region has at least N corners
    CHECK(m.count == ref.count);
    for (int k = 0; k < m.count; ++k) {
      const Vec<N>& x = m.points[std::size_t(k)].point;
      CHECK(std::abs(m.points[std::size_t(k)].depth) <= kTol);
      CHECK(in_box<N>(ha, ta, x, kTol));
      CHECK(in_box<N>(hb, tb, x, kTol));
    }
  }
}

TEMPLATE_TEST_CASE("A polytope and its mirror image across one of its facets touch along the whole facet",
                   "[oracle][touching]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(800 + N);
  constexpr double kTol = 1e-9;  // as above: round-off of O(1) coordinates, far below any real gap
  for (int trial = 0; trial < 40; ++trial) {
    const oracle::Points pts = oracle::random_points_in_ball(N, N + 4 + trial % 6, 1.0, oracle::Point::Zero(N), rng);
    std::vector<Vec<N>> pa;
    for (const auto& q : pts) pa.push_back(Vec<N>(q));
    const Shape<N> a = Shape<N>::polytope(pa);
    const auto& facets = a.features()->facets;
    const auto& f = facets[std::size_t(trial) % facets.size()];
    std::vector<Vec<N>> pb;  // the mirror image across f's plane: f's vertices stay (to round-off)
    for (const Vec<N>& x : a.features()->vertices) pb.push_back(x - 2.0 * (f.normal.dot(x) - f.offset) * f.normal);
    const Shape<N> b = Shape<N>::polytope(pb);
    const Transform<N> t;  // both placed as given
    INFO("trial " << trial << ", facet with " << f.vertices.size() << " vertices");

    const oracle::LpSeparation lp = oracle::lp_separation(world_points(pa, t), world_points(pb, t));
    REQUIRE(lp.optimal);
    CHECK(lp.distance <= kBand);

    const Manifold<N> m = collide(a, t, b, t, CollisionSettings{});
    REQUIRE(std::isfinite(m.depth));
    CHECK(std::abs(m.depth) <= kTol);
    CHECK((m.normal - f.normal).norm() <= kTol);
    // The facet is the contact region: its corners, as many as a manifold holds.
    CHECK(m.count == std::min<int>(int(f.vertices.size()), kMaxManifoldPoints<N>));
    for (int k = 0; k < m.count; ++k)
      CHECK(std::abs(f.normal.dot(m.points[std::size_t(k)].point) - f.offset) <= kTol);
  }
}
