// Time of impact by conservative advancement (wedge/collision/time_of_impact.hpp) against independent
// truth, n = 2..6:
//   - a sweep's ends are the poses it was made from, and every pose on it is a rotation;
//   - straight motion: the time a box or ball moving along a line reaches the target gap is known in
//     closed form (the gap falls linearly);
//   - turning and moving at once: a box swept towards a half-space or a box, its gap sampled at 2001
//     times along the sweep by an oracle that does not use GJK (the lowest corner against a plane), or at
//     401 by the Qhull hull of the corner differences for two boxes (2D and 3D). The result must be safe (no sample
//     before it comes nearer than the target) and tight (at the time returned the gap is within the
//     tolerance of the target), and no sample may come nearer than the target if it says "separated".
// Tolerances: 1e-9 m on gaps (GJK's relative accuracy is 1e-10 on O(1) shapes; the oracles are exact to
// round-off); the sampling spacing (1/2000 or 1/400 of the sweep) is finer than what a body moves
// between advancements, so a contact the samples see is one the method must see.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "convex_oracle.hpp"
#include "test_util.hpp"
#include "wedge/collision/time_of_impact.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/products.hpp"
#include "wedge/hull.hpp"

using namespace wedge;

namespace {

constexpr double kGap = 1e-9;  // m, gap accuracy (see above)
constexpr int kSamples = 2001;
constexpr int kHullSamples = 401;  // (a Qhull hull per sample)

template <int N>
Rotor<N> random_rotor(std::mt19937_64& rng, double scale) {
  return exp<N>(random_bivector<N>(rng, scale));
}

// The world corners of a box of half extents h placed by x.
template <int N>
std::vector<Vec<N>> corners(const Vec<N>& h, const Transform<N>& x) {
  std::vector<Vec<N>> out;
  for (int m = 0; m < (1 << N); ++m) {
    Vec<N> c;
    for (int i = 0; i < N; ++i) c[i] = (m >> i & 1) ? h[i] : -h[i];
    out.push_back(x.apply(c));
  }
  return out;
}

// The gap between a box and the half-space n . x <= offset: its lowest corner's height above the plane.
template <int N>
double plane_gap(const Vec<N>& h, const Transform<N>& x, const Vec<N>& n, double offset) {
  double low = 1e300;
  for (const Vec<N>& c : corners(h, x)) low = std::min(low, n.dot(c) - offset);
  return std::max(low, 0.0);
}

// The gap between two boxes: the distance from the origin to the hull of their corner differences.
template <int N>
double box_gap(const Vec<N>& ha, const Transform<N>& xa, const Vec<N>& hb, const Transform<N>& xb) {
  const auto hull = convex_hull<N>(oracle::minkowski_difference<N>(corners(ha, xa), corners(hb, xb)));
  if (oracle::min_offset<N>(hull) >= 0.0) return 0.0;
  return oracle::brute_distance<N>(hull);
}

// Checks a time of impact against the gap sampled along the sweep.
template <class Gap>
void check_against_samples(ImpactState state, double t, const TimeOfImpactSettings& s, const Gap& gap,
                           int samples = kSamples) {
  INFO("state " << int(state) << ", t = " << t);
  // Out of iterations is a safe stop short of the impact (the continuous stage treats it as one): checked
  // like a hit for safety, but not for tightness; the callers count them.
  const double end = state == ImpactState::Separated ? 1.0 : t;
  for (int k = 0; k < samples; ++k) {
    const double u = double(k) / (samples - 1);
    if (u >= end) break;
    INFO("sample t = " << u);
    CHECK(gap(u) >= s.target - kGap);  // safe: nothing before t comes nearer than the target
  }
  if (state == ImpactState::Hit) {
    const double g = gap(t);
    CHECK(g >= s.target - kGap);
    CHECK(g <= s.target + s.tolerance + kGap);  // tight: an impact, not a stop short of one
  }
}

}  // namespace

TEMPLATE_TEST_CASE("a sweep starts and ends at the poses it was made from, turning through rotations", "[toi]", D2,
                   D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(11 + N);
  for (int trial = 0; trial < 50; ++trial) {
    const Rotor<N> q0 = random_rotor<N>(rng, 1.0), q1 = random_rotor<N>(rng, 1.0);
    const Vec<N> c0 = oracle::gaussian<N>(rng), c1 = oracle::gaussian<N>(rng), local = 0.1 * oracle::gaussian<N>(rng);
    const Sweep<N> s = Sweep<N>::between(c0, q0, c1, q1, local);
    const Transform<N> end = s.transform(1.0);
    CHECK((end.rotation - to_matrix(q1)).cwiseAbs().maxCoeff() < 1e-9);
    CHECK((end.position - (c1 - to_matrix(q1) * local)).norm() < 1e-9);
    CHECK((s.transform(0.0).position - (c0 - to_matrix(q0) * local)).norm() < 1e-12);
    for (const double t : {0.25, 0.5, 0.75}) {
      const Mat<N> r = s.transform(t).rotation;
      CHECK((r * r.transpose() - Mat<N>::Identity()).cwiseAbs().maxCoeff() < 1e-12);
      CHECK(r.determinant() == Approx(1.0).margin(1e-12));
    }
  }
}

TEMPLATE_TEST_CASE("moving straight, the impact comes when the gap falls to the target, as the line says", "[toi]",
                   D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(23 + N);
  const Shape<N> ball = Shape<N>::ball(0.3);
  const Shape<N> box = Shape<N>::box(Vec<N>::Constant(0.5));
  TimeOfImpactSettings s;
  for (int trial = 0; trial < 40; ++trial) {
    // A ball towards a still box along the box's first axis, from gap g0 to gap g0 - travel.
    const Vec<N> dir = Vec<N>::Unit(0);
    const double g0 = 0.2 + 2.0 * std::uniform_real_distribution<double>()(rng);
    const double travel = 3.0 * std::uniform_real_distribution<double>()(rng);
    Vec<N> offset;  // sideways, staying within the face (half extent 0.5)
    for (int i = 0; i < N; ++i) offset[i] = std::uniform_real_distribution<double>(-0.4, 0.4)(rng);
    offset[0] = 0.0;
    const Vec<N> c0 = offset - (0.5 + 0.3 + g0) * dir;
    const Sweep<N> moving = Sweep<N>::between(c0, Rotor<N>::identity(), Vec<N>(c0 + travel * dir), Rotor<N>::identity());
    const Sweep<N> still = Sweep<N>::still(Vec<N>::Zero(), random_rotor<N>(rng, 0.0));
    const TimeOfImpact<N> r = time_of_impact(ball, moving, box, still, s);
    const double expected = (g0 - s.target) / travel;  // the gap is g0 - travel t
    INFO("g0 " << g0 << ", travel " << travel);
    if (expected >= 1.0) {
      CHECK(r.state == ImpactState::Separated);
    } else {
      REQUIRE(r.state == ImpactState::Hit);
      // Straight towards a face the bound is exact: one advancement lands on the target.
      CHECK(r.t == Approx(expected).margin(1e-9));
      CHECK(r.distance == Approx(s.target).margin(1e-9));
      CHECK(r.iterations <= 2);
      CHECK((r.normal - dir).norm() < 1e-9);
    }
  }
}

TEMPLATE_TEST_CASE("a box turning and moving at a half-space: safe and tight against the sampled gap", "[toi]", D2,
                   D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(37 + N);
  std::uniform_real_distribution<double> u01;
  TimeOfImpactSettings s;
  int hits = 0, misses = 0, stops = 0;
  for (int trial = 0; trial < 60; ++trial) {
    Vec<N> h;
    for (int i = 0; i < N; ++i) h[i] = 0.02 + 0.5 * u01(rng);  // plates and rods among them
    const Shape<N> box = Shape<N>::box(h);
    const Vec<N> n = oracle::unit<N>(rng);
    const double offset = -1.0;
    const Shape<N> plane = Shape<N>::halfspace(n, offset);
    // From up to 1.5 m above the plane (beyond the box's reach), towards it by 0.2-2 m, turning up to
    // about 3 rad.
    // (One draw per statement: the operands of + and * are evaluated in an order each compiler picks.)
    const double height = offset + h.norm() + 0.05 + 1.5 * u01(rng);
    const Vec<N> c0 = height * n + 0.3 * oracle::gaussian<N>(rng);
    const double approach = 0.2 + 1.8 * u01(rng);
    const Vec<N> c1 = c0 - approach * n + 0.3 * oracle::gaussian<N>(rng);
    const Rotor<N> q0 = random_rotor<N>(rng, 1.0);
    const Rotor<N> q1 = random_rotor<N>(rng, 0.7) * q0;
    const Sweep<N> moving = Sweep<N>::between(c0, q0, c1, q1);
    const Sweep<N> still = Sweep<N>::still(Vec<N>::Zero(), Rotor<N>::identity());
    const TimeOfImpact<N> r = time_of_impact(box, moving, plane, still, s);
    if (plane_gap<N>(h, moving.transform(0.0), n, offset) <= s.target) continue;  // (starts touching)
    (r.state == ImpactState::Hit ? hits : r.state == ImpactState::OutOfIterations ? stops : misses)++;
    check_against_samples(r.state, r.t, s, [&](double t) { return plane_gap<N>(h, moving.transform(t), n, offset); });
  }
  INFO(hits << " impacts, " << misses << " passing sweeps, " << stops << " out of iterations");
  CHECK(hits >= 20);  // both outcomes covered
  CHECK(misses >= 5);
  // Conservative advancement closes a gap geometrically, slowly where the motion bound (|w| times the
  // box's reach, over a metre for a 6D box) far exceeds the closing speed: one 6D sweep of these 60 stops
  // after 64 advancements at 6.3 mm, 1.3 mm short of the hit band (its contact comes at t = 0.96).
  CHECK(stops <= 2);
}

TEMPLATE_TEST_CASE("a box turning and moving at a box: safe and tight against the sampled Minkowski hull", "[toi]",
                   D2, D3) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(53 + N);
  std::uniform_real_distribution<double> u01;
  TimeOfImpactSettings s;
  int hits = 0, misses = 0;
  for (int trial = 0; trial < 12; ++trial) {
    Vec<N> ha, hb;
    for (int i = 0; i < N; ++i) ha[i] = 0.02 + 0.4 * u01(rng), hb[i] = 0.1 + 0.5 * u01(rng);
    const Shape<N> a = Shape<N>::box(ha), b = Shape<N>::box(hb);
    const Rotor<N> qb = random_rotor<N>(rng, 1.0);
    const Vec<N> dir = oracle::unit<N>(rng);
    const Vec<N> c0 = (ha.norm() + hb.norm() + 0.1 + 0.5 * u01(rng)) * dir;
    const double approach = 1.0 + 2.0 * u01(rng);  // (one draw per statement)
    const Vec<N> c1 = c0 - approach * dir + 0.4 * oracle::gaussian<N>(rng);
    const Rotor<N> q0 = random_rotor<N>(rng, 1.0);
    const Sweep<N> moving = Sweep<N>::between(c0, q0, c1, Rotor<N>(random_rotor<N>(rng, 0.7) * q0));
    const Sweep<N> still = Sweep<N>::still(Vec<N>::Zero(), qb);
    const TimeOfImpact<N> r = time_of_impact(a, moving, b, still, s);
    const Transform<N> xb = still.transform(0.0);
    (r.state == ImpactState::Hit ? hits : misses)++;
    CHECK(r.state != ImpactState::OutOfIterations);
    check_against_samples(r.state, r.t, s, [&](double t) { return box_gap<N>(ha, moving.transform(t), hb, xb); },
                          kHullSamples);
  }
  INFO(hits << " impacts, " << misses << " passing sweeps");
  CHECK(hits >= 6);
}
